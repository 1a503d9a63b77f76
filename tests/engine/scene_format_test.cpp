// The project file, format version 2: terrain, extent, instantiation settings, density fields and
// instancing settings; exact round trips; version 1 files; errors that name the place and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scene/field_json.h"
#include "scene/project.h"
#include "scene_test_util.h"

namespace ug {
namespace {

using test::sameStructure;
using test::sameValues;

// One of every node kind, and every instancing option across three types.
const char* kEverything = R"({
  "format": "undergrowth-project", "format_version": 2, "name": "everything",
  "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 9},
  "terrain": {"procedural": {"origin": [-4, -3], "cell_size_m": 0.25, "width": 33, "height": 25, "seed": 5,
                             "octaves": 3, "base_height_m": 0.1, "amplitude_m": 0.4, "feature_size_m": 3,
                             "lacunarity": 2.5, "gain": 0.6}},
  "extent": {"min": [-4, -3, -1], "max": [4, 3, 1.5]},
  "instantiation": {"seed": 18446744073709551615, "chunk_size_m": 4.5},
  "detail_types": [
    {"name": "a", "model": {"mesh": "../models/rock.glb"},
     "density": {"blend": [
       {"point": {"center": [0.5, 0.25, 0.1], "radius": 1.5, "weight": 0.7}},
       {"segment": {"a": [0, 0, 0], "b": [2, 1, 0.5], "radius": 0.6}},
       {"segment": {"a": [0, 0, 0], "b": [-1, 2, 0], "radius": 0.4, "end_radius": 0.9, "weight": -0.3, "stroke": 7}},
       {"union": [
         {"disc": {"center": [1, 1, 0.2], "normal": [0, 1, 1], "disc_radius": 0.8, "radius": 0.3, "weight": 2}},
         {"box": {"center": [-1, -1, 0], "half_extents": [0.5, 0.2, 0.1], "radius": 0.25}}]},
       {"intersection": [
         {"half_space": {"point": [0, 0, 0.3], "normal": [0.2, 0, 1], "radius": 0.5}},
         {"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.6}}]},
       {"difference": [
         {"polyline": {"vertices": [[-2, 0, 0, 0.5], [0, 1, 0.2, 0.7], [2, 0, 0, 0.4]], "weight": 0.9}},
         {"polyline": {"vertices": [[-2, 0, 0, 0.2], [2, 0, 0, 0.2]], "weight": -0.5}},
         {"terrain_solid": {"radius": 0.05}}]}]},
     "instancing": {"strategy": "elevation", "layer_m": 0.05,
                    "orientation": {"direction": [1, 1, 0], "max_angle_deg": 45},
                    "size": {"target": 1.2, "tolerance": 0.1}}},
    {"name": "b", "model": {"mesh": "../models/leaf_oak.glb"},
     "density": {"point": {"center": [0, 0, 0], "radius": 2}},
     "terrain_falloff_m": 0.1,
     "angle_of_repose_deg": 42.5,
     "instancing": {"strategy": "distance_to_boundary",
                    "orientation": {"direction": "gradient", "max_angle_deg": 180},
                    "size": {"target": {"field": {"blend": [{"point": {"center": [1, 0, 0], "radius": 1}},
                                                            {"terrain_layer": {"thickness": 0, "radius": 0.2}}]},
                                        "value_lo": 0.1, "value_hi": 0.9, "scale_lo": 1.1, "scale_hi": 0.7},
                             "tolerance": 0}}},
    {"name": "c", "model": {"mesh": "../models/pebble.glb"}, "subtract_terrain": false}
  ]
})";

DensityField handBuiltEverything() {
    DensityField h;
    auto prim = [&](const Primitive& p) { return primitiveChild(addPrimitive(&h, p)); };
    auto node = [&](FieldOp op, std::vector<uint32_t> refs) { return nodeChild(addNode(&h, op, refs)); };
    const uint32_t p0 = prim(makePoint({0.5f, 0.25f, 0.1f}, 1.5f, 0.7f));
    const uint32_t p1 = prim(makeSegment({0, 0, 0}, {2, 1, 0.5f}, 0.6f));
    Primitive cone = makeCone({0, 0, 0}, 0.4f, {-1, 2, 0}, 0.9f, -0.3f);
    cone.stroke = 7;  // the brush stroke's tag, kept through the file
    const uint32_t p2 = prim(cone);
    const uint32_t disc = prim(makeDisc({1, 1, 0.2f}, {0, 1, 1}, 0.8f, 0.3f, 2.0f));
    const uint32_t box = prim(makeBox({-1, -1, 0}, {0.5f, 0.2f, 0.1f}, 0.25f));
    const uint32_t uni = node(FieldOp::Union, {disc, box});
    const uint32_t half = prim(makeHalfSpace({0, 0, 0.3f}, {0.2f, 0, 1}, 0.5f));
    const uint32_t layer = prim(makeTerrainLayer(0, 0.05f, 0.1f, 0.6f));
    const uint32_t inter = node(FieldOp::Intersection, {half, layer});
    const std::vector<glm::vec4> v1 = {{-2, 0, 0, 0.5f}, {0, 1, 0.2f, 0.7f}, {2, 0, 0, 0.4f}};
    const std::vector<glm::vec4> v2 = {{-2, 0, 0, 0.2f}, {2, 0, 0, 0.2f}};
    uint32_t line1 = 0, line2 = 0;
    std::string error;
    EXPECT_TRUE(addPolyline(&h, v1, 0.9f, &line1, &error)) << error;
    EXPECT_TRUE(addPolyline(&h, v2, -0.5f, &line2, &error)) << error;
    const uint32_t solid = prim(makeTerrainSolid(0, 0.05f));
    const uint32_t diff = node(FieldOp::Difference, {line1, line2, solid});
    h.root = addNode(&h, FieldOp::Blend, std::vector<uint32_t>{p0, p1, p2, uni, inter, diff});
    return h;
}

std::shared_ptr<const HeightField> terrainOf(const Project& p) {
    HeightField hf;
    std::string error;
    EXPECT_TRUE(makeProceduralHeightField(p.terrain.procedural, &hf, &error)) << error;
    return std::make_shared<const HeightField>(std::move(hf));
}

DensityField withTerrain(DensityField f, const std::shared_ptr<const HeightField>& terrain) {
    addHeightField(&f, terrain);
    return f;
}

void expectSameProject(const Project& a, const Project& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.terrain.kind, b.terrain.kind);
    EXPECT_EQ(a.terrain.image_path, b.terrain.image_path);
    const ProceduralTerrainDesc &pa = a.terrain.procedural, &pb = b.terrain.procedural;
    EXPECT_TRUE(pa.origin_m == pb.origin_m && pa.cell_size_m == pb.cell_size_m && pa.width == pb.width &&
                pa.height == pb.height && pa.seed == pb.seed && pa.octaves == pb.octaves &&
                pa.base_height_m == pb.base_height_m && pa.amplitude_m == pb.amplitude_m &&
                pa.feature_size_m == pb.feature_size_m && pa.lacunarity == pb.lacunarity &&
                pa.gain == pb.gain);
    const HeightFieldImageDesc &ia = a.terrain.image, &ib = b.terrain.image;
    EXPECT_TRUE(ia.origin_m == ib.origin_m && ia.cell_size_m == ib.cell_size_m &&
                ia.min_height_m == ib.min_height_m && ia.max_height_m == ib.max_height_m);
    ASSERT_EQ(a.extent.has_value(), b.extent.has_value());
    if (a.extent) {
        EXPECT_TRUE(a.extent->lo == b.extent->lo && a.extent->hi == b.extent->hi);
    }
    EXPECT_EQ(a.instantiation_seed, b.instantiation_seed);
    EXPECT_EQ(a.chunk_size_m, b.chunk_size_m);
    ASSERT_EQ(a.detail_types.size(), b.detail_types.size());
    for (size_t t = 0; t < a.detail_types.size(); ++t) {
        SCOPED_TRACE("type " + std::to_string(t));
        const DetailTypeDesc &da = a.detail_types[t], &db = b.detail_types[t];
        EXPECT_TRUE(sameStructure(da.density, db.density));
        EXPECT_EQ(da.subtract_terrain, db.subtract_terrain);
        EXPECT_EQ(da.terrain_falloff_m, db.terrain_falloff_m);
        EXPECT_EQ(da.angle_of_repose_deg, db.angle_of_repose_deg);
        const InstancingDesc &x = da.instancing, &y = db.instancing;
        EXPECT_EQ(x.strategy, y.strategy);
        EXPECT_EQ(x.layer_m, y.layer_m);
        EXPECT_EQ(x.orientation.enabled, y.orientation.enabled);
        EXPECT_EQ(x.orientation.kind, y.orientation.kind);
        EXPECT_TRUE(test::sameBits(x.orientation.direction, y.orientation.direction));
        EXPECT_EQ(x.orientation.max_angle_deg, y.orientation.max_angle_deg);
        EXPECT_EQ(x.size.enabled, y.size.enabled);
        EXPECT_EQ(x.size.kind, y.size.kind);
        EXPECT_EQ(x.size.target, y.size.target);
        EXPECT_TRUE(sameStructure(x.size.field, y.size.field));
        EXPECT_TRUE(x.size.value_lo == y.size.value_lo && x.size.value_hi == y.size.value_hi &&
                    x.size.scale_lo == y.size.scale_lo && x.size.scale_hi == y.size.scale_hi);
        EXPECT_EQ(x.size.tolerance, y.size.tolerance);
    }
}

TEST(SceneFormat, ParsesEveryNodeKindIntoTheFieldTheBuildersMake) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kEverything, "e.json", &p, &error)) << error;
    ASSERT_EQ(p.detail_types.size(), 3u);
    EXPECT_TRUE(sameStructure(p.detail_types[0].density, handBuiltEverything()));
    EXPECT_TRUE(p.detail_types[0].density.height_fields.empty());  // the compiler attaches the terrain

    // A lone primitive becomes a one-child blend (a root must be a node); the absent density is empty.
    const DensityField& b = p.detail_types[1].density;
    ASSERT_EQ(b.nodes.size(), 1u);
    EXPECT_EQ(b.nodes[0].op, FieldOp::Blend);
    EXPECT_EQ(b.root, 0u);
    EXPECT_EQ(p.detail_types[2].density.root, kNoNode);
}

