#!/usr/bin/env python3
"""Writes the three winter sample scenes (assets/scenes/{street,road,montmartre}_winter.json) after the
environmental-objects paper's Table 1 and figures (Grosbellet et al. 2016, Fig. 3, 5, 21, 22). The scenes
are plain project files; this script only saves typing the repeated placements. Deterministic."""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "assets", "scenes")


def r(v, nd=3):
    return round(v, nd)


def head(name, extent, seed=5):
    return {
        "format": "undergrowth-project",
        "format_version": 3,
        "name": name,
        "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": seed},
        "extent": {"min": extent[0], "max": extent[1]},
        "instantiation": {"seed": 1, "chunk_size_m": 8},
        "settling": {"enabled": True, "passes": 8, "max_drop_m": 0.2},
    }


def flat_terrain(x0, y0, w, h, cell, amplitude=0.0, seed=3, feature=30.0):
    return {"procedural": {"origin": [x0, y0], "cell_size_m": cell, "width": int(w / cell) + 1,
                           "height": int(h / cell) + 1, "seed": seed, "octaves": 3, "base_height_m": 0,
                           "amplitude_m": amplitude, "feature_size_m": feature, "lacunarity": 2, "gain": 0.5},
            "material": {"base_color": [0.30, 0.26, 0.20], "roughness": 1, "texture": "ground",
                         "texture_scale_m": 0.6}}


def twigs(center, radius, weight=0.6):
    """The one detail type every scene has: twigs fallen under the tree."""
    return [{
        "name": "twig",
        "model": {"mesh": "../models/twig.glb"},
        "material": {"base_color": [0.25, 0.18, 0.11], "roughness": 0.9, "texture": "bark", "texture_scale_m": 0.1},
        "candidates": {"count": 60, "scale": [0.7, 1.2]},
        "density": {"point": {"center": center, "radius": radius, "weight": weight}},
        "instancing": {"strategy": "random", "layer_m": 0.02},
    }]


def env_type(name, snow=None, icicles=None, fields=None, material=None, shelters=True):
    t = {"name": name, "mesh": "../env_models/%s.glb" % name}
    if not shelters:
        t["shelters"] = False
    if snow:
        t["snow"] = snow
    if icicles:
        t["icicles"] = icicles
    if fields:
        t["fields"] = fields
    if material:
        t["material"] = material
    return t


def obj(type_name, at, yaw=0.0, scale=1.0, **extra):
    o = {"object": type_name, "at": [r(at[0]), r(at[1]), r(at[2])]}
    if yaw:
        o["yaw_deg"] = r(yaw, 2)
    if scale != 1.0:
        o["scale"] = r(scale, 4)
    o.update(extra)
    return o


def field(channel, value, shape=None):
    f = {"channel": channel, "value": value}
    if shape:
        f["shape"] = shape
    return f


def point(c, radius):
    return {"point": {"center": [r(c[0]), r(c[1]), r(c[2])], "radius": radius}}


def segment(a, b, radius):
    return {"segment": {"a": [r(a[0]), r(a[1]), r(a[2])], "b": [r(b[0]), r(b[1]), r(b[2])], "radius": radius}}


WINTER = [field("snow", 0.12), field("icicles", 1.0), field("temperature", -3.0), field("humidity", 0.2)]

TYPES = [
    env_type("road_segment", snow={"target_edge_m": 0.06, "d0_m": 0.01}, icicles={"enabled": False},
             material={"base_color": [0.10, 0.10, 0.11], "roughness": 0.9, "texture": "ground",
                       "texture_scale_m": 0.4}),
    env_type("pavement_slab", snow={"target_edge_m": 0.05, "d0_m": 0.01}, icicles={"enabled": False},
             material={"base_color": [0.45, 0.43, 0.40], "roughness": 0.9, "texture": "rock", "texture_scale_m": 0.5}),
    env_type("bench", snow={"target_edge_m": 0.02, "d0_m": 0.02}, icicles={"spacing_m": 0.05, "max_length_m": 0.08}),
    env_type("lamppost", snow={"target_edge_m": 0.02, "d0_m": 0.02}, icicles={"spacing_m": 0.04, "max_length_m": 0.25},
             fields=[field("temperature", 4.0, point([0, 0.72, 3.8], 0.6)),
                     field("temperature", 2.5, point([0, 0.72, 3.8], 1.8))]),
    env_type("trash_can", snow={"target_edge_m": 0.02, "d0_m": 0.03}, icicles={"spacing_m": 0.05, "max_length_m": 0.1}),
    env_type("bus_shelter", snow={"target_edge_m": 0.04}, icicles={"spacing_m": 0.07, "max_length_m": 0.3}),
    env_type("fence_segment", snow={"target_edge_m": 0.015, "d0_m": 0.01}, icicles={"spacing_m": 0.05, "max_length_m": 0.12}),
    # A bare tree's branches do not keep snow off the ground in their own shape: flakes drift around
    # twigs metres above it. As a shelter they drew each branch as a trough in the snow, and left the
    # ground bare where branches crowd over the trunk's foot; the crown's occlusion field thins it instead.
    env_type("tree", snow={"target_edge_m": 0.03, "d0_m": 0.02, "max_face_angle_deg": 70},
             icicles={"enabled": False}, fields=[field("occlusion", 0.5, point([0, 0, 3.5], 2.5))],
             # Bark's fibres run along u, which the box projection lays across an upright trunk: a quarter
             # turn stands them up.
             material={"base_color": [0.13, 0.11, 0.09], "roughness": 0.9, "texture": "bark", "texture_scale_m": 0.4,
                       "texture_rotation_deg": 90},
             shelters=False),
    env_type("fountain", snow={"target_edge_m": 0.03}, icicles={"spacing_m": 0.05, "max_length_m": 0.25},
             material={"base_color": [0.60, 0.58, 0.54], "roughness": 0.9, "texture": "rock", "texture_scale_m": 0.5}),
    env_type("facade", snow={"target_edge_m": 0.04, "d0_m": 0.03}, icicles={"spacing_m": 0.1, "max_length_m": 0.2},
             material={"base_color": [0.72, 0.66, 0.56], "roughness": 0.9}),
    env_type("steps", snow={"target_edge_m": 0.04}, icicles={"spacing_m": 0.06, "max_length_m": 0.1}),
]


