#!/usr/bin/env bash
# End-to-end tests of the editor in a real window under Xvfb (Mesa llvmpipe): `undergrowth edit --frames`
# on the meadow and the rock pile; the screenshots are decoded and checked (check_screenshot.py) and the
# instance counts compared with the headless `instantiate` on the same scene. Fails, never skips, when
# xvfb-run is missing (CI installs xvfb). UG_BIN is the binary; UG_GUI_KEEP=DIR keeps the outputs.
source "$(dirname "$0")/../lib/harness.sh"

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

# ---- the live editing loop: replayed strokes on the meadow (tools.h, replay.h) ----
meadow="$root/assets/scenes/meadow.json"
street="$root/assets/scenes/street_winter.json"
config="$tmp/config"
mkdir -p "$tmp/saved"
touch "$tmp/not_a_folder"
# A rock stroke where the meadow has no rock (its rock density is 0 around (0.5, -9)), a sculpted rock pile,
# undo and redo of each, a save that must fail (a file where the folder should be: the tests may run as
# root, who may write into a read-only folder) and one that succeeds.
cat >"$tmp/strokes.json" <<EOF
[{"frame": 1, "action": "view", "target": [0.5, -9, 0], "distance": 10},
 {"action": "screenshot", "path": "$tmp/before.png", "overlays": false},
 {"action": "paint_stroke", "type": "rock", "points": [[-1, -9], [2, -9]], "radius": 1.0, "strength": 1.0, "falloff": 0.5},
 {"action": "screenshot", "path": "$tmp/after.png", "overlays": false},
 {"action": "undo"}, {"action": "redo"},
 {"action": "sculpt_stroke", "type": "rock", "points": [[-6, -10], [-5.5, -10]], "radius": 0.6, "steps": 10},
 {"action": "view", "target": [-5.75, -10, 0.5], "distance": 4},
 {"action": "screenshot", "path": "$tmp/pile.png", "overlays": true},
 {"action": "undo"}, {"action": "redo"},
 {"action": "save_as", "path": "$tmp/not_a_folder/meadow_edit.json"},
 {"action": "save_as", "path": "$tmp/saved/meadow_edit.json"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$meadow" --frames 3 --size 640x360 --cache "$cache" \
    --config "$config" --replay "$tmp/strokes.json" --stats "$tmp/strokes.stats.json" >"$tmp/strokes.log" 2>&1; then
  ok "edit meadow: replayed paint and sculpt strokes, undo, redo, save as"
  if "$bin" instantiate "$tmp/saved/meadow_edit.json" -o "$tmp/saved.glb" --stats "$tmp/saved.cli.json" \
       --cache "$cache" >/dev/null 2>&1 &&
     out="$(python3 "$root/tests/gui/check_edit.py" strokes "$tmp/strokes.stats.json" "$tmp/saved.cli.json" 2>&1)"; then
    ok "edit meadow: strokes ($out)"
  else
    bad "edit meadow: strokes: $out"
  fi
  if out="$(python3 "$root/tests/gui/check_edit.py" diff "$tmp/before.png" "$tmp/after.png" 2>&1)"; then
    ok "edit meadow: the screenshot changes where the stroke went ($out)"
  else
    bad "edit meadow: screenshot before/after: $out"
  fi
else
  bad "edit meadow strokes: $(tail -5 "$tmp/strokes.log")"
fi

# Select and drag: a one-stamp rock disc painted where the meadow has no rock, dragged 4 m with the Select
# tool (one undo step), saved (the CLI re-instantiates the saved file), then undone. Then a rock pile from
# a held sculpt brush, and leaves painted onto it ("surface": the pile) and, for contrast, onto the ground.
cat >"$tmp/move.json" <<EOF
[{"frame": 1, "action": "paint_stroke", "type": "rock", "points": [[0.5, -9]], "radius": 1.0},
 {"action": "move", "from": [0.5, -9], "to": [4.5, -9], "steps": 8},
 {"action": "save_as", "path": "$tmp/saved/meadow_move.json"},
 {"action": "undo"},
 {"action": "sculpt_stroke", "type": "rock", "points": [[-6, -10]], "radius": 0.5, "steps": 20},
 {"action": "paint_stroke", "type": "leaf_oak", "surface": "rock", "points": [[-6, -10]], "radius": 0.6},
 {"action": "paint_stroke", "type": "leaf_oak", "points": [[-6, -10]], "radius": 0.6},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$meadow" --frames 2 --size 640x360 --cache "$cache" \
     --config "$config" --replay "$tmp/move.json" --stats "$tmp/move.stats.json" >"$tmp/move.log" 2>&1 &&
   "$bin" instantiate "$tmp/saved/meadow_move.json" -o "$tmp/move.glb" --stats "$tmp/move.cli.json" \
     --cache "$cache" >/dev/null 2>&1 &&
   out="$(python3 "$root/tests/gui/check_edit.py" move "$tmp/move.stats.json" "$tmp/move.cli.json" 2>&1)"; then
  ok "edit meadow: select and drag a painted disc ($out)"
  if out="$(python3 "$root/tests/gui/check_edit.py" pile_paint "$tmp/move.stats.json" 2>&1)"; then
    ok "edit meadow: held sculpt builds a cone, paint lands on the pile ($out)"
  else
    bad "edit meadow: sculpt cone / paint on the pile: $out"
  fi
else
  bad "edit meadow: select and drag: ${out:-$(tail -5 "$tmp/move.log")}"
fi

# ---- Sculpt from any view: held rock piles poured through the camera's rays ("from_camera") from an
# oblique, a side and a top view land on the brush's ground point as cones at the rock's angle of repose,
# each one primitive and one undo step; the oblique pile is photographed from the side; the side pile is
# moved as a unit; a dragged stroke (a cone every radius / 3) is moved as a unit too; the file is saved and
# re-instantiated by the CLI. ----
cat >"$tmp/piles.json" <<EOF
[{"frame": 1, "action": "view", "target": [-6, -10, 0], "distance": 8, "yaw_deg": -90, "pitch_deg": 30},
 {"action": "sculpt_stroke", "type": "rock", "points": [[-6, -10]], "radius": 0.6, "steps": 40, "from_camera": true},
 {"action": "view", "target": [-6, -10, 0.2], "distance": 5, "yaw_deg": 0, "pitch_deg": 4},
 {"action": "screenshot", "path": "$tmp/pile_side.png", "overlays": false},
 {"action": "screenshot", "path": "$tmp/pile_side_overlays.png", "overlays": true},
 {"action": "undo"}, {"action": "redo"},
 {"action": "view", "target": [3, -12, 0], "distance": 8, "yaw_deg": 0, "pitch_deg": 10},
 {"action": "sculpt_stroke", "type": "rock", "points": [[3, -12]], "radius": 0.6, "steps": 40, "from_camera": true},
 {"action": "view", "target": [-12, 4, 0], "distance": 8, "yaw_deg": -90, "pitch_deg": 89},
 {"action": "sculpt_stroke", "type": "rock", "points": [[-12, 4]], "radius": 0.6, "steps": 40, "from_camera": true},
 {"action": "move", "from": [3, -12], "to": [5, -12], "steps": 4},
 {"action": "view", "target": [9, -15, 0], "distance": 8, "yaw_deg": -60, "pitch_deg": 25},
 {"action": "sculpt_stroke", "type": "rock", "points": [[8, -15], [10, -15]], "radius": 0.6, "steps": 30, "from_camera": true},
 {"action": "view", "target": [9, -15, 0.3], "distance": 6, "yaw_deg": -90, "pitch_deg": 5},
 {"action": "screenshot", "path": "$tmp/ridge_side.png", "overlays": false},
 {"action": "move", "from": [9, -15], "to": [9, -13], "steps": 4},
 {"action": "save_as", "path": "$tmp/saved/meadow_piles.json"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$meadow" --frames 2 --size 640x360 --cache "$cache" \
     --config "$config" --replay "$tmp/piles.json" --stats "$tmp/piles.stats.json" >"$tmp/piles.log" 2>&1 &&
   "$bin" instantiate "$tmp/saved/meadow_piles.json" -o "$tmp/piles.glb" --stats "$tmp/piles.cli.json" \
     --cache "$cache" >/dev/null 2>&1 &&
   out="$(python3 "$root/tests/gui/check_edit.py" piles "$tmp/piles.stats.json" "$tmp/piles.cli.json" "$meadow" \
          "$tmp/saved/meadow_piles.json" 2>&1)"; then
  ok "edit meadow: held sculpt from oblique, side and top views ($out)"
else
  bad "edit meadow: sculpt from any view: ${out:-$(tail -5 "$tmp/piles.log")}"
fi

# ---- Ghost Tile panel: a replayed build of the rock pile with more rocks and another delta (replay.h,
# "ghost_tile"), saved, undone and redone; then a type pointed at a corrupt model file and a count of 0 ----
pile="$root/assets/scenes/rock_pile.json"
mkdir -p "$tmp/ghost"
printf 'glTF\002\000\000\000 not a binary glTF' >"$tmp/ghost/corrupt_model.glb"
cat >"$tmp/ghost.json" <<EOF
[{"frame": 1, "action": "ghost_tile", "type": "rock", "count": 360, "delta": -0.001},
 {"action": "save_as", "path": "$tmp/ghost/pile_ghost.json"},
 {"action": "undo"}, {"action": "redo"},
 {"action": "ghost_tile", "type": "twig", "model": "$tmp/ghost/corrupt_model.glb"},
 {"action": "ghost_tile", "type": "rock", "count": 0},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$pile" --frames 3 --size 640x360 --cache "$cache" \
    --config "$tmp/ghost-config" --replay "$tmp/ghost.json" --stats "$tmp/ghost.stats.json" >"$tmp/ghost.log" 2>&1; then
  ok "edit rock pile: replayed Ghost Tile build, save as, undo, redo, corrupt model, count 0 (exit 0)"
  if "$bin" instantiate "$tmp/ghost/pile_ghost.json" -o "$tmp/ghost.glb" --stats "$tmp/ghost.cli.json" \
       --cache "$cache" >/dev/null 2>&1 &&
     out="$(python3 "$root/tests/gui/check_ghost_tile.py" "$tmp/ghost.stats.json" "$tmp/ghost.cli.json" "$pile" \
            "$tmp/ghost/pile_ghost.json" rock 360 -0.001 corrupt_model.glb 2>&1)"; then
    ok "edit rock pile: Ghost Tile ($out)"
  else
    bad "edit rock pile: Ghost Tile: $out"
  fi
else
  bad "edit rock pile Ghost Tile: $(tail -5 "$tmp/ghost.log")"
fi

# ---- panels: seed and instancing edits, export, New and Open (check_panels.py) ----
# On the default scene (the whole of it in view): the outliner's eye hides exactly a type's instances
# and is no edit; set_seed vs `instantiate --seed`, undo exact; an export read back by the Khronos
# validator and glTF-Transform; a failed export; opening a truncated scene and a scene whose model is
# garbage (the run goes on, the messages say which file and why, the document stays); New, then Save As.
pdir="$tmp/panels"
mkdir -p "$pdir"
default_scene="$root/assets/scenes/default.json"
printf '{"format": "undergrowth-project", "format_version": 2, "name": "cut' >"$pdir/truncated.json"
printf 'v 1 2\nf 1 2 3 4 5\nvt x y z\n\001\002 not a mesh\n' >"$pdir/garbage.obj"
python3 - "$default_scene" "$pdir" <<'PY'
import json, os, sys
scene, out = sys.argv[1], sys.argv[2]
s = json.load(open(scene))
models = os.path.normpath(os.path.join(os.path.dirname(scene), "../models"))
for t in s["detail_types"]:
    t["model"]["mesh"] = os.path.join(models, os.path.basename(t["model"]["mesh"]))
s["detail_types"][0]["model"]["mesh"] = "garbage.obj"
json.dump(s, open(os.path.join(out, "bad_model.json"), "w"))
PY
cat >"$pdir/script.json" <<EOF
[{"frame": 1, "action": "set_visible", "type": "rock", "visible": false},
 {"action": "set_visible", "type": "grass_tuft", "visible": false},
 {"action": "set_visible", "type": "rock", "visible": true},
 {"action": "set_visible", "type": "grass_tuft", "visible": true},
 {"action": "set_seed", "seed": 5},
 {"action": "undo"}, {"action": "redo"},
 {"action": "set_instancing", "type": "rock", "strategy": "random"},
 {"action": "undo"},
 {"action": "export", "path": "$pdir/editor.glb"},
 {"action": "export", "path": "$tmp/not_a_folder/editor.glb"},
 {"action": "open", "path": "$pdir/truncated.json"},
 {"action": "open", "path": "$pdir/bad_model.json"},
 {"action": "new"},
 {"action": "save_as", "path": "$pdir/new.json"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$default_scene" --frames 3 --size 640x360 --cache "$cache" \
    --config "$pdir/config" --replay "$pdir/script.json" --stats "$pdir/stats.json" >"$pdir/log" 2>&1; then
  ok "edit panels: set_seed, set_instancing, export, failed opens, new, save as (exit 0)"
  if "$bin" instantiate "$default_scene" --seed 5 -o "$pdir/cli.glb" --stats "$pdir/cli.json" --cache "$cache" \
       >/dev/null 2>&1 &&
     out="$(python3 "$root/tests/gui/check_panels.py" "$pdir/stats.json" "$pdir/cli.json" 5 "$default_scene" 2>&1)"; then
    ok "edit panels: $out"
  else
    bad "edit panels: $out"
  fi
  n="$(python3 -c 'import json,sys; print([a for a in json.load(open(sys.argv[1]))["actions"] if a["action"] == "export"][0]["exported_instances"])' "$pdir/stats.json" 2>/dev/null)"
  if command -v node >/dev/null 2>&1 && bash "$root/tests/gltf/setup.sh" >"$pdir/npm.txt" 2>&1 &&
     node "$root/tests/gltf/check_gltf.mjs" "$pdir/editor.glb" --expect-detail-instances "${n:-0}" \
       --expect-types 9 >"$pdir/gltf.txt" 2>&1; then
    ok "edit panels: the editor's export is valid (Khronos validator) with its $n instances (glTF-Transform)"
  else
    bad "edit panels: export check: $(tail -5 "$pdir/gltf.txt" "$pdir/npm.txt" 2>/dev/null)"
  fi
  if "$bin" instantiate "$pdir/new.json" -o "$pdir/new.glb" --stats "$pdir/new.cli.json" --cache "$cache" >/dev/null 2>&1 &&
     python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["instances"] == 0, d["instances"]' "$pdir/new.cli.json"; then
    ok "edit panels: the new document saved by Save As loads in the CLI (0 instances)"
  else
    bad "edit panels: the saved new document does not load in the CLI"
  fi
else
  bad "edit panels: $(tail -5 "$pdir/log")"
fi

# ---- the editor's export of a scene with looks: what `instantiate` writes ----
# The autumn street's leaves take a wet flat look in the puddle and its grass a dried one where it is warm,
# each its own instanced mesh: the editor's File > Export must hold every look with the very count the CLI's
# statistics give it (glTF-Transform reads it back), not the types alone.
adir="$tmp/autumn"
mkdir -p "$adir"
autumn="$root/assets/scenes/street_autumn.json"
cat >"$adir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "export", "path": "$adir/editor.glb"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$autumn" --frames 3 --size 640x360 --cache "$cache" \
     --config "$adir/config" --replay "$adir/script.json" --stats "$adir/stats.json" >"$adir/log" 2>&1 &&
   "$bin" instantiate "$autumn" -o "$adir/cli.glb" --stats "$adir/cli.json" --cache "$cache" >/dev/null 2>&1 &&
   looks="$(python3 -c 'import json,sys; l=json.load(open(sys.argv[1]))["instances_per_look"]; assert any(n for k, n in l.items() if k.endswith("_wet")), l; print(json.dumps(l))' "$adir/cli.json")" &&
   bash "$root/tests/gltf/setup.sh" >"$adir/npm.txt" 2>&1 &&
   node "$root/tests/gltf/check_gltf.mjs" "$adir/editor.glb" --expect-per-mesh "$looks" >"$adir/gltf.txt" 2>&1; then
  ok "edit street_autumn: the editor's export holds every look as instantiate counts it ($looks)"
else
  bad "edit street_autumn: export looks: $(tail -5 "$adir/log" "$adir/gltf.txt" 2>/dev/null)"
fi

# edit_and_instantiate DIR SCENE SIZE: the editor on DIR's copy of the assets' SCENE with DIR/script.json
# (statistics in DIR/stats.json, log in DIR/log), then `instantiate` on the scene it saved (DIR/saved.glb).
edit_and_instantiate() {
  xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$1/assets/scenes/$2" --frames 3 --size "$3" \
    --cache "$cache" --config "$1/config" --replay "$1/script.json" --stats "$1/stats.json" >"$1/log" 2>&1 &&
    "$bin" instantiate "$1/assets/scenes/$2" -o "$1/saved.glb" --cache "$cache" >/dev/null 2>&1
}

# ---- a project's particle systems in the editor: drawn and exported as `instantiate` writes them ----
sdir="$tmp/strands"
mkdir -p "$sdir"
strands_scene="$root/assets/scenes/meadow_strands.json"
cat >"$sdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "view", "target": [-7.2, 8.2, 0.3], "distance": 2.6, "yaw_deg": -100, "pitch_deg": 20},
 {"action": "screenshot", "path": "$sdir/strands.png", "overlays": false},
 {"action": "export", "path": "$sdir/editor.glb"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$strands_scene" --frames 3 --size 640x360 --cache "$cache" \
     --config "$sdir/config" --replay "$sdir/script.json" --stats "$sdir/stats.json" >"$sdir/log" 2>&1 &&
   "$bin" instantiate "$strands_scene" -o "$sdir/cli.glb" --cache "$cache" >/dev/null 2>&1 &&
   out="$(python3 - "$sdir" <<'PY' 2>&1
import json, struct, sys
d = sys.argv[1]
def strands(path):
    b = open(path, "rb").read()
    doc = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
    return {m["name"]: m["extras"] for m in doc["meshes"] if m["name"].startswith("strands/")}
editor, cli = strands(d + "/editor.glb"), strands(d + "/cli.glb")
assert sorted(editor) == ["strands/meadow_grass_strands", "strands/meadow_grass_strands_2"], sorted(editor)
assert editor == cli, "the editor's strands differ from instantiate's"
print(sum(len(e["strands"]["offsets"]) - 1 for e in editor.values()), "strands")
PY
)" && python3 "$root/tests/gui/check_screenshot.py" "$sdir/strands.png" 640 360 meadow >/dev/null 2>&1; then
  ok "edit meadow_strands: the editor draws and exports the project's particle systems as instantiate does ($out)"
else
  bad "edit meadow_strands: $out $(tail -5 "$sdir/log" 2>/dev/null)"
fi

# ---- editing a particle system: the Particles window's edit re-grows the strands (incrementally), a
# third edit's growth cancelled (Cancel undoes it), undo gives the loaded strands back exactly, and Save
# writes the particle file so that `instantiate` grows what the editor showed. On a copy of the assets,
# since it saves.
pdir="$tmp/particle-edit"
mkdir -p "$pdir"
cp -r "$root/assets" "$pdir/assets"
cat >"$pdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "view", "target": [-7.6, 8.0, 0.2], "distance": 2.4, "yaw_deg": -100, "pitch_deg": 25},
 {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [-7.8, 8.0, 0.35], "influence": 0.45, "charge": 3},
 {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [-7.6, 8.0, 0.35]},
 {"action": "set_attractor", "system": 0, "attractor": 1, "influence": 0, "charge": -2, "cancel": true},
 {"action": "screenshot", "path": "$pdir/edited.png", "overlays": false, "ui": true},
 {"action": "export", "path": "$pdir/edited.glb"},
 {"action": "undo"},
 {"action": "undo"},
 {"action": "export", "path": "$pdir/undone.glb"},
 {"action": "redo"},
 {"action": "redo"},
 {"action": "particle_entry", "system": 1, "name": "east_patch", "offset_m": [-5.7, 8.6, 0]},
 {"action": "wait_idle"},
 {"action": "export", "path": "$pdir/entry.glb"},
 {"action": "save"},
 {"action": "wait_idle"}]
EOF
if edit_and_instantiate "$pdir" meadow_strands.json 960x540 &&
   out="$(python3 - "$pdir" "$sdir/cli.glb" <<'PY' 2>&1
import json, struct, sys
d, original = sys.argv[1], sys.argv[2]
def strands(path):
    b = open(path, "rb").read()
    doc = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
    return {m["name"]: m["extras"] for m in doc["meshes"] if m["name"].startswith("strands/")}
stats = json.load(open(d + "/stats.json"))
edits = [a for a in stats["actions"] if a["action"] == "set_attractor"]
assert len(edits) == 3 and all(e["ok"] and e["particles"]["ok"] for e in edits), edits
# The third edit's growth cancelled at once: the edit undone, so the export after it is the second's.
assert edits[2]["cancelled"] is True and edits[2]["undo_name"] == "Edit particles", edits[2]
assert not any(e.get("cancelled") for e in edits[:2]), edits
moved = edits[1]["particles"]
assert moved["incremental"] and moved["reused"] > moved["recomputed"], moved
edited, undone, saved = strands(d + "/edited.glb"), strands(d + "/undone.glb"), strands(d + "/saved.glb")
assert undone == strands(original), "undo did not give the loaded strands back"
assert edited != undone, "the edit changed no strand"
# The second entry renamed and moved 0.5 m east (the Particles window's "Name and offset"): its strands
# follow, the first entry's stay; the saved project grows what the editor showed.
entry_edit = [a for a in stats["actions"] if a["action"] == "particle_entry"]
assert len(entry_edit) == 1 and entry_edit[0]["ok"] and entry_edit[0]["undo_name"] == "Rename particle system", entry_edit
entry = strands(d + "/entry.glb")
assert sorted(entry) == ["strands/east_patch", "strands/meadow_grass_strands"], sorted(entry)
assert entry["strands/meadow_grass_strands"] == edited["strands/meadow_grass_strands"]
def mean_x(e):
    return sum(p[0] for p in e["strands"]["points"]) / len(e["strands"]["points"])
shift = mean_x(entry["strands/east_patch"]) - mean_x(edited["strands/meadow_grass_strands_2"])
assert 0.45 < shift < 0.55, "the renamed entry's strands did not move 0.5 m east: %.3f" % shift
assert entry == saved, "the saved project does not grow what the editor showed"
project = json.load(open(d + "/assets/scenes/meadow_strands.json"))
assert project["particles"][1]["name"] == "east_patch" and project["particles"][1]["offset_m"][0] == -5.7, project["particles"]
print("%d %% of the moves re-grown after the move" % (100 * moved["recomputed"] // (moved["recomputed"] + moved["reused"])))
PY
)"; then
  ok "edit meadow_strands: an attractor moved in the Particles window re-grows incrementally, a cancelled growth undoes its edit, undo is exact, an entry renamed and moved, it saves ($out)"
else
  bad "edit meadow_strands: particle edit: $out $(tail -5 "$pdir/log" 2>/dev/null)"
fi

# ---- strands among the objects: the bus stop's vines grow on and around the shelter; dragging the shelter
# takes them with it (their seeds, pull and solids are its), the export equals `instantiate` on the saved
# file (valid for the Khronos validator, read back by glTF-Transform), and undo gives the loaded vines back
# exactly. On a copy of the assets, since it saves.
vdir="$tmp/vines"
mkdir -p "$vdir"
cp -r "$root/assets" "$vdir/assets"
cat >"$vdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "view", "target": [0.3, -0.5, 1.2], "distance": 6.5, "yaw_deg": -120, "pitch_deg": 15},
 {"action": "export", "path": "$vdir/loaded.glb"},
 {"action": "env_move", "node": 0, "to": [1.0, 0.0], "steps": 5},
 {"action": "wait_idle"},
 {"action": "screenshot", "path": "$vdir/moved.png", "overlays": false},
 {"action": "export", "path": "$vdir/edited.glb"},
 {"action": "save"},
 {"action": "undo"},
 {"action": "export", "path": "$vdir/undone.glb"},
 {"action": "wait_idle"}]
EOF
if edit_and_instantiate "$vdir" bus_stop_vines.json 640x360 &&
   bash "$root/tests/gltf/setup.sh" >"$vdir/npm.txt" 2>&1 &&
   node "$root/tests/gltf/check_gltf.mjs" "$vdir/saved.glb" >"$vdir/check.txt" 2>&1 &&
   out="$(python3 - "$vdir" <<'PY' 2>&1
import json, struct, sys
d = sys.argv[1]
report = json.loads(open(d + "/check.txt").read().strip().splitlines()[-1])
assert report["errors"] == 0 and "strands/vines" in report["per_mesh"], report
def vines(path):
    b = open(path, "rb").read()
    doc = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
    return [m["extras"]["strands"] for m in doc["meshes"] if m["name"] == "strands/vines"][0]
loaded, edited, saved, undone = (vines("%s/%s.glb" % (d, n)) for n in ("loaded", "edited", "saved", "undone"))
assert edited == saved, "the editor's vines differ from instantiate's on the saved file"
assert undone == loaded, "undo did not give the loaded vines back"
def mean_x(v):
    return sum(p[0] for p in v["points"]) / len(v["points"])
shift = mean_x(edited) - mean_x(loaded)
assert 0.8 < shift < 1.2, "the vines did not follow the shelter 1 m along x: %.3f" % shift
print("%d vines, moved %.2f m with the shelter" % (len(edited["offsets"]) - 1, shift))
PY
)" && test -s "$vdir/moved.png"; then
  ok "edit bus_stop_vines: the vines follow the dragged shelter, export as instantiate does on the saved file, and undo exactly ($out)"
else
  bad "edit bus_stop_vines: $out $(tail -5 "$vdir/log" 2>/dev/null)"
fi

# ---- moss on the rock pile's settled rocks (a "details" generator) in the editor: drawn, and exported as
# `instantiate` writes it (the same tube vertices, byte for byte).
mdir="$tmp/moss"
mkdir -p "$mdir"
cat >"$mdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "view", "target": [0.6, -0.5, 0.2], "distance": 1.3, "yaw_deg": -100, "pitch_deg": 8},
 {"action": "screenshot", "path": "$mdir/moss.png", "overlays": false},
 {"action": "export", "path": "$mdir/editor.glb"},
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$root/assets/scenes/rock_pile_moss.json" --frames 3 --size 640x360 \
     --cache "$cache" --config "$mdir/config" --replay "$mdir/script.json" --stats "$mdir/stats.json" >"$mdir/log" 2>&1 &&
   "$bin" instantiate "$root/assets/scenes/rock_pile_moss.json" -o "$mdir/cli.glb" --cache "$cache" >/dev/null 2>&1 &&
   out="$(python3 - "$mdir" "$root/tests/gltf" <<'PY' 2>&1
import sys
d = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from glb_mesh import mesh_positions as positions
editor, cli = positions(d + "/editor.glb", "strands/moss"), positions(d + "/cli.glb", "strands/moss")
assert editor and len(editor) > 1000000, "the editor exported no moss"
assert editor == cli, "the editor's moss differs from instantiate's"
print("%d moss vertices" % (len(editor) // 12))
PY
)" && test -s "$mdir/moss.png"; then
  ok "edit rock_pile_moss: the moss on the rocks exports as instantiate writes it ($out)"
else
  bad "edit rock_pile_moss: $out $(tail -5 "$mdir/log" 2>/dev/null)"
fi

# ---- the environment in the editor (issue 13, after the paper's Fig. 3): deeper snow, a lamppost and a
# bench placed, the street's bench dragged under the bus shelter (no snow on it there), footprints walked
# across the pavement; the editor's export equals `instantiate` on the saved file in every environment
# mesh, and undoing every step gives the loaded scene's back. On a copy of the assets, since it saves.
edir="$tmp/env-edit"
mkdir -p "$edir"
cp -r "$root/assets" "$edir/assets"
cat >"$edir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "export", "path": "$edir/loaded.glb"},
 {"action": "env_global", "channel": "snow", "value": 0.2},
 {"action": "env_add", "type": "lamppost", "at": [8.2, 4.7], "yaw_deg": 180},
 {"action": "env_add", "type": "bench", "at": [5.0, 3.7]},
 {"action": "env_move", "node": 12, "to": [6.6, 6.9], "steps": 5},
 {"action": "footprints", "points": [[0.6, 3.3], [4.2, 3.5], [6.0, 5.6]]},
 {"action": "screenshot", "path": "$edir/edited.png", "overlays": false, "ui": true},
 {"action": "export", "path": "$edir/edited.glb"},
 {"action": "save"},
 {"action": "undo"}, {"action": "undo"}, {"action": "undo"}, {"action": "undo"}, {"action": "undo"},
 {"action": "export", "path": "$edir/undone.glb"},
 {"action": "wait_idle"}]
EOF
if edit_and_instantiate "$edir" street_winter.json 960x540 &&
   out="$(python3 - "$edir" "$root/tests/gui" <<'PY' 2>&1
import json, sys
sys.path.insert(0, sys.argv[2])
from env_meshes import env_meshes
d = sys.argv[1]
stats = json.load(open(d + "/stats.json"))
acts = {a["action"]: a for a in stats["actions"]}
for k in ("env_global", "env_add", "env_move", "footprints"):
    assert acts[k].get("ok", True) and acts[k]["environment"]["last"]["ok"], acts[k]
assert acts["env_move"]["moves"] == 5 and acts["footprints"]["stamps"] >= 15, (acts["env_move"], acts["footprints"])
env = stats["environment"]
assert env["objects"] == 16 and env["settled"], env
loaded, edited, saved, undone = (env_meshes("%s/%s.glb" % (d, n)) for n in ("loaded", "edited", "saved", "undone"))
assert edited == saved, sorted(set(edited.items()) ^ set(saved.items()))[:6]
assert undone == loaded, sorted(set(undone.items()) ^ set(loaded.items()))[:6]
assert edited != loaded
print("%d environment meshes as instantiate writes them; undo gives the loaded %d back; %.0f ms for the last update" % (
    len(edited), len(loaded), 1000 * acts["footprints"]["environment"]["last"]["seconds"]))
PY
)"; then
  ok "edit street_winter: objects placed and moved, snow deepened and footprints walked in the editor export as instantiate on the saved file, and undo exactly ($out)"
else
  bad "edit street_winter: environment edit: $out $(tail -5 "$edir/log" 2>/dev/null)"
fi

# ---- the sun's map kept across swaps that change no caster (a footprint replaces the terrain's snow, which
# casts nothing; a live result that changed no tile), and the static entries' buffers kept where their mesh,
# instances and material did not change: a bench placed, the street's bench dragged (its old shadow must
# go) and footprints walked; the picture equals the one drawn with the map redrawn and every entry uploaded
# again at every swap (UG_SHADOW_REDRAW_ALWAYS, UG_STATIC_REUPLOAD_ALWAYS), byte for byte, and the swaps
# after the first upload only some entries (a footprint: the snow it reached).
shdir="$tmp/shadow-kept"
mkdir -p "$shdir"
for mode in kept always; do
  cat >"$shdir/$mode.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "env_add", "type": "bench", "at": [5.0, 3.7]},
 {"action": "env_move", "node": 12, "to": [6.6, 6.9], "steps": 5},
 {"action": "footprints", "points": [[0.6, 3.3], [4.2, 3.5], [6.0, 5.6]]},
 {"action": "wait_idle"},
 {"action": "screenshot", "path": "$shdir/$mode.png", "overlays": false}]
EOF
done
street="$root/assets/scenes/street_winter.json"
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$street" --frames 3 --size 960x540 --cache "$cache" \
     --config "$shdir/config-kept" --replay "$shdir/kept.json" --stats "$shdir/kept-stats.json" >"$shdir/log" 2>&1 &&
   UG_SHADOW_REDRAW_ALWAYS=1 UG_STATIC_REUPLOAD_ALWAYS=1 xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$street" \
     --frames 3 --size 960x540 --cache "$cache" --config "$shdir/config-always" --replay "$shdir/always.json" \
     >>"$shdir/log" 2>&1 &&
   cmp -s "$shdir/kept.png" "$shdir/always.png" &&
   swaps="$(python3 - "$shdir/kept-stats.json" <<'PY' 2>&1
import json, sys
swaps = json.load(open(sys.argv[1]))["static_swaps"]
assert len(swaps) >= 3, swaps
assert swaps[0][1] == 0, swaps  # the first set: nothing to keep
later = swaps[1:]
assert all(kept > 0 for _, kept in later), swaps
uploaded, entries = swaps[-1][0], sum(swaps[-1])
assert uploaded * 4 <= entries, f"the last footprint uploaded {uploaded} of {entries} entries: {swaps}"
print(f"{len(swaps)} swaps; the last uploaded {uploaded} of {entries} entries")
PY
)"; then
  ok "edit street_winter: the sun's map and the static buffers kept across swaps equal them redrawn and uploaded at every swap (a bench placed and dragged, footprints; $swaps)"
else
  bad "edit street_winter: kept shadow map and static buffers: $(cmp "$shdir/kept.png" "$shdir/always.png" 2>&1) ${swaps:-} $(tail -5 "$shdir/log" 2>/dev/null)"
fi

# ---- the tree's edits (the Environment window's Group, drag onto a group, Make reusable, Instance): the bus
# shelter grouped with the bench, the group made reusable and placed again; the export equals `instantiate`
# on the saved file, and four undos give the loaded scene's meshes back.
tdir="$tmp/env-tree"
mkdir -p "$tdir"
cp -r "$root/assets" "$tdir/assets"
cat >"$tdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "export", "path": "$tdir/loaded.glb"},
 {"action": "env_tree", "op": "group", "node": [11]},
 {"action": "env_tree", "op": "into", "node": [12], "group": [11]},
 {"action": "env_tree", "op": "reusable", "node": [11], "name": "stop"},
 {"action": "env_tree", "op": "instance", "name": "stop", "at": [2.5, 6.8]},
 {"action": "export", "path": "$tdir/edited.glb"},
 {"action": "save"},
 {"action": "undo"}, {"action": "undo"}, {"action": "undo"}, {"action": "undo"},
 {"action": "export", "path": "$tdir/undone.glb"},
 {"action": "wait_idle"}]
EOF
if edit_and_instantiate "$tdir" street_winter.json 640x360 &&
   out="$(python3 - "$tdir" "$root/tests/gui" <<'PY' 2>&1
import json, sys
sys.path.insert(0, sys.argv[2])
from env_meshes import env_meshes, triangles
d = sys.argv[1]
stats = json.load(open(d + "/stats.json"))
edits = [a for a in stats["actions"] if a["action"] == "env_tree"]
assert len(edits) == 4 and all(a["ok"] for a in edits), [a.get("error") for a in edits]
assert [a["undo_name"] for a in edits] == ["Group", "Move into group", "Make group reusable", "Instance group"], \
    [a["undo_name"] for a in edits]
assert edits[-1]["environment"]["objects"] == 18, edits[-1]["environment"]["objects"]
saved = json.load(open(d + "/assets/scenes/street_winter.json"))["environment"]
assert list(saved["groups"]) == ["stop"], saved.get("groups")
assert env_meshes(d + "/edited.glb") == env_meshes(d + "/saved.glb"), "the export differs from instantiate"
assert env_meshes(d + "/undone.glb") == env_meshes(d + "/loaded.glb"), "four undos did not give the scene back"
assert triangles(d + "/edited.glb", "env/bus_shelter") == 2 * triangles(d + "/loaded.glb", "env/bus_shelter")
print("a bus stop group of 2 objects instanced twice; export as instantiate; undone")
PY
)"; then
  ok "edit street_winter: grouped, regrouped, made reusable and instanced again in the editor, exported as instantiate on the saved file, undone ($out)"
else
  bad "edit street_winter: tree edits: $out $(tail -5 "$tdir/log" 2>/dev/null)"
fi

# ---- the view's handles (env_handles.h): the street's bench turned a quarter round by its turn handle, the
# lamppost scaled by its scale handle, and the bench, put in a group, turned back inside it (a nested node);
# each is what the drag asked (the angle and the ratio of distances from the pivot), the export equals
# `instantiate` on the saved file, and five undos give the loaded scene's meshes back. A trash can placed
# "on the surface" stands on the pavement slab's top, not the road under it. The Outliner's eye hides the
# bus shelter in the view (fewer static triangles drawn, as many again when shown) but not in the export.
# Every palette picture shows its type (the mesh covers part of it, not all).
hdir="$tmp/env-handles"
mkdir -p "$hdir"
cp -r "$root/assets" "$hdir/assets"
cat >"$hdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "export", "path": "$hdir/loaded.glb"},
 {"action": "env_handle", "node": 12, "handle": "turn", "to": [3.4, 7.6], "steps": 6},
 {"action": "env_handle", "node": 10, "handle": "scale", "to": [3.4, 4.6], "steps": 4},
 {"action": "env_tree", "op": "group", "node": [12]},
 {"action": "env_handle", "node": [12, 0], "handle": "turn", "to": [2.4, 8.6], "steps": 6, "snap": true},
 {"action": "env_add", "type": "trash_can", "at": [3.0, 4.3], "on_surface": true},
 {"action": "view", "target": [5.0, 7.0, 0.0], "distance": 9.0, "yaw_deg": -100, "pitch_deg": 50},
 {"action": "screenshot", "path": "$hdir/handles.png", "ui": true},
 {"action": "set_visible", "node": 11, "visible": false},
 {"action": "export", "path": "$hdir/edited.glb"},
 {"action": "set_visible", "node": 11, "visible": true},
 {"action": "save"},
 {"action": "undo"}, {"action": "undo"}, {"action": "undo"}, {"action": "undo"}, {"action": "undo"},
 {"action": "export", "path": "$hdir/undone.glb"},
 {"action": "wait_idle"}]
