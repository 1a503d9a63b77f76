#!/usr/bin/env bash
# End-to-end checks of the environmental objects through the binary (issues 11, 12): `environment --at`
# values against hand-computed ones, the winter street and the three autumn samples exported and checked
# by the Khronos validator and an independent glTF reader (check_gltf.mjs, per mesh for the autumn looks),
# the union of regions equal to the whole, and bad trees refused with the file, the JSON Pointer and the
# reason. UG_BIN is the binary.
source "$(dirname "$0")/../lib/harness.sh"
expect_fail() {
  local name="$1" code="$2" pattern="$3"
  shift 4
  local out rc
  out="$("$@" 2>&1)"
  rc=$?
  if [ "$rc" -eq "$code" ] && grep -qF -- "$pattern" <<<"$out"; then ok "$name"; else
    bad "$name (exit $rc, wanted $code and '$pattern'): $out"; fi
}
street="$root/assets/scenes/street_winter.json"

# 1. The environment at points, by hand: the street's global fields are snow 0.12, icicles 1,
#    temperature -3, humidity 0.2; the warm pipe is a segment y = 7.4, x in [0, 4.6], z = 0, value 15,
#    radius 0.6; the first tyre track a segment y = 0.9, z = 0.08, value 0.9, radius 0.3; the bus shelter's
#    roof (3.2 x 1.6 m, 2.4-2.5 m high) stands at (6.6, 6.7) turned 180 degrees.
if "$bin" environment "$street" --at 2,7.4,0 --at 2,7.7,0 --at 5,0.9,0.08 --at 6.6,6.7,1.0 --at 6.6,6.7,2.6 \
     >"$tmp/env.json" 2>"$tmp/env.err"; then ok "environment: runs"; else bad "environment: $(cat "$tmp/env.err")"; fi
python3 - "$tmp/env.json" <<'PY' && ok "environment: hand-computed channels and shelter" || bad "environment values: $(cat "$tmp/env.json")"
import json, sys
d = json.load(open(sys.argv[1]))
p = d["points"]
K = lambda dd, R: (1 - dd * dd / (R * R)) ** 3 if dd < R else 0.0
close = lambda a, b: abs(a - b) < 1e-4
assert close(p[0]["temperature"], -3 + 15), p[0]              # on the pipe: K = 1
assert close(p[1]["temperature"], -3 + 15 * K(0.3, 0.6)), p[1] # 0.3 m off it
assert close(p[2]["occlusion"], 1 - 0.9), p[2]                 # in the track
assert close(p[0]["snow"], 0.12) and close(p[0]["humidity"], 0.2) and p[0]["icicles"] == 1, p[0]
assert p[3]["shelter"] == 0, p[3]                              # under the roof
assert p[4]["shelter"] == 1, p[4]                              # on top of it
PY

# The ground under a point: the street's terrain is flat at 0; the stone hut has none (null). The park's
# objects stand on its rolling terrain (scripts/make-autumn-scenes.py sets each at the lowest ground under its
# footprint): the fountain's base within 10 cm below the ground at its centre, never above it (at z = 0 it
# stood 20 cm under the lawn, its basin full of grass, and the paths were buried).
park="$root/assets/scenes/park_autumn.json"
fountain_at="$(python3 -c 'import json, sys
t = json.load(open(sys.argv[1]))["environment"]["tree"]
print(",".join("%g" % v for v in next(n["at"] for n in t if n.get("object") == "fountain")))' "$park")"
if "$bin" environment "$street" --at 1,2,0 >"$tmp/g_street.json" 2>&1 &&
   "$bin" environment "$root/assets/scenes/stone_hut.json" --at 1,2,0 >"$tmp/g_hut.json" 2>&1 &&
   "$bin" environment "$park" --at "$fountain_at" >"$tmp/g_park.json" 2>&1 &&
   out="$(python3 - "$tmp/g_street.json" "$tmp/g_hut.json" "$tmp/g_park.json" 2>&1 <<'PY'
