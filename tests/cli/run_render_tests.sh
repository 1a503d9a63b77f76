#!/usr/bin/env bash
# `undergrowth render` with no display at all (DISPLAY and WAYLAND_DISPLAY unset: EGL surfaceless or
# pbuffer on Mesa), and command 1 (`undergrowth run`) without a display or with --headless. The PNGs are
# decoded by an independent reader (tests/gui/check_screenshot.py: python3's zlib and the PNG filters,
# no PIL) and their content checked: the requested size, sky at the top (rows not flipped), the scene in
# the centre; a camera looking away shows no scene there. UG_BIN is the binary; UG_RENDER_KEEP=DIR keeps
# the outputs.
set -u
bin="${UG_BIN:?UG_BIN must name the undergrowth binary}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
tmp="$(mktemp -d)"
if [ -n "${UG_RENDER_KEEP:-}" ]; then trap 'mkdir -p "$UG_RENDER_KEEP"; cp -r "$tmp"/. "$UG_RENDER_KEEP"/; rm -rf "$tmp"' EXIT
else trap 'rm -rf "$tmp"' EXIT; fi
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   - $1"; }
bad() { failed=$((failed + 1)); echo "FAIL - $1"; }
nodisplay() { env -u DISPLAY -u WAYLAND_DISPLAY "$@"; }
# In the sanitizer build (scripts/test.sh), LeakSanitizer would report the few hundred bytes Mesa's EGL
# driver leaves allocated at exit, from a module it has unloaded by then: unsymbolizable, so no suppression
# can name them. Address and undefined-behaviour checks stay on; leak checks are the engine and CLI tests'.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
check="$root/tests/gui/check_screenshot.py"
cache="$tmp/cache"

# expect_fail NAME EXIT_CODE PATTERN -- command...: the command must exit EXIT_CODE and print PATTERN.
expect_fail() {
  local name="$1" code="$2" pattern="$3"
  shift 4
  local out rc
  out="$("$@" 2>&1)"
  rc=$?
  if [ "$rc" -eq "$code" ] && grep -qF -- "$pattern" <<<"$out"; then ok "$name"; else
    bad "$name (exit $rc, wanted $code and '$pattern'): $out"; fi
}

# render_ok NAME ARGS...: a render with no display that must succeed.
render_ok() {
  local name="$1"
  shift
  if nodisplay "$bin" render "$@" --cache "$cache" >"$tmp/$name.log" 2>&1; then ok "render $name: exit 0 without a display"
  else bad "render $name: $(tail -5 "$tmp/$name.log")"; return 1; fi
}

# 1. The rock pile from the default view at an odd size (row stride and flip), and from a camera looking
#    away from it (the same ground and sky, no pile).
pile="$root/assets/scenes/rock_pile.json"
if render_ok pile "$pile" -o "$tmp/pile.png" --size 333x197; then
  if out="$(python3 "$check" "$tmp/pile.png" 333 197 pile 2>&1)"; then ok "render pile: 333x197, sky on top, pile in the centre ($out)"
  else bad "render pile: $out"; fi
  grep -q "EGL" "$tmp/pile.log" && ok "render pile: says which EGL path it used" || bad "render pile: no EGL path in: $(cat "$tmp/pile.log")"
fi
# Looking away: the target 4 m on the pile's -Y side, the eye between it and the pile (yaw 90: on the
# target's +Y side), low (15 degrees), so the pile is behind the eye and the view is ground and sky.
if render_ok away "$pile" -o "$tmp/away.png" --size 333x197 --camera 0,-4,0,3,90,15; then
  if out="$(python3 - "$tmp/pile.png" "$tmp/away.png" <<PY
