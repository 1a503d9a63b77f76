#!/usr/bin/env python3
"""Checks a scripted editor run of the panels' actions (run_gui_tests.sh, "panels").

  check_panels.py STATS.json CLI_SEED.json SEED ORIGINAL_SCENE

The script is: set_visible rock off, grass_tuft off, rock on, grass_tuft on, set_seed SEED, undo, redo, set_instancing rock random, undo, export (ok), export (fails:
a file where the folder should be), open a truncated scene, open a scene whose model is garbage, new,
save_as. Prints a one-line summary; exits 1 with the reason on the first failed check.
"""
import json
import os
import sys


def main():
    stats_path, cli_path, seed, scene = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    s = json.load(open(stats_path))
    cli = json.load(open(cli_path))
    acts = s["actions"]
    names = [a["action"] for a in acts]
    want = ["set_visible"] * 4 + ["set_seed", "undo", "redo", "set_instancing", "undo", "export", "export", "open", "open", "new",
            "save_as"]
    assert names[:len(want)] == want, names
    vis = acts[:4]
    seed_a, undo_a, redo_a, inst_a, inst_undo, exp_ok, exp_bad, open_trunc, open_model, new_a, save_a = acts[4:15]

    # Visibility: hiding a type stops drawing exactly its instances (the whole scene is in view), showing
    # it draws them again; the instance set is unchanged and the document stays clean (view state only).
    for a in vis:
        n = a["per_type_after"][a["type"]]
        assert n > 0, a
        delta = a["drawn_instances_after"] - a["drawn_instances_before"]
        assert delta == (n if a["visible"] else -n), (a["type"], a["visible"], delta, n)
        assert not a["dirty"] and a["instance_store_hash_after"] == a["instance_store_hash_before"], a
    assert vis[3]["drawn_instances_after"] == vis[0]["drawn_instances_before"], vis

    # set_seed N gives the CLI's instance set for --seed N (per type), and it is a different set.
    assert seed_a["ok"] and seed_a["seed"] == seed, seed_a
    assert seed_a["per_type_after"] == cli["instances_per_type"], (seed_a["per_type_after"], cli["instances_per_type"])
    assert seed_a["instances_after"] == cli["instances"], (seed_a["instances_after"], cli["instances"])
    assert seed_a["instance_store_hash_after"] != seed_a["instance_store_hash_before"], seed_a
    # Undo gives back the previous set exactly (hash), redo the new one.
    assert undo_a["instance_store_hash_after"] == seed_a["instance_store_hash_before"], undo_a
    assert redo_a["instance_store_hash_after"] == seed_a["instance_store_hash_after"], redo_a
    # set_instancing: one step that changes the rocks; undo restores the exact set.
    assert inst_a["ok"] and inst_a["strategy"] == "random", inst_a
    assert inst_a["instance_store_hash_after"] != inst_a["instance_store_hash_before"], inst_a
    assert inst_undo["instance_store_hash_after"] == inst_a["instance_store_hash_before"], inst_undo

    # Export: the settled set, every instance; the bad path fails with the path and the reason.
    assert exp_ok["ok"] and os.path.getsize(exp_ok["path"]) > 0, exp_ok
    assert exp_ok["exported_instances"] == exp_ok["instances_after"] == redo_a["instances_after"], exp_ok
    assert not exp_bad["ok"] and exp_bad["path"] in exp_bad["error"], exp_bad
    assert "Not a directory" in exp_bad["error"] or "cannot" in exp_bad["error"], exp_bad
    assert not os.path.exists(exp_bad["path"]), exp_bad

    # Failed opens: the message names the file and the reason; the document and its instances stay.
    for a, file, reason in ((open_trunc, "truncated.json", "invalid JSON"),
                            (open_model, "garbage.obj", "line 1: vertex 1 has only 2 coordinates")):
        assert a["ok"] is False, a
        assert file in a["error"] and reason in a["error"], a["error"]
        assert any(file in m and reason in m for m in s["messages"]), s["messages"]
        assert a["document"] == scene, (a["document"], scene)
        assert a["instance_store_hash_after"] == a["instance_store_hash_before"], a
        assert a["instances_after"] == exp_ok["instances_after"] > 0, a

    # New: an untitled, clean, empty document with the template's types; Save As gives it a file.
    assert new_a["ok"] and new_a["document"] == "" and new_a["instances_after"] == 0, new_a
    assert not new_a["dirty"] and len(new_a["per_type_after"]) > 0, new_a
    assert save_a["ok"] and os.path.getsize(save_a["path"]) > 0, save_a
    assert s["document"]["path"] == save_a["path"] and not s["document"]["dirty"], s["document"]
    saved = json.load(open(save_a["path"]))
    assert saved["format"] == "undergrowth-project", saved
    assert all("density" not in t for t in saved["detail_types"]), "a new document has no density"
    print("hide/show draws -/+ exactly a type's instances; seed %d: %d instances as the CLI, undo exact; exported %d; opens failed cleanly (%d instances kept); "
          "new + save as" % (seed, seed_a["instances_after"], exp_ok["exported_instances"],
                             open_model["instances_after"]))


if __name__ == "__main__":
    try:
        main()
    except AssertionError as e:
        print("check failed: %s" % e)
        sys.exit(1)