TEST(SceneFormat, ParsesTheSettings) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kEverything, "e.json", &p, &error)) << error;
    EXPECT_EQ(p.source, "e.json");
    EXPECT_EQ(p.terrain.kind, TerrainKind::Procedural);
    EXPECT_EQ(p.terrain.procedural.width, 33);
    EXPECT_EQ(p.terrain.procedural.origin_m, glm::vec2(-4, -3));
    EXPECT_FLOAT_EQ(p.terrain.procedural.lacunarity, 2.5f);
    ASSERT_TRUE(p.extent.has_value());
    EXPECT_EQ(p.extent->hi, glm::vec3(4, 3, 1.5f));
    EXPECT_EQ(p.instantiation_seed, UINT64_MAX);
    EXPECT_EQ(p.chunk_size_m, 4.5f);

    const DetailTypeDesc &a = p.detail_types[0], &b = p.detail_types[1], &c = p.detail_types[2];
    EXPECT_EQ(a.instancing.strategy, PriorityStrategy::Elevation);
    EXPECT_EQ(a.instancing.layer_m, 0.05f);
    EXPECT_TRUE(a.instancing.orientation.enabled);
    EXPECT_EQ(a.instancing.orientation.kind, DirectionFieldKind::Constant);
    EXPECT_NEAR(a.instancing.orientation.direction.x, std::sqrt(0.5f), 1e-6f);  // normalized on load
    EXPECT_EQ(a.instancing.orientation.max_angle_deg, 45.0f);
    EXPECT_TRUE(a.instancing.size.enabled);
    EXPECT_EQ(a.instancing.size.kind, SizeFieldKind::Constant);
    EXPECT_EQ(a.instancing.size.target, 1.2f);
    EXPECT_EQ(a.instancing.size.tolerance, 0.1f);
    EXPECT_TRUE(a.subtract_terrain);  // the default with a terrain
    EXPECT_EQ(a.terrain_falloff_m, 0.05f);
    EXPECT_EQ(a.angle_of_repose_deg, 35.0f);  // the default: loose gravel

    EXPECT_EQ(b.instancing.strategy, PriorityStrategy::DistanceToBoundary);
    EXPECT_EQ(b.instancing.layer_m, 0.02f);
    EXPECT_EQ(b.instancing.orientation.kind, DirectionFieldKind::Gradient);
    EXPECT_EQ(b.instancing.orientation.max_angle_deg, 180.0f);
    EXPECT_EQ(b.instancing.size.kind, SizeFieldKind::Ramp);
    EXPECT_EQ(b.instancing.size.field.primitives.size(), 2u);
    EXPECT_EQ(b.instancing.size.value_lo, 0.1f);
    EXPECT_EQ(b.instancing.size.scale_hi, 0.7f);
    EXPECT_EQ(b.instancing.size.tolerance, 0.0f);
    EXPECT_EQ(b.terrain_falloff_m, 0.1f);
    EXPECT_EQ(b.angle_of_repose_deg, 42.5f);

    EXPECT_EQ(c.instancing.strategy, PriorityStrategy::Random);
    EXPECT_FALSE(c.instancing.orientation.enabled);
    EXPECT_FALSE(c.instancing.size.enabled);
    EXPECT_FALSE(c.subtract_terrain);
}