EOF
if edit_and_instantiate "$hdir" street_winter.json 960x540 &&
   out="$(python3 - "$hdir" "$root/tests/gui" <<'PY' 2>&1
import json, math, sys
sys.path.insert(0, sys.argv[2])
from env_meshes import env_meshes
d = sys.argv[1]
stats = json.load(open(d + "/stats.json"))
acts = [a for a in stats["actions"] if a["action"] in ("env_handle", "env_tree")]
assert len(acts) == 4 and all(a.get("ok", True) for a in acts), acts
hide, show = [a for a in stats["actions"] if a["action"] == "set_visible"]
assert hide["static_triangles_after"] < hide["static_triangles_before"], hide
assert show["static_triangles_after"] == hide["static_triangles_before"], (hide, show)
turn, scale, _, nested = acts
assert turn["moves"] > 0 and scale["moves"] > 0 and nested["moves"] > 0, acts
# The bench (origin 3.4, 8.6, turned 180): its handle dragged to straight south of the origin turns it to -90.
assert abs(turn["yaw_deg"] - (-90.0)) < 0.01, turn
assert turn["undo_name"] == "Turn object", turn["undo_name"]
# The lamppost (origin 2.0, 4.6): scaled by the ratio of the distances from its origin.
want = math.dist([3.4, 4.6], [2.0, 4.6]) / math.dist(scale["from"][:2], [2.0, 4.6])
assert abs(scale["scale"] - want) < 1e-3, (scale["scale"], want)
assert scale["undo_name"] == "Scale object", scale["undo_name"]
# Inside its group, dragged back to the west and snapped: the bench faces 180 again, in the world.
assert abs(nested["yaw_deg"] % 360 - 180.0) < 0.01, nested
saved = json.load(open(d + "/assets/scenes/street_winter.json"))["environment"]["tree"]
assert "group" in saved[12], saved[12]
assert env_meshes(d + "/edited.glb") == env_meshes(d + "/saved.glb"), "the export differs from instantiate"
assert env_meshes(d + "/undone.glb") == env_meshes(d + "/loaded.glb"), "five undos did not give the scene back"
placed = [a for a in stats["actions"] if a["action"] == "env_add"][0]
assert placed["ok"] and abs(placed["at"][2] - 0.12) < 0.005, placed["at"]
palette = placed["environment"]["palette_coverage"]
assert len(palette) == 11 and all(0.01 < c < 0.9 for c in palette), palette
print("turned to -90, scaled %.3f, turned back inside a group; a trash can on a slab at z %.3f; export as instantiate; undone"
      % (scale["scale"], placed["at"][2]))
