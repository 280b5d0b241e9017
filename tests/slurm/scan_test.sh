#!/usr/bin/env bash
# `ddafit scan --slurm` against a real one-node SLURM (tests/slurm/cluster.sh): the job
# array's results, collected into the cache, must give the same chi2 at every point as the
# same scan run locally. If the daemons do not start the test fails; it never skips.
#   bash tests/slurm/scan_test.sh DDAFIT STUDY WORK_DIR
set -euo pipefail
ddafit=${1:?ddafit binary}
study=${2:?study}
work=${3:?work folder}
source "$(dirname "$0")/start_cluster.sh"

design=(--design lhs --samples 4 --seed 11)
"$ddafit" scan "$study" "${design[@]}" --out "$work/local" > "$work/local.log" 2>&1
"$ddafit" scan "$study" "${design[@]}" --slurm "$work/job" --array-limit 2 --out "$work/cluster-out" > "$work/submit.log"
sbatch --wait "$work/job/job.sh" > "$work/sbatch.log"
"$ddafit" scan "$study" "${design[@]}" --collect "$work/job" --out "$work/cluster-out" > "$work/collect.log" 2>&1
grep -q "collected 8 of 8 results" "$work/collect.log" || { cat "$work/collect.log" >&2; exit 1; }
# runs.csv: column 5 is chi2 (run, three parameters, chi2): every point the same.
if ! diff <(cut -d, -f1-5 "$work/local/runs.csv") <(cut -d, -f1-5 "$work/cluster-out/runs.csv"); then
  echo "scan_test.sh: chi2 per point differs between the local scan and the SLURM array" >&2
  exit 1
fi
echo "SLURM scan: 8 points, same chi2 as the local scan"
