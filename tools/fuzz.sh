#!/usr/bin/env bash
# The loaders of untrusted files under libFuzzer + AddressSanitizer + UndefinedBehaviorSanitizer (fuzz/).
#   bash tools/fuzz.sh [SECONDS] [TARGET ...]   build build-fuzz/, run the loader tests, then fuzz each target for
#                                               SECONDS (default 60; targets: gltf scene_file environment
#                                               method_file camera_path), all targets at once (libFuzzer is
#                                               single-threaded): the wall time stays SECONDS whatever their number
#   bash tools/fuzz.sh --tests                  build and run only the loader tests (tests/hostile_input_test.cpp,
#                                               tests/output_files_test.cpp) under the sanitizers
# Fails on a crash, sanitizer report, leak, timeout (> 30 s per input) or out-of-memory (> 2.5 GB) of any input;
# the input is kept as build-fuzz/artifacts/<target>-crash-* (add it to tests/data/hostile/ with a test). Seeds
# come from fuzz/corpus/<target> (committed); what the fuzzer learns stays in build-fuzz/corpus/<target>.
# Needs clang and libclang-rt-14-dev (installed by tools/bootstrap.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
tests_only=0
targets=()
for arg in "$@"; do
  case "$arg" in
    --tests) tests_only=1 ;;
    [0-9]*) seconds=$arg ;;
    gltf|scene_file|environment|method_file|camera_path) targets+=("$arg") ;;
    *) echo "fuzz.sh: unknown argument '$arg' (use SECONDS, --tests, gltf, scene_file, environment, method_file, camera_path)" >&2; exit 2 ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(gltf scene_file environment method_file camera_path)

# -O1 with line tables: what AddressSanitizer's documentation suggests, stack traces keep file and line, and the build
# (part of CI's budget) is ~20 % faster than -O2 -g.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DGLIMMER_FUZZ=ON >/dev/null
cmake --build build-fuzz -j "$(nproc)"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp
ctest --test-dir build-fuzz --output-on-failure --no-tests=error -j "$(nproc)"
[ "$tests_only" = 1 ] && exit 0

mkdir -p build-fuzz/artifacts
pids=()
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t
  seeds=fuzz/corpus/${t%_file}
  mkdir -p "$corpus"
  build-fuzz/fuzz/fuzz_"$t" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2560 -max_len=32768 \
    -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/"$t"- "$corpus" "$seeds" \
    >build-fuzz/fuzz-"$t".log 2>&1 &
  pids+=($!)
done
status=0
for i in "${!targets[@]}"; do
  t=${targets[$i]}
  if wait "${pids[$i]}"; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' build-fuzz/fuzz-"$t".log | grep -o '[0-9]*$' || echo "?")
    echo "fuzz $t: clean, $runs inputs in ${seconds} s"
  else
    status=1
    echo "fuzz $t: FAILED (log: build-fuzz/fuzz-$t.log)" >&2
    grep -E 'ERROR|SUMMARY|Test unit written' build-fuzz/fuzz-"$t".log | head -5 >&2 || true
  fi
done
exit $status