PY
)"; then
  ok "edit street_winter: turned and scaled by the view's handles (a nested node too), placed on a slab, hidden in the view only, palette pictures drawn, exported as instantiate on the saved file, undone ($out)"
else
  bad "edit street_winter: handles: $out $(tail -5 "$hdir/log" 2>/dev/null)"
fi

# ---- the paper's Fig. 3, "a four step creation of a winter scene", rebuilt in the editor from a street
# with the type library and nothing placed: street pieces and a tree; global snow; a lamppost; a bench; a
# bus shelter over it that keeps it dry; footprints. After every step the editor saves and exports, and
# `instantiate` on the saved file writes the same environment meshes.
fdir="$tmp/fig3"
mkdir -p "$fdir"
cp -r "$root/assets" "$fdir/assets"
step() { echo " {\"action\": \"save_as\", \"path\": \"$fdir/step$1.json\"}, {\"action\": \"export\", \"path\": \"$fdir/step$1.glb\"},"; }
cat >"$fdir/script.json" <<EOF
[{"frame": 1, "action": "wait_idle"},
 {"action": "env_add", "type": "road_segment", "at": [1.667, 1.667], "scale": 0.8333},
 {"action": "env_add", "type": "road_segment", "at": [5.0, 1.667], "scale": 0.8333},
 {"action": "env_add", "type": "road_segment", "at": [8.333, 1.667], "scale": 0.8333},
 {"action": "env_add", "type": "pavement_slab", "at": [1, 4.333], "yaw_deg": 180},
 {"action": "env_add", "type": "pavement_slab", "at": [3, 4.333], "yaw_deg": 180},
 {"action": "env_add", "type": "pavement_slab", "at": [5, 4.333], "yaw_deg": 180},
 {"action": "env_add", "type": "pavement_slab", "at": [7, 4.333], "yaw_deg": 180},
 {"action": "env_add", "type": "pavement_slab", "at": [9, 4.333], "yaw_deg": 180},
 {"action": "env_add", "type": "tree", "at": [8.0, 8.3], "yaw_deg": 20},
$(step 1)
 {"action": "env_global", "channel": "snow", "value": 0.12},
 {"action": "env_global", "channel": "icicles", "value": 1.0},
 {"action": "env_global", "channel": "temperature", "value": -3.0},
 {"action": "env_global", "channel": "humidity", "value": 0.2},
$(step 2)
 {"action": "env_add", "type": "lamppost", "at": [2.0, 4.6, 0.12], "yaw_deg": 180},
$(step 3)
 {"action": "env_add", "type": "bench", "at": [6.6, 6.5], "yaw_deg": 180},
$(step 4)
 {"action": "env_add", "type": "bus_shelter", "at": [6.6, 6.7], "yaw_deg": 180},
 {"action": "env_view", "channel": "shelter", "height": 0.3},
$(step 5)
 {"action": "env_view", "channel": "off"},
 {"action": "footprints", "points": [[0.6, 6.2], [3.0, 6.5], [5.2, 7.6]]},
 {"action": "view", "target": [5.0, 6.0, 0.5], "distance": 9, "yaw_deg": -110, "pitch_deg": 35},
 {"action": "screenshot", "path": "$fdir/step6.png", "overlays": false},
$(step 6)
 {"action": "wait_idle"}]