TEST(SceneFormat, RoundTripIsExact) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kEverything, "e.json", &p, &error)) << error;
    const std::string text = projectToJson(p);
    Project back;
    ASSERT_TRUE(parseProject(text, "back.json", &back, &error)) << error << "\n" << text;
    expectSameProject(p, back);
    EXPECT_EQ(projectToJson(back), text);

    const auto terrain = terrainOf(p);
    const Bounds box = *p.extent;
    EXPECT_TRUE(sameValues(withTerrain(p.detail_types[0].density, terrain),
                           withTerrain(back.detail_types[0].density, terrain), box, 100));
    EXPECT_TRUE(sameValues(withTerrain(p.detail_types[1].instancing.size.field, terrain),
                           withTerrain(back.detail_types[1].instancing.size.field, terrain), box, 50));
    // Floats are written as the shortest decimal that reads back the same.
    EXPECT_NE(text.find("\"delta_m\": -0.002"), std::string::npos) << text;
    EXPECT_EQ(text.find("0.0020000"), std::string::npos);
}

TEST(SceneFormat, ImageTerrainRoundTrips) {
    const std::string text = R"({"format": "undergrowth-project", "format_version": 2,
      "terrain": {"image": {"path": "ground/h.png", "origin": [1, 2], "cell_size_m": 0.5, "min_height_m": -3,
                            "max_height_m": 12.5}},
      "detail_types": [{"name": "g", "model": {"mesh": "g.glb"},
                        "density": {"terrain_layer": {"thickness": 0.1, "radius": 0.2}}}]})";
    Project p, back;
    std::string error;
    ASSERT_TRUE(parseProject(text, "i.json", &p, &error)) << error;
    EXPECT_EQ(p.terrain.kind, TerrainKind::Image);
    EXPECT_EQ(p.terrain.image_path, "ground/h.png");
    EXPECT_EQ(p.terrain.image.max_height_m, 12.5f);
    EXPECT_FALSE(p.extent.has_value());
    ASSERT_TRUE(parseProject(projectToJson(p), "back.json", &back, &error)) << error;
    expectSameProject(p, back);
}

