// Compiling the document. The document keeps fields free of loaded data (terrain primitives say "height
// field 0" and nothing is attached) so it stays a small value that saves, compares and undoes cheaply;
// the compiled fields carry the shared terrain and the subtracted ground solid (Ghost Tile §6.1: "density
// fields are modified by computing the difference with the other solid objects in the scene such as the
// tree and the terrain").
#include "scene/scene_compile.h"

#include <limits>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "material/procedural_texture.h"
#include "mesh/terrain_mesh.h"

namespace ug {

namespace {

std::string sceneLabel(const Project& project) {
    if (!project.source.empty()) return project.source;
    if (!project.name.empty()) return "project '" + project.name + "'";
    return "project";
}

bool fail(std::string* error, const Project& project, const std::string& pointer, const std::string& reason) {
    if (error) *error = sceneLabel(project) + ": " + pointer + ": " + reason;
    return false;
}

bool finiteBounds(const Bounds& b) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a])) return false;
    return true;
}

bool terrainMatches(const Project& project, const HeightField* terrain, std::string* error) {
    if (project.terrain.kind != TerrainKind::None && !terrain)
        return fail(error, project, "/terrain", "the terrain is not loaded (call loadTerrain first)");
    if (project.terrain.kind == TerrainKind::None && terrain)
        return fail(error, project, "/terrain", "a terrain was given but the project has none");
    if (terrain && terrain->empty()) return fail(error, project, "/terrain", "the loaded terrain is empty");
    return true;
}

// A document field with the loaded terrain attached as height field 0 (what its terrain primitives
// refer to).
bool attachTerrain(const DensityField& doc, const std::shared_ptr<const HeightField>& terrain,
                   DensityField* out, std::string* why) {
    if (!doc.height_fields.empty()) {
        *why =
            "the document's field has height fields attached; terrain primitives must refer to the project's "
            "terrain as height field 0 and leave attaching to the compiler";
        return false;
    }
    *out = doc;
    if (terrain) addHeightField(out, terrain);
    return true;
}

// The positive bounds of one compiled field, clipped by the terrain as computeSceneExtent says.
Bounds typeExtent(const DensityField& field, const HeightField* terrain) {
    Bounds b = positiveBounds(field);
    if (b.empty()) return Bounds{};
    if (!terrain) return b;
    const glm::vec2 lo = terrain->origin();
    const glm::vec2 hi =
        lo + glm::vec2(float(terrain->width() - 1), float(terrain->height() - 1)) * terrain->cellSize();
    b.lo.x = std::max(b.lo.x, lo.x);
    b.lo.y = std::max(b.lo.y, lo.y);
    b.hi.x = std::min(b.hi.x, hi.x);
    b.hi.y = std::min(b.hi.y, hi.y);
    if (std::isinf(b.lo.z)) b.lo.z = terrain->minHeight() - kTerrainExtentPadM;
    if (std::isinf(b.hi.z)) b.hi.z = terrain->maxHeight() + kTerrainExtentPadM;
    return b.empty() ? Bounds{} : b;
}

}  // namespace

bool loadTerrain(const Project& project, std::shared_ptr<const HeightField>* out, std::string* error) {
    HeightField hf;
    std::string why;
    switch (project.terrain.kind) {
        case TerrainKind::None:
            out->reset();
            return true;
        case TerrainKind::Procedural:
            if (!makeProceduralHeightField(project.terrain.procedural, &hf, &why))
                return fail(error, project, "/terrain/procedural", why);
            break;
        case TerrainKind::Image: {
            const std::string path = resolveProjectPath(project, project.terrain.image_path);
            if (!loadHeightFieldPng(path, project.terrain.image, &hf, &why))
                return fail(error, project, "/terrain/image/path", why);
            // Refused here, not when the job is done and the terrain mesh cannot be built for the export.
            if (hf.width() < kMinTerrainSide || hf.height() < kMinTerrainSide)
                return fail(error, project, "/terrain/image/path",
                            path + ": the image is " + std::to_string(hf.width()) + "x" + std::to_string(hf.height()) +
                                " pixels; a terrain needs at least " + std::to_string(kMinTerrainSide) +
                                " samples per side");
            break;
        }
    }
    *out = std::make_shared<const HeightField>(std::move(hf));
    return true;
}