EOF
if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$fdir/assets/scenes/street_winter_start.json" --frames 3 \
     --size 960x540 --cache "$cache" --config "$fdir/config" --replay "$fdir/script.json" --stats "$fdir/stats.json" \
     >"$fdir/log" 2>&1; then
  fails=""
  for k in 1 2 3 4 5 6; do
    "$bin" instantiate "$fdir/step$k.json" -o "$fdir/cli$k.glb" --cache "$cache" >/dev/null 2>&1 &&
      python3 "$root/tests/gui/env_meshes.py" "$fdir/step$k.glb" "$fdir/cli$k.glb" >/dev/null 2>&1 || fails="$fails $k"
  done
  if [ -z "$fails" ] && out="$(python3 - "$fdir" "$root/tests/gui" <<'PY' 2>&1
import json, sys
sys.path.insert(0, sys.argv[2])
from env_meshes import env_meshes, triangles
d = sys.argv[1]
stats = json.load(open(d + "/stats.json"))
assert all(a.get("ok", True) for a in stats["actions"]), [a for a in stats["actions"] if not a.get("ok", True)]
snow = [triangles("%s/step%d.glb" % (d, k), "snow/") for k in range(1, 7)]
bench = [triangles("%s/step%d.glb" % (d, k), "snow/bench/") for k in range(1, 7)]
icicles = [triangles("%s/step%d.glb" % (d, k), "icicles/") for k in range(1, 7)]
assert snow[0] == 0 and snow[1] > 0, snow           # no snow before the global field, then everywhere
assert icicles[1] == 0 and icicles[2] > 0, icicles   # the lamppost's lamp grows icicles in the cold
assert bench[3] > 0 and bench[4] < 0.1 * bench[3], bench  # the shelter keeps the bench dry
assert env_meshes(d + "/step6.glb") != env_meshes(d + "/step5.glb")  # footprints change the snow
view = [a for a in stats["actions"] if a["action"] == "env_view"][0]["channel_map"]
assert view["channel"] == "shelter" and view["lo"] < 0.5 and view["hi"] == 1.0, view  # sheltered under the roof
print("6 steps as instantiate writes them; snow triangles %s; bench snow %d -> %d under the shelter" % (
    snow, bench[3], bench[4]))
