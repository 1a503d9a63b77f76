#!/usr/bin/env python3
"""Writes the three autumn sample scenes (assets/scenes/{street,park,road}_autumn.json) after the
environmental-objects paper's scattered effects (Grosbellet et al. 2016, §5.3-5.4, Fig. 12, 14, 19-21,
Table 1): fallen leaves, trash and grass as detail types whose density comes from the environment
(env/env_scatter.h). The environmental objects and helpers are the winter scenes' (make-winter-scenes.py).
Deterministic."""
import importlib.util
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "assets", "scenes")
_spec = importlib.util.spec_from_file_location("winter", os.path.join(HERE, "make-winter-scenes.py"))
W = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(W)
r, obj, field, point, segment, env_type = W.r, W.obj, W.field, W.point, W.segment, W.env_type

FLAT = {"mode": "tilt", "tilt_ranges": [[0, 25, 0.8], [25, 50, 0.2]]}  # leaves lie nearly flat
UPRIGHT = {"mode": "tilt", "tilt_ranges": [[0, 12, 1]]}                 # grass tufts stand
LYING = {"mode": "tilt", "tilt_ranges": [[0, 10, 1]]}                   # trash lies on its side
CENTRE = {"mode": "center"}  # one anchor: a scattered layer is tested where each candidate's origin is


def leaf(name, color, wet_color, count, thickness=0.12):
    """A leaf type: dry and wrinkled where the humidity is below 0, wet and flat at or above it (Fig. 12).
    The selection uses the dry leaf's spheres; the wet look only changes the mesh and material drawn."""
    return {
        "name": name,
        "model": {"mesh": "../models/%s_dry.glb" % name, "anchors": CENTRE},
        "material": {"base_color": color, "roughness": 0.8, "texture": "leaf", "texture_scale_m": 0.1,
                     "tint_variation": 0.35},
        "candidates": {"count": count, "scale": [0.8, 1.25], "orientation": FLAT},
        "scatter": {"channel": "leaves", "thickness_m": thickness,
                    "variants": [{"name": name + "_wet", "model": {"mesh": "../models/%s_wet.glb" % name},
                                  "material": {"base_color": wet_color, "roughness": 0.35, "texture": "leaf",
                                               "texture_scale_m": 0.1, "tint_variation": 0.2},
                                  "when": {"channel": "humidity", "min": 0}}]},
    }


def trash(name, mesh, color, count, height_m):
    """Litter lying on the ground: the anchor is 5 mm above the model's bottom (the models are centred and
    `height_m` tall), the layer 1.5 cm thick, so each piece rests on its support."""
    return {
        "name": name,
        "model": {"mesh": "../models/%s.glb" % mesh,
                  "anchors": {"mode": "authored", "points": [[0, 0, -0.5 * height_m + 0.005]]}},
        "material": {"base_color": color, "roughness": 0.5},
        "candidates": {"count": count, "scale": [0.9, 1.1], "orientation": LYING},
        "scatter": {"channel": "trash", "thickness_m": 0.015, "ramp_m": 0.005},
    }


# The tuft's anchor, 1.2 cm above its base (the model is 9.3 cm tall, centred): the layer holds the anchor,
# so the tufts stand on the surface with their roots a little in the ground instead of hovering.
TUFT_FOOT = {"mode": "authored", "points": [[0, 0, -0.035]]}


def grass(count, thickness=0.02, scale=(0.8, 1.3)):
    """Grass tufts standing on the ground, a thin layer of their feet thinned where the occlusion is low
    (trails), dried where it is warm (Fig. 14)."""
    return {
        "name": "grass_tuft",
        "model": {"mesh": "../models/grass_tuft.glb", "anchors": TUFT_FOOT},
        "material": {"base_color": [0.22, 0.42, 0.12], "roughness": 0.8, "texture": "grass", "texture_scale_m": 0.1,
                     "tint_variation": 0.3},
        "candidates": {"count": count, "scale": list(scale), "orientation": UPRIGHT},
        "scatter": {"channel": "grass", "thickness_m": thickness,
                    "variants": [{"name": "grass_tuft_dry", "model": {"mesh": "../models/grass_tuft_dried.glb"},
                                  "material": {"base_color": [0.55, 0.47, 0.25], "roughness": 0.9, "texture": "grass",
                                               "texture_scale_m": 0.1, "tint_variation": 0.3},
                                  "when": {"channel": "temperature", "min": 22}}]},
    }


LEAVES = ["leaves"]
LEAVES_TRASH = ["leaves", "trash"]