TEST(SceneFormat, FieldsBuiltInMemoryRoundTripAsTrees) {
    // What the editor may produce: a node nobody refers to, a shared child and a DAG root. Writing walks
    // the tree: the orphan is dropped, the shared point written twice, and the values stay identical.
    DensityField f;
    const uint32_t a = primitiveChild(addPrimitive(&f, makePoint({0, 0, 0}, 1.0f)));
    const uint32_t b =
        primitiveChild(addPrimitive(&f, makeBox({0.5f, 0, 0}, {0.2f, 0.2f, 0.2f}, 0.3f, 0.5f)));
    addNode(&f, FieldOp::Union, std::vector<uint32_t>{b});  // unreachable
    const uint32_t u = nodeChild(addNode(&f, FieldOp::Union, std::vector<uint32_t>{a, b}));
    f.root = addNode(&f, FieldOp::Blend, std::vector<uint32_t>{u, a});

    Project p;
    p.detail_types.push_back({});
    p.detail_types[0].model.name = "x";
    p.detail_types[0].model.mesh_path = "x.glb";
    p.detail_types[0].ghost.name = "x";
    p.detail_types[0].density = f;
    Project back;
    std::string error;
    ASSERT_TRUE(parseProject(projectToJson(p), "m.json", &back, &error)) << error;
    const DensityField& g = back.detail_types[0].density;
    EXPECT_EQ(g.primitives.size(), 3u);
    EXPECT_EQ(g.nodes.size(), 2u);
    EXPECT_TRUE(sameValues(f, g, Bounds{glm::vec3(-1.5f), glm::vec3(1.5f)}, 100));
}