PY
)"; then
    ok "edit: the paper's Fig. 3 winter scene built step by step in the editor, each step as instantiate on its saved file ($out)"
  else
    bad "edit: Fig. 3 sequence: steps differing from instantiate:${fails:- none} ${out:-}"
  fi
else
  bad "edit: Fig. 3 sequence: $(tail -5 "$fdir/log")"
fi

# The particle tool by real X input: an attractor dragged in the view with the mouse, then Ctrl+Z; the
# generator's dot dragged; a key of a(t) dragged on the Particles window's plot, then Ctrl+Z; New system,
# then Remove system.
if command -v xdotool >/dev/null 2>&1; then
  xwork="$tmp/driven-particles"
  mkdir -p "$xwork"
  cp -r "$root/assets" "$xwork/assets"
  if out="$(xvfb-run -a -s "-screen 0 1600x900x24" bash "$root/tests/gui/driven_particles.sh" "$bin" \
              "$xwork/assets/scenes/meadow_strands.json" "$xwork" "$cache" 2>&1)" &&
     out="$(python3 - "$xwork" <<'PY' 2>&1
import json, sys
d = sys.argv[1]
stats = {n: json.load(open("%s/%s.json" % (d, n))) for n in ("start.stats", "dragged", "undone", "generator", "curve", "curve_undone", "new_system", "removed", "placed", "place_undone")}
start, dragged, undone = (stats[n]["particles"] for n in ("start.stats", "dragged", "undone"))
a0, a1, a2 = (p["systems"][0]["attractors"][1] for p in (start, dragged, undone))
assert dragged["selected_attractor"] == 1, dragged
assert a1[0] - a0[0] > 0.15 and abs(a1[1] - a0[1]) < 0.05 and a1[2] == a0[2], (a0, a1)
last = dragged["last"]
assert last["ok"] and last["incremental"] and last["reused"] > last["recomputed"], last
assert a2 == a0, ("Ctrl+Z did not put the attractor back", a0, a2)
assert dragged["systems"][1]["attractors"][1][0] - start["systems"][1]["attractors"][1][0] > 0.15, "the shared file's other entry did not follow"
# The generator's dot dragged 100 px right: its centre moves along x, one undo step, the strands re-grown.
g0, g1 = (stats[n]["particles"]["systems"][0]["generators"][0] for n in ("undone", "generator"))
assert stats["generator"]["particles"]["selected_handle"] == {"part": "generator", "index": 0, "tilt": False}, stats["generator"]["particles"]
assert g1[0] - g0[0] > 0.15 and abs(g1[1] - g0[1]) < 0.05 and g1[2] == g0[2], (g0, g1)
assert stats["generator"]["document"]["undo_name"] == "Move generator", stats["generator"]["document"]
assert stats["generator"]["particles"]["last"]["ok"], stats["generator"]["particles"]["last"]
# The a(t) key dragged on the window's plot: later and negative (repelling), one undo step that Ctrl+Z takes back.
k0, k1, k2 = (stats[n]["particles"]["systems"][0]["charge_keys"][1] for n in ("generator", "curve", "curve_undone"))
assert k0 == [[0, 3.0]] and len(k1) == 1 and k1[0][0] > 4 and k1[0][1] < 0, (k0, k1)
assert stats["curve"]["document"]["undo_name"] == "Edit a(t)", stats["curve"]["document"]
assert k2 == k0 and stats["curve_undone"]["document"]["undo_name"] == "Move generator", (k2, stats["curve_undone"]["document"])
# New system: a third system named "strands" at the view's centre, its file written beside the project,
# one undo step, its strands grown.
new = stats["new_system"]
names = [s["name"] for s in new["particles"]["systems"]]
assert names == ["meadow_grass_strands", "meadow_grass_strands_2", "strands"], names
assert new["document"]["undo_name"] == "Add particle system", new["document"]
centre = new["viewport"]["camera"]["target"]
assert abs(new["particles"]["systems"][2]["generators"][0][0] - centre[0]) < 1e-3, (new["particles"]["systems"][2], centre)
written = json.load(open("%s/assets/scenes/particles/strands.json" % d))
assert written["name"] == "strands" and written["generators"][0]["count"] == 600, written
assert new["particles"]["last"]["ok"] and new["particles"]["last"]["strands"] > start["last"]["strands"], new["particles"]["last"]
# Remove system: back to the two loaded systems, one undo step; the new file stays on disk.
removed = stats["removed"]
assert [s["name"] for s in removed["particles"]["systems"]] == names[:2], removed["particles"]["systems"]
assert removed["document"]["undo_name"] == "Remove particle system", removed["document"]
# The two systems as before New system, their strands taken whole from their records.
before_new = stats["curve_undone"]["particles"]["last"]
assert removed["particles"]["last"]["strands"] == before_new["strands"], (removed["particles"]["last"], before_new)
assert removed["particles"]["last"]["recomputed"] == 0, removed["particles"]["last"]
# Click to place: one more generator in the shown system, its dot (on the ground under its centre: it
# lies on the terrain) where the view was clicked, one undo step "Place generator"; Ctrl+Z takes it away.
placed, place_undone = stats["placed"]["particles"], stats["place_undone"]["particles"]
shown = placed["selected_system"]
gens_before = removed["particles"]["systems"][shown]["generators"]
gens = placed["systems"][shown]["generators"]
assert len(gens) == len(gens_before) + 1 and gens[:-1] == gens_before, (gens_before, gens)
assert placed["selected_handle"] == {"part": "generator", "index": len(gens) - 1, "tilt": False}, placed["selected_handle"]
dot = [h["px"] for h in placed["handles_px"] if h["part"] == "generator" and h["index"] == len(gens) - 1 and not h["tilt"]]
assert dot and abs(dot[0][0] - 1000) < 4 and abs(dot[0][1] - 600) < 4, (dot, "not where the view was clicked")
assert stats["placed"]["document"]["undo_name"] == "Place generator", stats["placed"]["document"]
assert placed["last"]["ok"] and placed["last"]["strands"] > removed["particles"]["last"]["strands"], placed["last"]
assert place_undone["systems"][shown]["generators"] == gens_before, place_undone["systems"][shown]
print("moved %.2f m by the mouse, %d %% re-grown; generator moved %.2f m; a(t) key to step %d, charge %.2f; new system: %d strands in all; a generator placed at (%.2f, %.2f)" % (
    a1[0] - a0[0], 100 * last["recomputed"] // (last["recomputed"] + last["reused"]), g1[0] - g0[0], k1[0][0], k1[0][1],
    new["particles"]["last"]["strands"], gens[-1][0], gens[-1][1]))
