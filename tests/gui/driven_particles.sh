#!/usr/bin/env bash
# The particle tool driven by real X input (xdotool): with the Particles window open (the start script's
# set_attractor opens it and puts the wind attractor in the left patch, in the middle of the view), a
# left-drag from the attractor's dot moves it and the strands re-grow; Ctrl+Z puts it back. F12 writes
# the statistics after each step (WORKDIR/dragged.json, undone.json; the start script's in
# start.stats.json). Runs inside an X server (run_gui_tests.sh starts it with xvfb-run at 1600x900); exits
# non-zero only when a step cannot be driven, the checks are the caller's.
# usage: driven_particles.sh UNDERGROWTH_BIN PROJECT.json WORKDIR CACHE
set -u
bin="$1" project="$2" work="$3" cache="$4"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$work" || exit 1
# The view's target is the attractor: its dot is at the window's centre, right of the Particles window.
cat >start.json <<'JSON'
[{"frame": 1, "action": "wait_idle"},
 {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [-7.6, 8.0, 0.35], "influence": 0.45, "charge": 3},
 {"action": "view", "target": [-7.6, 8.0, 0.35], "distance": 3, "yaw_deg": -90, "pitch_deg": 50}]
JSON
source "$here/driven_lib.sh"
start_editor "$project" 1600x900 "$cache"
# Drag 120 px to the right in 10 moves (the Select tool is active at start). F12 once the strands on
# screen are the document's.
settled='"strands_settled": true'
drag 800 450 920 450
dump dragged "$settled"
undo
dump undone "$settled"
quit_editor
exit 0