bool compileDetailType(const Project& project, size_t type_index,
                       const std::shared_ptr<const HeightField>& terrain, InstanceTypeSettings* out,
                       std::string* error, const std::shared_ptr<const EnvScene>& environment) {
    if (type_index >= project.detail_types.size())
        return fail(error, project, "/detail_types",
                    "no detail type " + std::to_string(type_index) + " (there are " +
                        std::to_string(project.detail_types.size()) + ")");
    if (!terrainMatches(project, terrain.get(), error)) return false;
    const DetailTypeDesc& d = project.detail_types[type_index];
    const std::string tp = "/detail_types/" + std::to_string(type_index);
    std::string why;

    InstanceTypeSettings s;
    auto field = std::make_shared<DensityField>();
    if (!attachTerrain(d.density, terrain, field.get(), &why))
        return fail(error, project, tp + "/density", why);
    if (!validate(*field, &why)) return fail(error, project, tp + "/density", why);
    if (d.scatter.enabled) {
        if (!environment)
            return fail(error, project, tp + "/scatter", "a scattered type needs the environment (none was compiled)");
        if (!validateScatterSettings(d.scatter.settings, tp + "/scatter", &why)) {
            if (error) *error = sceneLabel(project) + ": " + why;
            return false;
        }
        const uint32_t e = addExternal(field.get(), std::make_shared<ScatterField>(environment, d.scatter.settings));
        const uint32_t term = primitiveChild(addPrimitive(field.get(), makeExternal(e)));
        if (field->root == kNoNode) {
            field->root = addNode(field.get(), FieldOp::Blend, std::span<const uint32_t>(&term, 1));
        } else {
            const uint32_t pair[2] = {nodeChild(field->root), term};
            field->root = addNode(field.get(), FieldOp::Blend, pair);
        }
    }
    if (terrain && d.subtract_terrain) {
        if (!std::isfinite(d.terrain_falloff_m) || !(d.terrain_falloff_m > 0.0f))
            return fail(error, project, tp + "/terrain_falloff_m", "must be finite and > 0");
        subtractSolids(field.get(), {makeTerrainSolid(0, d.terrain_falloff_m)});
        s.sink.terrain = terrain;  // what keeps details out of the ground also keeps them from sinking in
    } else if (!terrain && project.settling.ground_z) {
        s.sink.ground_z = *project.settling.ground_z;  // the floor the settling rests them on
    }
    s.field = field;

    const InstancingDesc& in = d.instancing;
    const std::string ip = tp + "/instancing";
    s.strategy = in.strategy;
    if (!std::isfinite(in.layer_m) || !(in.layer_m > 0.0f))
        return fail(error, project, ip + "/layer_m", "must be finite and > 0");
    s.layer_m = in.layer_m;

    if (in.orientation.enabled) {
        const OrientationDesc& o = in.orientation;
        if (!(o.max_angle_deg >= 0.0f && o.max_angle_deg <= 180.0f))
            return fail(error, project, ip + "/orientation/max_angle_deg", "must be in [0, 180]");
        s.orientation.enabled = true;
        s.orientation.direction.kind = o.kind;
        if (o.kind == DirectionFieldKind::Constant)
            s.orientation.direction.direction = o.direction;
        else
            s.orientation.direction.field = field;  // Fig. 17 right: u = ∇f_i of this very type
        s.orientation.min_cos =
            float(std::clamp(std::cos(double(o.max_angle_deg) * std::numbers::pi / 180.0), -1.0, 1.0));
        if (!validate(s.orientation.direction, &why))
            return fail(error, project, ip + "/orientation/direction", why);
    }

    if (in.size.enabled) {
        const SizeDesc& z = in.size;
        if (!std::isfinite(z.tolerance) || z.tolerance < 0.0f)
            return fail(error, project, ip + "/size/tolerance", "must be finite and >= 0");
        s.size.enabled = true;
        s.size.tolerance = z.tolerance;
        s.size.target.kind = z.kind;
        if (z.kind == SizeFieldKind::Constant) {
            s.size.target.scale = z.target;
        } else {
            auto size_field = std::make_shared<DensityField>();
            if (!attachTerrain(z.field, terrain, size_field.get(), &why))
                return fail(error, project, ip + "/size/target/field", why);
            s.size.target.field = std::move(size_field);
            s.size.target.value_lo = z.value_lo;
            s.size.target.value_hi = z.value_hi;
            s.size.target.scale_lo = z.scale_lo;
            s.size.target.scale_hi = z.scale_hi;
        }
        if (!validate(s.size.target, &why)) return fail(error, project, ip + "/size/target", why);
    }
    *out = std::move(s);
    return true;
}

Bounds computeSceneExtent(const Project& project, const CompiledScene& scene) {
    if (project.extent) return *project.extent;
    Bounds u;
    for (const InstanceTypeSettings& t : scene.types)
        if (t.field) u = unite(u, typeExtent(*t.field, scene.terrain.get()));
    return u;
}