def autumn_types():
    """The winter scenes' objects, told what rests on them: roads, pavements, benches, steps take leaves and
    trash; roofs and the fountain's rim leaves; trees let leaves through (their crown is where the leaves
    come from)."""
    receives = {"road_segment": LEAVES_TRASH, "pavement_slab": LEAVES_TRASH, "bench": LEAVES_TRASH,
                "steps": LEAVES_TRASH, "bus_shelter": LEAVES, "fountain": LEAVES}
    types = []
    for t in W.TYPES:
        t = json.loads(json.dumps(t))
        if t["name"] in receives:
            t["receives"] = receives[t["name"]]
        if t["name"] == "bench":
            # Its occlusion field keeps the leaves off the ground beneath it (Fig. 20); it stops below the
            # seat (0.45 m), which receives them.
            t["fields"] = t.get("fields", []) + [
                field("occlusion", 1.0, {"box": {"center": [0, 0, 0.14], "half_extents": [0.72, 0.2, 0.12],
                                                 "radius": 0.12}})]
        if t["name"] == "tree":
            t["shelters"] = False
            # A large spherical leaf field around the crown (Fig. 20), and the shade under it.
            t["fields"] = [field("leaves", 1.5, point([0, 0, 3.2], 8.5)), field("occlusion", 0.3, point([0, 0, 3.5], 2.5))]
        types.append(t)
    # The fountain's water, an object of its own (a material of its own): leaves float on it.
    types.append(W.env_type("fountain_water", material={"base_color": [0.04, 0.09, 0.10], "roughness": 0.1}))
    types[-1]["receives"] = LEAVES
    return types


AUTUMN = [field("humidity", -0.3), field("temperature", 14.0)]


def head(name, extent, tile=0.5, settle=True):
    """Settling brings each layer down onto what it lies on — the ground, a seat, a roof, each other (the
    environment's objects are support too). The park and the road do not settle: millions of instances
    take minutes to settle (settling's speed is not yet that of the instantiation)."""
    p = W.head(name, extent)
    p["ghost_tile"]["tile_size_m"] = tile
    # Four tile variants chosen per tile by a hash: with one, the leaves and the grass repeat every tile
    # and read as stripes running into the distance (the park's warm corner, seen from 7 m).
    p["ghost_tile"]["variants"] = 4
    p["settling"] = {"enabled": True, "passes": 8, "max_drop_m": 0.1} if settle else {"enabled": False}
    return p


def street_autumn():
    """10 x 10 m (Fig. 20, Table 1 "Street"): a tree whose large spherical leaf field covers road and
    pavement, two small leaf piles, a bench (its occlusion field) and a bus shelter (its roof) that keep
    leaves off the ground beneath them, leaves on the bench's seat, a wet puddle with flat wet leaves, trash around the trash
    can and grass on the verge behind the pavement, trampled along a path."""
    p = head("street_autumn", [[0, 0, -0.5], [10, 10, 5.5]])
    p["terrain"] = W.flat_terrain(0, 0, 10, 10, 0.25)
    p["detail_types"] = [
        leaf("leaf_oak", [0.55, 0.27, 0.08], [0.20, 0.08, 0.03], 1000, thickness=0.05),
        leaf("leaf_birch", [0.80, 0.62, 0.14], [0.30, 0.20, 0.04], 1000, thickness=0.05),
        grass(1000),
        trash("can", "trash_can", [0.70, 0.12, 0.10], 48, 0.066),
        trash("paper", "trash_paper", [0.88, 0.86, 0.80], 40, 0.061),
        trash("cup", "trash_cup", [0.92, 0.92, 0.90], 10, 0.080),
        trash("bottle", "trash_bottle", [0.30, 0.55, 0.50], 16, 0.064),
    ]
    s = 10.0 / 12.0
    tree = [obj("road_segment", [(2 + 4 * i) * s, 2 * s, 0], scale=s) for i in range(3)]
    tree += [obj("pavement_slab", [1 + 2 * i, 4 * s + 1, 0], yaw=180) for i in range(5)]
    tree += [
        obj("tree", [5.0, 5.4, 0.15], yaw=20),
        obj("trash_can", [8.4, 5.9, 0.15]),
        obj("lamppost", [2.0, 4.6, 0.12], yaw=180),
        obj("bus_shelter", [2.4, 7.6, 0], yaw=180),
        obj("bench", [6.6, 7.2, 0], yaw=180),
    ]
    piles = [field("leaves", 3.0, point([7.6, 4.9, 0.15], 0.7)), field("leaves", 2.5, point([3.9, 2.6, 0.0], 0.6))]
    puddle = [field("humidity", 1.5, point([6.2, 2.2, 0.0], 0.9))]
    litter = [field("trash", 4.0, point([8.4, 5.9, 0.15], 1.8))]
    lawn = [field("grass", 1.0, {"box": {"center": [5, 8.2, 0], "half_extents": [5, 1.8, 0.5], "radius": 0.3}})]
    path = [field("occlusion", 0.9, segment([4.6, 6.4, 0.0], [5.4, 10.0, 0.0], 0.45))]
    p["environment"] = {
        "types": autumn_types(),
        "tree": tree,
        "global_fields": AUTUMN + piles + puddle + litter + lawn + path,
        "terrain": {"snow": False, "receives": ["leaves", "grass", "trash"]},
    }
    return p


