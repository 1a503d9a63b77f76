#!/usr/bin/env python3
"""Checks a scripted Ghost Tile run (tests/gui/run_gui_tests.sh, replay action "ghost_tile", replay.h).

usage: check_ghost_tile.py STATS.json CLI_STATS.json SCENE.json SAVED.json TYPE COUNT DELTA CORRUPT_FILE
The script is: ghost_tile (TYPE to COUNT candidates, delta DELTA), save_as SAVED, undo, redo, ghost_tile
pointing a type at CORRUPT_FILE, ghost_tile with count 0, wait_idle.
"""
import json
import sys


def main(stats_path, cli_path, scene_path, saved_path, typ, count, delta, corrupt):
    count, delta = int(count), float(delta)
    s = json.load(open(stats_path))
    acts = s["actions"]
    kinds = [a["action"] for a in acts]
    assert kinds == ["ghost_tile", "save_as", "undo", "redo", "ghost_tile", "ghost_tile", "wait_idle"], kinds
    build, save, undo, redo, bad_model, bad_count, _ = acts
    out = []

    # The build: applied, the tile has the new count, and the instances changed.
    g = build["ghost_tile"]
    assert g["ok"], g
    scene = json.load(open(scene_path))
    # The tile holds every variant of every type's candidates.
    variants = scene["ghost_tile"].get("variants", 1)
    expected_n = variants * sum(count if t["name"] == typ else t["candidates"]["count"] for t in scene["detail_types"])
    assert g["candidates"] == expected_n, (g["candidates"], expected_n)
    assert g["pairs"] > 0 and abs(g["rho"] - g["pairs"] / g["candidates"]) < 1e-9, g
    assert 0 < g["bytes_per_pair"] <= 8 and g["graph_bytes"] > 0, g
    assert build["instance_store_hash_after"] != build["instance_store_hash_before"], build
    out.append("build: #N %d, %d pairs, rho %.1f, %.2f bytes/pair, %.2f s (%s); instances %d -> %d" % (
        g["candidates"], g["pairs"], g["rho"], g["bytes_per_pair"], g["job_seconds"], g["cache"],
        build["instances_before"], build["instances_after"]))

    # Saved: the file has the new settings; the CLI instantiates it to the editor's per-type counts.
    assert save["ok"], save
    saved = json.load(open(saved_path))
    assert abs(saved["ghost_tile"]["delta_m"] - delta) < 1e-7, saved["ghost_tile"]
    counts = {t["name"]: t["candidates"]["count"] for t in saved["detail_types"]}
    assert counts[typ] == count, counts
    cli = json.load(open(cli_path))
    assert cli["instances_per_type"] == build["per_type_after"] == s["instances_per_type"], (
        cli["instances_per_type"], build["per_type_after"], s["instances_per_type"])
    out.append("saved file re-instantiated by the CLI: %s, as the editor" % json.dumps(cli["instances_per_type"]))

    # Undo gives back exactly the previous instance set; redo the build's.
    assert undo["ok"] and redo["ok"], (undo, redo)
    assert undo["instance_store_hash_after"] == build["instance_store_hash_before"], (undo, build)
    assert undo["per_type_after"] == build["per_type_before"]
    assert redo["instance_store_hash_after"] == build["instance_store_hash_after"], (redo, build)
    out.append("undo gives back hash %s exactly, redo %s" % (undo["instance_store_hash_after"],
                                                             redo["instance_store_hash_after"]))

    # A corrupt model: reported with the file's name, nothing changed, the run went on.
    b = bad_model["ghost_tile"]
    assert not b["ok"] and corrupt in b["error"], b
    assert any(corrupt in m for m in s["messages"]), s["messages"]
    assert bad_model["instance_store_hash_after"] == bad_model["instance_store_hash_before"] == \
        redo["instance_store_hash_after"], bad_model
    # Absurd settings: refused at once, with the setting named.
    c = bad_count["ghost_tile"]
    assert not c["ok"] and "candidate_count is 0" in c["error"], c
    assert bad_count["instance_store_hash_after"] == bad_count["instance_store_hash_before"], bad_count
    assert s["instance_store_hash"] == build["instance_store_hash_after"], s["instance_store_hash"]
    out.append("corrupt model and count 0 reported (%d messages), instance set unchanged" % len(s["messages"]))
    print("; ".join(out))


if __name__ == "__main__":
    main(*sys.argv[1:])