PY
)"; then
    ok "edit meadow_strands: an attractor, a generator and an a(t) key dragged, a system added and removed by real X input ($out)"
  else
    bad "edit meadow_strands: attractor drag by X input: $out $(tail -3 "$xwork/session.log" 2>/dev/null)"
  fi
else
  bad "xdotool is not installed: the particle tool's driven test needs it (scripts/install-deps.sh)"
fi

# The environment tools by real X input (issue 13): a bench placed from the Environment window's palette,
# dragged in the view, footprints walked with the weather brush, a trash can placed by a click on its
# picture and one in the view, then four Ctrl+Z.
if command -v xdotool >/dev/null 2>&1; then
  vwork="$tmp/driven-environment"
  mkdir -p "$vwork"
  cp -r "$root/assets" "$vwork/assets"
  if out="$(xvfb-run -a -s "-screen 0 1600x900x24" bash "$root/tests/gui/driven_environment.sh" "$bin" \
              "$vwork/assets/scenes/street_winter.json" "$vwork" "$cache" 2>&1)" &&
     out="$(python3 - "$vwork" <<'PY' 2>&1
import json, sys
d = sys.argv[1]
start, added, moved, walked, placed, undone = (json.load(open("%s/%s.json" % (d, n)))["environment"]
                                               for n in ("start.stats", "added", "moved", "walked", "placed", "undone"))
