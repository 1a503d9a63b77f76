#!/usr/bin/env bash
# The editor's viewport fixes of issue 10 under Xvfb: a scripted run (camera kept above the ground, File >
# Open frames the new scene, the Statistics panel and the title after Save As) and a session driven by
# real X input (driven_viewport.sh: the brush ring under the cursor, the title's unsaved mark, zoom toward
# the cursor, the keyboard given back after typing in a field). UG_BIN is the binary; UG_GUI_KEEP=DIR
# keeps the outputs. Fails, never skips, when xvfb-run or xdotool is missing.
set -u
bin="${UG_BIN:?UG_BIN must name the undergrowth binary}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
tmp="$(mktemp -d)"
trap 'if [ -n "${UG_GUI_KEEP:-}" ]; then mkdir -p "$UG_GUI_KEEP" && cp -r "$tmp"/. "$UG_GUI_KEEP"/; fi; rm -rf "$tmp"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   - $1"; }
bad() { failed=$((failed + 1)); echo "FAIL - $1"; }
for tool in xvfb-run xdotool; do
  command -v "$tool" >/dev/null 2>&1 || { echo "FAIL - $tool is not installed (scripts/install-deps.sh)"; exit 1; }
done
cache="$tmp/cache"
meadow="$root/assets/scenes/meadow.json"
default_scene="$root/assets/scenes/default.json"

# ---- scripted: a view 30 degrees below the horizon, a view far off in the meadow's corner, File > Open of
# the default scene, Save As ----
mkdir -p "$tmp/saved"
cat >"$tmp/fixes.json" <<EOF2
[{"frame": 1, "action": "view", "target": [0, 0, 0], "distance": 10, "yaw_deg": -90, "pitch_deg": -30},
 {"action": "view", "target": [15, 15, 0], "distance": 5, "pitch_deg": 20},
 {"action": "open", "path": "$default_scene"},
 {"action": "save_as", "path": "$tmp/saved/fixes.json"},
 {"action": "wait_idle"}]
EOF2
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$meadow" --frames 2 --size 640x360 --cache "$cache" \
     --config "$tmp/config" --replay "$tmp/fixes.json" --stats "$tmp/fixes.stats.json" >"$tmp/fixes.log" 2>&1 &&
   out="$(python3 "$root/tests/gui/check_viewport.py" replay "$tmp/fixes.stats.json" "$default_scene" 2>&1)"; then
  ok "edit: camera above the ground, open frames the new scene, Save As shown ($out)"
else
  bad "edit: scripted viewport fixes: ${out:-$(tail -5 "$tmp/fixes.log")}"
fi

# ---- driven by X input, on a copy of the assets (it saves the project) ----
dwork="$tmp/driven"
mkdir -p "$dwork"
cp -r "$root/assets" "$dwork/assets"
# In a 960x540 window: the Tools panel's "radius (m)" slider (the panel at (10, 420)) and the Outliner's
# "paint" button of the rock type.
export RADIUS_X=120 RADIUS_Y=507 ROCK_PAINT_X=693 ROCK_PAINT_Y=380
if out="$(xvfb-run -a -s "-screen 0 1280x720x24" bash "$root/tests/gui/driven_viewport.sh" "$bin" \
            "$dwork/assets/scenes/meadow.json" "$dwork" 2>&1)" &&
   out="$(python3 "$root/tests/gui/check_viewport.py" driven "$dwork" 2>&1)"; then
  ok "edit meadow: viewport driven by X input ($out)"
else
  bad "edit meadow: viewport driven by X input: $out $(tail -3 "$dwork/session.log" 2>/dev/null)"
fi

echo "editor fixes: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
