#!/usr/bin/env bash
# The CTest entry gltf.validate: independent validation of scene exports.
#
#   run_gltf_checks.sh WRITER OUT_DIR
#
# 1. installs the pinned checkers (setup.sh) and checks that check_gltf.mjs rejects bad files (self_test.mjs);
# 2. runs WRITER (write_sample_export) into OUT_DIR and checks every sample it lists with
#    check_gltf.mjs --expect-instances N --expect-types K (and, for the samples with materials,
#    --expect-images I --expect-textured-materials M);
# 3. checks extra files given as UG_GLTF_EXTRA="file1.glb:count1 file2.gltf:count2" (paths without spaces;
#    count = every mesh copy the file draws, as check_gltf.mjs counts "instances").
# Fails (never skips) when node is missing. Exit 0 only when every check passed.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [ $# -ne 2 ]; then
  echo "usage: run_gltf_checks.sh WRITER OUT_DIR" >&2
  exit 2
fi
writer="$1"
out="$2"

if ! command -v node >/dev/null 2>&1; then
  echo "gltf checks FAILED: 'node' is not installed, so the exports cannot be validated." >&2
  echo "Install Node.js and npm (Debian 12: apt-get install nodejs npm; scripts/install-deps.sh does it)." >&2
  exit 1
fi
bash "$here/setup.sh" || { echo "gltf checks FAILED: could not install the Node packages" >&2; exit 1; }

failures=0
fail() {
  echo "gltf checks: FAILED: $*" >&2
  failures=$((failures + 1))
}

node "$here/self_test.mjs" || fail "check_gltf.mjs self test"

rm -rf "$out"
mkdir -p "$out"
if listing="$("$writer" "$out")"; then
  while read -r file count types images textured; do
    [ -n "$file" ] || continue
    extra=()
    [ -n "$images" ] && extra+=(--expect-images "$images")
    [ -n "$textured" ] && extra+=(--expect-textured-materials "$textured")
    node "$here/check_gltf.mjs" "$out/$file" --expect-instances "$count" --expect-types "$types" "${extra[@]}" ||
      fail "$file"
  done <<<"$listing"
  [ -n "$listing" ] || fail "the writer listed no samples"
else
  fail "the sample writer $writer"
fi

for entry in ${UG_GLTF_EXTRA:-}; do
  file="${entry%:*}"
  count="${entry##*:}"
  if [[ "$entry" != *:* || ! "$count" =~ ^[0-9]+$ ]]; then
    fail "UG_GLTF_EXTRA entry '$entry' is not FILE:COUNT"
    continue
  fi
  node "$here/check_gltf.mjs" "$file" --expect-instances "$count" || fail "$file"
done

if [ "$failures" -ne 0 ]; then
  echo "gltf checks: $failures failure(s)" >&2
  exit 1
fi
echo "gltf checks: all passed"