assert added["objects"] == start["objects"] + 1 and added["tree"][-1]["object"] == "bench", added["tree"][-1]
a, m = added["tree"][-1]["at"], moved["tree"][-1]["at"]
assert m[0] - a[0] > 0.5 and abs(m[1] - a[1]) < 0.05 and m[2] == a[2], (a, m)
steps = walked["local_fields"] - moved["local_fields"]
assert steps >= 4 and walked["brush"] == "footprints", walked
assert placed["objects"] == walked["objects"] + 1 and placed["tree"][-1]["object"] == "trash_can", placed["tree"][-1]
assert placed["tree"][-1]["at"][2] > 0.05, ("not on the pavement slab", placed["tree"][-1])
assert undone["tree"] == start["tree"] and undone["local_fields"] == start["local_fields"], "four undos did not give the scene back"
assert all(s["settled"] for s in (added, moved, walked, placed, undone))
print("bench placed, moved %.2f m, %d footprints, a trash can placed on a slab at z %.2f, undone"
      % (m[0] - a[0], steps, placed["tree"][-1]["at"][2]))
PY
)"; then
    ok "edit street_winter: a bench placed, dragged, footprints walked and a trash can placed from its picture by real X input, and undone ($out)"
  else
    bad "edit street_winter: driven environment session: $out $(tail -5 "$vwork/session.log" 2>/dev/null)"
  fi
else
  bad "xdotool is not installed: the environment tools' driven test needs it (scripts/install-deps.sh)"
fi

