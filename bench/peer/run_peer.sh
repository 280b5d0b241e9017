#!/usr/bin/env bash
# run_peer.sh: measure the public DDA peer ntdda (github doolin/ntdda) against ddafit's two
# solvers (implicit, substep) on running-bond brick walls of 411 and 1621 blocks.
#
#   DDAFIT=build/apps/ddafit/ddafit bash bench/peer/run_peer.sh   # everything; ~3 min (see README.md)
#
# Run it on an IDLE machine: it times programs, one at a time, never two at once.
# Knobs (environment variables, all optional):
#   WALLS="411 1621"          walls to run (411 = ntdda_wall.py 20 20, 1621 = 40 40)
#   REPEAT=1                  runs of every program/solver/thread count (the table gives the median)
#   SUBSTEP_THREADS="1 2"     --threads values for ddafit's substep solver
#   IMPLICIT_THREADS_411="1 2", IMPLICIT_THREADS_1621="1"   --threads for ddafit's implicit solver
#   SKIP_NTDDA=0 SKIP_IMPLICIT=0 SKIP_SUBSTEP=0             1 = leave that program/solver out
#   TIMEOUT_411=1800 TIMEOUT_1621=7200   seconds before a single run is stopped (reported TIMEOUT)
#   STAND_MM=10               the wall "stands" if measured point 1 moved less than this (mm)
#   REQUIRE_IDLE=0            1 = refuse to start when the 1-min load average is above 0.5
#   NTDDA_CTEST=0             1 = run ntdda's own ctest after building it (11 of 13 pass upstream)
#   OUT=bench/peer/runs/DATE  where the run folders and results.md go
#   DDAFIT, NTDDA_GIT, WALL_PY, ANA: the ddafit binary, the ntdda git directory, the wall writer, the .ana
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
NTDDA_GIT=${NTDDA_GIT:-/work/.mirror/doolin+ntdda/repo}
W=/tmp                                  # ntdda source in $W/ntdda, build in $W/ntdda-build (docs/peers/ntdda.md)
PIPELINE=${NTDDA_PIPELINE:-$W/ntdda-build/tests/unit/pipeline_test}   # override only to test this script
DDAFIT=${DDAFIT:-/work/main/build/apps/ddafit/ddafit}
# Every run starts in its own folder, so a relative path (the documented
# DDAFIT=build/apps/ddafit/ddafit) is made absolute here; before, each ddafit run failed rc=127.
[ -e "$DDAFIT" ] && DDAFIT=$(realpath "$DDAFIT")
WALL_PY=${WALL_PY:-/work/shared/docs/peers/ntdda_wall.py}
ANA=${ANA:-$HERE/wall.ana}
REPORT_PY=$HERE/peer_report.py
PY=${PYTHON:-python3}
WALLS=${WALLS:-"411 1621"}
REPEAT=${REPEAT:-1}
SUBSTEP_THREADS=${SUBSTEP_THREADS:-"1 2"}
IMPLICIT_THREADS_411=${IMPLICIT_THREADS_411:-"1 2"}
IMPLICIT_THREADS_1621=${IMPLICIT_THREADS_1621:-"1"}
SKIP_NTDDA=${SKIP_NTDDA:-0}
SKIP_IMPLICIT=${SKIP_IMPLICIT:-0}
SKIP_SUBSTEP=${SKIP_SUBSTEP:-0}
TIMEOUT_411=${TIMEOUT_411:-1800}
TIMEOUT_1621=${TIMEOUT_1621:-7200}
STAND_MM=${STAND_MM:-10}
REQUIRE_IDLE=${REQUIRE_IDLE:-0}
NTDDA_CTEST=${NTDDA_CTEST:-0}
OUT=${OUT:-$HERE/runs/$(date +%Y%m%d-%H%M%S)}

say()  { printf '[%s] %s\n' "$(date +%H:%M:%S)" "$*" >&2; }
die()  { printf '[%s] ERROR: %s\n' "$(date +%H:%M:%S)" "$*" >&2; exit 1; }
on_err() { if [[ $- == *e* ]]; then printf '[%s] ERROR: run_peer.sh stopped at line %s (exit %s)\n' "$(date +%H:%M:%S)" "$2" "$1" >&2; fi; }
trap 'on_err $? $LINENO' ERR

