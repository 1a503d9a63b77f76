#!/usr/bin/env bash
# Installs the glTF checks' pinned Node packages (package-lock.json) into tests/gltf/node_modules with
# `npm ci`. Idempotent and quiet: does nothing when node_modules was installed after the last change to
# the lock file (npm writes node_modules/.package-lock.json on every install).
set -euo pipefail
cd "$(dirname "$0")"
if ! command -v npm >/dev/null 2>&1; then
  echo "tests/gltf/setup.sh: npm is missing; install Node.js and npm (Debian: apt-get install nodejs npm," \
       "or scripts/install-deps.sh)" >&2
  exit 1
fi
if [ -f node_modules/.package-lock.json ] && [ node_modules/.package-lock.json -nt package-lock.json ]; then
  exit 0
fi
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
if ! npm ci --no-audit --no-fund --loglevel=error >"$log" 2>&1; then
  echo "tests/gltf/setup.sh: 'npm ci' failed (the npm registry must be reachable the first time):" >&2
  cat "$log" >&2
  exit 1
fi
