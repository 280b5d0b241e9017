#!/usr/bin/env bash
# Vajont sections I-X (seed Table 2 block sizes), reference and degraded states, 45 s each,
# with the solver the scene's size picks (substep from 100 blocks up), one command:
#   bash scripts/vajont_sections.sh [OUT_DIR] [SECTIONS] [STATES]
# OUT_DIR defaults to results/vajont-sections; SECTIONS to all ten ("I II ... X");
# STATES to "reference degraded". Extra settings for every run go in DDAFIT_SETS
# (e.g. DDAFIT_SETS="time.step=0.0025"); DDAFIT_THREADS sets --threads (results are the
# same on any thread count, so one thread leaves a core free for other work); DDAFIT_BIN
# names another ddafit binary (a copy keeps a long batch safe from rebuilds). A finished run (summary.json present) is not
# redone. Writes OUT_DIR/sections.csv: one row per run with point 1's results, the wall
# time, steps, contact points and worst overlap (about 42 minutes of both cores for all 20 on a
# slow machine, 2026-12-08).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/vajont-sections}
sections=${2:-"I II III IV V VI VII VIII IX X"}
states=${3:-"reference degraded"}
ddafit=${DDAFIT_BIN:-./build/apps/ddafit/ddafit}
mkdir -p "$out"

size_of() {  # seed Table 2 mean block sizes, m (cases/vajont/vajont.yaml)
  case $1 in
    I) echo 34.3 ;; II) echo 23.1 ;; III) echo 16.0 ;; IV) echo 12.1 ;; V) echo 9.8 ;;
    VI) echo 8.9 ;; VII) echo 8.2 ;; VIII) echo 7.4 ;; IX) echo 6.6 ;; X) echo 5.7 ;;
    *) echo "unknown section '$1' (I-X)" >&2; exit 2 ;;
  esac
}

# The scene runs 20 ms steps of four substeps, each step moving a block 0.5 m at most by its
# turning (control.step_by_turn), after a 250-step quiet start. Sections VIII-X (7.4, 6.6 and
# 5.7 m blocks) overlap by more than 1 % there (VIII degraded: 1.32 %), so they run 10 ms steps,
# each moving a vertex 0.25 m at most over its whole travel (by turn, VIII degraded overlapped by
# 1.62 %): VIII and IX in four substeps, X in five (in four its reference state overlapped by
# 1.06 %). docs/vajont.md, "Sections VIII-X at 10 ms x 4"; 5 ms x 4 and a 500-step quiet start
# until 2026-12-08.
step_of() {
  local substeps
  case $1 in
    VIII|IX) substeps=4 ;;
    X) substeps=5 ;;
    *) return ;;
  esac
  echo "--set time.step=0.01 --set time.substeps=$substeps --set control.max_displacement_ratio=0.0002" \
    "--set control.step_by_turn=false"
}

sets=()
for s in ${DDAFIT_SETS:-}; do sets+=(--set "$s"); done
[ -n "${DDAFIT_THREADS:-}" ] && sets+=(--threads "$DDAFIT_THREADS")
for section in $sections; do
  size=$(size_of "$section")
  for state in $states; do
    scene=cases/vajont/vajont.yaml
    [ "$state" = degraded ] && scene=cases/vajont/degraded.yaml
    dir="$out/${section}_${state}"
    if [ ! -f "$dir/summary.json" ]; then
      echo "section $section ($size m), $state" >&2
      # shellcheck disable=SC2046  # step_of gives whole --set words
      "$ddafit" simulate "$scene" --set mesh.block_size="$size" $(step_of "$section") "${sets[@]}" --out "$dir" \
        --quiet || true
    fi
  done
done

python3 - "$out" $sections <<'EOF'
import csv, json, os, sys
out, sections = sys.argv[1], sys.argv[2:]
# Free blocks per section as meshed (docs/vajont.md, block counts; a test holds them).
blocks = dict(I=183, II=408, III=842, IV=1461, V=2209, VI=2677, VII=3136, VIII=3849, IX=4846, X=6481)
rows = []
for section in sections:
    for state in ("reference", "degraded"):
        path = os.path.join(out, f"{section}_{state}", "summary.json")
        if not os.path.exists(path):
            continue
        d = json.load(open(path))
        p = d["points"].get("1", {})
        run, solver = d["run"], d.get("solver", {})
        rows.append({
            "section": section, "state": state, "blocks": blocks[section],
            "solver": solver.get("integrator", ""), "status": d["status"],
            "simulated_s": round(run["simulated_time"], 2),
            "p1_lateral_m": round(p.get("max_lateral_displacement", float("nan")), 1),
            "p1_total_m": round(p.get("max_total_displacement", float("nan")), 1),
            "p1_peak_lateral_v": round(p.get("peak_lateral_velocity", float("nan")), 2),
            "p1_duration_s": round(p.get("duration", float("nan")), 1),
            "wall_s": round(run["wall_seconds"], 1), "steps": run["steps"],
            "contact_points": round(solver.get("mean_contact_points", 0)),
            "worst_overlap_ratio": round(solver.get("worst_penetration_ratio", 0), 4),
            "message": d.get("message", "")[:160],
        })
with open(os.path.join(out, "sections.csv"), "w", newline="") as f:
    if rows:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
for r in rows:
    print(" | ".join(str(v) for v in r.values()))
EOF
