#!/usr/bin/env bash
# One interactive editor session driven through real X input (xdotool: mouse and keys go through GLFW and
# Dear ImGui exactly as a user's do), run inside an X server (run_gui_tests.sh starts it with xvfb-run):
#   B, click            paint: one stamp, one user disc
#   S, press and hold   sculpt a pile (many stamps, one stroke)
#   Ctrl+Z              undo the pile
#   B, click elsewhere  a second disc
#   Q, click the first disc's centre, Delete     select by picking, delete
#   S, press, drag, release    a dragged sculpt stroke: a cone every radius / 3 of travel, one stroke
#   Q, click its first cone, Delete                  the whole stroke goes (a stroke is one unit)
#   F12                 screenshot
#   Ctrl+Q, Esc         the unsaved-changes dialog, cancelled: the editor keeps running
#   Ctrl+Q, Enter       the dialog's default: save, then quit
# usage: driven_session.sh UNDERGROWTH_BIN PROJECT.json WORKDIR
# Writes WORKDIR/session.start.json and session.stats.json (the editor's statistics once the scene is on
# screen and at exit), WORKDIR/session.log, and the
# screenshot in WORKDIR; exits non-zero when a step cannot be driven (the checks are check_edit.py's).
set -u
bin="$1" project="$2" work="$3"
cd "$work" || exit 1
cat >view.json <<'JSON'
[{"frame": 1, "action": "view", "target": [0.5, -9, 0], "distance": 10, "yaw_deg": -90, "pitch_deg": 60}]
JSON
"$bin" edit "$project" --size 960x540 --config "$work/config" --cache "$work/cache" --replay view.json \
  --stats session.stats.json --autosave-interval 600 >session.log 2>&1 &
editor=$!
# The script's statistics appear once the instances are on screen and the view is set.
for _ in $(seq 1 240); do [ -s session.stats.json ] && break; sleep 0.25; done
[ -s session.stats.json ] || { echo "the editor never showed its instances"; kill "$editor"; exit 1; }
mv session.stats.json session.start.json
# ImGui 1.86 samples keys once a frame: hold each long enough for a slow llvmpipe frame to see it.
hold=0.3
key() { xdotool keydown "$1"; sleep "$hold"; xdotool keyup "$1"; sleep "$hold"; }
chord() { xdotool keydown "$1"; sleep 0.1; key "$2"; xdotool keyup "$1"; sleep "$hold"; }
click() { xdotool mousemove "$1" "$2"; sleep "$hold"; xdotool mousedown 1; sleep "$hold"; xdotool mouseup 1; sleep "$hold"; }
alive() { kill -0 "$editor" 2>/dev/null; }

xdotool mousemove 480 330; sleep 0.5
key b; click 480 330
key s; xdotool mousemove 420 250; sleep "$hold"; xdotool mousedown 1; sleep 1.5; xdotool mouseup 1; sleep "$hold"
chord ctrl z
key b; click 560 200
key q; click 480 330; key Delete
key s; xdotool mousemove 300 400; sleep "$hold"; xdotool mousedown 1; sleep "$hold"
for x in $(seq 310 10 420); do xdotool mousemove "$x" 400; sleep 0.15; done
xdotool mouseup 1; sleep "$hold"
key q; click 300 400; key Delete
sleep 1
key F12
chord ctrl q; sleep 1
alive || { echo "Ctrl+Q quit without asking about unsaved changes"; exit 1; }
key Escape; sleep 1
alive || { echo "Escape in the unsaved-changes dialog quit the editor"; exit 1; }
chord ctrl q; sleep 1
key Return
for _ in $(seq 1 120); do alive || break; sleep 0.25; done
if alive; then echo "Enter in the unsaved-changes dialog did not save and quit"; kill "$editor"; exit 1; fi
wait "$editor"
