#!/usr/bin/env python3
"""Checks of scripted editor runs (tests/gui/run_gui_tests.sh): the per-action statistics of `undergrowth
edit --replay --stats` (viewer.cpp, "Statistics") and screenshots taken before and after a stroke.

usage: check_edit.py strokes STATS.json CLI_STATS.json     paint, sculpt, undo/redo, save_as, failed save
       check_edit.py diff BEFORE.png AFTER.png                the stroke shows in the centre, nowhere far off
       check_edit.py recovered PRE_KILL_STATS.json RECOVERED_STATS.json
       check_edit.py move STATS.json CLI_STATS.json           a painted disc dragged with the Select tool
       check_edit.py pile_paint STATS.json                    a held sculpt brush, paint onto the pile
       check_edit.py piles STATS.json CLI_STATS.json ORIGINAL.json SAVED.json   held sculpt from three views
       check_edit.py driven ORIGINAL.json SAVED.json STATS.json CLI_STATS.json WORKDIR   driven_session.sh
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_screenshot import decode_png  # noqa: E402


def actions(stats, name):
    return [a for a in stats["actions"] if a["action"] == name]


def check_stroke(a, kind, typ):
    assert a["stamps"] > 0, (kind, a["stamps"])
    assert a["inside_before"][typ] == 0 or kind == "sculpt", (kind, "the area had %s already" % typ, a["inside_before"])
    assert a["inside_after"][typ] > a["inside_before"][typ], (kind, "no new %s inside the stroke's box" % typ,
                                                             a["inside_before"], a["inside_after"])
    # Nothing changed outside the box, for any type.
    assert a["outside_before"] == a["outside_after"], (kind, "instances changed outside the box",
                                                       a["outside_before"], a["outside_after"])
    assert len(a["stamp_to_frame_ms"]) == a["stamps"], (kind, a["stamp_to_frame_ms"], a["stamps"])
    return "%s: %d stamps, %s %d -> %d inside, outside unchanged; stamp->frame max %.0f ms" % (
        kind, a["stamps"], typ, a["inside_before"][typ], a["inside_after"][typ], max(a["stamp_to_frame_ms"]))


def check_uploads(a, kind):
    """Per-tile residency: a stroke's live results re-upload only tiles near the stroke."""
    ups = a["uploads"]
    assert ups and not any(u["full"] for u in ups), (kind, "no incremental upload, or a full one", ups)
    total = a["tiles_resident"]
    biggest = max(u["tiles"] for u in ups)
    assert 0 < biggest * 20 < total, (kind, "a stamp re-uploaded %d of %d tiles" % (biggest, total))
    s = a["tile_size_m"]
    lo, hi = a["box"]["min"], a["box"]["max"]
    for t in a["uploaded_tiles"]:
        cell_lo, cell_hi = [c * s for c in t], [(c + 1) * s for c in t]
        assert all(cell_hi[i] >= lo[i] and cell_lo[i] <= hi[i] for i in range(3)), (
            kind, "uploaded tile %s is outside the stroke's box" % t, a["box"])
    return "%s: at most %d of %d tiles uploaded per live result, %d tiles in all, all inside the box" % (
        kind, biggest, total, len(a["uploaded_tiles"]))


def strokes(stats_path, cli_path):
    s = json.load(open(stats_path))
    out = []
    paint, sculpt = actions(s, "paint_stroke")[0], actions(s, "sculpt_stroke")[0]
    out.append(check_stroke(paint, "paint", "rock"))
    out.append(check_stroke(sculpt, "sculpt", "rock"))
    out.append(check_uploads(paint, "paint"))
    out.append(check_uploads(sculpt, "sculpt"))
    undos, redos = actions(s, "undo"), actions(s, "redo")
    assert len(undos) == 2 and len(redos) == 2, s["actions"]
    # Undo gives back exactly the instance set before the stroke (hash and counts per type), redo the after.
    for stroke, undo, redo in ((paint, undos[0], redos[0]), (sculpt, undos[1], redos[1])):
        assert undo["ok"] and redo["ok"]
        assert undo["instance_store_hash_after"] == stroke["instance_store_hash_before"], (undo, stroke)
        assert undo["per_type_after"] == stroke["per_type_before"], (undo["per_type_after"], stroke["per_type_before"])
        assert redo["instance_store_hash_after"] == stroke["instance_store_hash_after"], (redo, stroke)
        assert redo["per_type_after"] == stroke["per_type_after"]
    out.append("undo restores the exact set (hash), redo the stroke's")
    saves = actions(s, "save_as")
    # The failed save changes nothing (still dirty, same instances) and the editor goes on: the good save
    # and the actions after it ran.
    failed, saved = saves
    assert not failed["ok"] and failed["dirty"] and failed["error"], failed
    assert failed["instance_store_hash_after"] == failed["instance_store_hash_before"]
    assert any("Save failed" in m for m in s["messages"]), s["messages"]
    assert saved["ok"] and not saved["dirty"], saved
    assert s["actions"][-1]["action"] == "wait_idle", s["actions"][-1]
    cli = json.load(open(cli_path))
    assert cli["instances"] == s["instances"] == saved["instances_after"], (cli["instances"], s["instances"])
    assert cli["instances_per_type"] == s["instances_per_type"], (cli["instances_per_type"], s["instances_per_type"])
    out.append("saved file re-instantiated by the CLI: %d instances, same per type" % cli["instances"])
    out.append("failed save reported, document still dirty")
    print("; ".join(out))


