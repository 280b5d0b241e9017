#!/usr/bin/env bash
# Speed against accuracy for both solvers (docs/speed-accuracy.md), one command:
#   bash scripts/speed_accuracy.sh [OUT_DIR] [SECTIONS]
# OUT_DIR defaults to results/speed-accuracy; SECTIONS to "34.3 23.1" (Vajont I and II;
# add 16.0 for III, about ten minutes more). Needs a Release build in build/, python3 and
# gnuplot. Writes incline.csv, vajont.csv and the two log-log charts into OUT_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/speed-accuracy}
sections=${2:-"34.3 23.1"}
ddafit=./build/apps/ddafit/ddafit
mkdir -p "$out/runs"

run() {  # run NAME SCENE SETS...
  local name=$1 scene=$2; shift 2
  local sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  if [ ! -f "$out/runs/$name/summary.json" ]; then
    "$ddafit" simulate "$scene" "${sets[@]}" --out "$out/runs/$name" --quiet || true
  fi
}

# The seed's incline with degradation (phi 25, i 5): both solvers over their step settings.
for dt in 0.0005 0.001 0.002 0.005 0.01; do
  run "incline_implicit_$dt" cases/verification/incline_i5.yaml time.integrator=implicit time.step=$dt
done
for dt in 0.001 0.002 0.005 0.01 0.02; do
  for n in 1 4 16; do
    run "incline_substep_${dt}_$n" cases/verification/incline_i5.yaml time.integrator=substep time.step=$dt time.substeps=$n
  done
done

# Vajont, degraded state: the finest substep run of each section is its reference.
for size in $sections; do
  run "vajont_${size}_substep_0.0025_8" cases/vajont/degraded.yaml mesh.block_size=$size time.integrator=substep time.step=0.0025 time.substeps=8
  for dt in 0.005 0.01 0.0167; do
    for n in 2 4 8; do
      run "vajont_${size}_substep_${dt}_$n" cases/vajont/degraded.yaml mesh.block_size=$size time.integrator=substep time.step=$dt time.substeps=$n
    done
  done
  run "vajont_${size}_implicit_0.005" cases/vajont/degraded.yaml mesh.block_size=$size time.integrator=implicit time.step=0.005
done

python3 scripts/speed_accuracy.py "$out"
gnuplot -e "out='$out'" scripts/speed_accuracy.gp
echo "wrote $out/incline.csv, $out/vajont.csv, $out/incline.png, $out/vajont.png"