import json, sys
street, hut, park = (json.load(open(f))["points"][0] for f in sys.argv[1:])
assert street["ground"] == 0.0, street
assert hut["ground"] is None, hut
base, ground = park["at"][2], park["ground"]
assert ground - 0.1 <= base <= ground and abs(ground) > 0.05, park
print("the fountain's base %.3f m, the ground %.3f m" % (base, ground))
PY
)"; then ok "environment: the ground under a point; the park's fountain on it ($out)"
else bad "environment ground: $out $(cat "$tmp"/g_*.json)"; fi

# 2. The street exported: statistics, the validator, and every mesh copy counted by an independent reader.
if "$bin" instantiate "$street" -o "$tmp/street.glb" --stats "$tmp/street.json" >"$tmp/inst.txt" 2>&1; then
  ok "instantiate: winter street"
else
  bad "instantiate: winter street: $(cat "$tmp/inst.txt")"
fi
copies="$(python3 - "$tmp/street.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
e = s["environment"]
assert e["objects"] == 16 and e["effect_computations"] < e["objects"], e
assert e["snow_triangles"] > e["snow_triangles_computed"] > 100000 and e["icicles"] > 100, e
print(s["instances"] + 1 + e["static_mesh_copies"])  # details, the terrain, the environment
PY
)" && ok "instantiate: environment statistics" || bad "instantiate: environment statistics"
if command -v node >/dev/null 2>&1 && bash "$root/tests/gltf/setup.sh" >/dev/null 2>&1; then
  if node "$root/tests/gltf/check_gltf.mjs" "$tmp/street.glb" --expect-instances "$copies" >"$tmp/check.txt" 2>&1; then
    ok "export: valid glTF, $copies mesh copies"
  else
    bad "export: $(tail -20 "$tmp/check.txt")"
  fi
  "$bin" instantiate "$street" -o "$tmp/plain.gltf" --plain-nodes >/dev/null 2>&1 &&
    node "$root/tests/gltf/check_gltf.mjs" "$tmp/plain.gltf" --expect-instances "$copies" >"$tmp/check2.txt" 2>&1 &&
    ok "export: --plain-nodes realizes the same copies" || bad "export --plain-nodes: $(tail -20 "$tmp/check2.txt")"
else
  bad "export: node and the pinned checkers are needed (scripts/install-deps.sh)"
fi

# 3. Two regions give the whole: every object in one of them, the same snow and icicles.
"$bin" instantiate "$street" -o "$tmp/a.glb" --stats "$tmp/a.json" --region -1,-1,-5,5,11,10 >/dev/null 2>&1
"$bin" instantiate "$street" -o "$tmp/b.glb" --stats "$tmp/b.json" --region 5.0001,-1,-5,11,11,10 >/dev/null 2>&1
python3 - "$tmp/street.json" "$tmp/a.json" "$tmp/b.json" <<'PY' && ok "regions: the union is the whole" || bad "regions"
import json, sys
w, a, b = (json.load(open(f))["environment"] for f in sys.argv[1:])
for k in ("objects", "snow_triangles", "icicles", "terrain_snow_chunks"):
    assert a[k] + b[k] == w[k], (k, a[k], b[k], w[k])
PY

# 4. The autumn samples exported (issue 12): the validator finds no error, and glTF-Transform reads back
#    every look (the scattered types and their variants, each its own instanced mesh) with the count the
#    statistics give it; the looks add up to the instances, and the variants are really used.
for scene in street_autumn park_autumn road_autumn; do
  if ! "$bin" instantiate "$root/assets/scenes/$scene.json" -o "$tmp/$scene.glb" --stats "$tmp/$scene.json" \
       >"$tmp/$scene.txt" 2>&1; then
    bad "instantiate: $scene: $(tail -5 "$tmp/$scene.txt")"
    continue
  fi
  looks="$(python3 - "$tmp/$scene.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
looks = s["instances_per_look"]
assert sum(looks.values()) == s["instances"], (sum(looks.values()), s["instances"])
assert sum(n for k, n in looks.items() if k.endswith(("_wet", "_dry"))) > 0, looks  # puddles, a warm corner
print(json.dumps(looks))
PY
)" || { bad "$scene: looks do not add up: $(cat "$tmp/$scene.json" | head -c 600)"; continue; }
  if command -v node >/dev/null 2>&1 &&
     node "$root/tests/gltf/check_gltf.mjs" "$tmp/$scene.glb" --expect-per-mesh "$looks" >"$tmp/$scene.check" 2>&1; then
    ok "export: $scene valid, every look's copies as counted"
  else
    bad "export: $scene: $(tail -c 1500 "$tmp/$scene.check")"
  fi
  rm -f "$tmp/$scene.glb"