import sys
sys.path.insert(0, "$root/tests/gui")
from check_screenshot import decode_png, lum_std, region_mean
(w, h, pile), (w2, h2, away) = decode_png(sys.argv[1]), decode_png(sys.argv[2])
assert (w, h) == (w2, h2) == (333, 197), (w, h, w2, h2)
box = [(x, y) for y in range(int(h * 0.4), int(h * 0.6)) for x in range(int(w * 0.4), int(w * 0.6))]
s_pile, s_away = lum_std([pile[y][x] for x, y in box]), lum_std([away[y][x] for x, y in box])
# The pile's lit and shadowed rocks against the bare ground grid (whose lines alone give about 10).
assert s_pile > 12 and s_away < s_pile / 1.3, (s_pile, s_away)
diff = sum(max(abs(a - b) for a, b in zip(pile[y][x], away[y][x])) for x, y in box) / len(box)
# (About 20 since far rocks cast the sun's shadow, which brings the shadowed ones nearer the ground's grey.)
assert diff > 15, diff
# Both views have the sky at the top (bright, blue-dominant).
for top in (region_mean(pile, 0, w, 0, h // 20), region_mean(away, 0, w, 0, h // 20)):
    assert sum(top) / 3 > 150 and top[2] > top[0] + 10, top
print("centre std %.1f vs %.1f away, mean centre difference %.1f" % (s_pile, s_away, diff))
PY
)"; then ok "render away: the pile is gone from the centre ($out)"; else bad "render away: $out"; fi
fi

# A particle system's strands drawn into a scene (--particles): the split grass of Fig. 6 at the centre
# of the default scene, against the same view without it: greener there, and its blades' triangles more.
grass="$root/assets/particles/fig6_split_grass.json"
if render_ok plain "$root/assets/scenes/default.json" -o "$tmp/plain.png" --size 320x200 --camera 0,0,0.2,1.4,-60,15 &&
   render_ok strands "$root/assets/scenes/default.json" -o "$tmp/strands.png" --size 320x200 --camera 0,0,0.2,1.4,-60,15 \
     --particles "$grass"; then
  if out="$(python3 - "$tmp/plain.png" "$tmp/strands.png" "$tmp/plain.log" "$tmp/strands.log" <<PY
import re, sys
sys.path.insert(0, "$root/tests/gui")
from check_screenshot import decode_png, region_mean
(w, h, plain), (_, _, strands) = decode_png(sys.argv[1]), decode_png(sys.argv[2])
def green(img):
    r, g, b = region_mean(img, int(w * 0.3), int(w * 0.7), int(h * 0.3), int(h * 0.7))
    return g - (r + b) / 2
tri = [int(re.search(r"([0-9]+) triangles", open(f).read()).group(1)) for f in sys.argv[3:5]]
assert green(strands) > green(plain) + 5, (green(plain), green(strands))
assert tri[1] > tri[0] + 30000, tri
print("centre greenness %.1f -> %.1f, triangles %d -> %d" % (green(plain), green(strands), tri[0], tri[1]))
PY
)"; then ok "render --particles: the strands are drawn ($out)"; else bad "render --particles: $out"; fi
fi
out=$(nodisplay "$bin" render "$root/assets/scenes/default.json" -o "$tmp/np.png" --particles "$tmp/missing.json" 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q "missing.json" <<<"$out" && [ ! -e "$tmp/np.png" ]; then ok "render --particles: a missing file fails, no picture"; else
  bad "render --particles missing (exit $rc): $out"; fi

# 2. The meadow's default view (the README's picture) at 640x360: ground and grass under the sky.
if render_ok meadow "$root/assets/scenes/meadow.json" -o "$tmp/sub/meadow.png" --size 640x360; then
  if out="$(python3 "$check" "$tmp/sub/meadow.png" 640 360 meadow 2>&1)"; then ok "render meadow: $out"
  else bad "render meadow: $out"; fi
fi

# The stone hut from 30 m, where every stone is a far sprite: with shadows on, its far side and the ground
# behind it are darker than with --no-shadows (sprites cast into the sun's map; before they cast nothing,
# and the two pictures were identical around the hut).
hut="$root/assets/scenes/stone_hut.json"
if render_ok hut_lit "$hut" -o "$tmp/hut_lit.png" --size 320x180 --camera 0,0,1,30,120,25 &&
   render_ok hut_flat "$hut" -o "$tmp/hut_flat.png" --size 320x180 --camera 0,0,1,30,120,25 --no-shadows; then
  if out="$(python3 - "$tmp/hut_lit.png" "$tmp/hut_flat.png" 2>&1 <<PY
import sys
sys.path.insert(0, "$root/tests/gui")
from check_screenshot import decode_png
(w, h, lit), (_, _, flat) = decode_png(sys.argv[1]), decode_png(sys.argv[2])
box = [(x, y) for y in range(int(h * 0.3), int(h * 0.7)) for x in range(int(w * 0.35), int(w * 0.65))]
lum = lambda p: sum(p[:3]) / 3
darker = sum(1 for x, y in box if lum(flat[y][x]) - lum(lit[y][x]) > 12) / len(box)
assert darker > 0.05, darker
print("%.1f %% of the pixels around the hut darker by more than 12" % (100 * darker))
PY
)"; then ok "render hut: far sprites cast the sun's shadow ($out)"; else bad "render hut: $out"; fi
fi