def leaf_types(count, thickness=0.12):
    return [leaf("leaf_oak", [0.55, 0.27, 0.08], [0.20, 0.08, 0.03], count, thickness),
            leaf("leaf_birch", [0.80, 0.62, 0.14], [0.30, 0.20, 0.04], count, thickness)]


def tree_clusters(trees, per_cluster=3):
    """The park's trees as LOD nodes of `per_cluster` neighbours (by angle about the fountain), §6.1: each
    node's one leaf field, over its trees' crowns, stands for theirs when the scene uses LOD nodes. The
    park ships with them acting as plain groups (use_lod_nodes false: exact); `undergrowth bench` times
    both (env.park.lod_speedup)."""
    order = sorted(range(len(trees)), key=lambda i: math.atan2(trees[i][1], trees[i][0]))
    nodes = []
    for c in range(0, len(order), per_cluster):
        members = [trees[i] for i in order[c:c + per_cluster]]
        cx = sum(x for x, _ in members) / len(members)
        cy = sum(y for _, y in members) / len(members)
        reach = max(math.hypot(x - cx, y - cy) for x, y in members)
        children = [obj("tree", [x - cx, y - cy, 0], yaw=37 * order[c + k]) for k, (x, y) in enumerate(members)]
        nodes.append({"lod": {"at": [r(cx), r(cy), 0], "children": children,
                              "fields": [field("leaves", 1.2, point([0, 0, 3.2], r(reach + 8.5)))]}})
    return nodes


# Each object's base across the ground, half its extent along its own x and y (metres; env_models.h), for
# setting it down.
FOOTPRINT_M = {"fountain": (1.05, 1.05), "fountain_water": (1.05, 1.05), "bench": (0.8, 0.31), "pavement_slab": (1.0, 1.0), "tree": (0.4, 0.4)}


def set_on_ground(scene, binary):
    """Sets every object of the scene's tree down on its terrain: its base at the lowest ground under its
    footprint (its centre, corners and edges' midpoints), so nothing floats over a dip and the rest sits a
    little into the ground, as a paved path or a fountain's basin does. The heights come from the tool
    (`undergrowth environment --at`, its "ground"), which samples the terrain the scene will have."""
    placed = []  # (object node, its parent's world translation)

    def walk(nodes, origin):
        for n in nodes:
            kind = next(k for k in ("object", "group", "lod", "ref") if k in n)
            assert kind != "ref", "set_on_ground: references are not set down"
            body = n if kind == "object" else n[kind]
            assert kind == "object" or not (body.get("yaw_deg") or body.get("scale", 1) != 1), \
                "set_on_ground: a turned or scaled group"
            if kind == "object":
                placed.append((n, origin))
            else:
                at = body.get("at", [0, 0, 0])
                walk(body.get("children", []), [origin[i] + at[i] for i in range(3)])

    walk(scene["environment"]["tree"], [0.0, 0.0, 0.0])
    points = []
    for n, origin in placed:
        x, y = origin[0] + n["at"][0], origin[1] + n["at"][1]
        hx, hy = (h * n.get("scale", 1) for h in FOOTPRINT_M.get(n["object"], (0.5, 0.5)))
        c, s = math.cos(math.radians(n.get("yaw_deg", 0))), math.sin(math.radians(n.get("yaw_deg", 0)))
        points.append([(x + c * u * hx - s * v * hy, y + s * u * hx + c * v * hy)
                       for u in (-1, 0, 1) for v in (-1, 0, 1)])
    # Beside the scenes: the models' paths are relative to the scene's folder.
    with tempfile.NamedTemporaryFile("w", dir=OUT, prefix=".ground-", suffix=".json", delete=False) as f:
        json.dump(scene, f)
    try:
        args = [binary, "environment", f.name]
        for footprint in points:
            for x, y in footprint:
                args += ["--at", "%.4f,%.4f,0" % (x, y)]
        run = subprocess.run(args, capture_output=True, text=True)
    finally:
        os.remove(f.name)
    if run.returncode != 0:
        sys.exit("set_on_ground: %s failed: %s" % (binary, run.stderr.strip()))
    ground = [p["ground"] for p in json.loads(run.stdout)["points"]]
    for k, (n, origin) in enumerate(placed):
        n["at"][2] = r(min(ground[9 * k:9 * k + 9]) - origin[2])


