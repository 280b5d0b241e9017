#!/usr/bin/env bash
# A study whose model spread is measured (model_sigma: ensemble) scanned through a real
# one-node SLURM (tests/slurm/cluster.sh): the spread's realisations go into the job array
# beside the design's points, the collecting run measures the spread from the cache
# without running anything, and sigma and chi2 come out as in the same scan run locally.
# If the daemons do not start the test fails; it never skips.
#   bash tests/slurm/spread_test.sh DDAFIT TWIN_STUDY WORK_DIR
set -euo pipefail
ddafit=${1:?ddafit binary}
twin=${2:?twin study}
work=${3:?work folder}
source "$(dirname "$0")/start_cluster.sh"

# The twin study with its first observation's model sigma measured by 4 realisations.
study="$work/study.yaml"
sed -e "s|^scene: two_sliders.yaml|scene: $(dirname "$twin")/two_sliders.yaml|" \
    -e "s|value: 2.6943, sigma: 0.01}|value: 2.6943, sigma: 0.01, model_sigma: ensemble}|" "$twin" > "$study"
echo "ensemble: 4" >> "$study"
grep -q "model_sigma: ensemble" "$study" || { echo "spread_test.sh: the twin study changed; cannot add model_sigma" >&2; exit 1; }

design=(--design lhs --samples 2 --seed 7)
"$ddafit" scan "$study" "${design[@]}" --out "$work/local" > "$work/local.log" 2>&1
"$ddafit" scan "$study" "${design[@]}" --slurm "$work/job" --array-limit 2 --out "$work/cluster-out" > "$work/submit.log"
# 4 realisations (the start point and 3 nudged) + 2 x 2 design points (two critical-distance levels).
tasks=$(wc -l < "$work/job/points.txt")
[ "$tasks" -eq 8 ] || { echo "spread_test.sh: $tasks tasks in points.txt, expected 8" >&2; cat "$work/job/points.txt" >&2; exit 1; }
sbatch --wait "$work/job/job.sh" > "$work/sbatch.log"
"$ddafit" scan "$study" "${design[@]}" --collect "$work/job" --out "$work/cluster-out" > "$work/collect.log" 2>&1
grep -q "collected 8 of 8 results" "$work/collect.log" || { cat "$work/collect.log" >&2; exit 1; }
if grep -q "model spread: realisation" "$work/collect.log"; then
  echo "spread_test.sh: the collecting run ran realisations itself" >&2; cat "$work/collect.log" >&2; exit 1
fi
local_sigma=$(grep -o "model_sigma = [^;]*" "$work/local.log")
cluster_sigma=$(grep -o "model_sigma = [^;]*" "$work/collect.log")
[ -n "$local_sigma" ] && [ "$local_sigma" = "$cluster_sigma" ] || {
  echo "spread_test.sh: model sigma '$cluster_sigma' from the array against '$local_sigma' locally" >&2; exit 1; }
if ! diff <(cut -d, -f1-5 "$work/local/runs.csv") <(cut -d, -f1-5 "$work/cluster-out/runs.csv"); then
  echo "spread_test.sh: chi2 per point differs between the local scan and the SLURM array" >&2
  exit 1
fi
echo "SLURM scan with a measured model spread: 8 tasks, $local_sigma as locally, same chi2"