TEST(SceneFormat, NormalsAreNormalizedOnLoadAndSavedNormalsReloadBitForBit) {
    const std::string text = R"({"format": "undergrowth-project", "format_version": 2,
      "detail_types": [{"name": "g", "model": {"mesh": "g.glb"},
        "density": {"half_space": {"point": [0, 0, 0], "normal": [3, 0, 4], "radius": 1}}}]})";
    Project p, back;
    std::string error;
    ASSERT_TRUE(parseProject(text, "n.json", &p, &error)) << error;
    const glm::vec3 n = p.detail_types[0].density.primitives[0].normal;
    EXPECT_NEAR(n.x, 0.6f, 1e-7f);
    EXPECT_NEAR(n.z, 0.8f, 1e-7f);
    ASSERT_TRUE(parseProject(projectToJson(p), "back.json", &back, &error)) << error;
    EXPECT_TRUE(test::sameBits(back.detail_types[0].density.primitives[0].normal, n));
}

TEST(SceneFormat, Version1FilesStillLoad) {
    const std::string text = R"({"format": "undergrowth-project", "format_version": 1, "name": "old",
      "detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"count": 10}}]})";
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(text, "old.json", &p, &error)) << error;
    EXPECT_EQ(p.terrain.kind, TerrainKind::None);
    EXPECT_FALSE(p.extent.has_value());
    EXPECT_EQ(p.instantiation_seed, 1u);
    EXPECT_EQ(p.chunk_size_m, 8.0f);
    EXPECT_EQ(p.detail_types[0].density.root, kNoNode);
    EXPECT_EQ(p.detail_types[0].instancing.strategy, PriorityStrategy::Random);
    EXPECT_NE(projectToJson(p).find("\"format_version\": 2"),
              std::string::npos);  // saved as the current version
}