# ---------------------------------------------------------------------------------------------
# 0. prerequisites
# ---------------------------------------------------------------------------------------------
check_prerequisites() {
  local f
  for f in "$ANA" "$REPORT_PY" "$WALL_PY"; do [[ -r $f ]] || die "missing file: $f"; done
  [[ -x /usr/bin/time ]] || die "/usr/bin/time is needed (apt-get install time)"
  command -v timeout >/dev/null || die "timeout (coreutils) is needed"
  command -v "$PY" >/dev/null || die "python3 is needed"
  if [[ $SKIP_IMPLICIT != 1 || $SKIP_SUBSTEP != 1 ]]; then
    [[ -x $DDAFIT ]] || die "ddafit binary not found or not executable: $DDAFIT (this script does not build ddafit)"
  fi
  for f in $WALLS; do
    [[ $f == 411 || $f == 1621 ]] || die "WALLS may hold 411 and/or 1621, not '$f'"
  done
  [[ $REPEAT =~ ^[1-9][0-9]*$ ]] || die "REPEAT must be a whole number >= 1"
}

check_idle() {
  local load others
  load=$(cut -d' ' -f1 /proc/loadavg)
  others=$(pgrep -d' ' -x ddafit || true; pgrep -d' ' -x pipeline_test || true)
  others=$(echo $others)
  say "load average (1 min): $load; cores: $(nproc)"
  if [[ -n $others ]]; then
    say "WARNING: other ddafit/pipeline_test processes are running (pids: $others): the timings will be slowed"
    if [[ $REQUIRE_IDLE == 1 ]]; then die "REQUIRE_IDLE=1 and the machine is busy"; fi
  fi
  if awk -v l="$load" 'BEGIN{exit !(l > 0.5)}'; then
    say "WARNING: the machine is not idle (load $load > 0.5): timings will be slowed"
    if [[ $REQUIRE_IDLE == 1 ]]; then die "REQUIRE_IDLE=1 and the load average is $load"; fi
  fi
  return 0
}

# ---------------------------------------------------------------------------------------------
# 1. build ntdda exactly as /work/shared/docs/peers/ntdda.md says (skipped if already built)
# ---------------------------------------------------------------------------------------------
build_ntdda() {
  if [[ -x $PIPELINE ]]; then
    say "ntdda: $PIPELINE exists, not rebuilding (rm -rf $W/ntdda-build to force a build)"
    return 0
  fi
  say "ntdda: building from $NTDDA_GIT into $W/ntdda-build (about 1 minute)"
  [[ -d $NTDDA_GIT ]] || die "ntdda git directory not found: $NTDDA_GIT"
  command -v cmake >/dev/null || die "cmake is needed to build ntdda"
  command -v cc >/dev/null || command -v gcc >/dev/null || die "a C compiler is needed to build ntdda"
  [[ -r /usr/include/libxml2/libxml/parser.h ]] || die "libxml2 headers are needed to build ntdda (apt-get install libxml2-dev)"
  local brc=0
  set +e
  (
    set -euo pipefail
    G="$NTDDA_GIT"
    # 1. source
    rm -rf $W/ntdda && mkdir -p $W/ntdda
    git --git-dir=$G archive HEAD | tar -x -C $W/ntdda
    cd $W/ntdda
    # 2. fix 1 of 2: Win32-compatible rand() in src/blocks.c (verbatim from ntdda.md)
    sed -i '/^#include "dda.h" \/\/ for dda_display_warning$/a\
\
/* Portability: crr()/rlt() pick a ray from rand() assuming Win32 RAND_MAX=32767.\
 * glibc RAND_MAX is 2^31-1 -> sqrt(1-e1^2)=NaN, points misclassified, rlt() loops.\
 * Use the MSVC linear congruential generator instead. */\
static unsigned int ntdda_rand_state = 1u;\
static void ntdda_srand(unsigned int s) { ntdda_rand_state = s; }\
static int ntdda_rand(void) {\
   ntdda_rand_state = ntdda_rand_state * 214013u + 2531011u;\
   return (int)((ntdda_rand_state >> 16) \& 0x7fffu);\
}\
#define srand ntdda_srand\
#define rand ntdda_rand' src/blocks.c
    n=$(grep -c ntdda_rand src/blocks.c || true)
    [[ $n == 6 ]] || { echo "ntdda rand() fix: expected 6 lines with ntdda_rand in src/blocks.c, found $n" >&2; exit 1; }
    # 3. fix 2 of 2: -fcommon, then build (Release = -O3 -DNDEBUG)
    rm -rf $W/ntdda-build
    cmake -S . -B $W/ntdda-build -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-fcommon
    cmake --build $W/ntdda-build -j2
  ) > "$OUT/ntdda-build.log" 2>&1
  brc=$?
  set -e
  if [[ $brc != 0 ]]; then
    tail -n 30 "$OUT/ntdda-build.log" >&2
    die "ntdda build failed (exit $brc; log: $OUT/ntdda-build.log)"
  fi
  [[ -x $PIPELINE ]] || die "ntdda build finished but $PIPELINE is missing (log: $OUT/ntdda-build.log)"
  say "ntdda: built (log: $OUT/ntdda-build.log)"
  if [[ $NTDDA_CTEST == 1 ]]; then
    say "ntdda: ctest (11 of 13 pass upstream: analysisdata_test and bolttest fail there too)"
    (cd $W/ntdda-build/tests/unit && ctest) > "$OUT/ntdda-ctest.log" 2>&1 || true
    tail -n 5 "$OUT/ntdda-ctest.log" >&2
  fi
}