def street_winter():
    """10 x 10 m (Fig. 3, 5, Table 1 "Street"): a road, a pavement with its kerb, a tree, a trash can, a
    lamppost, a bench under a bus shelter, a fence, footprints and tyre tracks as local occlusion fields and
    a warm pipe melting a band of snow."""
    p = head("street_winter", [[0, 0, -0.5], [10, 10, 5.5]])
    p["terrain"] = flat_terrain(0, 0, 10, 10, 0.25)
    p["detail_types"] = twigs([6.6, 6.1, 0.0], 0.6, weight=4.0)  # blown in under the bus shelter, where no snow lies
    s = 10.0 / 12.0  # three road segments scaled to the 10 m street
    tree = []
    for i in range(3):
        tree.append(obj("road_segment", [(2 + 4 * i) * s, 2 * s, 0], scale=s))
    for i in range(5):
        tree.append(obj("pavement_slab", [1 + 2 * i, 4 * s + 1, 0], yaw=180))  # kerb towards the road
    tree += [
        obj("tree", [8.0, 8.3, 0], yaw=20),
        obj("trash_can", [5.6, 5.9, 0]),
        obj("lamppost", [2.0, 4.6, 0.12], yaw=180),
        obj("bus_shelter", [6.6, 6.7, 0], yaw=180),
        obj("bench", [3.4, 8.6, 0], yaw=180),
        obj("fence_segment", [1.0, 9.8, 0]), obj("fence_segment", [3.0, 9.8, 0]), obj("fence_segment", [5.0, 9.8, 0]),
    ]
    # Footprints across the snow (alternating feet 0.3 m apart), tyre tracks along the road.
    steps = []
    a, b = (0.6, 6.0), (5.2, 9.3)
    n = 16
    for k in range(n):
        t = (k + 0.5) / n
        x, y = a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t
        dx, dy = b[0] - a[0], b[1] - a[1]
        ln = math.hypot(dx, dy)
        side = 0.1 if k % 2 == 0 else -0.1
        steps.append(field("occlusion", 0.85, point([x - dy / ln * side, y + dx / ln * side, 0.0], 0.13)))
    tracks = [field("occlusion", 0.9, segment([0, y, 0.08], [10, y, 0.08], 0.3)) for y in (0.9, 2.45)]
    pipe = [field("temperature", 15.0, segment([0.0, 7.4, 0.0], [4.6, 7.4, 0.0], 0.6))]
    p["environment"] = {
        "types": TYPES,
        "tree": tree,
        "global_fields": WINTER + steps + tracks + pipe,
        "terrain": {"snow": True, "snow_cell_m": 0.05},
    }
    return p


def tree_with_pavers(name, pavers, ring, yaw):
    """A tree standing in a ring of small square pavers (road_segment at 1/8 scale, 0.5 m): one group, instanced
    twelve times by references (the paper's Road: 24 trees from two groups of ~110 objects)."""
    children = [obj("tree", [0, 0, 0], yaw=yaw)]
    k = 0
    for j in range(-ring, ring):
        for i in range(-ring, ring):
            if k >= pavers:
                break
            cx, cy = (i + 0.5) * 0.55, (j + 0.5) * 0.55
            if abs(cx) < 0.8 and abs(cy) < 0.8:
                continue
            children.append(obj("road_segment", [cx, cy, 0], scale=0.125))
            k += 1
    return {"group": {"children": children}}


