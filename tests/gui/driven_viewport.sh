#!/usr/bin/env bash
# A second interactive session driven through real X input (xdotool), for the viewport fixes of issue 10:
# the brush ring under the cursor (also over a pile), the window title's unsaved mark, zoom toward the
# cursor and the keyboard given back to the viewport after typing into a panel's field. Runs inside an X
# server (run_editor_fixes.sh starts it with xvfb-run). After each step F12 rewrites the statistics
# (--stats), copied to WORKDIR/NAME.json; the window title goes to WORKDIR/NAME.title. The checks are
# check_viewport.py's; this script exits non-zero only when a step cannot be driven.
# usage: driven_viewport.sh UNDERGROWTH_BIN PROJECT.json WORKDIR
set -u
bin="$1" project="$2" work="$3"
cd "$work" || exit 1
# A sculpted rock pile, then a view of it from 35 degrees: the cursor at the window's centre is on its flank.
cat >start.json <<'JSON'
[{"frame": 1, "action": "sculpt_stroke", "type": "rock", "points": [[-6, -10]], "radius": 0.6, "steps": 40},
 {"action": "view", "target": [-6, -10, 0.4], "distance": 6, "yaw_deg": -90, "pitch_deg": 35}]
JSON
"$bin" edit "$project" --size 960x540 --config "$work/config" --cache "$work/cache" --replay start.json \
  --stats stats.json --autosave-interval 600 >session.log 2>&1 &
editor=$!
for _ in $(seq 1 240); do [ -s stats.json ] && break; sleep 0.25; done
[ -s stats.json ] || { echo "the editor never finished its start script"; kill "$editor"; exit 1; }
mv stats.json start.stats.json
hold=0.3
key() { xdotool keydown "$1"; sleep "$hold"; xdotool keyup "$1"; sleep "$hold"; }
chord() { xdotool keydown "$1"; sleep 0.1; key "$2"; xdotool keyup "$1"; sleep "$hold"; }
click() { xdotool mousemove "$1" "$2"; sleep "$hold"; xdotool mousedown 1; sleep "$hold"; xdotool mouseup 1; sleep "$hold"; }
win="$(xdotool search --sync --limit 1 --name Undergrowth 2>/dev/null | head -1)"
title() { xdotool getwindowname "$win" >"$1.title" 2>/dev/null || echo "?" >"$1.title"; }
# F12: a screenshot and the statistics; waits for the new statistics file.
dump() {
  rm -f stats.json
  key F12
  for _ in $(seq 1 40); do [ -s stats.json ] && break; sleep 0.25; done
  [ -s stats.json ] || { echo "F12 wrote no statistics ($1): the key never reached the shortcuts (a field kept the keyboard?)"; kill "$editor"; exit 1; }
  mv stats.json "$1.json"
  title "$1"
}
title start
# The brush ring: the Outliner's "paint" of the rock type (the Paint tool, on the rock pile's surface), the
# pointer on the pile's flank, then on the bare ground. Panels (docked as in the default layout of a 960x540
# window) are kept clear of: the viewport is x 350-600, and x 610-950 for y 100-255.
click "$ROCK_PAINT_X" "$ROCK_PAINT_Y"
xdotool mousemove 481 301; sleep 0.5
dump ring_pile
xdotool mousemove 780 180; sleep 0.5
dump ring_ground
# Ctrl+S: saved, the title's unsaved mark goes.
chord ctrl s; sleep 0.5
title saved
# Zoom toward the cursor: three wheel steps up with the pointer off the centre.
xdotool mousemove 800 150; sleep 0.5
dump zoom_before
for _ in 1 2 3; do xdotool click 4; sleep 0.3; done
sleep 0.5
dump zoom_after
# Focus: Ctrl+click the Tools panel's radius slider (it becomes a number field) and type "3" and "e" into
# it: while the field has the keyboard, E is text, not the Erase shortcut (F12 is ignored too).
ctrl_click() {
  xdotool mousemove "$1" "$2"; sleep "$hold"
  xdotool keydown ctrl; sleep 0.1; xdotool mousedown 1; sleep "$hold"; xdotool mouseup 1; sleep 0.1; xdotool keyup ctrl
  sleep "$hold"
}
ctrl_click "$RADIUS_X" "$RADIUS_Y"
for _ in 1 2 3 4 5 6; do key BackSpace; done
key 3; key e
# Moving into the viewport gives the keyboard back: E now selects Erase.
xdotool mousemove 560 450; sleep 0.5
key e
dump after_move
# Typed "2", then a click in the viewport (the Erase tool erases there); Q: Select.
ctrl_click "$RADIUS_X" "$RADIUS_Y"
for _ in 1 2 3 4 5 6; do key BackSpace; done
key 2
click 560 450
key q
dump after_click
# Typed "4", ended with Enter with the pointer still on the panel; B: Paint.
ctrl_click "$RADIUS_X" "$RADIUS_Y"
for _ in 1 2 3 4 5 6; do key BackSpace; done
key 4; key Return
key b
dump after_enter
# Quit without saving the stamp (the dialog's "don't save" is not driven: kill; the dumps are in).
kill "$editor" 2>/dev/null
wait "$editor" 2>/dev/null
exit 0
