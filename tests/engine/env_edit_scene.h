// A small street for tests that edit environmental objects (tests/engine, tests/editor): the project's
// JSON, its meshes named by absolute path (the file may be written anywhere).
#pragma once

#include <filesystem>
#include <string>

namespace ug::test {

// A 4 m square: oak leaves scattered by the environment, settling on, a bench (it takes leaves) and a bus
// shelter (it keeps snow and leaves off what is under it), global snow, leaves and cold.
inline std::string envEditProjectJson() {
    const std::string assets = (std::filesystem::path(UG_SOURCE_DIR) / "assets").string();
    return R"({"format": "undergrowth-project", "format_version": 3, "name": "env_doc_test",
 "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 5},
 "extent": {"min": [0, 0, -0.5], "max": [4, 4, 3]},
 "instantiation": {"seed": 1, "chunk_size_m": 8},
 "settling": {"enabled": true, "passes": 8, "max_drop_m": 0.1},
 "terrain": {"procedural": {"origin": [0, 0], "cell_size_m": 0.25, "width": 17, "height": 17, "seed": 3,
                            "octaves": 1, "amplitude_m": 0.0, "feature_size_m": 30}},
 "detail_types": [
  {"name": "leaf", "model": {"mesh": ")" + assets + R"(/models/leaf_oak_dry.glb", "anchors": {"mode": "center"}},
   "candidates": {"count": 200, "scale": [0.8, 1.25]},
   "scatter": {"channel": "leaves", "thickness_m": 0.05}}],
 "environment": {
  "types": [
   {"name": "bench", "mesh": ")" + assets + R"(/env_models/bench.glb", "receives": ["leaves"],
    "snow": {"target_edge_m": 0.04}, "icicles": {"spacing_m": 0.08}},
   {"name": "bus_shelter", "mesh": ")" + assets + R"(/env_models/bus_shelter.glb", "snow": {"target_edge_m": 0.08}}],
  "tree": [{"object": "bench", "at": [1.0, 1.0, 0]}, {"object": "bus_shelter", "at": [2.6, 2.6, 0]}],
  "global_fields": [{"channel": "snow", "value": 0.1}, {"channel": "leaves", "value": 1.0},
                    {"channel": "icicles", "value": 1.0}, {"channel": "temperature", "value": -3.0}],
  "terrain": {"snow": true, "snow_cell_m": 0.1, "receives": ["leaves"]}}})";
}

}  // namespace ug::test
