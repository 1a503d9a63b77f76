#!/usr/bin/env bash
# The CTest entry gltf.measurements: the rest and tiling figures that `undergrowth instantiate --stats`
# reports (engine/analysis) must agree with an independent measurement of the export (measure_rest.mjs,
# JavaScript over glTF-Transform, written from the definitions, not from our code).
#
#   run_measure_checks.sh UNDERGROWTH OUT_DIR
#
# Scenes without a terrain only (the JavaScript side measures against the ground plane). Agreement: the
# counts may differ by at most 0.2 % of the instances (float32 in the file against float in the engine
# can move an instance across the 2 cm threshold or a millimetre bin).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
bin="$1"
out="$2"
command -v node >/dev/null 2>&1 || { echo "measure checks FAILED: 'node' is not installed" >&2; exit 1; }
bash "$here/setup.sh" || { echo "measure checks FAILED: could not install the Node packages" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
failures=0
for scene in rock_pile stone_hut; do
  if ! "$bin" instantiate "$root/assets/scenes/$scene.json" -o "$out/$scene.glb" --stats "$out/$scene.json" --measure \
       --cache "$out/cache" >/dev/null 2>"$out/$scene.log"; then
    echo "measure checks: FAILED: instantiate $scene" >&2; cat "$out/$scene.log" >&2
    failures=$((failures + 1)); continue
  fi
  if ! node "$here/measure_rest.mjs" "$out/$scene.glb" >"$out/$scene.js.json"; then
    echo "measure checks: FAILED: measure_rest.mjs on $scene" >&2
    failures=$((failures + 1)); continue
  fi
  python3 - "$out/$scene.json" "$out/$scene.js.json" "$scene" <<'PY' || failures=$((failures + 1))
import json, sys
ours = json.load(open(sys.argv[1]))["measurements"]
theirs = json.load(open(sys.argv[2]))
scene = sys.argv[3]
n = ours["rest"]["instances"]
ok = theirs["instances"] == n and n > 0
checks = [("hovering", ours["rest"]["hovering_fraction"] * n, theirs["hovering"]),
          ("sunk", ours["rest"]["sunk_fraction"] * n, theirs["sunk"]),
          ("twins", ours["tiling"]["twin_fraction"] * n, theirs["twins"])]
for name, a, b in checks:
    if abs(a - b) > max(1.0, 0.002 * n):
        ok = False
    print(f"{scene}: {name}: engine {a:.0f}, export {b} of {n}")
# Issue 9: nothing more than 2 cm below the ground it is exported with (the floor y = 0 here).
if theirs["sunk"] != 0:
    ok = False
    print(f"{scene}: {theirs['sunk']} instances reach more than 2 cm into the floor")
if theirs["instances"] != n:
    print(f"{scene}: instances: engine {n}, export {theirs['instances']}")
sys.exit(0 if ok else 1)
PY
done
[ "$failures" -eq 0 ] || { echo "measure checks: $failures failure(s)" >&2; exit 1; }
echo "measure checks: passed"
