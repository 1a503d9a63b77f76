#!/usr/bin/env bash
# The environment tools driven by real X input (xdotool), issue 13: with the Environment window open (the
# start script opens it and looks down on the winter street's open snow, right of the window), the palette's type is set to
# "bench" and "Add at the view's centre" clicked; the new bench is dragged 150 px to the right by its
# origin (the Select tool); the weather brush is switched on (footprints, its default) and dragged across
# the open snow; the palette's trash-can picture is clicked and then the pavement in the view (a trash can
# stands there, on the slab); Ctrl+Z four times. F12 writes the statistics after each step
# (WORKDIR/added.json, moved.json, walked.json, placed.json, undone.json; the start script's in
# start.stats.json). Runs inside an X server
# (run_gui_tests.sh starts it with xvfb-run at 1600x900); exits non-zero only when a step cannot be driven,
# the checks are the caller's. Coordinates are the default layout's at 1600 x 900.
# usage: driven_environment.sh UNDERGROWTH_BIN PROJECT.json WORKDIR CACHE
set -u
bin="$1" project="$2" work="$3" cache="$4"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$work" || exit 1
cat >start.json <<'JSON'
[{"frame": 1, "action": "wait_idle"},
 {"action": "show_window", "window": "environment"},
 {"action": "view", "target": [2.6, 6.4, 0.0], "distance": 8, "yaw_deg": -90, "pitch_deg": 60}]
JSON
source "$here/driven_lib.sh"
start_editor "$project" 1600x900 "$cache"
settled='"settled": true'
# The palette: open the type combo, pick its third entry (bench), then Add; again if a slow frame missed a
# click (the statistics then still count the 16 objects the street starts with).
for _ in 1 2 3; do
  click 580 285
  click 450 340
  click 445 307
  dump added "$settled"
  grep -q '"objects": 16,' added.json || break
  key Escape
done
# The new bench stands at the view's centre: drag it by its origin.
drag 800 450 950 450
dump moved "$settled"
# The weather brush (footprints) across the snow below the bench.
click 368 83
drag 760 525 1100 525
dump walked "$settled"
# The palette's fifth picture (the trash can) arms it; a click on the pavement in the view places one there.
click 623 346
click 1100 700
dump placed "$settled"
undo
undo
undo
undo
dump undone "$settled"
quit_editor
exit 0
