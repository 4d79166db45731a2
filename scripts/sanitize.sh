#!/usr/bin/env bash
# The reliability checks of docs/reliability.md: builds stochtex with clang under AddressSanitizer
# and UndefinedBehaviorSanitizer (-fno-sanitize-recover: the first report fails), runs the unit,
# CLI, deterministic fuzz and studio server tests in that build, then runs every libFuzzer target
# (tests/fuzz/libfuzzer) for a bounded time from a copy of its committed seed corpus.
# Usage: bash scripts/sanitize.sh [build-dir] [seconds per libFuzzer target, default 20]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build-sanitize}"
seconds="${2:-20}"
source "$root/scripts/timing.sh"
bash "$root/scripts/install-deps.sh" --sanitize
phase "sanitizer packages"
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# On a machine with AVX-512 that is the one SIMD target compiled: the build's baseline is then
# x86-64-v4, with the AES and PCLMUL that Highway's AVX-512 target also needs, so AVX-512 is
# Highway's static target and the targets below it are not compiled. Elsewhere the build has the
# portable target and AVX-512 (STOCHTEX_SIMD_DISABLED_TARGETS below).
has_avx512_baseline() {
  local cpu_flags feature
  cpu_flags=" $(grep -m1 '^flags' /proc/cpuinfo 2>/dev/null) "
  for feature in avx512f avx512bw avx512cd avx512dq avx512vl avx2 bmi1 bmi2 f16c fma abm movbe \
    aes pclmulqdq; do
    [[ $cpu_flags == *" $feature "* ]] || return 1
  done
}
if has_avx512_baseline; then
  flags="$flags -march=x86-64-v4 -maes -mpclmul"
fi
# Warnings are checked by the gcc build of scripts/test.sh; clang's differ, so no -Werror here.
# Only what this script runs is built (no statistical or GL test programs, benchmarks or Python
# module), with line tables only for debug information: enough for the sanitizers' reports to name
# file and line. Of the SIMD targets, AVX-512 alone where the machine has it (above), else the
# portable one (4 lanes) and AVX-512 (16 lanes): texton's evaluator alone took 7 minutes to compile
# instrumented for all four (CMakeLists.txt), and the release build checks every target's bytes.
# (-O1 was measured twice and not taken: docs/reliability.md.) The front ends (CLI, studio server)
# compile at -O0: a third of the compiler time, at the same speed of the CLI tests (CMakeLists.txt).
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="$flags" \
  -DSTOCHTEX_LIBFUZZER=ON -DSTOCHTEX_BUILD_BENCH=OFF -DSTOCHTEX_BUILD_PYTHON=OFF \
  -DSTOCHTEX_BUILD_SLOW_TESTS=OFF -DSTOCHTEX_TEST_TIMEOUT_SCALE=4 -DSTOCHTEX_UNITY_BUILD=ON \
  -DSTOCHTEX_FRONT_END_OPTIMISATION=-O0 \
  -DSTOCHTEX_SIMD_DISABLED_TARGETS="HWY_SSSE3|HWY_AVX3_DL|HWY_SSE4|HWY_AVX2"
cmake --build "$build" --parallel
phase "sanitizer build"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Mesa's software OpenGL driver (llvmpipe in swrast_dri.so) leaks 128 bytes at every
# eglTerminate and is unloaded by it, so LeakSanitizer sees a leak from an unknown module that no
# suppression can name. Kept loaded, the driver's memory stays reachable from its own globals and
# stochtex's allocations are still checked (docs/reliability.md). The CLI checks put it back for
# stochtex alone (tests/cli/common.sh): their other processes started slowly with it.
mesa_driver=$(find /usr/lib -name swrast_dri.so -print -quit)
# Every CLI check runs here, its GL renders included: keeping one per method
# (STOCHTEX_CLI_GL=one-per-method, tests/cli/common.sh) saved about 4% of the CLI tests' time
# under the sanitizers, where the gabor analyses, not llvmpipe, take it (docs/reliability.md).
LD_PRELOAD=$mesa_driver ctest --test-dir "$build" -L "unit|cli|fuzz|studio" --output-on-failure \
  --parallel 2
phase "sanitizer tests (unit, cli, fuzz, studio)"
# One libFuzzer target for $seconds from a copy of its committed seeds; prints the failing input's
# report and returns non-zero when it finds one.
fuzz_one() {
  local fuzzer=$1 name corpus
  name=$(basename "$fuzzer" _fuzzer)
  corpus=$(mktemp -d)
  cp "$root/tests/fuzz/corpus/$name"/* "$corpus"/
  echo "sanitize.sh: $name for ${seconds} s from $(ls "$corpus" | wc -l) seeds" >&2
  if ! (cd "$corpus" && "$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 "$corpus" 2>"$corpus.log"); then
    tail -n 60 "$corpus.log" >&2
    echo "sanitize.sh: $name found a failing input (above)" >&2
    return 1
  fi
  grep -E "^stat::(number_of_executed_units|new_units_added|peak_rss_mb)" "$corpus.log" | \
    sed "s/^/$name /" >&2 || true
  rm -rf "$corpus" "$corpus.log"
}
# Two targets at a time, one per core: each still has a core for its whole $seconds.
failed=0
running=0
for fuzzer in "$build"/tests/*_fuzzer; do
  fuzz_one "$fuzzer" &
  running=$((running + 1))
  if ((running == 2)); then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while ((running > 0)); do
  wait -n || failed=1
  running=$((running - 1))
done
if ((failed)); then exit 1; fi
phase "libFuzzer runs"
echo "sanitize.sh: sanitizer tests and libFuzzer runs passed"
