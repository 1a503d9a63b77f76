#!/usr/bin/env python3
"""Writes the sample worlds for region jobs (docs/worlds.md): rolling procedural terrain, meadow-like
layers (grass tufts everywhere, denser in clearings; pebble trails) and rock piles.
- assets/scenes/world_1km.json: one square kilometre, 11.5 M instances; more than one process may hold
  (the instancer's 8 GiB check refuses it), run as a plan's job array.
- assets/scenes/world_250m.json: the same recipe on 250 m x 250 m, which still fits one process: the
  bench runs it both ways to measure what the scheduler costs.
Deterministic (a fixed random seed per world)."""
import json
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def r(v, digits=2):
    return round(v, digits)


def world(name, half, rng):
    """The world [-half, half]^2; its clearings, piles and trails scale with its area."""
    per_km2 = (2 * half / 1000.0) ** 2

    def spot():
        return [r(rng.uniform(-half + 20, half - 20)), r(rng.uniform(-half + 20, half - 20))]

    clearings = [{"point": {"center": spot() + [0], "radius": r(rng.uniform(15, 40)), "weight": 0.5}}
                 for _ in range(round(40 * per_km2))]
    piles = [{"point": {"center": spot() + [0], "radius": r(rng.uniform(2, 5)), "weight": r(rng.uniform(0.2, 0.4))}}
             for _ in range(round(120 * per_km2))]
    trails = []
    for _ in range(max(1, round(12 * per_km2))):
        x, y = spot()
        vertices = []
        for _ in range(6):
            vertices.append([r(x), r(y), 0, r(rng.uniform(1.5, 3))])
            x = max(-half + 5, min(half - 5, x + rng.uniform(-60, 60)))
            y = max(-half + 5, min(half - 5, y + rng.uniform(-60, 60)))
        trails.append({"polyline": {"vertices": vertices, "weight": 0.25}})

    def layer(thickness, radius, weight=None):
        d = {"thickness": thickness, "radius": radius}
        if weight is not None:
            d["weight"] = weight
        return {"terrain_layer": d}

    scene = {
        "format": "undergrowth-project",
        "format_version": 2,
        "name": name,
        "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7, "variants": 32},
        "terrain": {
            "procedural": {"origin": [-half, -half], "cell_size_m": 2.0,
                           "width": int(half) + 1, "height": int(half) + 1, "seed": 23, "octaves": 6,
                           "base_height_m": 0, "amplitude_m": 6.0, "feature_size_m": 220, "lacunarity": 2,
                           "gain": 0.5},
            "material": {"base_color": [0.3, 0.25, 0.16], "roughness": 1, "texture": "ground", "texture_scale_m": 0.5},
        },
        "extent": {"min": [-half, -half, -8], "max": [half, half, 8]},
        "instantiation": {"seed": 1, "chunk_size_m": 16},
        "settling": {"enabled": False},
        "detail_types": [
            {
                "name": "grass_tuft",
                "model": {"mesh": "../models/grass_tuft.glb"},
                "material": {"base_color": [0.18, 0.32, 0.09], "roughness": 0.8, "texture": "grass",
                             "texture_scale_m": 0.04, "tint_variation": 0.3},
                "candidates": {"count": 200, "scale": [0.8, 1.3], "orientation": {"mode": "tilt", "tilt_ranges": [[0, 20, 1]]}},
                "density": {"blend": [layer(0.05, 0.1, 0.25),
                                      {"intersection": [layer(0.05, 0.1, 0.5), {"union": clearings}]}]},
                "instancing": {"strategy": "random", "orientation": {"direction": [0, 0, 1], "max_angle_deg": 30}},
            },
            {
                "name": "rock",
                "model": {"mesh": "../models/rock.glb"},
                "material": {"base_color": [0.36, 0.33, 0.29], "roughness": 0.85, "texture": "rock",
                             "texture_scale_m": 0.12, "tint_variation": 0.35},
                "candidates": {"count": 60, "scale": [0.8, 1.3]},
                "density": {"intersection": [layer(0.08, 0.1), {"blend": piles}]},
                "instancing": {"strategy": "random"},
            },
            {
                "name": "pebble",
                "model": {"mesh": "../models/pebble.glb"},
                "material": {"base_color": [0.46, 0.44, 0.41], "roughness": 0.7, "texture": "rock",
                             "texture_scale_m": 0.05, "tint_variation": 0.4},
                "candidates": {"count": 120, "scale": [0.7, 1.4], "position": "jittered"},
                "density": {"intersection": [layer(0.03, 0.05), {"blend": trails}]},
                "instancing": {"strategy": "random"},
            },
        ],
    }
    return scene


def write(name, scene):
    out = os.path.join(HERE, "..", "assets", "scenes", name + ".json")
    with open(out, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    print("wrote", os.path.relpath(out))


write("world_1km", world("world_1km", 500.0, random.Random(20261202)))
write("world_250m", world("world_250m", 125.0, random.Random(20261203)))
