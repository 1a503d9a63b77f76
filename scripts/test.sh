#!/usr/bin/env bash
# README command 2: install what is missing, build, and run every test:
#   1. the Release build's whole suite (engine unit/property tests and CLI end-to-end tests), via CTest;
#   2. the engine tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer.
# Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"

echo "== Release build and test suite"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DUG_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

echo "== Engine tests under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUG_SANITIZE=ON -DUG_BUILD_APP=OFF >/dev/null
cmake --build build-asan -j"$jobs" --target engine_tests
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -L engine
echo "== all tests passed"
