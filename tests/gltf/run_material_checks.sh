#!/usr/bin/env bash
# The CTest entry gltf.materials: a sample scene's materials change how it looks, never what it
# instantiates, and its export passes the independent checks.
#
#   run_material_checks.sh UNDERGROWTH OUT_DIR [SCENE.json]     (default: assets/scenes/default.json)
#
# 1. instantiates the scene, and a copy of it with every "material" removed (model paths made absolute),
#    and compares the two exports' instance hashes (instance_hash.mjs: every instance transform);
# 2. runs check_gltf.mjs on the scene's export (Khronos validator, glTF-Transform, the material checks
#    of check_materials.mjs on whatever textures the export holds).
# Fails (never skips) when node is missing.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: run_material_checks.sh UNDERGROWTH OUT_DIR [SCENE.json]" >&2
  exit 2
fi
bin="$1"
out="$2"
scene="${3:-$here/../../assets/scenes/default.json}"
if ! command -v node >/dev/null 2>&1; then
  echo "material checks FAILED: 'node' is not installed (apt-get install nodejs npm)" >&2
  exit 1
fi
bash "$here/setup.sh" || { echo "material checks FAILED: could not install the Node packages" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"

# The copy without materials; mesh paths resolved against the scene's folder so it can live elsewhere.
node -e '
  const fs = require("fs"), path = require("path");
  const [scene, copy] = process.argv.slice(1);
  const p = JSON.parse(fs.readFileSync(scene, "utf8"));
  let removed = 0;
  if (p.terrain && p.terrain.material) { delete p.terrain.material; ++removed; }
  for (const t of p.detail_types) {
    if (t.material) { delete t.material; ++removed; }
    t.model.mesh = path.resolve(path.dirname(scene), t.model.mesh);
  }
  if (!removed) { console.error(scene + ": has no material to remove"); process.exit(1); }
  fs.writeFileSync(copy, JSON.stringify(p, null, 1));
' "$scene" "$out/without_materials.json" || { echo "material checks FAILED: could not strip the materials" >&2; exit 1; }

failures=0
"$bin" instantiate "$scene" -o "$out/with.glb" --cache "$out/cache" >/dev/null || failures=$((failures + 1))
"$bin" instantiate "$out/without_materials.json" -o "$out/without.glb" --cache "$out/cache" >/dev/null ||
  failures=$((failures + 1))
if [ "$failures" -ne 0 ]; then
  echo "material checks FAILED: undergrowth instantiate failed" >&2
  exit 1
fi
with="$(node "$here/instance_hash.mjs" "$out/with.glb")" || exit 1
without="$(node "$here/instance_hash.mjs" "$out/without.glb")" || exit 1
echo "instances and hash: with materials $with, without $without"
if [ "$with" != "$without" ] || [ "${with%% *}" = "0" ]; then
  echo "material checks FAILED: the materials changed what is instantiated (or nothing was)" >&2
  exit 1
fi
node "$here/check_gltf.mjs" "$out/with.glb" || { echo "material checks FAILED: check_gltf" >&2; exit 1; }
echo "material checks: all passed"
