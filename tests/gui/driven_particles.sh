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
cd "$work" || exit 1
# The view's target is the attractor: its dot is at the window's centre, right of the Particles window.
cat >start.json <<'JSON'
[{"frame": 1, "action": "wait_idle"},
 {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [-7.6, 8.0, 0.35], "influence": 0.45, "charge": 3},
 {"action": "view", "target": [-7.6, 8.0, 0.35], "distance": 3, "yaw_deg": -90, "pitch_deg": 50}]
JSON
"$bin" edit "$project" --size 1600x900 --config "$work/config" --cache "$cache" --replay start.json \
  --stats stats.json --autosave-interval 600 >session.log 2>&1 &
editor=$!
for _ in $(seq 1 480); do [ -s stats.json ] && break; sleep 0.25; done
[ -s stats.json ] || { echo "the editor never finished its start script"; kill "$editor"; exit 1; }
mv stats.json start.stats.json
hold=0.3
key() { xdotool keydown "$1"; sleep "$hold"; xdotool keyup "$1"; sleep "$hold"; }
chord() { xdotool keydown "$1"; sleep 0.1; key "$2"; xdotool keyup "$1"; sleep "$hold"; }
# F12 once the strands on screen are the document's (statistics "particles"/"strands_settled"). A frame
# of this 1600 x 900 view takes a second on a loaded machine, so the key is held a second and pressed
# again when no statistics came.
dump() {
  local tries=0
  for _ in $(seq 1 40); do
    rm -f stats.json
    xdotool keydown F12; sleep 1; xdotool keyup F12
    for _ in $(seq 1 32); do [ -s stats.json ] && break; sleep 0.25; done
    if [ ! -s stats.json ]; then
      tries=$((tries + 1))
      [ "$tries" -lt 5 ] && continue
      echo "F12 wrote no statistics ($1)"; kill "$editor"; exit 1
    fi
    grep -q '"strands_settled": true' stats.json && break
    sleep 0.5
  done
  mv stats.json "$1.json"
}
# Drag 120 px to the right in 10 moves (the Select tool is active at start).
xdotool mousemove 800 450; sleep 0.5
xdotool mousedown 1; sleep 0.4
for k in $(seq 1 10); do xdotool mousemove $((800 + 12 * k)) 450; sleep 0.15; done
sleep 0.3
xdotool mouseup 1; sleep 0.5
dump dragged
xdotool keydown ctrl; sleep 0.2; xdotool keydown z; sleep 1; xdotool keyup z; sleep 0.2; xdotool keyup ctrl; sleep 1
dump undone
chord ctrl q; sleep 0.5
key d; sleep 1  # Discard
kill "$editor" 2>/dev/null
wait "$editor" 2>/dev/null
exit 0