def park_autumn():
    """115 x 90 m (Fig. 19, Table 1 "Park"): a lawn crossed by two paved paths, 18 trees shedding their
    leaves on it, benches along the paths (leaves on their seats, none under them), a fountain whose rim
    collects leaves, a warm, dry corner where the grass has dried (Fig. 14) and trampled trails across the
    lawn (low occlusion: sparse grass)."""
    p = head("park_autumn", [[-57.5, -45, -1], [57.5, 45, 8]], settle=False)
    p["terrain"] = W.flat_terrain(-57.5, -45, 115, 90, 0.5, amplitude=0.4, feature=40.0)
    p["detail_types"] = leaf_types(160) + [grass(1500, scale=(0.6, 0.85))]
    tree = []
    # Two paths of pavement slabs crossing at the fountain.
    for i in range(-28, 28):
        if abs(i) > 1:
            tree.append(obj("pavement_slab", [2 * i + 1, 0, 0]))
    for j in range(-22, 22):
        if abs(j) > 1:
            tree.append(obj("pavement_slab", [0, 2 * j + 1, 0], yaw=90))
    tree.append(obj("fountain", [0, 0, 0]))
    tree.append(obj("fountain_water", [0, 0, 0]))  # set down with the fountain's footprint: the same height
    trees = [(-40, 20), (-25, 28), (-10, 22), (12, 24), (28, 30), (44, 18), (-45, -15), (-30, -28),
             (-14, -20), (15, -26), (30, -18), (46, -30), (-20, 8), (22, 9), (-35, 5), (38, -5),
             (8, -12), (-8, 36)]
    tree += tree_clusters(trees)
    for i, x in enumerate([-44, -30, -16, 16, 30, 44]):
        tree.append(obj("bench", [x, 2.2, 0], yaw=180))
        tree.append(obj("bench", [2.2, (x * 0.8), 0], yaw=90))
    trails = [field("occlusion", 0.8, segment([-50, -40, 0], [-5, -3, 0], 0.6)),
              field("occlusion", 0.8, segment([50, 38, 0], [6, 4, 0], 0.6))]
    dry = [field("temperature", 12.0, point([45, -35, 0], 14.0))]
    puddles = [field("humidity", 1.5, point([x, y, 0], 1.6)) for x, y in ((-12, 3.5), (9, -18), (-30, -24))]
    lawn = [field("grass", 1.0)]
    p["environment"] = {
        "types": autumn_types(),
        "tree": tree,
        "global_fields": AUTUMN + lawn + trails + dry + puddles + [field("leaves", 0.06)],
        "terrain": {"snow": False, "receives": ["leaves", "grass", "trash"]},
        "use_lod_nodes": False,
    }
    return p


def road_autumn():
    """70 x 70 m (Fig. 21, Table 1 "Road"): the winter road in autumn — a road and its fences between two
    grass verges, 24 trees in rings of pavers, their leaves over the verges and the road, tyre tracks."""
    p = head("road_autumn", [[-35, -35, -1], [35, 35, 8]], tile=0.25, settle=False)
    p["terrain"] = W.flat_terrain(-35, -35, 70, 70, 0.5, amplitude=0.0)
    p["detail_types"] = leaf_types(150, thickness=0.1) + [grass(1800, scale=(0.3, 0.4))]
    groups, tree, tracks = W.road_layout()
    puddles = [field("humidity", 1.5, point([x, y, 0.1], 1.1)) for x, y in ((-21, 1.4), (4, -1.6), (26, 0.4))]
    verges = [field("grass", 1.0)]
    p["environment"] = {
        "types": autumn_types(),
        "groups": groups,
        "tree": tree,
        "global_fields": AUTUMN + verges + tracks + puddles + [field("leaves", 0.3)],
        "terrain": {"snow": False, "receives": ["leaves", "grass", "trash"]},
    }
    return p


def main():
    binary = os.environ.get("UG_BIN", os.path.join(HERE, "..", "build", "undergrowth"))
    if not os.access(binary, os.X_OK):
        sys.exit("make-autumn-scenes: needs the built tool to set objects on the park's terrain: %s "
                 "(build it, or name it with UG_BIN)" % binary)
    for make in (street_autumn, park_autumn, road_autumn):
        scene = make()
        if make is park_autumn:
            set_on_ground(scene, os.path.abspath(binary))
        path = os.path.join(OUT, scene["name"] + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
            f.write("\n")
        print("wrote", os.path.relpath(path))
    return 0


if __name__ == "__main__":
    sys.exit(main())
