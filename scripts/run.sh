#!/usr/bin/env bash
# README command 1: install what is missing, build Release, run the main job on the bundled default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DUG_BUILD_TESTS=OFF >/dev/null
cmake --build build -j"$(nproc)"
exec build/undergrowth run assets/scenes/default.json --out out "$@"