done

# 5. Bad input: each a clear error with the file, the place and the reason; the CLI exits non-zero.
mk() {  # mk NAME ENVIRONMENT_JSON: a project with the given environment
  printf '{"format": "undergrowth-project", "format_version": 3, "name": "%s",
  "detail_types": [{"name": "p", "model": {"mesh": "%s/assets/models/pebble.glb"}, "candidates": {"count": 4},
                    "density": {"point": {"center": [0, 0, 0], "radius": 1}}}],
  "environment": %s}\n' "$1" "$root" "$2" >"$tmp/$1.json"
}
road="{\"name\": \"road\", \"mesh\": \"$root/assets/env_models/road_segment.glb\""
mk cycle "{\"types\": [$road}], \"groups\": {\"a\": {\"group\": {\"children\": [{\"ref\": \"b\"}]}}, \"b\": {\"group\": {\"children\": [{\"ref\": \"a\"}]}}}, \"tree\": [{\"ref\": \"a\"}]}"
expect_fail "bad: reference cycle" 1 "reference cycle" -- "$bin" environment "$tmp/cycle.json" --at 0,0,0
mk unknown "{\"types\": [$road}], \"tree\": [{\"ref\": \"nowhere\"}]}"
expect_fail "bad: unknown group" 1 "/environment/tree/0/ref: no group named \"nowhere\"" -- "$bin" environment "$tmp/unknown.json" --at 0,0,0
mk missing "{\"types\": [{\"name\": \"x\", \"mesh\": \"gone.glb\"}], \"tree\": [{\"object\": \"x\"}]}"
expect_fail "bad: missing base mesh" 1 "/environment/types/0/mesh" -- "$bin" environment "$tmp/missing.json" --at 0,0,0
printf 'glTF garbage' >"$tmp/corrupt.glb"
mk corrupt "{\"types\": [{\"name\": \"x\", \"mesh\": \"corrupt.glb\"}], \"tree\": [{\"object\": \"x\"}]}"
expect_fail "bad: corrupt base mesh" 1 "corrupt.glb" -- "$bin" environment "$tmp/corrupt.json" --at 0,0,0
mk nan "{\"types\": [$road}], \"global_fields\": [{\"channel\": \"snow\", \"value\": 1e999}]}"
expect_fail "bad: a non-finite field value" 1 "/environment/global_fields/0/value" -- "$bin" environment "$tmp/nan.json" --at 0,0,0
python3 - "$tmp/deep.env" <<'PY'
import sys
n = 100000
open(sys.argv[1], "w").write('{"tree": [' + '{"group": {"children": [' * n + '{"object": "road"}' + ']}}' * n + ']}')
PY
mk deep "$(sed "s|{\"tree\"|{\"types\": [$(printf '%s' "$road" | sed 's/[&|]/\\&/g')}], \"tree\"|" "$tmp/deep.env")"
expect_fail "bad: a 100,000-deep tree" 1 "deeper than 64 levels" -- "$bin" environment "$tmp/deep.json" --at 0,0,0
mk fine "{\"types\": [$road, \"snow\": {\"target_edge_m\": 0.000001}}], \"tree\": [{\"object\": \"road\"}], \"global_fields\": [{\"channel\": \"snow\", \"value\": 0.1}]}"
expect_fail "bad: a 1 um snow edge over the road, refused up front" 1 "/environment/tree/0: snow: about" -- \
  "$bin" instantiate "$tmp/fine.json" -o "$tmp/fine.glb"
expect_fail "bad: --at needs three numbers" 2 "three numbers" -- "$bin" environment "$street" --at 1,2
expect_fail "bad: a missing scene" 1 "nope.json" -- "$bin" environment "$tmp/nope.json" --at 0,0,0

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