TEST(SceneFormat, ErrorsNameThePlaceAndTheReason) {
    struct Case {
        std::string text;
        std::string expect;
    };
    const std::string v2 = R"({"format": "undergrowth-project", "format_version": 2, )";
    const std::string terrain = R"("terrain": {"procedural": {"width": 9, "height": 9}}, )";
    // A single detail type "t" with the given extra members.
    auto type = [&](const std::string& members, const std::string& top = "") {
        return v2 + top + R"("detail_types": [{"name": "t", "model": {"mesh": "t.glb"})" +
               (members.empty() ? "" : ", " + members) + "}]}";
    };
    auto density = [&](const std::string& node, const std::string& top = "") {
        return type(R"("density": )" + node, top);
    };
    std::string deep = R"({"point": {"center": [0, 0, 0], "radius": 1}})";
    for (int k = 0; k < kMaxFieldDepth; ++k) deep = R"({"blend": [)" + deep + "]}";
    std::string deep_pointer = "/detail_types/0/density";
    for (int k = 0; k < kMaxFieldDepth; ++k) deep_pointer += "/blend/0";

    const std::vector<Case> cases = {
        // density nodes
        {density(R"({"point": {"center": [0, 0, 0], "radius": -1}})"),
         "s.json: /detail_types/0/density/point/radius: must be > 0, got -1"},
        {density(
             R"({"blend": [{"segment": {"a": [0, 0, 0], "b": [1, 0, 0], "radius": 1, "end_radius": 0}}]})"),
         "/detail_types/0/density/blend/0/segment/end_radius: must be > 0, got 0"},
        {density(R"({"disc": {"center": [0, 0, 0], "normal": [0, 0, 0], "disc_radius": 1, "radius": 1}})"),
         "/detail_types/0/density/disc/normal: must not be zero"},
        {density(R"({"half_space": {"point": [0, 0, 0], "normal": [0, 0, 0], "radius": 1}})"),
         "/detail_types/0/density/half_space/normal: must not be zero"},
        {density(R"({"disc": {"center": [0, 0, 0], "normal": [0, 0, 1], "disc_radius": -1, "radius": 1}})"),
         "/detail_types/0/density/disc/disc_radius: must be >= 0, got -1"},
        {density(R"({"box": {"center": [0, 0, 0], "half_extents": [1, -1, 1], "radius": 1}})"),
         "/detail_types/0/density/box/half_extents: must be >= 0 on every axis"},
        {density(R"({"point": {"center": [0, 0, 0], "radius": 1, "stroke": 0}})"),
         "/detail_types/0/density/point/stroke: 0 is out of range [1, "},
        {density(R"({"point": {"center": [0, 0, 0], "radius": 1, "stroke": -2}})"),
         "/detail_types/0/density/point/stroke: expected a non-negative integer, got a negative one"},
        {density(R"({"point": {"center": "here", "radius": 1}})"),
         "/detail_types/0/density/point/center: expected [x, y, z]"},
        {density(R"({"point": {"center": [0, "y", 0], "radius": 1}})"),
         "/detail_types/0/density/point/center/1: expected a number, got a string"},
        {density(R"({"point": {"center": [0, 0, 0], "radius": "big"}})"),
         "/detail_types/0/density/point/radius: expected a number, got a string"},
        {density(R"({"point": {"center": [0, 0, 0]}})"),
         "/detail_types/0/density/point/radius: missing (required)"},
        {density(R"({"point": {"center": [0, 0, 0], "radius": 1, "weight": 1e39}})"),
         "/detail_types/0/density/point/weight: not a finite number (single precision)"},
        {density(R"({"point": {"center": [0, 0, 0], "radius": 1, "colour": 3}})"),
         "/detail_types/0/density/point/colour: unknown field"},
        {density(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})"),
         "/detail_types/0/density/sphere: unknown field node kind 'sphere'"},
        {density(R"({"point": {"center": [0, 0, 0], "radius": 1}, "box": {}})"),
         "/detail_types/0/density: a field node has exactly one key"},
        {density(R"({})"), "/detail_types/0/density: a field node has exactly one key"},
        {density(R"([1, 2])"),
         "/detail_types/0/density: expected a field node such as {\"point\": {...}}, got an array"},
        {density(R"({"blend": {"point": {}}})"),
         "/detail_types/0/density/blend: expected an array of field nodes, got an object"},
        {density(R"({"union": [{"point": {"center": [0, 0, 0], "radius": 1}}, 7]})"),
         "/detail_types/0/density/union/1: expected a field node"},
        {density(R"({"polyline": {"vertices": []}})"),
         "/detail_types/0/density/polyline/vertices: a polyline needs at least 2 vertices, got 0"},
        {density(R"({"polyline": {"weight": 1}})"),
         "/detail_types/0/density/polyline/vertices: missing (required)"},
        {density(R"({"polyline": {"vertices": [[0, 0, 0, 1], [1, 0, 0]]}})"),
         "/detail_types/0/density/polyline/vertices/1: expected [x, y, z, radius]"},
        {density(R"({"polyline": {"vertices": [[0, 0, 0, 1], [1, 0, 0, -0.5]]}})"),
         "/detail_types/0/density/polyline/vertices/1/3: radius must be > 0, got -0.5"},
        {density(R"({"blend": [{"terrain_layer": {"thickness": 0.1, "radius": 0.1}}]})"),
         "/detail_types/0/density/blend/0/terrain_layer: the project has no terrain"},
        {density(R"({"terrain_solid": {"radius": 0.1}})"),
         "/detail_types/0/density/terrain_solid: the project has no terrain"},
        {density(R"({"terrain_layer": {"thickness": -0.1, "radius": 0.1}})", terrain),
         "/detail_types/0/density/terrain_layer/thickness: must be >= 0, got -0.1"},
        {density(deep), deep_pointer + ": field nodes nested deeper than 64 levels"},
        // per-type settings
        {type(R"("subtract_terrain": "yes")"),
         "/detail_types/0/subtract_terrain: expected true or false, got a string"},
        {type(R"("terrain_falloff_m": 0)"), "/detail_types/0/terrain_falloff_m: must be > 0"},
        {type(R"("angle_of_repose_deg": 0)"), "/detail_types/0/angle_of_repose_deg: must be > 0"},
        {type(R"("angle_of_repose_deg": 90)"), "/detail_types/0/angle_of_repose_deg: 90 is out of range [0, 89]"},
        {type(R"("angle_of_repose_deg": "steep")"),
         "/detail_types/0/angle_of_repose_deg: expected a number, got a string"},
        {type(R"("instancing": {"strategy": "lowest"})"),
         "/detail_types/0/instancing/strategy: unknown strategy 'lowest' (random, elevation, "
         "distance_to_boundary)"},
        {type(R"("instancing": {"strategy": 2})"),
         "/detail_types/0/instancing/strategy: expected a string, got an integer"},
        {type(R"("instancing": {"layer_m": 0})"), "/detail_types/0/instancing/layer_m: must be > 0"},
        {type(R"("instancing": {"layer_m": -1})"), "/detail_types/0/instancing/layer_m: -1 is out of range"},
        {type(R"("instancing": {"priority": "random"})"),
         "/detail_types/0/instancing/priority: unknown field"},
        {type(R"("instancing": {"orientation": {"max_angle_deg": 200}})"),
         "/detail_types/0/instancing/orientation/max_angle_deg: 200 is out of range [0, 180]"},
        {type(R"("instancing": {"orientation": {"max_angle_deg": -1}})"),
         "/detail_types/0/instancing/orientation/max_angle_deg: -1 is out of range [0, 180]"},
        {type(R"("instancing": {"orientation": {"direction": [0, 0, 0]}})"),
         "/detail_types/0/instancing/orientation/direction: must not be zero"},
        {type(R"("instancing": {"orientation": {"direction": "up"}})"),
         "/detail_types/0/instancing/orientation/direction: unknown direction 'up'"},
        {type(R"("instancing": {"orientation": {"direction": 1}})"),
         "/detail_types/0/instancing/orientation/direction: expected [x, y, z] or \"gradient\", got an "
         "integer"},
        {type(R"("instancing": {"size": {"tolerance": 0.1}})"),
         "/detail_types/0/instancing/size/target: missing (required)"},
        {type(R"("instancing": {"size": {"target": 0}})"),
         "/detail_types/0/instancing/size/target: must be > 0"},
        {type(R"("instancing": {"size": {"target": "big"}})"),
         "/detail_types/0/instancing/size/target: expected a scale > 0 or {\"field\""},
        {type(R"("instancing": {"size": {"target": 1, "tolerance": -0.5}})"),
         "/detail_types/0/instancing/size/tolerance: -0.5 is out of range"},
        {type(R"("instancing": {"size": {"target": {"value_lo": 0}}})"),
         "/detail_types/0/instancing/size/target/field: missing (required)"},
        {type(R"("instancing": {"size": {"target": {"field": {"point": {"center": [0, 0, 0], "radius": 1}},
                                                     "value_lo": 1, "value_hi": 1}}})"),
         "/detail_types/0/instancing/size/target/value_hi: must be > value_lo (1)"},
        {type(
             R"("instancing": {"size": {"target": {"field": {"point": {"center": [0, 0, 0], "radius": 0}}}}})"),
         "/detail_types/0/instancing/size/target/field/point/radius: must be > 0, got 0"},
        {type(R"("instancing": {"size": {"target": {"field": {"point": {"center": [0, 0, 0], "radius": 1}},
                                                     "scale_lo": 0}}})"),
         "/detail_types/0/instancing/size/target/scale_lo: must be > 0"},
        // top level
        {type("", R"("extent": {"min": [0, 2, 0], "max": [1, 1, 1]}, )"),
         "s.json: /extent: min must be < max on every axis (y: 2 >= 1)"},
        {type("", R"("extent": {"min": [0, 0, 0], "max": [1, 1, 0]}, )"),
         "/extent: min must be < max on every axis (z: 0 >= 0)"},
        {type("", R"("extent": {"min": [0, 0, 0]}, )"), "/extent/max: missing (required)"},
        {type("", R"("extent": {"min": [0, 0], "max": [1, 1, 1]}, )"), "/extent/min: expected [x, y, z]"},
        {type("", R"("terrain": {}, )"), "/terrain: expected {\"procedural\": {...}} or {\"image\": {...}}"},
        {type("", R"("terrain": {"procedural": {}, "image": {"path": "x.png"}}, )"),
         "/terrain: expected {\"procedural\""},
        {type("", R"("terrain": {"procedural": {"gain": 2}}, )"),
         "/terrain/procedural/gain: 2 is out of range [0, 1]"},
        {type("", R"("terrain": {"procedural": {"width": 0}}, )"),
         "/terrain/procedural/width: 0 is out of range"},
        {type("", R"("terrain": {"procedural": {"cell_size_m": 0}}, )"),
         "/terrain/procedural/cell_size_m: must be > 0"},
        {type("", R"("terrain": {"procedural": {"octaves": 17}}, )"),
         "/terrain/procedural/octaves: 17 is out of range"},
        {type("", R"("terrain": {"procedural": {"origin": [0]}}, )"),
         "/terrain/procedural/origin: expected [x, y]"},
        {type("", R"("terrain": {"procedural": {"height_m": 3}}, )"),
         "/terrain/procedural/height_m: unknown field"},
        {type("", R"("terrain": {"image": {"cell_size_m": 1}}, )"),
         "/terrain/image/path: missing (required)"},
        {type("", R"("terrain": {"image": {"path": ""}}, )"), "/terrain/image/path: must not be empty"},
        {type("", R"("terrain": {"image": {"path": "h.png", "min_height_m": 5, "max_height_m": 1}}, )"),
         "/terrain/image/max_height_m: must be >= min_height_m (5)"},
        {type("", R"("instantiation": {"chunk_size_m": 0}, )"), "/instantiation/chunk_size_m: must be > 0"},
        {type("", R"("instantiation": {"seed": -1}, )"),
         "/instantiation/seed: expected a non-negative integer"},
        {type("", R"("instantiation": {"threads": 4}, )"), "/instantiation/threads: unknown field"},
        // version 1 files do not know the version 2 members
        {R"({"format": "undergrowth-project", "format_version": 1, "terrain": {"procedural": {}},
             "detail_types": [{"name": "t", "model": {"mesh": "t.glb"}}]})",
         "s.json: /terrain: needs format_version 2 (this file says 1)"},
        {R"({"format": "undergrowth-project", "format_version": 1,
             "detail_types": [{"name": "t", "model": {"mesh": "t.glb"}, "density": {"blend": []}}]})",
         "/detail_types/0/density: needs format_version 2 (this file says 1)"},
        {R"({"format": "undergrowth-project", "format_version": 5, "detail_types": []})",
         "/format_version: version 5 is newer than this program reads (4)"},
        {R"({"format": "undergrowth-project", "format_version": 2, "environment": {},
             "detail_types": [{"name": "t", "model": {"mesh": "t.glb"}}]})",
         "/environment: needs format_version 3 (this file says 2)"},
    };
    for (const Case& c : cases) {
        Project p;
        std::string error;
        EXPECT_FALSE(parseProject(c.text, "s.json", &p, &error)) << c.text;
        EXPECT_NE(error.find(c.expect), std::string::npos)
            << "expected: " << c.expect << "\n     got: " << error;
        EXPECT_EQ(error.rfind("s.json: /", 0), 0u) << error;
    }
}