# ---------------------------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------------------------
wall_args()    { case $1 in 411) echo "20 20";; 1621) echo "40 40";; esac; }
wall_timeout() { case $1 in 411) echo "$TIMEOUT_411";; 1621) echo "$TIMEOUT_1621";; esac; }

# timed DIR CMD...: runs CMD in DIR under /usr/bin/time (wall seconds -> DIR/time.txt) and timeout,
# stdout -> DIR/stdout.txt, stderr -> DIR/stderr.txt; echoes the exit code (124 = timed out).
timed() {
  local dir=$1 limit=$2; shift 2
  local rc=0
  ( cd "$dir" && /usr/bin/time -f %e -o "$dir/time.txt" \
      timeout --foreground --kill-after=30 "$limit" "$@" >"$dir/stdout.txt" 2>"$dir/stderr.txt" ) || rc=$?
  echo "$rc"
}

wall_seconds_of() { tail -n 1 "$1/time.txt" 2>/dev/null || echo "?"; }

# ---------------------------------------------------------------------------------------------
# 2. ntdda on one wall
# ---------------------------------------------------------------------------------------------
# One line on how a run ended: LABEL OUTCOME(exit code) FOLDER BLOCKS DONE-MESSAGE.
report_outcome() {
  local label=$1 outcome=$2 d=$3 blocks=$4 done_message=$5
  if [[ $outcome == 0 ]]; then
    say "$label: done, $done_message"
  elif [[ $outcome == 124 ]]; then
    say "$label: TIMEOUT after $(wall_timeout "$blocks") s (see $d/stderr.txt)"
  else
    say "$label: FAILED (exit $outcome); last lines of $d/stderr.txt:"
    tail -n 5 "$d/stderr.txt" >&2 || true
  fi
}

run_ntdda() {
  local blocks=$1 rep=$2
  local d=$OUT/w${blocks}_1ntdda_r${rep}
  mkdir -p "$d"
  "$PY" "$WALL_PY" $(wall_args "$blocks") "$d/wall.geo" > "$d/wall_py.txt"
  cp "$ANA" "$d/wall.ana"
  if ! cmp -s "$d/wall.geo" "$OUT/w${blocks}_0import/wall.geo"; then
    die "$d/wall.geo differs from the imported $OUT/w${blocks}_0import/wall.geo"
  fi
  say "ntdda, wall $blocks (run $rep): $PIPELINE $d/wall.geo $d/wall.ana"
  local rc
  rc=$(timed "$d" "$(wall_timeout "$blocks")" "$PIPELINE" "$d/wall.geo" "$d/wall.ana")
  rm -f "$d/output/pushblock.m"     # MATLAB dump of K and F: 86 MB at 1621 blocks
  {
    echo "program=ntdda"; echo "wall=${blocks}"; echo "blocks_asked=$blocks"; echo "repeat=$rep"; echo "rc=$rc"
    echo "folder=$d"
  } > "$d/meta"
  local total
  total=$(sed -n 's/.*<li>Total: *\([0-9.]*\)<\/li>.*/\1/p' "$d/output/pushblock.html" 2>/dev/null | head -n 1 || true)
  local outcome=$rc
  [[ $rc == 0 ]] && ! grep -q 'pipeline_test: PASSED' "$d/stderr.txt" && outcome="0 without 'PASSED'"
  report_outcome "ntdda, wall $blocks" "$outcome" "$d" "$blocks" \
    "${total:-?} s of analysis (Total: of pushblock.html), $(wall_seconds_of "$d") s wall"
  return 0
}

# ---------------------------------------------------------------------------------------------
# 3. ddafit: import once per wall, then run each solver / thread count
# ---------------------------------------------------------------------------------------------
import_wall() {
  local blocks=$1
  local d=$OUT/w${blocks}_0import
  mkdir -p "$d"
  "$PY" "$WALL_PY" $(wall_args "$blocks") "$d/wall.geo" > "$d/wall_py.txt"
  cp "$ANA" "$d/wall.ana"
  local rc=0
  "$DDAFIT" import "$d/wall.geo" --analysis "$d/wall.ana" --units kN --out "$d/wall.yaml" > "$d/import.txt" 2>&1 || rc=$?
  if [[ $rc != 0 ]]; then
    say "ddafit import, wall $blocks: FAILED (exit $rc):"
    cat "$d/import.txt" >&2
    return 1
  fi
  say "ddafit import, wall $blocks: $(grep '^wrote' "$d/import.txt" || echo '?')"
  return 0
}

