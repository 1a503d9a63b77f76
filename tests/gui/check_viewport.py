#!/usr/bin/env python3
"""Checks of the viewport fixes (issue 10) from the editor's statistics ("viewport", "window_title",
"actions") and the window titles read by xdotool.

  check_viewport.py driven WORKDIR          the xdotool session of driven_viewport.sh
  check_viewport.py replay STATS.json NEW_SCENE.json   the scripted run of run_editor_fixes.sh
"""
import json
import math
import os
import sys

MARK = "\u2022"


def load(path):
    with open(path) as f:
        return json.load(f)


def dist(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def title(work, name):
    with open(os.path.join(work, name + ".title"), encoding="utf-8") as f:
        return f.read().strip()


def driven(work):
    out = []
    # Window title: the file name, the unsaved mark after the start script's sculpt stroke, none once saved.
    t = title(work, "start")
    assert t == "meadow.json %s \u2014 Undergrowth" % MARK, "title while dirty: %r" % t
    t = title(work, "saved")
    assert t == "meadow.json \u2014 Undergrowth", "title after Ctrl+S: %r" % t
    t = title(work, "after_click")
    assert t == "meadow.json %s \u2014 Undergrowth" % MARK, "title after an erase stroke: %r" % t
    out.append("title %r" % title(work, "saved"))

    # The brush ring around the cursor: on the pile's flank and on the bare ground.
    for name, want_pile in (("ring_pile", True), ("ring_ground", False)):
        v = load(os.path.join(work, name + ".json"))["viewport"]
        b = v["brush"]
        assert v["tool"] == "paint", (name, v["tool"])
        assert b["drawn"], "%s: no brush ring drawn (cursor %s)" % (name, v.get("cursor_px"))
        assert b["on_pile"] == want_pile, (name, b)
        off = dist(b["ring_center_px"], v["cursor_px"])
        # The ring's mean on screen is its centre's projection up to the circle's perspective (a few px).
        assert off < 8.0, "%s: ring centre %s is %.1f px from the cursor %s" % (
            name, b["ring_center_px"], off, v["cursor_px"])
        out.append("%s ring %.1f px from the cursor" % ("pile" if want_pile else "ground", off))

    # Zoom toward the cursor: closer, the ground point under the cursor stays, the target moves toward it.
    a = load(os.path.join(work, "zoom_before.json"))["viewport"]
    z = load(os.path.join(work, "zoom_after.json"))["viewport"]
    assert a["cursor_px"] == z["cursor_px"], (a["cursor_px"], z["cursor_px"])
    d0, d1 = a["camera"]["distance"], z["camera"]["distance"]
    assert d1 < 0.8 * d0, "the wheel did not zoom in: %.3f -> %.3f m" % (d0, d1)
    g0, g1 = a["ground_under_cursor"], z["ground_under_cursor"]
    drift = dist(g0, g1)
    assert drift < 0.02 * d0, "the ground under the cursor moved %.3f m (distance %.2f m)" % (drift, d0)
    t0, t1 = a["camera"]["target"], z["camera"]["target"]
    assert dist(t1, g0) < dist(t0, g0) - 0.1 * dist(t0, g0), ("the target did not move toward the cursor", t0, t1, g0)
    out.append("zoom %.2f -> %.2f m, the point under the cursor moved %.4f m" % (d0, d1, drift))

    # Focus: "3" and "e" typed into the radius field; moving the pointer into the viewport gives the keyboard
    # back (E then selects Erase, the radius is 3: the "e" was the field's); so do a click (Q: Select) and
    # Enter (B: Paint).
    for name, radius, tool in (("after_move", 3.0, "erase"), ("after_click", 2.0, "select"),
                               ("after_enter", 4.0, "paint")):
        v = load(os.path.join(work, name + ".json"))["viewport"]
        assert abs(v["brush_radius"] - radius) < 1e-4, ("%s: the radius field did not get the typed %g" % (name, radius),
                                                        v["brush_radius"])
        assert not v["imgui_wants_keyboard"], "%s: ImGui kept the keyboard" % name
        assert v["tool"] == tool, "%s: the shortcut did not reach the viewport: tool %s, not %s" % (name, v["tool"], tool)
    out.append("shortcuts back after moving into the viewport, a click, Enter")
    print("; ".join(out))


def replay(stats_path, new_scene_path):
    s = load(stats_path)
    acts = s["actions"]
    views = [a for a in acts if a["action"] == "view"]
    opens = [a for a in acts if a["action"] == "open"]
    out = []
    # The camera stays above the ground: a view asking for 30 degrees below the horizon.
    below = views[0]
    eye = below["eye"]
    assert eye[2] >= below["eye_ground_z"] + 0.04, ("eye below the ground", eye, below["eye_ground_z"])
    assert eye[2] > -1.8, ("eye below the meadow's lowest ground", eye)
    out.append("eye %.2f m above the ground" % (eye[2] - below["eye_ground_z"]))
    # File > Open frames the new scene: the camera was far off in a corner of the meadow.
    far = views[1]
    assert dist(far["target"][:2], [15, 15]) < 0.5, far["target"]
    o = opens[0]
    assert o["ok"] and o["document"].endswith(os.path.basename(new_scene_path)), o
    ext = load(new_scene_path)["extent"]
    lo, hi = ext["min"], ext["max"]
    t = o["camera_target"]
    assert all(lo[i] <= t[i] <= hi[i] for i in range(3)), ("camera target %s outside the new scene %s..%s" % (t, lo, hi))
    out.append("open framed %s at %s" % (os.path.basename(new_scene_path), [round(x, 2) for x in t]))
    # The Statistics panel and the title show the Save As path.
    v = s["viewport"]
    saved = [a for a in acts if a["action"] == "save_as"][-1]["path"]
    assert v["statistics_scene"] == saved, (v["statistics_scene"], saved)
    assert s["window_title"] == os.path.basename(saved) + " \u2014 Undergrowth", s["window_title"]
    out.append("statistics and title follow Save As")
    print("; ".join(out))


if __name__ == "__main__":
    try:
        if sys.argv[1] == "driven":
            driven(sys.argv[2])
        else:
            replay(sys.argv[2], sys.argv[3])
    except (AssertionError, KeyError, IndexError, OSError, ValueError) as e:
        print("FAIL: %r" % (e,))
        sys.exit(1)