def mean_abs_diff(a, b, x0, x1, y0, y1):
    n, total = 0, 0
    for y in range(y0, y1):
        ra, rb = a[y], b[y]
        for x in range(x0, x1):
            pa, pb = ra[x], rb[x]
            total += abs(pa[0] - pb[0]) + abs(pa[1] - pb[1]) + abs(pa[2] - pb[2])
            n += 3
    return total / n


def diff(before_path, after_path):
    w, h, a = decode_png(before_path)
    w2, h2, b = decode_png(after_path)
    assert (w, h) == (w2, h2)
    centre = mean_abs_diff(a, b, int(0.4 * w), int(0.6 * w), int(0.4 * h), int(0.6 * h))
    corner = mean_abs_diff(a, b, 0, int(0.15 * w), int(0.85 * h), h)
    assert centre > 8.0, "the stroke area barely changed: mean |diff| %.1f" % centre
    assert corner < 2.0, "far from the stroke the picture changed: mean |diff| %.1f" % corner
    print("stroke area mean |diff| %.1f, far corner %.2f" % (centre, corner))


def recovered(pre_path, rec_path):
    pre, rec = json.load(open(pre_path)), json.load(open(rec_path))
    assert rec["document"]["recovered"] and rec["document"]["dirty"], rec["document"]
    assert rec["document"]["user_primitives"] == pre["document"]["user_primitives"] > 1, (
        rec["document"], pre["document"])
    assert rec["instances"] == pre["instances"], (rec["instances"], pre["instances"])
    assert rec["instance_store_hash"] == pre["instance_store_hash"]
    print("recovered %d user primitives, %d instances as before the kill" % (
        rec["document"]["user_primitives"], rec["instances"]))


def move(stats_path, cli_path):
    s = json.load(open(stats_path))
    paint, mv, saved, undo = (actions(s, n)[0] for n in ("paint_stroke", "move", "save_as", "undo"))
    assert paint["stamps"] == 1 and paint["inside_after"]["rock"] > 0, paint
    dx = [b - a for a, b in zip(mv["from_center"], mv["to_center"])]
    assert abs(dx[0] - 4.0) < 1e-3 and abs(dx[1]) < 1e-3 and abs(dx[2]) < 1e-3, ("moved by", dx)
    assert mv["moves"] >= 1, mv
    # The rocks went with the disc: the set changed, only inside the old and new supports, and about as
    # many rocks stand at the new place as the disc made at the old one (same disc, similar ground). The
    # meadow has 4 Ghost Tile variants: the new place's tiles hold other variants than the old one's (with
    # one variant, 4 m = 8 tiles gave the very same candidates), so its count is a fresh draw: measured
    # 217 -> 133 rocks with one variant, 236 -> 117 with four, hence 0.4 rather than 0.5 below.
    assert mv["instance_store_hash_after"] != mv["instance_store_hash_before"], mv
    assert mv["outside_before"] == mv["outside_after"], ("changed outside", mv["outside_before"], mv["outside_after"])
    base, before, after = (paint["per_type_before"]["rock"], mv["per_type_before"]["rock"],
                           mv["per_type_after"]["rock"])
    assert 0.4 * (before - base) <= after - base <= 2.0 * (before - base), (base, before, after)
    assert len(mv["stamp_to_frame_ms"]) >= 1, mv
    # The whole drag is one undo step: undo gives back exactly the set before the drag.
    assert undo["ok"] and undo["instance_store_hash_after"] == mv["instance_store_hash_before"], (undo, mv)
    cli = json.load(open(cli_path))
    assert cli["instances_per_type"] == saved["per_type_after"], (cli["instances_per_type"], saved["per_type_after"])
    print("disc moved by (4, 0, 0) in %d drag steps: rock %d -> %d, outside unchanged; one undo step gives the set "
          "back; saved file = CLI" % (mv["moves"], before, after))


