#!/usr/bin/env bash
# The particle tool driven by real X input (xdotool): with the Particles window open (the start script's
# set_attractor opens it and puts the wind attractor in the left patch, in the middle of the view), a
# left-drag from the attractor's dot moves it and the strands re-grow; Ctrl+Z puts it back. Then the
# generator's dot is dragged, the attractor's a(t) key on the window's plot, and New system clicked, then
# Remove system; last a generator is placed by a click on the ground ("Click to place") and undone. F12 writes the statistics
# after each step (WORKDIR/dragged.json, undone.json, generator.json, curve.json, curve_undone.json, new_system.json,
# removed.json, placed.json, place_undone.json; the start script's in
# start.stats.json). Runs inside an X server (run_gui_tests.sh starts it with xvfb-run at 1600x900); exits
# non-zero only when a step cannot be driven, the checks are the caller's.
# usage: driven_particles.sh UNDERGROWTH_BIN PROJECT.json WORKDIR CACHE
set -u
bin="$1" project="$2" work="$3" cache="$4"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$work" || exit 1
# The view's target is the attractor: its dot is at the window's centre, right of the Particles window,
# and the generator's 114 px above it.
cat >start.json <<'JSON'
[{"frame": 1, "action": "wait_idle"},
 {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [-8.0, 7.6, 0.35], "influence": 0.45, "charge": 3},
 {"action": "view", "target": [-8.0, 7.6, 0.35], "distance": 3, "yaw_deg": -90, "pitch_deg": 50}]
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
# The generator's dot, where the start statistics put it on screen: dragged 100 px to the right.
read -r gx gy < <(python3 -c '
import json
for h in json.load(open("start.stats.json"))["particles"]["handles_px"]:
    if h["part"] == "generator": print(int(h["px"][0]), int(h["px"][1])); break')
drag "$gx" "$gy" $((gx + 100)) "$gy"
dump generator "$settled"
# The wind attractor's a(t) plot in the Particles window (at 350, 30: its single key, charge 3, at the
# plot's left edge, 7 px below its top): the key dragged right and down.
drag 387 460 547 505
dump curve "$settled"
undo
dump curve_undone "$settled"
# New system, right of the window's system combo: a grass patch at the view's centre, in a new file.
click 655 66
dump new_system '"name": "strands"'
# Remove system, under the new system's lists (one attractor open, the other headers closed).
click 407 444
dump removed "$settled"
# Click to place: the window's "generator" button (right of "Place:" under the status line), then a
# click on the ground in the view: a new generator there, one undo step; Ctrl+Z takes it away.
click 441 103
click 1000 600
dump placed "$settled"
undo
dump place_undone "$settled"
quit_editor
exit 0