# An orbit drag (--orbit): the sun's map drawn for one frame serves the next ones while it covers their view
# (shadow_frame.h), so 4 frames turning 2 degrees each draw it fewer than 4 times, and the last picture,
# shadowed from a held map, shows the shadows of the still view of the same camera (before, every moving
# frame drew the map again).
cam="0.2,-0.1,0.25,1.4"
if render_ok orbit "$pile" -o "$tmp/orbit.png" --size 320x180 --camera "$cam,-76,38" --frames 4 --orbit 2 &&
   render_ok orbit_still "$pile" -o "$tmp/orbit_still.png" --size 320x180 --camera "$cam,-70,38" &&
   render_ok orbit_flat "$pile" -o "$tmp/orbit_flat.png" --size 320x180 --camera "$cam,-70,38" --no-shadows; then
  draws=$(sed -n 's/.*shadow map drawn in \([0-9]*\) of 4 frames.*/\1/p' "$tmp/orbit.log")
  if [ -n "$draws" ] && [ "$draws" -ge 1 ] && [ "$draws" -lt 4 ]; then ok "render --orbit: the sun's map drawn in $draws of 4 frames"
  else bad "render --orbit: the sun's map drawn in '${draws}' of 4 frames: $(cat "$tmp/orbit.log")"; fi
  grep -q "camera 0.200,-0.100,0.250,1.400,-70.00,38.00" "$tmp/orbit.log" && ok "render --orbit: the last frame's camera reported" ||
    bad "render --orbit: camera line: $(grep camera "$tmp/orbit.log")"
  if out="$(python3 - "$tmp/orbit.png" "$tmp/orbit_still.png" "$tmp/orbit_flat.png" 2>&1 <<PY
import sys
sys.path.insert(0, "$root/tests/gui")
from check_screenshot import decode_png
from check_edit import mean_abs_diff
(w, h, orbit), (_, _, still), (_, _, flat) = (decode_png(p) for p in sys.argv[1:4])
held = mean_abs_diff(orbit, still, 0, w, 0, h)
shadows = mean_abs_diff(still, flat, 0, w, 0, h)
assert shadows > 3.0, "the still view's shadows change the picture by only %.2f" % shadows
assert held < 0.1 * shadows, "from the held map: %.3f off the still view (its shadows: %.2f)" % (held, shadows)
print("mean |diff| from the still view %.3f, the shadows themselves %.2f" % (held, shadows))
PY
)"; then ok "render --orbit: $out"; else bad "render --orbit: $out"; fi
fi
# A camera under the ground (looking up at the pile from 0.7 m below its floor) is raised above it, as the
# editor keeps its eye: the pitch goes up until the eye is 5 cm over the floor (asin(-0.25 / 2) = -7.18°),
# and the run says so; a camera above the ground is left as given.
if render_ok under "$pile" -o "$tmp/under.png" --size 160x90 --camera 0,0,0.3,2,-90,-30; then
  pitch=$(sed -n 's/^render: camera [^,]*,[^,]*,[^,]*,[^,]*,[^,]*,\([-0-9.]*\)$/\1/p' "$tmp/under.log")
  if grep -q "the eye was under the ground in 1 of 1 frames" "$tmp/under.log" &&
     awk -v p="$pitch" 'BEGIN { exit !(p > -7.3 && p < -7.0) }'; then
    ok "render: an eye under the ground is raised above it (pitch -30 -> $pitch)"
  else bad "render: eye under the ground: pitch '$pitch': $(cat "$tmp/under.log")"; fi
fi
if grep -q "under the ground" "$tmp/orbit.log" "$tmp/pile.log" 2>/dev/null; then
  bad "render: a camera above the ground was reported as raised: $(grep -h "under the ground" "$tmp/orbit.log" "$tmp/pile.log")"
else ok "render: cameras above the ground are left as given"; fi
expect_fail "orbit: out of range" 2 "--orbit: expected one number of degrees in [-45, 45]" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --orbit 90 --frames 4
expect_fail "orbit: without frames" 2 "--orbit: turns the camera between frames: give --frames 2 or more" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --orbit 2

# The fallback: the default display with a pbuffer (UG_EGL=pbuffer skips the surfaceless platform; Mesa's
# default display is made surfaceless by EGL_PLATFORM, having no X server to reach), the same picture. With
# no platform that works (the default display is X11 and there is no DISPLAY): one message, exit 1.
if UG_EGL=pbuffer EGL_PLATFORM=surfaceless nodisplay "$bin" render "$pile" -o "$tmp/pbuffer.png" --size 333x197 \
     --cache "$cache" >"$tmp/pbuffer.log" 2>&1 && grep -q "EGL pbuffer" "$tmp/pbuffer.log"; then
  cmp -s "$tmp/pile.png" "$tmp/pbuffer.png" && ok "render pbuffer: the same picture as surfaceless" ||
    bad "render pbuffer: the picture differs from the surfaceless one"