TEST(SceneFormat, NestingUpToTheLimitIsAccepted) {
    std::string node = R"({"point": {"center": [0, 0, 0], "radius": 1}})";
    for (int k = 1; k < kMaxFieldDepth; ++k) node = R"({"blend": [)" + node + "]}";
    const std::string text = R"({"format": "undergrowth-project", "format_version": 2,
      "detail_types": [{"name": "t", "model": {"mesh": "t.glb"}, "density": )" +
                             node + "}]}";
    Project p, back;
    std::string error;
    ASSERT_TRUE(parseProject(text, "d.json", &p, &error)) << error;
    EXPECT_EQ(p.detail_types[0].density.nodes.size(), size_t(kMaxFieldDepth - 1));
    ASSERT_TRUE(parseProject(projectToJson(p), "back.json", &back, &error)) << error;
    EXPECT_TRUE(sameStructure(p.detail_types[0].density, back.detail_types[0].density));
}

TEST(SceneFormat, TooManyPrimitivesIsAnError) {
    std::string vertices;
    vertices.reserve((kMaxFieldPrimitives + 2) * 10);
    for (size_t k = 0; k < kMaxFieldPrimitives + 2; ++k) vertices += "[0,0,0,1],";
    vertices.pop_back();
    const std::string text = R"({"format": "undergrowth-project", "format_version": 2,
      "detail_types": [{"name": "t", "model": {"mesh": "t.glb"},
        "density": {"blend": [{"point": {"center": [0, 0, 0], "radius": 1}},
                              {"polyline": {"vertices": [)" +
                             vertices + "]}}]}}]}";
    Project p;
    std::string error;
    EXPECT_FALSE(parseProject(text, "big.json", &p, &error));
    EXPECT_EQ(
        error,
        "big.json: /detail_types/0/density/blend/1/polyline: more than 1000000 primitives in one field");
}

TEST(SceneFormat, SaveAndLoadThroughAFile) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kEverything, "e.json", &p, &error)) << error;
    const std::string path = ::testing::TempDir() + "ug_scene_format_test.json";
    ASSERT_TRUE(saveProject(path, p, &error)) << error;
    Project back;
    ASSERT_TRUE(loadProject(path, &back, &error)) << error;
    EXPECT_EQ(back.source, path);
    expectSameProject(p, back);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace ug