def cones(node):
    """Sculpted piles in a saved density tree: vertical segments narrowing upwards (sculpt_pile.h). A
    polyline is saved as segments too, so "segment" alone does not tell them apart."""
    if isinstance(node, dict):
        seg = node.get("segment")
        found = 1 if (isinstance(seg, dict) and seg["a"][:2] == seg["b"][:2] and seg["b"][2] > seg["a"][2]
                      and seg.get("end_radius", seg["radius"]) < seg["radius"]) else 0
        return found + sum(cones(v) for v in node.values())
    if isinstance(node, list):
        return sum(cones(v) for v in node)
    return 0


def check_pile(a, xy, label, tolerance=0.2):
    """A sculpt stroke's pile (viewer.cpp "pile", measured from the rock field's isosurface above the ground):
    centred on the brush's ground point, as steep as the type's angle of repose, one primitive."""
    pile = a["pile"]
    assert pile["found"], (label, "no pile", pile)
    off = math.hypot(pile["centroid"][0] - xy[0], pile["centroid"][1] - xy[1])
    assert off < tolerance, (label, "pile centre %.3f m from the brush's ground point" % off, pile)
    want = math.tan(math.radians(pile["angle_of_repose_deg"]))
    ratio = pile["height"] / pile["radius"]
    assert abs(ratio / want - 1.0) <= 0.25, (label, "height / radius %.3f, tan(repose) %.3f" % (ratio, want), pile)
    # One unit: the stroke left one primitive (a cone grown in place), however many stamps it took.
    assert pile["primitives"] == 1, (label, pile)
    assert a["user_primitives_after"] - a["user_primitives_before"] == 1, (label, a["user_primitives_before"],
                                                                          a["user_primitives_after"])
    text = "%s: %d stamps -> 1 primitive, centre %.3f m off, h %.2f r %.2f h/r %.3f (tan %g = %.3f)" % (
        label, a["stamps"], off, pile["height"], pile["radius"], ratio, pile["angle_of_repose_deg"], want)
    if "instances" in pile:
        # The rocks the pile made (none stood there before) sit on the same cone: centred on the ground
        # point (the slopes' downhill pull of a cone's volume reaches 0.19 m here, hence 0.25 m), and the
        # highest one about tan(repose) radii up.
        inst, before = pile["instances"], pile["instances_before"]
        assert before["count"] == 0 and inst["count"] > 30, (label, before, inst)
        ioff = math.hypot(inst["centroid"][0] - xy[0], inst["centroid"][1] - xy[1])
        assert ioff < max(tolerance, 0.25), (label, "the rocks' centre is %.3f m off" % ioff, inst)
        itop = inst["top"] / pile["radius"]
        assert abs(itop / want - 1.0) <= 0.25, (label, "highest rock / radius %.3f" % itop, inst)
        text += "; %d rocks, their centre %.3f m off, the highest %.2f m up (%.3f radii)" % (
            inst["count"], ioff, inst["top"], itop)
    return text


def pile_paint(stats_path):
    s = json.load(open(stats_path))
    sculpt = actions(s, "sculpt_stroke")[0]
    on_pile, on_ground = actions(s, "paint_stroke")[1:3]
    pts = sculpt["stamp_points"]
    assert len(pts) == sculpt["stamps"] == 20, (len(pts), sculpt["stamps"])
    ground_z = pts[0][2]
    # Held still, every stamp feeds the same cone at the brush's ground point.
    assert all(p == pts[0] for p in pts), ("held stamps should all land at the brush", pts)
    out = check_pile(sculpt, (-6, -10), "held from above")
    top = sculpt["pile"]["height"]
    # Paint with the pile as surface lands on the pile's top; without, on the ground under it.
    zp, zg = on_pile["stamp_points"][0][2], on_ground["stamp_points"][0][2]
    assert zp > ground_z + 0.3 and abs(zg - ground_z) < 0.05, (zp, zg, ground_z)
    assert abs(zp - ground_z - top) < 0.1, ("paint should land on the pile's top", zp - ground_z, top)
    assert on_pile["inside_after"]["leaf_oak"] > on_pile["inside_before"]["leaf_oak"], on_pile
    assert on_pile["outside_before"] == on_pile["outside_after"], on_pile
    print("%s; paint lands %.2f m up on the pile (ground %.2f), leaves %d -> %d" % (
        out, zp - ground_z, zg - ground_z, on_pile["inside_before"]["leaf_oak"], on_pile["inside_after"]["leaf_oak"]))


