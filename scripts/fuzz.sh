#!/usr/bin/env bash
# Fuzz one of ddafit's input readers with libFuzzer (clang):
#   bash scripts/fuzz.sh TARGET SECONDS [JOBS]
# TARGET: scene_reader | region_mesh | study | set_parser | ddaml (fuzz/targets.hpp). Builds
# build-fuzz with clang, AddressSanitizer and UBSan (once; later runs rebuild what
# changed), starts from fuzz/corpus/TARGET plus fuzz/regressions/TARGET, and keeps what it
# learns in build-fuzz/corpus/TARGET. A finding is written to fuzz/findings/ and the
# script exits non-zero: reduce it, fix the class of input, and move it to
# fuzz/regressions/TARGET, where the test suite runs it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/fuzz.sh TARGET SECONDS [JOBS]}
seconds=${2:?usage: scripts/fuzz.sh TARGET SECONDS [JOBS]}
jobs=${3:-1}
case $target in
  scene_reader|region_mesh|study|set_parser|ddaml) ;;
  *) echo "fuzz.sh: unknown target '$target' (scene_reader, region_mesh, study, set_parser, ddaml)" >&2; exit 2 ;;
esac
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDDAFIT_FUZZ=ON \
    -DDDAFIT_BUILD_TESTS=OFF -DDDAFIT_BUILD_BENCH=OFF > /dev/null
fi
cmake --build build-fuzz -j2 --target "fuzz_$target"
mkdir -p "build-fuzz/corpus/$target" fuzz/findings
# The YAML dictionary words help the fuzzer past the parser into the readers' checks.
# The mesher's target caps the arrangement at 2e5 edges (fuzz/reader_targets.cpp), about
# 17 s under the sanitizers: it gets a minute before an input counts as a hang.
timeout=20
[ "$target" = region_mesh ] && timeout=60
parallel=()
[ "$jobs" -gt 1 ] && parallel=(-jobs="$jobs" -workers="$jobs")
UBSAN_OPTIONS=print_stacktrace=1 ASAN_OPTIONS=detect_leaks=0 "./build-fuzz/fuzz/fuzz_$target" -max_total_time="$seconds" "${parallel[@]}" -timeout="$timeout" -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 \
  -dict=fuzz/yaml.dict -artifact_prefix=fuzz/findings/"$target"- \
  "build-fuzz/corpus/$target" "fuzz/corpus/$target" "fuzz/regressions/$target"
