#!/usr/bin/env bash
# Particle sculpting from the command line (docs/particles.md): every bundled particle system grows and
# exports; the file is the same bytes with 1 and 2 threads (the strands are a pure function of the file);
# the Khronos validator finds no error and glTF-Transform reads the strand mesh back (check_gltf.mjs); the
# polylines in its extras are the ones the statistics count; bad files fail with the file, the JSON
# Pointer and the reason, and write nothing. UG_BIN is the binary.
source "$(dirname "$0")/../lib/harness.sh"
check="$root/tests/gltf/check_gltf.mjs"
if ! bash "$root/tests/gltf/setup.sh" >"$tmp/npm.txt" 2>&1; then
  bad "the glTF checks (tests/gltf/setup.sh): $(cat "$tmp/npm.txt")"; echo "$passed passed, $failed failed"; exit 1; fi

for f in "$root"/assets/particles/*.json; do
  name="$(basename "$f" .json)"
  if grep -q '"on_terrain": true' "$f"; then
    # Seeds on a project's terrain: grown from a scene (below), refused alone.
    out=$("$bin" grow "$f" -o "$tmp/$name.glb" 2>&1); rc=$?
    if [ $rc -eq 1 ] && grep -qF "on_terrain: needs a terrain" <<<"$out" && [ ! -e "$tmp/$name.glb" ]; then
      ok "grow $name alone: refused, it needs a project's terrain"; else bad "grow $name alone (exit $rc): $out"; fi
    continue
  fi
  if grep -q '"kind": "details", "detail_type"' "$f"; then
    # Seeds on a project's detail instances: grown from its scene (below), refused alone.
    out=$("$bin" grow "$f" -o "$tmp/$name.glb" 2>&1); rc=$?
    if [ $rc -eq 1 ] && grep -qF "instance to seed on in its box" <<<"$out" && [ ! -e "$tmp/$name.glb" ]; then
      ok "grow $name alone: refused, it needs a project's instances"; else bad "grow $name alone (exit $rc): $out"; fi
    continue
  fi
  if grep -q '"kind": "objects", "object_type"' "$f"; then
    # Seeds on a project's environmental objects: grown from its scene (the GUI and engine tests), refused alone.
    out=$("$bin" grow "$f" -o "$tmp/$name.glb" 2>&1); rc=$?
    if [ $rc -eq 1 ] && grep -qF "object to seed on" <<<"$out" && [ ! -e "$tmp/$name.glb" ]; then
      ok "grow $name alone: refused, it needs a project's objects"; else bad "grow $name alone (exit $rc): $out"; fi
    continue
  fi
  if ! "$bin" grow "$f" -o "$tmp/$name.1.glb" --threads 1 --stats "$tmp/$name.json" >"$tmp/$name.out" 2>&1 ||
     ! "$bin" grow "$f" -o "$tmp/$name.2.glb" --threads 2 >>"$tmp/$name.out" 2>&1; then
    bad "grow $name: $(tail -3 "$tmp/$name.out")"; continue; fi
  if cmp -s "$tmp/$name.1.glb" "$tmp/$name.2.glb"; then ok "grow $name: the same file with 1 and 2 threads"; else
    bad "grow $name: 1 and 2 threads differ"; fi
  if node "$check" "$tmp/$name.1.glb" >"$tmp/$name.check" 2>&1 &&
     python3 - "$tmp/$name.check" "$tmp/$name.json" "$tmp/$name.1.glb" "$f" <<'PY'
import json, struct, sys
report = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
stats = json.load(open(sys.argv[2]))
assert report["errors"] == 0, report
# The strands, then the surface of each mesh generator (what they grow out of) and the model of each mesh
# attractor (what they reach for).
system = json.load(open(sys.argv[4]))
surfaces = ["strands/%s/surface_%d" % (stats["name"], i) for i, g in enumerate(system["generators"]) if g["kind"] == "mesh"]
surfaces += ["strands/%s/attractor_%d" % (stats["name"], i)
             for i, a in enumerate(system.get("attractors", [])) if a["kind"] == "mesh"]
assert list(report["per_mesh"]) == ["strands/" + stats["name"]] + surfaces, report
assert stats["strands"] > 0 and stats["triangles"] > 0, stats
# The extras' polylines (when written) are the strands the statistics count.
b = open(sys.argv[3], "rb").read()
doc = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
extras = doc["meshes"][0].get("extras", {})
if "strands" in extras:
    s = extras["strands"]
    assert len(s["offsets"]) == stats["strands"] + 1 and len(s["points"]) == stats["points"], (len(s["offsets"]), stats)
    assert all(s["offsets"][i] + 2 <= s["offsets"][i + 1] for i in range(stats["strands"]))
else:
    assert "strands_omitted" in extras, extras
PY
  then ok "grow $name: valid (Khronos validator), read back by glTF-Transform, polylines as counted"; else
    bad "grow $name: $(tail -c 800 "$tmp/$name.check")"; fi
done

# Bad files: exit 1, the file and the place named, nothing written.
expect_refused() {  # expect_refused NAME JSON MESSAGE
  printf '%s' "$2" >"$tmp/bad.json"
  out=$("$bin" grow "$tmp/bad.json" -o "$tmp/bad.glb" 2>&1); rc=$?
  if [ $rc -eq 1 ] && grep -qF -- "$3" <<<"$out" && grep -qF "bad.json" <<<"$out" && [ ! -e "$tmp/bad.glb" ]; then
    ok "grow refuses $1: $out"; else bad "grow $1 (exit $rc): $out"; fi
}
head='{"format": "undergrowth-particles", "format_version": 1, "name": "x",'
gen='"generators": [{"kind": "rectangle", "count": 10}]'
expect_refused "zero trials" "$head $gen, \"walk\": {\"trials\": 0}}" "/walk/trials: 0 is out of range"
expect_refused "a billion particles" "$head \"generators\": [{\"kind\": \"sphere\", \"count\": 1000000000}]}" "/generators/0/count"
expect_refused "an out-of-range charge" "$head $gen, \"attractors\": [{\"kind\": \"point\", \"charge\": 1e400}]}" "out of range"
expect_refused "a typo" "$head $gen, \"walk\": {\"step_lenght_m\": 0.1}}" "/walk/step_lenght_m: unknown field"
expect_refused "truncated JSON" "$head $gen" "invalid JSON"
expect_refused "too many triangles" "$head $gen, \"walk\": {\"steps\": 50}, \"mesh\": {\"max_triangles\": 100}}" "mesh.max_triangles"
out=$("$bin" grow "$tmp/missing.json" -o "$tmp/m.glb" 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q "missing.json" <<<"$out"; then ok "grow: a missing file: $out"; else bad "grow missing (exit $rc): $out"; fi
out=$("$bin" grow "$root/assets/particles/fur_ball.json" -o "$tmp/x.obj" 2>&1); rc=$?
if [ $rc -eq 2 ]; then ok "grow: a bad output name is a usage error"; else bad "grow -o x.obj (exit $rc): $out"; fi

# A project's particle systems ("particles", format 4) are grown into its exports: the meadow with two
# patches of grass strands on its terrain, the whole scene and two regions that split the patches.
scene="$root/assets/scenes/meadow_strands.json"
if "$bin" instantiate "$scene" -o "$tmp/ms.glb" --stats "$tmp/ms.json" --cache "$tmp/cache" >"$tmp/ms.out" 2>&1 &&
   "$bin" instantiate "$scene" -o "$tmp/west.glb" --stats "$tmp/west.json" --cache "$tmp/cache" \
     --region=-20,-20,-10,-7.1,20,10 >>"$tmp/ms.out" 2>&1 &&
   "$bin" instantiate "$scene" -o "$tmp/east.glb" --stats "$tmp/east.json" --cache "$tmp/cache" \
     --region=-7.1,-20,-10,20,20,10 >>"$tmp/ms.out" 2>&1 &&
   node "$check" "$tmp/ms.glb" >"$tmp/ms.check" 2>&1 &&
   python3 - "$tmp" <<'PY'
import json, struct, sys
t = sys.argv[1]
def meshes(path):
    b = open(path, "rb").read()
    doc = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
    return {m["name"]: m for m in doc["meshes"]}
report = json.loads(open(t + "/ms.check").read().strip().splitlines()[-1])
assert report["errors"] == 0, report
whole = meshes(t + "/ms.glb")
names = ["strands/meadow_grass_strands", "strands/meadow_grass_strands_2"]
assert all(n in report["per_mesh"] for n in names), report["per_mesh"]
stats = json.load(open(t + "/ms.json"))
assert stats["particles"]["systems"] == 2 and stats["particles"]["strands"] > 5000, stats["particles"]
assert stats["particles"]["strands"] == sum(len(whole[n]["extras"]["strands"]["offsets"]) - 1 for n in names)
assert stats["instances"] > 50000, stats["instances"]
# Each region holds the one system whose strands are centred in it, the same strands as the whole run.
west, east = meshes(t + "/west.glb"), meshes(t + "/east.glb")
assert [n for n in west if n.startswith("strands/")] == names[:1], list(west)
assert [n for n in east if n.startswith("strands/")] == names[1:], list(east)
assert west[names[0]]["extras"] == whole[names[0]]["extras"] and east[names[1]]["extras"] == whole[names[1]]["extras"]
assert json.load(open(t + "/west.json"))["particles"]["systems"] == 1
PY
then ok "instantiate meadow_strands: two strand meshes beside the instances, valid, read back; regions hold one each"
else bad "instantiate meadow_strands: $(tail -5 "$tmp/ms.out") $(tail -c 600 "$tmp/ms.check" 2>/dev/null)"; fi
# Moss on the rock pile's settled rocks (a "details" generator): the whole export is valid and carries the
# moss; a region job grows it from the rocks its own instantiation of the moss's box gives: the same tubes.
moss="$root/assets/scenes/rock_pile_moss.json"
if "$bin" instantiate "$moss" -o "$tmp/moss.glb" --stats "$tmp/moss.json" --cache "$tmp/cache" >"$tmp/moss.out" 2>&1 &&
   "$bin" instantiate "$moss" -o "$tmp/moss_w.glb" --cache "$tmp/cache" --region=-5,-5,-1,0,5,3 >>"$tmp/moss.out" 2>&1 &&
   "$bin" instantiate "$moss" -o "$tmp/moss_e.glb" --cache "$tmp/cache" --region=0,-5,-1,5,5,3 >>"$tmp/moss.out" 2>&1 &&
   node "$check" "$tmp/moss.glb" >"$tmp/moss.check" 2>&1 &&
   python3 - "$tmp" "$root/tests/gltf" <<'PY'
import json, sys
t = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from glb_mesh import mesh_positions as positions
report = json.loads(open(t + "/moss.check").read().strip().splitlines()[-1])
assert report["errors"] == 0, report
assert "strands/moss" in report["per_mesh"], report["per_mesh"]
stats = json.load(open(t + "/moss.json"))
assert stats["particles"]["systems"] == 1 and stats["particles"]["strands"] > 50000, stats["particles"]
whole = positions(t + "/moss.glb", "strands/moss")
assert whole and len(whole) > 1000000, "no moss tubes"
held = [p for p in (positions(t + "/moss_w.glb", "strands/moss"), positions(t + "/moss_e.glb", "strands/moss")) if p]
assert len(held) == 1, "the moss must be in exactly one region"
assert held[0] == whole, "a region grew other moss than the whole scene"
PY
then ok "instantiate rock_pile_moss: moss on the settled rocks, valid, read back; a region grows the same tubes"
else bad "instantiate rock_pile_moss: $(tail -5 "$tmp/moss.out") $(tail -c 600 "$tmp/moss.check" 2>/dev/null)"; fi
# A bad entry names the scene, the entry and the particle file's own place; nothing is written.
sed -e 's|"../particles/meadow_grass_strands.json", "name"|"nowhere.json", "name"|' \
    -e "s|\"\\.\\./|\"$root/assets/|g" "$scene" >"$tmp/bad_strands.json"
out=$("$bin" instantiate "$tmp/bad_strands.json" -o "$tmp/bad.glb" --cache "$tmp/cache" 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -qF "bad_strands.json: /particles/1/file: " <<<"$out" && grep -qF "nowhere.json" <<<"$out" &&
   [ ! -e "$tmp/bad.glb" ]; then
  ok "instantiate: a missing particle file is named with its entry: $out"; else bad "instantiate bad entry (exit $rc): $out"; fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
