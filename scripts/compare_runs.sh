#!/usr/bin/env bash
# Records, or compares, the outputs a refactor must not change (issue "The step's seams"):
# the incline (implicit and substep), the 1621-brick wall for 1 s (substep), Vajont section I
# degraded on both solvers, and the built-in twin study's report.
#   bash scripts/compare_runs.sh record DDAFIT_BINARY OUT_DIR    # about 6 minutes on 2 cores
#   bash scripts/compare_runs.sh compare BEFORE_DIR AFTER_DIR     # exit 1 if anything differs
# `compare` checks every CSV and JSON file bitwise after dropping what a run may vary
# (wall times, profiles, the command line, paths); where a file differs it prints the
# largest absolute and relative difference of its numbers, so a change can be explained.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-}
case "$mode" in
  record)
    bin=${2:?"usage: $0 record DDAFIT_BINARY OUT_DIR"}; out=${3:?"usage: $0 record DDAFIT_BINARY OUT_DIR"}
    mkdir -p "$out"
    run() { local name=$1; shift; echo "  $name" >&2; "$bin" "$@" --out "$out/$name" > "$out/$name.log" 2>&1 || true; }
    run incline_implicit simulate cases/verification/incline_i5.yaml --set time.integrator=implicit --quiet
    run incline_substep simulate cases/verification/incline_i5.yaml --set time.integrator=substep --quiet
    run brick_wall simulate cases/walls/brick_wall_1621.yaml --set time.duration=1 --quiet
    run vajont_I_implicit simulate cases/vajont/degraded.yaml --set mesh.block_size=34.3 --set time.integrator=implicit --quiet
    run vajont_I_substep simulate cases/vajont/degraded.yaml --set mesh.block_size=34.3 --set time.integrator=substep --quiet
    run twin invert
    ;;
  compare)
    before=${2:?"usage: $0 compare BEFORE_DIR AFTER_DIR"}; after=${3:?"usage: $0 compare BEFORE_DIR AFTER_DIR"}
    python3 - "$before" "$after" <<'PY'
import json, math, os, re, sys
before, after = sys.argv[1], sys.argv[2]
VARYING = re.compile(r"wall|seconds|profile|elapsed|command|path|directory|out_dir|cache|date|host|threads")
def numbers(text):
    return [float(x) for x in re.findall(r"-?\d+\.?\d*(?:[eE][-+]?\d+)?", text)]
def clean(obj):
    if isinstance(obj, dict):
        return {k: clean(v) for k, v in obj.items() if not VARYING.search(k)}
    if isinstance(obj, list):
        return [clean(v) for v in obj]
    return obj
differ = 0
for root, _, files in os.walk(before):
    for name in sorted(files):
        if not name.endswith((".csv", ".json")):
            continue
        a = os.path.join(root, name)
        b = os.path.join(after, os.path.relpath(a, before))
        rel = os.path.relpath(a, before)
        if not os.path.exists(b):
            print(f"missing after: {rel}"); differ += 1; continue
        ta, tb = open(a).read(), open(b).read()
        if name.endswith(".json"):
            ta = json.dumps(clean(json.loads(ta)), sort_keys=True)
            tb = json.dumps(clean(json.loads(tb)), sort_keys=True)
        if ta == tb:
            continue
        differ += 1
        na, nb = numbers(ta), numbers(tb)
        if len(na) != len(nb):
            print(f"differs: {rel} ({len(na)} numbers before, {len(nb)} after)"); continue
        absd = max((abs(x - y) for x, y in zip(na, nb)), default=0.0)
        reld = max((abs(x - y) / max(abs(x), abs(y)) for x, y in zip(na, nb) if x != y), default=0.0)
        print(f"differs: {rel}: largest difference {absd:.3g} absolute, {reld:.3g} relative")
print(f"{differ} file(s) differ" if differ else "identical: every CSV and JSON file matches")
sys.exit(1 if differ else 0)
PY
    ;;
  *) echo "usage: $0 record DDAFIT_BINARY OUT_DIR | compare BEFORE_DIR AFTER_DIR" >&2; exit 2 ;;
esac
