#!/usr/bin/env bash
# Command 1 (`undergrowth run`, what scripts/run.sh runs) with and without a display, and `undergrowth
# render` against the editor: under Xvfb `run` opens the editor on the scene (a scripted run here:
# --frames/--screenshot) after saying what to do next, and writes none of the headless job's outputs;
# with --headless, without DISPLAY, or with a DISPLAY no server answers, it runs the headless job. The
# offscreen render of a scene is the editor's viewport at the same size, pixel for pixel (within one level).
# Fails, never skips, when xvfb-run is missing. UG_BIN is the binary.
source "$(dirname "$0")/../lib/harness.sh"

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "FAIL - xvfb-run is not installed: the GUI tests need it (apt-get install xvfb xauth; scripts/install-deps.sh)"
  exit 1
fi
# The editor keeps recent files and recovery under the config folder: keep them in the test's.
export XDG_CONFIG_HOME="$tmp/config"
pile="$root/assets/scenes/rock_pile.json"
xvfb() { xvfb-run -a -s "-screen 0 1280x720x24" "$@"; }
headless_outputs() { [ -f "$1/rock_pile.glb" ] && [ -f "$1/rock_pile.stats.json" ] && [ -f "$1/rock_pile.tile-stats.json" ]; }

# 1. With a display: the editor, its "what to do next", its screenshot; no headless outputs.
if xvfb "$bin" run "$pile" --out "$tmp/gui" --frames 3 --screenshot "$tmp/gui.png" >"$tmp/gui.out" 2>"$tmp/gui.err"; then
  ok "run under Xvfb: exit 0"
else
  bad "run under Xvfb: $(tail -5 "$tmp/gui.err")"
fi
if grep -q "Opening the editor on $pile" "$tmp/gui.out" && grep -q "paint  *B, then left drag" "$tmp/gui.out" &&
   grep -q "sculpt  *S" "$tmp/gui.out" && grep -q "run --headless" "$tmp/gui.out"; then
  ok "run under Xvfb: says what to do next on stdout"
else
  bad "run under Xvfb: stdout: $(cat "$tmp/gui.out")"
fi
if out="$(python3 "$root/tests/gui/check_screenshot.py" "$tmp/gui.png" 1280 720 pile 2>&1)"; then
  ok "run under Xvfb: the editor's screenshot ($out)"
else
  bad "run under Xvfb: screenshot: $out"
fi
if ! headless_outputs "$tmp/gui" && ! grep -q "headless" "$tmp/gui.err"; then ok "run under Xvfb: the headless job did not run"
else bad "run under Xvfb: the headless job ran too: $(cat "$tmp/gui.err")"; fi

# 2. --headless under Xvfb, no DISPLAY at all, and a DISPLAY with no server behind it: the headless job.
xvfb "$bin" run "$pile" --out "$tmp/flag" --headless >"$tmp/flag.out" 2>&1
rc=$?
if [ "$rc" -eq 0 ] && headless_outputs "$tmp/flag" && ! grep -q "Opening the editor" "$tmp/flag.out"; then
  ok "run --headless under Xvfb: the headless job"
else
  bad "run --headless under Xvfb (exit $rc): $(tail -5 "$tmp/flag.out")"
fi
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" run "$pile" --out "$tmp/none" --frames 3 --screenshot "$tmp/none.png" \
  >"$tmp/none.out" 2>&1
rc=$?
if [ "$rc" -eq 0 ] && headless_outputs "$tmp/none" && [ ! -e "$tmp/none.png" ] && ! grep -q "Opening the editor" "$tmp/none.out"; then
  ok "run without a display: the headless job"
else
  bad "run without a display (exit $rc): $(tail -5 "$tmp/none.out")"
fi
env -u WAYLAND_DISPLAY DISPLAY=:31999 "$bin" run "$pile" --out "$tmp/dead" >"$tmp/dead.out" 2>&1
rc=$?
if [ "$rc" -eq 0 ] && headless_outputs "$tmp/dead" && grep -q "note: the editor did not open" "$tmp/dead.out"; then
  ok "run with a DISPLAY no server answers: a note, then the headless job"
else
  bad "run with a dead DISPLAY (exit $rc): $(tail -5 "$tmp/dead.out")"
fi

# 3. The offscreen render is the editor's viewport: the same scene, view and size, pixel for pixel.
cache="$tmp/cache"
if xvfb "$bin" edit "$pile" --frames 3 --size 640x360 --cache "$cache" --config "$tmp/config" \
     --screenshot "$tmp/edit.png" >"$tmp/edit.log" 2>&1 &&
   env -u DISPLAY -u WAYLAND_DISPLAY "$bin" render "$pile" -o "$tmp/render.png" --size 640x360 --cache "$cache" \
     >"$tmp/render.log" 2>&1; then
  if out="$(python3 - "$tmp/edit.png" "$tmp/render.png" <<PY
import sys
sys.path.insert(0, "$root/tests/gui")
from check_screenshot import decode_png
(w, h, a), (w2, h2, b) = decode_png(sys.argv[1]), decode_png(sys.argv[2])
assert (w, h) == (w2, h2) == (640, 360), (w, h, w2, h2)
d = [max(abs(p - q) for p, q in zip(a[y][x], b[y][x])) for y in range(h) for x in range(w)]
far = sum(1 for v in d if v > 8) / len(d)
assert far < 0.002, "%.2f %% of the pixels differ by more than 8 levels" % (100 * far)
print("mean difference %.3f levels, %.3f %% of the pixels over 8" % (sum(d) / len(d), 100 * far))
PY
)"; then ok "render = the editor's viewport ($out)"; else bad "render vs editor: $out"; fi
else
  bad "render vs editor: $(tail -3 "$tmp/edit.log") $(tail -3 "$tmp/render.log")"
fi

echo "command 1 tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
