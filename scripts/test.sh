#!/usr/bin/env bash
# README command 2: install what is missing, build, and run every test:
#   1. the Release build's whole suite (engine unit/property tests and CLI end-to-end tests), via CTest;
#   2. an AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan) of the engine tests, the app and
#      the fuzz harness, running the engine tests, the CLI tests and the fuzz targets: every reader of
#      scene, model, cache and image files fed mutated inputs, a bounded time per target (tests/fuzz);
#   3. a ThreadSanitizer build (build-tsan) running the engine tests that start worker threads.
# Every stage runs even when an earlier one failed, so one CI run reports everything; the script exits
# non-zero when any stage failed. Each stage prints its wall time; the fuzz targets print their counts
# ("fuzz scene: N inputs, C crashes, H hangs, ...").
set -uo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh || exit 1
jobs="$(nproc)"
failed=()

# stage NAME FUNCTION: runs it, times it, remembers a failure.
stage() {
  local start=$SECONDS
  echo "== $1"
  if "$2"; then echo "== $1: passed ($((SECONDS - start)) s)"; else
    echo "== $1: FAILED ($((SECONDS - start)) s)"; failed+=("$1"); fi
}

release() {
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DUG_WERROR=ON >/dev/null &&
    cmake --build build -j"$jobs" &&
    ctest --test-dir build --output-on-failure -j"$jobs"
}

# The fuzz targets append their counts to build-asan/fuzz-summary.txt, printed whether they passed or not
# (CTest shows the output of failed tests only).
asan() {
  local rc
  rm -f build-asan/fuzz-summary.txt
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUG_SANITIZE=ON -DUG_BUILD_APP=ON >/dev/null &&
    cmake --build build-asan -j"$jobs" --target engine_tests undergrowth fuzz_inputs &&
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --test-dir build-asan --output-on-failure -j"$jobs" -L '^(engine|cli|fuzz)$'
  rc=$?
  echo "== fuzz counts (failing inputs: build-asan/fuzz-findings/)"
  sort build-asan/fuzz-summary.txt 2>/dev/null || echo "(no fuzz target ran)"
  return $rc
}

# halt_on_error: the first data race fails its test (TSan's default only sets the exit code at the end).
tsan() {
  cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUG_TSAN=ON -DUG_BUILD_APP=OFF >/dev/null &&
    cmake --build build-tsan -j"$jobs" --target engine_tests editor_tests &&
    TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
      ctest --test-dir build-tsan --output-on-failure -j"$jobs" -L '^tsan$'
}

stage "Release build and test suite" release
stage "AddressSanitizer + UndefinedBehaviorSanitizer: engine, CLI and fuzz tests" asan
stage "ThreadSanitizer: threaded engine tests" tsan

if [ "${#failed[@]}" -ne 0 ]; then
  printf '== FAILED: %s\n' "${failed[@]}"
  exit 1
fi
echo "== all tests passed"
