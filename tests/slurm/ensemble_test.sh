#!/usr/bin/env bash
# `ddafit simulate --ensemble --slurm` against a real one-node SLURM (tests/slurm/cluster.sh):
# the job array's realisations, collected into the output folder's cache, must give the
# members and realisation 0's history the same ensemble run locally gives, to the last
# digit the files carry. If the daemons do not start the test fails; it never skips.
#   bash tests/slurm/ensemble_test.sh DDAFIT SCENE WORK_DIR
set -euo pipefail
ddafit=${1:?ddafit binary}
scene=${2:?scene}
work=${3:?work folder}
source "$(dirname "$0")/start_cluster.sh"

# A --set with a space and braces: job.sh must hand it to every task as one argument.
run=(simulate "$scene" --ensemble 5 --set "time.duration=0.45" --set "output={interval: 0.01}")
"$ddafit" "${run[@]}" --quiet --out "$work/local" > "$work/local.log" 2>&1
"$ddafit" "${run[@]}" --slurm "$work/job" --array-limit 2 --out "$work/cluster-out" > "$work/submit.log"
grep -q "5 realisations" "$work/submit.log" || { cat "$work/submit.log" >&2; exit 1; }
sbatch --wait "$work/job/job.sh" > "$work/sbatch.log"
"$ddafit" "${run[@]}" --collect "$work/job" --out "$work/cluster-out" > "$work/collect.log" 2>&1
grep -q "collected 5 of 5 results" "$work/collect.log" || { cat "$work/collect.log" >&2; exit 1; }
if grep -q "^realisation " "$work/collect.log"; then
  echo "ensemble_test.sh: the collecting run ran realisations itself" >&2; cat "$work/collect.log" >&2; exit 1
fi
for f in ensemble.csv history.csv; do
  if ! cmp -s "$work/local/$f" "$work/cluster-out/$f"; then
    echo "ensemble_test.sh: $f differs between the local ensemble and the SLURM array" >&2
    diff "$work/local/$f" "$work/cluster-out/$f" | head -5 >&2
    exit 1
  fi
done
echo "SLURM ensemble: 5 realisations, the local ensemble's members and history"