bool compileScene(const Project& project, std::shared_ptr<const HeightField> terrain, CompiledScene* out,
                  std::string* error, std::shared_ptr<const EnvScene> environment) {
    if (!terrainMatches(project, terrain.get(), error)) return false;
    CompiledScene scene;
    scene.terrain = std::move(terrain);
    scene.environment = std::move(environment);
    scene.types.resize(project.detail_types.size());
    for (size_t t = 0; t < project.detail_types.size(); ++t)
        if (!compileDetailType(project, t, scene.terrain, &scene.types[t], error, scene.environment)) return false;

    if (project.extent) {
        const Bounds& e = *project.extent;
        if (!finiteBounds(e) || !(e.lo.x < e.hi.x && e.lo.y < e.hi.y && e.lo.z < e.hi.z))
            return fail(error, project, "/extent", "must be finite with min < max on every axis");
    } else {
        // Name the type that makes the extent unbounded: that is the one whose density needs changing
        // (or the reason to write an extent).
        for (size_t t = 0; t < scene.types.size(); ++t) {
            const Bounds b = typeExtent(*scene.types[t].field, scene.terrain.get());
            if (!b.empty() && !finiteBounds(b))
                return fail(error, project, "/extent",
                            "required because the density of '" + project.detail_types[t].model.name +
                                "' is unbounded");
        }
    }
    scene.extent = computeSceneExtent(project, scene);
    if (scene.extent.empty())
        return fail(error, project, "/extent", "required because no detail type has any density");
    for (int a = 0; a < 3; ++a)
        if (!(scene.extent.lo[a] < scene.extent.hi[a]))
            return fail(error, project, "/extent",
                        std::string("required because the derived extent is flat along ") + "xyz"[a]);
    *out = std::move(scene);
    return true;
}

SettleInput settleInput(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                        const GhostTile& tile, const std::vector<DetailModel>& models, const EnvScene* environment) {
    SettleInput in;
    if (environment && !environment->objects().empty()) in.support.surfaces = environment;
    in.tile = &tile;
    for (const DetailModel& m : models) in.models.push_back(&m);
    in.settings = project.settling.settle;
    in.support.terrain = terrain.get();
    in.support.ground_z = project.settling.ground_z ? *project.settling.ground_z : -std::numeric_limits<float>::infinity();
    return in;
}

SceneMaterials compileSceneMaterials(const Project& project, const std::vector<DetailModel>& models,
                                     const std::vector<std::vector<DetailModel>>* variant_models) {
    SceneMaterials out;
    // The detail map is the slow part (tens of ms) and depends only on the kind and the cut-out; the
    // bake per colour is cheap. Identical baked textures are shared, not copied.
    struct DetailMap {
        TextureKind kind;
        bool cutout;
        TextureImage image;
    };
    std::vector<DetailMap> maps;
    std::vector<SurfaceMaterial> baked;
    auto resolve = [&](const Material& m, glm::vec3 surface_color) {
        Material flat = m;
        flat.texture = TextureKind::None;  // resolveMaterial would bake; the texture is found or made below
        SurfaceMaterial s = resolveMaterial(flat, surface_color);
        s.texture_kind = m.texture;
        if (m.texture == TextureKind::None) return s;
        for (const SurfaceMaterial& b : baked)
            if (b.texture_kind == m.texture && b.alpha_cutout == m.alpha_cutout && b.base_color == s.base_color) {
                s.texture = b.texture;
                return s;
            }
        auto map = std::find_if(maps.begin(), maps.end(),
                                [&](const DetailMap& d) { return d.kind == m.texture && d.cutout == m.alpha_cutout; });
        if (map == maps.end()) {
            maps.push_back({m.texture, m.alpha_cutout, makeDetailMap(m.texture, m.alpha_cutout)});
            map = maps.end() - 1;
        }
        s.texture = std::make_shared<const TextureImage>(bakeTexture(map->image, s.base_color));
        baked.push_back(s);
        return s;
    };
    out.types.reserve(project.detail_types.size());
    for (size_t t = 0; t < project.detail_types.size(); ++t)
        out.types.push_back(resolve(project.detail_types[t].material,
                                    t < models.size() ? models[t].mesh.base_color : TriangleMesh{}.base_color));
    out.terrain = resolve(project.terrain.material, kTerrainColor);
    // The scattered types' variants, after every type (detail_looks.h: the looks' order), against their
    // own models' colours when given.
    for (size_t t = 0; t < project.detail_types.size(); ++t) {
        const std::vector<ScatterVariantDesc>& variants = project.detail_types[t].scatter.variants;
        for (size_t k = 0; k < variants.size(); ++k) {
            const glm::vec3 own = variant_models && t < variant_models->size() && k < (*variant_models)[t].size()
                                      ? (*variant_models)[t][k].mesh.base_color
                                      : TriangleMesh{}.base_color;
            out.types.push_back(resolve(variants[k].material, own));
        }
    }
    return out;
}

InstancerInput instancerInputOf(const GhostTile& tile, const std::vector<DetailModel>& models,
                                const CompiledScene& compiled, uint64_t seed) {
    InstancerInput in;
    in.tile = &tile;
    for (const DetailModel& m : models) in.models.push_back(&m);
    in.types = compiled.types;
    in.extent = compiled.extent;
    in.seed = seed;
    return in;
}

}  // namespace ug