def piles(stats_path, cli_path, original_path, saved_path):
    """Held sculpt strokes from an oblique, a side and a top view (rays from the camera, replay.h
    "from_camera"): the same cone under the brush from every view; one undo step; moved as a unit; saved."""
    s = json.load(open(stats_path))
    out = []
    sculpts = actions(s, "sculpt_stroke")
    assert len(sculpts) == 4, len(sculpts)
    for a, xy, label in zip(sculpts, ((-6, -10), (3, -12), (-12, 4)), ("oblique", "side", "top")):
        assert a["stamps"] == 40, (label, a["stamps"])
        out.append(check_pile(a, xy, label))
    heights = [a["pile"]["height"] for a in sculpts[:3]]
    assert max(heights) < 1.2 * min(heights), ("the view changed the pile", heights)
    # One undo step takes the whole stroke away (the exact set before it), redo brings it back.
    undo, redo = actions(s, "undo")[0], actions(s, "redo")[0]
    assert undo["ok"] and undo["instance_store_hash_after"] == sculpts[0]["instance_store_hash_before"], undo
    assert undo["per_type_after"] == sculpts[0]["per_type_before"], undo
    assert redo["ok"] and redo["instance_store_hash_after"] == sculpts[0]["instance_store_hash_after"], redo
    out.append("one undo removes the whole %d-stamp stroke (exact set), redo restores it" % sculpts[0]["stamps"])
    # The side pile moved by the Select tool as one primitive: its rocks go with it.
    mv = actions(s, "move")[0]
    assert mv["id"] in sculpts[1]["pile"]["ids"], (mv["id"], sculpts[1]["pile"])
    dx = [b - a for a, b in zip(mv["from_center"], mv["to_center"])]
    assert abs(dx[0] - 2.0) < 1e-3 and abs(dx[1]) < 1e-3, dx
    assert mv["instance_store_hash_after"] != mv["instance_store_hash_before"], mv
    out.append("the side pile moved by (2, 0) as one primitive")
    # A dragged stroke (through an oblique camera's rays) leaves a cone every radius / 3 of travel, all one
    # unit: grabbing one moves them all.
    dragged, mv2 = sculpts[3], actions(s, "move")[1]
    cone_ids = dragged["pile"]["ids"]
    assert len(cone_ids) >= 6, dragged["pile"]
    # Dragged slowly, the stroke pours a ridge on the ground whose height levels off where each cone's
    # material fills its 0.2 m stretch (sqrt(V / 0.2 m * tan 35°) = 0.39 m for this brush; 0.36 m on flat
    # ground in SculptTool.ASlowDragPoursARidgeOfSteadyHeightOnTheGround; here the pile's thickness is
    # measured above the sloping meadow, so its downhill flank adds the ground's drop: 0.64 m). It used to
    # stack cones on each other's flanks into a 2.5 m ramp.
    assert dragged["pile"]["height"] < 0.8, ("the dragged stroke climbs", dragged["pile"])
    # Dragged through the rays of an oblique camera, it still lies along the drag's ground line (y = -15),
    # not pulled towards the camera.
    assert abs(dragged["pile"]["centroid"][1] + 15.0) < 0.2, ("the ridge left the drag line", dragged["pile"])
    assert sorted(mv2["stroke_ids"]) == sorted(cone_ids), (mv2["stroke_ids"], cone_ids)
    assert len(mv2["from_centers"]) == len(cone_ids) == len(mv2["to_centers"]), mv2
    for a, b in zip(mv2["from_centers"], mv2["to_centers"]):
        assert abs(b[0] - a[0]) < 1e-3 and abs(b[1] - a[1] - 2.0) < 1e-3, (a, b)
    out.append("a dragged stroke of %d cones, a ridge %.2f m high, moved by (0, 2) as one unit" % (
        len(cone_ids), dragged["pile"]["height"]))
    # Saved and re-read: the rock density holds three cones (vertical, narrowing segments; the file had
    # none), and the CLI makes the same instances.
    rock = lambda doc: [t for t in doc["detail_types"] if t["name"] == "rock"][0]
    original, saved = json.load(open(original_path)), json.load(open(saved_path))
    before, after = cones(rock(original).get("density")), cones(rock(saved)["density"])
    assert before == 0 and after == 3 + len(cone_ids), (before, after)
    assert rock(saved)["angle_of_repose_deg"] == 35, rock(saved)
    cli = json.load(open(cli_path))
    saved_a = actions(s, "save_as")[0]
    assert saved_a["ok"] and cli["instances_per_type"] == saved_a["per_type_after"], (
        cli["instances_per_type"], saved_a["per_type_after"])
    out.append("saved: %d cones, the CLI re-instantiates %d instances as the editor" % (after, cli["instances"]))
    print("; ".join(out))