def road_layout():
    """The road's objects, shared by its winter and autumn versions: the two tree groups (a tree in a ring
    of pavers), the road, fences along both verges, 24 trees referencing the groups, and the tyre tracks
    (occlusion). Returns (groups, tree, tracks)."""
    groups = {"tree_a": tree_with_pavers("tree_a", 109, 6, 0), "tree_b": tree_with_pavers("tree_b", 109, 6, 140)}
    tree = [obj("road_segment", [-34 + 4 * i + 2, 0, 0]) for i in range(17)]
    # Fences along both verges (their rails and pickets grow icicles).
    tree += [obj("fence_segment", [-34 + 2 * i + 1, 2.6 * side, 0], yaw=0 if side > 0 else 180)
             for side in (-1, 1) for i in range(34)]
    k = 0
    for side in (-1, 1):
        for i in range(12):
            x = -30 + i * 5.4
            tree.append({"ref": "tree_a" if (i + side) % 2 == 0 else "tree_b", "at": [r(x), 6.0 * side, 0], "yaw_deg": 30 * k})
            k += 1
    tracks = [field("occlusion", 0.9, segment([-35, y, 0.1], [35, y, 0.1], 0.18)) for y in (-0.9, 0.9)]
    return groups, tree, tracks


def road_winter():
    """70 x 70 m (Fig. 21, Table 1 "Road"): a terrain, a road, and 24 trees instanced from two groups of about
    110 objects each."""
    p = head("road_winter", [[-35, -35, -2], [35, 35, 8]])
    p["terrain"] = flat_terrain(-35, -35, 70, 70, 0.5, amplitude=0.0)
    p["detail_types"] = twigs([6.0, 6.0, 0.0], 1.5)
    groups, tree, tracks = road_layout()
    p["environment"] = {
        "types": TYPES,
        "groups": groups,
        "tree": tree,
        "global_fields": WINTER + tracks,
        "terrain": {"snow": True, "snow_cell_m": 0.025},
    }
    return p


def montmartre_winter():
    """33 x 100 m (Fig. 22, Table 1 "Montmartre"): a cobbled street between two rows of four-storey facades with
    windows and balconies, lampposts warming the windows near them, footprints and wheel tracks."""
    p = head("montmartre_winter", [[-16.5, -50, -0.5], [16.5, 50, 25]])
    p["detail_types"] = twigs([0.0, 0.0, 0.0], 1.0)
    # One building: 4 storeys of facade pieces (6 m each) with steps at the door.
    building = {"group": {"children": [obj("facade", [0, 0, 6.0 * k]) for k in range(4)] +
                          [obj("steps", [0, 0.8, 0])]}}
    # A cobbled patch: 11 x 11 pavers of 4/11 m (road_segment at 1/11 scale), one group.
    c = 4.0 / 11.0
    # Procedural box snow (§5.1) for the cobbles: a few dozen triangles each instead of the asphalt grid's 2,048.
    cobbles = {"group": {"snow": {"mode": "box"},
                         "children": [obj("road_segment", [(i - 5) * c, (j - 5) * c, 0], scale=1.0 / 11.0)
                                      for j in range(11) for i in range(11)]}}
    groups = {"building": building, "cobbles": cobbles}
    tree = []
    for side in (-1, 1):
        for i in range(25):
            y = -48 + 4 * i
            tree.append({"ref": "building", "at": [10.4 * side, r(y), 0], "yaw_deg": 90 * side})
    # The street: 12 m of cobbles (3 x 25 patches of 4 m) and 4 m pavements each side, the kerb on the street.
    for j in range(25):
        for i in range(-1, 2):
            tree.append({"ref": "cobbles", "at": [i * 4.0, -48 + 4 * j, 0]})
    for side in (-1, 1):
        for j in range(50):
            tree.append(obj("pavement_slab", [7.0 * side, -49 + 2 * j, 0], yaw=90 * side))
            tree.append(obj("pavement_slab", [9.0 * side, -49 + 2 * j, 0], yaw=-90 * side))
    for side in (-1, 1):
        for i in range(10):
            y = -45 + 10 * i
            tree.append(obj("lamppost", [9.7 * side, y, 0.12], yaw=90 * side))  # the head warms the sills
    for i in range(8):
        tree.append(obj("bench", [-8.8, -42 + 12 * i, 0.12], yaw=-90))
        tree.append(obj("trash_can", [8.8, -38 + 12 * i, 0.12]))
    # A walker's steps, 0.8 m apart, left and right of a line down the east pavement.
    steps = []
    for k in range(32):
        y = -30 + k * 0.8
        steps.append(field("occlusion", 0.85, point([6.9 + (0.12 if k % 2 else -0.12), r(y), 0.12], 0.13)))
    tracks = [field("occlusion", 0.9, segment([x, -50, 0.0], [x, 50, 0.0], 0.18)) for x in (-1.8, 1.8)]
    p["environment"] = {
        # A wind from the west: the snow falls 10 degrees off vertical onto the east row's windward sills
        # and balconies; the west row's stay sheltered under their cornices, and its pavement in its lee
        # (so the footprints walk the east pavement, where there is snow to keep them).
        "snow_direction": [0.176, 0, -1],
        "types": TYPES,
        "groups": groups,
        "tree": tree,
        "global_fields": WINTER + steps + tracks,
        "terrain": {"snow": False},
    }
    return p


def main():
    for make in (street_winter, road_winter, montmartre_winter):
        scene = make()
        path = os.path.join(OUT, scene["name"] + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
            f.write("\n")
        print("wrote", os.path.relpath(path))
    return 0


if __name__ == "__main__":
    sys.exit(main())
