#!/usr/bin/env bash
# README command 1: install what is missing, build Release, then open the editor on the bundled default
# scene when a display is there (DISPLAY or WAYLAND_DISPLAY), else run the headless main job on it.
# Arguments pass through: scripts/run.sh --headless runs the job even with a display.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DUG_BUILD_TESTS=OFF >/dev/null
cmake --build build -j"$(nproc)"
exec build/undergrowth run assets/scenes/default.json --out out "$@"