def driven(original_path, saved_path, stats_path, cli_path, work):
    s = json.load(open(stats_path))
    doc = s["document"]
    start = json.load(open(os.path.join(work, "session.start.json")))["document"]
    # Two discs painted, the pile undone, the first disc picked and deleted, a dragged sculpt stroke picked
    # and deleted as one, then saved from the dialog.
    # (Editable primitives include the file's own top-level ones, present from the start.)
    assert not doc["dirty"] and doc["user_primitives"] == start["user_primitives"] + 1, (start, doc)
    assert not s["messages"], s["messages"]
    original, saved = open(original_path).read(), open(saved_path).read()
    count = lambda text, kind: text.count('"%s"' % kind)
    assert count(saved, "disc") == count(original, "disc") + 1, ("user discs", count(original, "disc"),
                                                                  count(saved, "disc"))
    assert count(saved, "point") == count(original, "point"), ("the pile should be undone",
                                                                count(original, "point"), count(saved, "point"))
    assert cones(json.loads(saved)) == cones(json.loads(original)) == 0, ("the pile (a cone) should be undone",
                                                                        cones(json.loads(saved)))
    # The held sculpt (the mouse, from the 60-degree view): a cone at the rock's angle of repose under the
    # cursor's ground point, one primitive, measured as it was released (before Ctrl+Z took it away).
    strokes = s["sculpt_strokes"]
    assert len(strokes) == 2, strokes
    # The dragged stroke left several cones, and one click and Delete took them all: the document ends
    # with the file's primitives and one disc (above), and no cone is saved (below).
    assert strokes[1]["primitives"] >= 3, strokes[1]
    pile = strokes[0]
    assert pile["stamps"] > 5, pile
    # On sloping ground a cone's volume lies downhill of its apex (the meadow's slopes put the centroid of
    # the default 1.5 m brush's 2.7 m pile ~0.3 m downhill), so a large pile gets 15 % of its radius.
    held = check_pile({"pile": pile, "stamps": pile["stamps"], "user_primitives_before": 0,
                       "user_primitives_after": 1}, pile["ground_point"], "mouse-held",
                      max(0.2, 0.15 * pile["radius"]))
    cli = json.load(open(cli_path))
    assert cli["instances_per_type"] == s["instances_per_type"], (cli["instances_per_type"], s["instances_per_type"])
    shots = [f for f in os.listdir(work) if "-screenshot-" in f and f.endswith(".png")]
    assert len(shots) == 1, ("F12 should write one screenshot", os.listdir(work))
    w, h, _ = decode_png(os.path.join(work, shots[0]))
    assert (w, h) == (960, 540), (w, h)
    print(held)
    print("mouse paint, a held stroke undone by Ctrl+Z, click-pick + Delete, a dragged %d-cone sculpt stroke "
          "click-picked and deleted as one, F12, Ctrl+Q/Esc kept running, Ctrl+Q/Enter saved 1 user disc; "
          "the CLI re-instantiates %d instances as the editor" % (strokes[1]["primitives"], cli["instances"]))


if __name__ == "__main__":
    {"strokes": strokes, "diff": diff, "recovered": recovered, "move": move, "pile_paint": pile_paint, "piles": piles, "driven": driven}[sys.argv[1]](*sys.argv[2:])
