// From the project document to what the instantiator runs on: the terrain as a height field, one
// InstanceTypeSettings per detail type (density with the terrain attached and the ground solid
// subtracted, direction and size fields) and the region to instantiate.
//
//   Project project;
//   if (!loadProject("meadow.json", &project, &error)) ...
//   std::shared_ptr<const HeightField> terrain;
//   if (!loadTerrain(project, &terrain, &error)) ...        // once; the slow part for a big image
//   CompiledScene scene;
//   if (!compileScene(project, terrain, &scene, &error)) ...
//   SceneMaterials looks = compileSceneMaterials(project, models);   // what the surfaces look like
//   // after the user edits detail type 2:
//   if (!compileDetailType(project, 2, terrain, &scene.types[2], &error)) ...
//
// Errors: "<scene>: <JSON pointer>: <reason>", the pointer naming the offending setting where there is
// one ("/detail_types/2/density", "/terrain/image/path", "/extent"); <scene> is Project::source, or the
// project's name when it was not loaded from a file.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "field/height_field.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instancing_settings.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "material/material.h"
#include "env/env_scene.h"
#include "scene/project.h"

namespace ug {

// computeSceneExtent pads the terrain's height range by this much where a field is unbounded in Z.
constexpr float kTerrainExtentPadM = 2.0f;

struct CompiledScene {
    std::shared_ptr<const HeightField> terrain;  // null when the project has none
    // What scattered types (DetailTypeDesc::scatter) read their density from; null when the project has
    // no environment (then no type may scatter).
    std::shared_ptr<const EnvScene> environment;
    std::vector<InstanceTypeSettings> types;     // one per detail type, same order
    Bounds extent;                               // finite, lo < hi on every axis
};

// What the instantiator runs on for a compiled scene: the tile and its models (pointers into them: they
// must outlive the input), the compiled types and extent, the seed. The one builder the document, the
// loader and the CLI share.
InstancerInput instancerInputOf(const GhostTile& tile, const std::vector<DetailModel>& models,
                                const CompiledScene& compiled, uint64_t seed);

// Builds the project's terrain: null for TerrainKind::None, the procedural fBm, or the PNG (its path
// resolved against the project's folder).
bool loadTerrain(const Project& project, std::shared_ptr<const HeightField>* out, std::string* error);

// Every type's settings (compileDetailType) and the extent (computeSceneExtent). `terrain` must be what
// loadTerrain returned for this project (null exactly when it has none). Fails when the extent is not
// given and cannot be derived: "<scene>: /extent: required because the density of '<type>' is
// unbounded", or "... because no detail type has any density" when every field is empty.
// `environment`: the project's compiled environment (env_scene.h), needed by scattered types (an error
// names the first one when it is missing).
bool compileScene(const Project& project, std::shared_ptr<const HeightField> terrain, CompiledScene* out,
                  std::string* error, std::shared_ptr<const EnvScene> environment = nullptr);

// One type, for the editor's per-edit recompile:
//   field        the document's density with `terrain` attached as height field 0, then
//                Difference(field, terrain solid(falloff)) when subtract_terrain and there is a terrain;
//                never null (an empty density compiles to a field that is 0 everywhere);
//   orientation  Constant: the direction; Gradient: of `field` (the same shared object);
//                min_cos = cos(max_angle_deg);
//   size         Constant: the target; Ramp: its own field, with the terrain attached (no subtraction).
// A scattered type's field is Blend(its density, External(ScatterField on `environment`)) before the
// ground solid is subtracted.
// *out is untouched on failure.
bool compileDetailType(const Project& project, size_t type_index,
                       const std::shared_ptr<const HeightField>& terrain, InstanceTypeSettings* out,
                       std::string* error, const std::shared_ptr<const EnvScene>& environment = nullptr);

// The project's extent when it has one. Otherwise the union over types of the positive bounds of their
// compiled fields (positiveBounds: conservative), where, when there is a terrain,
//   - X and Y are clipped to the terrain's rectangle (a terrain layer is unbounded in XY, and the
//     terrain is the world),
//   - an unbounded Z side becomes the terrain's lowest height - kTerrainExtentPadM or its highest
//     + kTerrainExtentPadM (bounded sides are kept: a tall pile on a hilltop stays whole).
// The result may be empty (no density anywhere) or infinite (a field unbounded without a terrain to clip
// it): compileScene reports both.
Bounds computeSceneExtent(const Project& project, const CompiledScene& scene);

// The settling pass's input for the project (instancer/settling.h): the project's settings, the terrain
// as support (or the ground plane when the project gives ground_z, or none), and the environment's
// objects when given (details rest on a bench's seat); `tile`, `models` (one per type) and `environment`
// are kept by pointer, so they must outlive the result.
SettleInput settleInput(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                        const GhostTile& tile, const std::vector<DetailModel>& models,
                        const EnvScene* environment = nullptr);

// Every detail type's material resolved against its model's base colour, and the terrain's against
// kTerrainColor, with their textures baked (material/procedural_texture.h): the same bytes as
// resolveMaterial gives, but each kind's detail map is made once and identical textures (same kind,
// cut-out and colour) are shared. `models` is loadProjectModels' result (one per type); a missing model
// resolves against the default mesh colour. Cost: 5-110 ms per distinct kind (256 x 256, measured on
// the loaded 2-core build machine; rock is the slowest), about 1 ms per further colour.
// SceneMaterials::types holds one material per look (detail_looks.h): the types', then their scatter
// variants' (resolved against `variant_models`' colours when given, else the default mesh colour).
SceneMaterials compileSceneMaterials(const Project& project, const std::vector<DetailModel>& models,
                                     const std::vector<std::vector<DetailModel>>* variant_models = nullptr);

}  // namespace ug