# An interactive session driven by real X input (xdotool): mouse tools, picking, shortcuts and the
# unsaved-changes dialog (driven_session.sh). On a copy of the assets, since it saves the project.
if command -v xdotool >/dev/null 2>&1; then
  dwork="$tmp/driven"
  mkdir -p "$dwork"
  cp -r "$root/assets" "$dwork/assets"
  if out="$(xvfb-run -a -s "-screen 0 1280x720x24" bash "$root/tests/gui/driven_session.sh" "$bin" \
              "$dwork/assets/scenes/meadow.json" "$dwork" 2>&1)" &&
     "$bin" instantiate "$dwork/assets/scenes/meadow.json" -o "$dwork/out.glb" --stats "$dwork/cli.json" \
       --cache "$dwork/cache" >/dev/null 2>&1 &&
     out="$(python3 "$root/tests/gui/check_edit.py" driven "$root/assets/scenes/meadow.json" \
              "$dwork/assets/scenes/meadow.json" "$dwork/session.stats.json" "$dwork/cli.json" "$dwork" 2>&1)"; then
    ok "edit meadow: driven by X input ($out)"
  else
    bad "edit meadow: driven by X input: $out $(tail -3 "$dwork/session.log" 2>/dev/null)"
  fi
else
  bad "xdotool is not installed: the driven-session test needs it (scripts/install-deps.sh)"
fi

# kill -9 while editing: an interactive session paints, autosaves every second, and is killed; the next
# start recovers the autosave with the painted primitives and the same instances.
kconfig="$tmp/kill-config"
cat >"$tmp/kill.json" <<EOF
[{"frame": 1, "action": "paint_stroke", "type": "rock", "points": [[-1, -9], [2, -9]], "radius": 1.0},
 {"action": "wait_idle"}]
EOF
xvfb-run -a -s "-screen 0 1280x720x24" sh -c 'echo $$ >"$0"; exec "$@"' "$tmp/kill.pid" "$bin" edit "$meadow" \
  --size 640x360 --cache "$cache" --config "$kconfig" --replay "$tmp/kill.json" --stats "$tmp/kill.stats.json" \
  --autosave-interval 1 >"$tmp/kill.log" 2>&1 &
runner=$!
for _ in $(seq 1 120); do [ -s "$tmp/kill.stats.json" ] && break; sleep 0.5; done
sleep 2.5  # more than the autosave interval after the stroke's last edit
if [ -s "$tmp/kill.stats.json" ] && ls "$kconfig"/recovery/*.meta.json >/dev/null 2>&1; then
  kill -9 "$(cat "$tmp/kill.pid")"
  wait "$runner" 2>/dev/null
  if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$meadow" --recover yes --frames 5 --size 640x360 \
       --cache "$cache" --config "$kconfig" --stats "$tmp/recovered.stats.json" >"$tmp/recovered.log" 2>&1 &&
     out="$(python3 "$root/tests/gui/check_edit.py" recovered "$tmp/kill.stats.json" "$tmp/recovered.stats.json" 2>&1)"; then
    ok "edit: kill -9 while editing, then --recover yes ($out)"
  else
    bad "edit: recovery after kill -9: ${out:-$(tail -5 "$tmp/recovered.log")}"
  fi
else
  [ -f "$tmp/kill.pid" ] && kill -9 "$(cat "$tmp/kill.pid")" 2>/dev/null
  wait "$runner" 2>/dev/null
  bad "edit: the interactive session wrote no statistics or no autosave: $(tail -5 "$tmp/kill.log")"
fi
# kill -9 while editing the environment: the bench moved and footprints walked, autosaved, killed; the
# recovered session holds the same tree and exports the same environment meshes (effects).
econfig="$tmp/kill-env-config"
ework="$tmp/kill-env"
mkdir -p "$ework"
cat >"$ework/edit.json" <<EOF
[{"frame": 1, "action": "env_move", "node": 12, "to": [6.6, 6.9], "steps": 3},
 {"action": "footprints", "points": [[1.0, 6.6], [4.0, 6.6]]},
 {"action": "export", "path": "$ework/edited.glb"},
 {"action": "wait_idle"}]
EOF
echo "[{\"frame\": 1, \"action\": \"export\", \"path\": \"$ework/recovered.glb\"}]" >"$ework/recover.json"
xvfb-run -a -s "-screen 0 1280x720x24" sh -c 'echo $$ >"$0"; exec "$@"' "$ework/pid" "$bin" edit "$street" \
  --size 640x360 --cache "$cache" --config "$econfig" --replay "$ework/edit.json" --stats "$ework/edit.stats.json" \
  --autosave-interval 1 >"$ework/log" 2>&1 &
runner=$!
for _ in $(seq 1 120); do [ -s "$ework/edit.stats.json" ] && break; sleep 0.5; done
sleep 2.5  # more than the autosave interval after the last edit
if [ -s "$ework/edit.stats.json" ] && ls "$econfig"/recovery/*.meta.json >/dev/null 2>&1; then
  kill -9 "$(cat "$ework/pid")"
  wait "$runner" 2>/dev/null
  if xvfb-run -a -s "-screen 0 1280x720x24" "$bin" edit "$street" --recover yes --replay "$ework/recover.json" \
       --frames 3 --size 640x360 --cache "$cache" --config "$econfig" --stats "$ework/recovered.stats.json" \
       >"$ework/recovered.log" 2>&1 &&
     out="$(python3 "$root/tests/gui/env_meshes.py" "$ework/edited.glb" "$ework/recovered.glb" 2>&1)" &&
     python3 -c 'import json, sys; a, b = (json.load(open(p))["environment"] for p in sys.argv[1:]); assert a["tree"] == b["tree"] and a["local_fields"] == b["local_fields"] > 19, (a, b)' \
       "$ework/edit.stats.json" "$ework/recovered.stats.json" 2>>"$ework/recovered.log"; then
    ok "edit street_winter: kill -9 after environment edits, then --recover yes: the same tree and effects ($out)"
  else
    bad "edit street_winter: environment recovery after kill -9: ${out:-} $(tail -5 "$ework/recovered.log")"
  fi
else
  [ -f "$ework/pid" ] && kill -9 "$(cat "$ework/pid")" 2>/dev/null
  wait "$runner" 2>/dev/null
  bad "edit street_winter: the environment session wrote no statistics or no autosave: $(tail -5 "$ework/log")"
fi

# --recover yes without an autosave: exit 1, says so. The editor's own exit status is recorded by a wrapper:
# xvfb-run returns 5 when it cannot clean up its temporary folder after a client that exits at once, which
# says nothing about the editor.
out="$(xvfb-run -a -s "-screen 0 1280x720x24" sh -c '"$0" "$@"; echo $? >"'"$tmp/recover.rc"'"' \
       "$bin" edit "$meadow" --recover yes --frames 1 --cache "$cache" --config "$tmp/empty-config" 2>&1)"
rc="$(cat "$tmp/recover.rc" 2>/dev/null || echo none)"
if [ "$rc" -eq 1 ] && grep -q "no autosave" <<<"$out"; then ok "edit: --recover yes without an autosave fails clearly"; else
  bad "edit --recover yes without an autosave (exit $rc): $out"; fi

# No display: a clear message and exit 1.
out="$(env -u DISPLAY -u WAYLAND_DISPLAY "$bin" edit "$root/assets/scenes/rock_pile.json" --frames 1 2>&1)"
rc=$?
if [ "$rc" -eq 1 ] && grep -q "cannot open a display" <<<"$out"; then ok "edit: no display gives exit 1 and says so"; else
  bad "edit without a display (exit $rc): $out"; fi
# Bad command lines: exit 2.
out="$("$bin" edit "$root/assets/scenes/rock_pile.json" --size 12 2>&1)"; rc=$?
if [ "$rc" -eq 2 ] && grep -q -- "--size" <<<"$out"; then ok "edit: bad --size is a usage error"; else bad "edit --size 12 (exit $rc): $out"; fi

if [ -n "${UG_GUI_KEEP:-}" ]; then mkdir -p "$UG_GUI_KEEP" && cp "$tmp"/*.png "$tmp"/*.json "$UG_GUI_KEEP"/ 2>/dev/null; fi
echo "gui tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
