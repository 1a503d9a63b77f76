# Shared steps of the sessions driven by real X input (xdotool) inside an X server: sourced by
# driven_particles.sh and driven_environment.sh after they set `bin`, `work` (the current folder) and
# write start.json. Every step sleeps a little: on a loaded machine a frame of the editor takes a second.

hold=0.3
key() { xdotool keydown "$1"; sleep "$hold"; xdotool keyup "$1"; sleep "$hold"; }
chord() { xdotool keydown "$1"; sleep 0.1; key "$2"; xdotool keyup "$1"; sleep "$hold"; }
# Dear ImGui 1.86 reads the mouse once a frame: a press must last a frame where the pointer already is,
# and a frame takes up to a second here, so presses are held a second before anything else moves.
click() { xdotool mousemove "$1" "$2"; sleep 1; xdotool mousedown 1; sleep 1; xdotool mouseup 1; sleep 1; }
# drag X0 Y0 X1 Y1: the left button held from one point to the other in 10 moves. The button is held a
# second at the end too: the backend polls the pointer once a frame, so a release sooner than a frame
# after the last move ends the drag wherever the last frame saw the pointer, part of the way there (a CI
# run ended an a(t) key drag at a third of its way down).
drag() {
  xdotool mousemove "$1" "$2"; sleep 1
  xdotool mousedown 1; sleep 1
  for k in $(seq 1 10); do xdotool mousemove $(($1 + ($3 - $1) * k / 10)) $(($2 + ($4 - $2) * k / 10)); sleep 0.15; done
  sleep 1.2
  xdotool mouseup 1; sleep 0.5
}
undo() { xdotool keydown ctrl; sleep 0.2; xdotool keydown z; sleep 1; xdotool keyup z; sleep 0.2; xdotool keyup ctrl; sleep 1; }

# start_editor PROJECT SIZE CACHE: the editor on PROJECT with start.json, until its start script has run
# (its statistics, moved to start.stats.json). Sets `editor` (the pid).
start_editor() {
  "$bin" edit "$1" --size "$2" --config "$work/config" --cache "$3" --replay start.json \
    --stats stats.json --autosave-interval 600 >session.log 2>&1 &
  editor=$!
  for _ in $(seq 1 480); do [ -s stats.json ] && break; sleep 0.25; done
  [ -s stats.json ] || { echo "the editor never finished its start script"; kill "$editor"; exit 1; }
  mv stats.json start.stats.json
}

# dump NAME PATTERN: F12 until the statistics hold PATTERN (what is on screen is settled), saved as
# NAME.json. The key is held a second and pressed again when a slow frame missed it.
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
    grep -q "$2" stats.json && break
    sleep 0.5
  done
  mv stats.json "$1.json"
}

# Quit, discarding the edits, and make sure the editor is gone.
quit_editor() {
  chord ctrl q; sleep 0.5
  key d; sleep 1  # Discard
  kill "$editor" 2>/dev/null
  wait "$editor" 2>/dev/null
}