else
  bad "render pbuffer: not the pbuffer path: $(cat "$tmp/pbuffer.log")"
fi
expect_fail "no EGL context" 1 "cannot render without a display: no OpenGL 4.3 core context" -- \
  env -u DISPLAY -u WAYLAND_DISPLAY -u EGL_PLATFORM UG_EGL=pbuffer "$bin" render "$pile" -o "$tmp/none.png" --cache "$cache"
[ ! -e "$tmp/none.png" ] && ok "no EGL context: no picture" || bad "no EGL context: a picture was written"

# 3. Bad command lines exit 2 with the usage; a missing or malformed scene exits 1 naming the file.
expect_fail "no -o" 2 "missing -o PICTURE.png" -- nodisplay "$bin" render "$pile"
expect_fail "no scene" 2 "usage: undergrowth render" -- nodisplay "$bin" render -o "$tmp/x.png"
expect_fail "not a png" 2 "must end in .png" -- nodisplay "$bin" render "$pile" -o "$tmp/x.jpg"
expect_fail "camera: 3 numbers" 2 "--camera: expected tx,ty,tz,distance,yaw_deg,pitch_deg" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --camera 1,2,3
expect_fail "camera: not a number" 2 "--camera: 'nan' is not a finite number" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --camera 0,0,0,5,nan,30
expect_fail "camera: zero distance" 2 "the distance must be in (0, 100000]" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --camera 0,0,0,0,0,30
expect_fail "camera: pitch over 89" 2 "the pitch must be in [-89, 89]" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --camera 0,0,0,5,0,90
expect_fail "size: not WxH" 2 "--size: expected WIDTHxHEIGHT" -- nodisplay "$bin" render "$pile" -o "$tmp/x.png" --size 640
expect_fail "size: a side over 16384" 2 "each in [16, 16384]" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --size 20000x100
expect_fail "size: too many pixels" 2 "more than 67,108,864 pixels" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/x.png" --size 16384x16384
expect_fail "unknown option" 2 "unknown option --fov" -- nodisplay "$bin" render "$pile" -o "$tmp/x.png" --fov 60
expect_fail "missing scene" 1 "$tmp/nope.json: cannot open" -- nodisplay "$bin" render "$tmp/nope.json" -o "$tmp/x.png"
printf '{"format": "undergrowth-project", "format_version": 1, "detail_types": [' >"$tmp/trunc.json"
expect_fail "truncated scene" 1 "trunc.json: invalid JSON" -- nodisplay "$bin" render "$tmp/trunc.json" -o "$tmp/x.png"
[ ! -e "$tmp/x.png" ] && ok "no picture is written by a failed render" || bad "a failed render left $tmp/x.png"
# A picture that cannot be written (its folder is a file): exit 1 naming the path.
expect_fail "unwritable picture" 1 "$tmp/trunc.json/x.png" -- \
  nodisplay "$bin" render "$pile" -o "$tmp/trunc.json/x.png" --size 64x64 --cache "$cache"

# 4. Command 1 without a display runs the headless job; with --headless too, whatever the environment.
for mode in nodisplay headless; do
  out_dir="$tmp/run-$mode"
  if [ "$mode" = nodisplay ]; then cmd=(nodisplay "$bin" run "$pile" --out "$out_dir")
  else cmd=("$bin" run "$pile" --out "$out_dir" --headless); fi
  if "${cmd[@]}" >"$tmp/run-$mode.log" 2>&1 && grep -q "headless" "$tmp/run-$mode.log" &&
     ! grep -q "Opening the editor" "$tmp/run-$mode.log" &&
     python3 - "$out_dir" <<'PY'
import json, os, sys
d = sys.argv[1]
stats = json.load(open(os.path.join(d, "rock_pile.stats.json")))
assert stats["instances"] > 0, stats["instances"]
glb = open(os.path.join(d, "rock_pile.glb"), "rb").read(12)
assert glb[:4] == b"glTF", glb
assert json.load(open(os.path.join(d, "rock_pile.tile-stats.json")))["ghost_tile"]["candidates"] > 0
PY
  then ok "run ($mode): the headless job wrote the scene and its statistics"
  else bad "run ($mode): $(tail -5 "$tmp/run-$mode.log")"; fi
done
expect_fail "run: bad --frames" 2 "--frames: expected an integer" -- nodisplay "$bin" run "$pile" --out "$tmp/r" --frames zero

echo "render tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