run_ddafit() {
  local blocks=$1 solver=$2 threads=$3 rep=$4
  local imp=$OUT/w${blocks}_0import
  local d=$OUT/w${blocks}_2ddafit_${solver}_t${threads}_r${rep}
  mkdir -p "$d"
  local at
  at=$(sed -n 's/.*{name: 1, at: \[\([-0-9.e+]*\), *\([-0-9.e+]*\)\]}.*/\1,\2/p' "$imp/wall.yaml" | head -n 1)
  say "ddafit $solver --threads $threads, wall $blocks (run $rep)"
  local rc
  rc=$(timed "$d" "$(wall_timeout "$blocks")" "$DDAFIT" simulate "$imp/wall.yaml" --out "$d" \
         --set time.integrator="$solver" --threads "$threads" --quiet)
  {
    echo "program=ddafit"; echo "wall=${blocks}"; echo "blocks_asked=$blocks"; echo "solver=$solver"
    echo "threads=$threads"; echo "repeat=$rep"; echo "rc=$rc"; echo "folder=$d"
    echo "import_log=$imp/import.txt"; echo "measure_at=$at"
  } > "$d/meta"
  report_outcome "ddafit $solver --threads $threads, wall $blocks" "$rc" "$d" "$blocks" "$(wall_seconds_of "$d") s wall"
  return 0
}

# ---------------------------------------------------------------------------------------------
# main
# ---------------------------------------------------------------------------------------------
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
check_prerequisites
say "results go to $OUT"
[[ $SKIP_NTDDA == 1 ]] || build_ntdda
check_idle

{
  echo "date: $(date -Is)"
  echo "host: $(uname -srm), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "ntdda: $(git --git-dir="$NTDDA_GIT" rev-parse HEAD 2>/dev/null || echo '?') ($NTDDA_GIT), binary $PIPELINE"
  if [[ -x $DDAFIT ]]; then
    echo "ddafit: $("$DDAFIT" --version 2>&1 | head -n 1), binary $DDAFIT, modified $(stat -c %y "$DDAFIT"), sha256 $(sha256sum "$DDAFIT" | cut -c1-16)"
    echo "ddafit source: $(git -C /work/main rev-parse HEAD 2>/dev/null || echo '?'), $(git -C /work/main status --porcelain 2>/dev/null | wc -l) changed files in the work tree"
  fi
  echo "analysis file: $ANA (sha256 $(sha256sum "$ANA" | cut -c1-16))"
  echo "settings: WALLS='$WALLS' REPEAT=$REPEAT SUBSTEP_THREADS='$SUBSTEP_THREADS' IMPLICIT_THREADS_411='$IMPLICIT_THREADS_411' IMPLICIT_THREADS_1621='$IMPLICIT_THREADS_1621'"
} > "$OUT/versions.txt"
cp "$ANA" "$OUT/wall.ana"

for blocks in $WALLS; do
  imported=1
  if [[ $SKIP_IMPLICIT != 1 || $SKIP_SUBSTEP != 1 ]]; then
    import_wall "$blocks" || imported=0
  else
    mkdir -p "$OUT/w${blocks}_0import"
    "$PY" "$WALL_PY" $(wall_args "$blocks") "$OUT/w${blocks}_0import/wall.geo" > /dev/null
  fi
  if [[ $blocks == 411 ]]; then implicit_threads=$IMPLICIT_THREADS_411; else implicit_threads=$IMPLICIT_THREADS_1621; fi
  for rep in $(seq 1 "$REPEAT"); do
    [[ $SKIP_NTDDA == 1 ]] || run_ntdda "$blocks" "$rep"
    if [[ $imported == 1 ]]; then
      if [[ $SKIP_IMPLICIT != 1 ]]; then
        for t in $implicit_threads; do run_ddafit "$blocks" implicit "$t" "$rep"; done
      fi
      if [[ $SKIP_SUBSTEP != 1 ]]; then
        for t in $SUBSTEP_THREADS; do run_ddafit "$blocks" substep "$t" "$rep"; done
      fi
    fi
  done
done

say "all runs finished; table (also in $OUT/results.md):"
{
  echo "# ntdda vs ddafit on running-bond brick walls ($(date +%Y-%m-%d))"
  echo
  sed 's/^/    /' "$OUT/versions.txt"
  echo
  "$PY" "$REPORT_PY" "$OUT" "$STAND_MM"
} > "$OUT/results.md"
cat "$OUT/results.md"
