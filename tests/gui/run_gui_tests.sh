#!/usr/bin/env bash
# End-to-end tests of the editor in a real window under Xvfb (Mesa llvmpipe): `undergrowth edit --frames`
# on the meadow and the rock pile; the screenshots are decoded and checked (check_screenshot.py) and the
# instance counts compared with the headless `instantiate` on the same scene. Fails, never skips, when
# xvfb-run is missing (CI installs xvfb). UG_BIN is the binary; UG_GUI_KEEP=DIR keeps the outputs.
set -u
bin="${UG_BIN:?UG_BIN must name the undergrowth binary}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   - $1"; }
bad() { failed=$((failed + 1)); echo "FAIL - $1"; }

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "FAIL - xvfb-run is not installed: the GUI tests need it (apt-get install xvfb xauth; scripts/install-deps.sh)"
  exit 1
fi
cache="$tmp/cache"

# run_scene NAME SCENE WxH: a scripted editor run, then its screenshot and statistics checks.
run_scene() {
  local name="$1" scene="$2" size="$3" kind="$4"
  local w="${size%x*}" h="${size#*x}"
  if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$scene" --frames 30 --size "$size" --cache "$cache" \
      --screenshot "$tmp/$name.png" --stats "$tmp/$name.stats.json" >"$tmp/$name.log" 2>&1; then
    ok "edit $name: 30 frames in a ${size} window"
  else
    bad "edit $name: $(tail -5 "$tmp/$name.log")"
    return
  fi
  if out="$(python3 "$root/tests/gui/check_screenshot.py" "$tmp/$name.png" "$w" "$h" "$kind" 2>&1)"; then
    ok "edit $name: screenshot ($out)"
  else
    bad "edit $name: screenshot: $out"
  fi
  if "$bin" instantiate "$scene" -o "$tmp/$name.glb" --stats "$tmp/$name.cli.json" --cache "$cache" >/dev/null 2>&1 &&
     out="$(python3 - "$tmp/$name.stats.json" "$tmp/$name.cli.json" <<'PY'
import json, sys
gui, cli = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert gui["instances"] == cli["instances"] > 0, (gui["instances"], cli["instances"])
assert gui["instances_per_type"] == cli["instances_per_type"], (gui["instances_per_type"], cli["instances_per_type"])
assert gui["frames_measured"] == 30 and gui["frame_ms"] > 0, gui
assert gui["triangles"] > 0 and gui["draw_calls"] >= 3, gui
assert gui["gl_version"] and gui["renderer"], gui
assert gui["framebuffer"] == gui["window"], gui
print("%d instances as the CLI; %.1f ms, %d triangles, %d points, %d draws" % (
    gui["instances"], gui["frame_ms"], gui["triangles"], gui["impostor_points"], gui["draw_calls"]))
PY
)"; then
    ok "edit $name: statistics ($out)"
  else
    bad "edit $name: statistics: $out"
  fi
}

run_scene meadow "$root/assets/scenes/meadow.json" 1280x720 meadow
run_scene rock_pile "$root/assets/scenes/rock_pile.json" 640x360 pile

# No display: a clear message and exit 1.
out="$(env -u DISPLAY -u WAYLAND_DISPLAY "$bin" edit "$root/assets/scenes/rock_pile.json" --frames 1 2>&1)"
rc=$?
if [ "$rc" -eq 1 ] && grep -q "cannot open a display" <<<"$out"; then ok "edit: no display gives exit 1 and says so"; else
  bad "edit without a display (exit $rc): $out"; fi
# Bad command lines: exit 2.
out="$("$bin" edit "$root/assets/scenes/rock_pile.json" --size 12 2>&1)"; rc=$?
if [ "$rc" -eq 2 ] && grep -q -- "--size" <<<"$out"; then ok "edit: bad --size is a usage error"; else bad "edit --size 12 (exit $rc): $out"; fi

if [ -n "${UG_GUI_KEEP:-}" ]; then mkdir -p "$UG_GUI_KEEP" && cp "$tmp"/*.png "$tmp"/*.json "$UG_GUI_KEEP"/; fi
echo "gui tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
