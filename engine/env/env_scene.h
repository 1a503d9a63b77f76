// The environmental-object scene compiled (Grosbellet et al. 2016 §3-§4, §6.1; docs/architecture.md
// "Environmental objects"): the type library with its meshes loaded, the tree expanded into a flat list of
// objects (references followed, group overrides inherited), every emitted field placed in the world, and
// the environment e(p) with the shelter term.
//
//   EnvScene env;
//   if (!compileEnvScene(project.environment, project.base_dir, "street.json", terrain, &env, &error)) ...
//   EnvSample e = env.sample({1, 2, 0.5});             // channels + shelter at a world point
//   env.sampleBatch(points, n, out);                   // bit-identical to sample() per point
//
// Fields: channels blend by sum, occlusion by product of α_i = 1 - value·K(d) (§4). A point sums the fields
// whose support holds it, always in the order the fields were placed (types' fields per object in tree
// order, then nodes' own, then the global ones), so the scalar, batched and any region's evaluation agree
// bit for bit. An LOD node's own fields replace its subtree's for these queries when use_lod_nodes is on
// (§6.1); with it off, LOD nodes act as groups.
//
// Shelter: the fraction of 9 rays, from a 3 x 3 grid of kShelterCellM around the point and going back up
// along the snowfall (EnvironmentDesc::snow_direction; straight up by default), that no object's base
// geometry crosses more than kShelterEpsM above the point (height_span_map.h). With a snow_spread_deg the
// 8 outer rays fan out over a cone of that half-angle around the snowfall (the centre one keeps to it),
// so a lee or the snow line under a roof fades over a distance that grows with the height of what
// shelters it. The terrain shelters nothing (it is below).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "env/env_desc.h"
#include "env/env_sample.h"
#include "env/height_span_map.h"
#include "field/bounds.h"
#include "instancer/rest_support.h"
#include "field/height_field.h"
#include "mesh/triangle_mesh.h"

namespace ug {

constexpr float kShelterEpsM = 0.03f;  // geometry closer above a point than this does not shelter it

// object space -> world: translate(t) * rotateZ(yaw) * scale(s).
struct EnvPlacement {
    glm::vec3 t{0.0f};
    float c = 1.0f, s = 0.0f;  // cos and sin of the yaw
    float scale = 1.0f;
    float yaw_deg = 0.0f;

    static EnvPlacement of(const EnvTransform& tr);
    // this ∘ child: the child's placement in this one's space, composed.
    EnvPlacement compose(const EnvPlacement& child) const;
    glm::vec3 toWorld(glm::vec3 p) const;
    glm::vec3 toLocal(glm::vec3 p) const;
    bool operator==(const EnvPlacement&) const = default;
};

struct EnvObjectType {
    EnvTypeDesc desc;
    std::shared_ptr<const TriangleMesh> mesh;  // object space, Z up, normals
    std::shared_ptr<const HeightSpanMap> spans;
    Bounds3 bounds;                            // of the mesh
};

struct EnvObject {
    uint32_t type = 0;
    EnvPlacement placement;
    SnowEffectDesc snow;        // the type's, with the overrides of the object and its ancestors applied
    IcicleEffectDesc icicles;
    Bounds bounds;              // world AABB of the base mesh
    std::string where;          // the node's JSON Pointer in the file, for messages
};

struct EnvWorldField {
    EnvChannel channel = EnvChannel::Snow;
    bool everywhere = false;
    float value = 0.0f;
    Primitive shape;          // in the owner's space
    EnvPlacement owner;       // owner space -> world
    uint32_t owner_object = UINT32_MAX;  // the object whose type emits it; none for a node's or a global one
    Bounds bounds;            // world AABB of the support (everything for a global field)
};

class EnvScene : public RestSurfaces {
public:
    const std::vector<EnvObjectType>& types() const { return types_; }
    const std::vector<EnvObject>& objects() const { return objects_; }
    const std::vector<EnvWorldField>& fields() const { return fields_; }
    const std::shared_ptr<const HeightField>& terrain() const { return terrain_; }
    const EnvironmentDesc& desc() const { return desc_; }
    bool empty() const { return objects_.empty() && fields_.empty(); }
    // World AABB of every object (empty when there is none).
    const Bounds& objectBounds() const { return object_bounds_; }

    EnvSample sample(glm::vec3 p) const;
    void sampleBatch(const glm::vec3* points, size_t n, EnvSample* out) const;
    // The channels only (shelter left at 1); the batch is bit-identical to channels() per point.
    EnvSample channels(glm::vec3 p) const;
    // `channels` (envChannelBit bits) restricts the sums to those channels: the others read 0 (occlusion
    // 1), the asked ones are bit-identical to channels().
    void channelsBatch(const glm::vec3* points, size_t n, EnvSample* out, uint32_t channels = kAllEnvChannels) const;
    float shelter(glm::vec3 p) const { return shelterRays(p, false); }
    // Only the centre ray (0 or 1): what effect sharing compares objects by (a ninth of the cost).
    float shelterCentre(glm::vec3 p) const { return shelterRays(p, true); }
    // The free fall below p: p.z minus the highest base geometry or terrain under it (+inf over nothing).
    float clearanceBelow(glm::vec3 p) const;
    // What p would rest on (env_scatter.h): the highest up-facing surface at or below it, the terrain's or
    // an object's.
    struct Support {
        float z = -std::numeric_limits<float>::infinity();  // -inf: nothing below
        int64_t object = -1;  // the object whose surface it is; -1: the terrain (or nothing)
        bool inside = false;  // p lies inside an object's base geometry: nothing rests there
    };
    Support supportBelow(glm::vec3 p) const;
    // RestSurfaces (instancer/rest_support.h): what settled details rest on — supportBelow's height over
    // every object (receiving or not), and the tops of the objects over a rectangle.
    float surfaceBelow(float x, float y, float z) const override;
    float surfaceTopIn(glm::vec2 lo, glm::vec2 hi) const override;
    // An upper bound of channel c over box: the sum over the fields meeting it of each one's largest value in
    // the box (value·K at the box's distance from the field's skeleton; the value itself where that is not
    // known).
    float channelBound(EnvChannel c, const Bounds& box) const;
    // Calls fn(object id) for every object whose XY bounds may meet box's XY (ids may repeat).
    template <typename Fn>
    void forObjectsNearXY(const Bounds& box, Fn fn) const;
    // The environment at object-space points of `object` (EnvQuery for the effects).
    EnvQuery objectQuery(size_t object) const;

    // Horizontal drift per metre of rise back along the snowfall ((0, 0) for snow falling straight down).
    glm::vec2 snowSlope() const;
    // The largest horizontal drift per metre of rise of any shelter ray (the snowfall's plus the spread):
    // how far sideways what shelters a point can lie, per metre above it.
    float shelterDrift() const { return shelter_drift_; }
    // The shelter below which nothing takes snow (SnowSettings::min_open): half the rays when they all
    // follow the snowfall (a face half under a roof's edge), any one of them when they fan out, where the
    // depth, which grows with the shelter, already fades the snow out behind a lee.
    float snowMinOpen() const { return desc_.snow_spread_deg > 0.0f ? 0.1f : 0.5f; }
    // How many fields a query in `box` has to look at (the LOD nodes' gain, §6.1, in the bench).
    size_t candidateFieldCount(const Bounds& box) const;

private:
    friend bool compileEnvScene(const EnvironmentDesc&, const std::string&, const std::string&,
                                std::shared_ptr<const HeightField>, EnvScene*, std::string*, const EnvScene*);
    void buildIndex();
    // The indices (ascending) of the fields whose bounds meet `box` (the global ones always).
    void fieldsMeeting(const Bounds& box, std::vector<uint32_t>* out) const;
    // Appends the indices (ascending) of fields whose bounds hold p.
    void fieldsAt(glm::vec3 p, std::vector<uint32_t>* out) const;
    // The objects whose XY bounds, padded by the shelter rays' reach, hold (x, y) (ascending ids; empty
    // outside the grid).
    std::span<const uint32_t> objectsAt(float x, float y) const;
    // The grid cell holding (x, y), or -1 outside the grid.
    long objectCellAt(float x, float y) const;
    EnvSample accumulate(glm::vec3 p, const uint32_t* ids, size_t n) const;
    float shelterRays(glm::vec3 p, bool centre_only) const;
    // The objects a point's shelter rays may meet, each once (a fanned snowfall's nine rays cross mostly
    // the same grid cells): ids in the order found, an object marked by the set's current round.
    struct ShelterCandidates {
        std::vector<uint32_t> ids;
        std::vector<uint32_t> round_of;       // per object: the last round that listed it
        std::vector<uint32_t> cell_round_of;  // per grid cell: the last round that read its list
        uint32_t round = 0;
        void begin(size_t objects, size_t cells);
    };
    // Adds the objects that may shelter p along drift `slope` per metre of rise.
    void shelterCandidates(glm::vec3 p, glm::vec2 slope, ShelterCandidates* out) const;

    EnvironmentDesc desc_;
    std::vector<EnvObjectType> types_;
    std::vector<EnvObject> objects_;
    std::vector<EnvWorldField> fields_;
    std::shared_ptr<const HeightField> terrain_;
    Bounds object_bounds_;
    // Each shelter ray's drift per metre of rise, world XY (ray 4, the centre, is the snowfall's own).
    std::array<glm::vec2, 9> ray_slopes_{};
    float shelter_drift_ = 0.0f;

    // Field index: a BVH over the local fields' bounds (leaves hold field ids), plus the global ones.
    struct Node {
        Bounds box;
        uint32_t first = 0, count = 0;  // leaf: range in leaf_ids_; inner: count 0, children first, first + 1
    };
    std::vector<Node> nodes_;
    std::vector<uint32_t> leaf_ids_;
    std::vector<uint32_t> global_ids_;
    // Object index: a uniform XY grid of object ids (ascending per cell).
    glm::vec2 grid_origin_{0.0f};
    float grid_cell_ = 1.0f;
    int grid_nx_ = 0, grid_ny_ = 0;
    std::vector<uint32_t> grid_first_, grid_ids_;
};

template <typename Fn>
void EnvScene::forObjectsNearXY(const Bounds& box, Fn fn) const {
    if (grid_nx_ == 0) return;
    const auto cell = [&](float v, float origin, int n) {
        return std::clamp(int(std::floor((v - origin) / grid_cell_)), 0, n - 1);
    };
    if (box.hi.x < grid_origin_.x || box.hi.y < grid_origin_.y ||
        box.lo.x >= grid_origin_.x + grid_cell_ * float(grid_nx_) || box.lo.y >= grid_origin_.y + grid_cell_ * float(grid_ny_))
        return;
    const int i0 = cell(box.lo.x, grid_origin_.x, grid_nx_), i1 = cell(box.hi.x, grid_origin_.x, grid_nx_);
    const int j0 = cell(box.lo.y, grid_origin_.y, grid_ny_), j1 = cell(box.hi.y, grid_origin_.y, grid_ny_);
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            const size_t c = size_t(j) * size_t(grid_nx_) + size_t(i);
            for (uint32_t k = grid_first_[c]; k < grid_first_[c + 1]; ++k) fn(grid_ids_[k]);
        }
}

// Loads every type's mesh (relative paths against base_dir), expands the tree and indexes the fields.
// Errors: "<name>: /environment/...: <reason>" (a missing or corrupt mesh names the file too; a reference to
// an unknown group or a reference cycle names the reference; more than kMaxEnvObjects objects after
// expansion is refused before they are made). `previous` (may be null): a scene compiled before an edit,
// whose loaded meshes are reused for types with the same mesh path, scale and axes (an edit then costs
// the tree's expansion, not the mesh loads).
bool compileEnvScene(const EnvironmentDesc& desc, const std::string& base_dir, const std::string& name,
                     std::shared_ptr<const HeightField> terrain, EnvScene* out, std::string* error,
                     const EnvScene* previous = nullptr);

// True when what details rest on is the same in both (RestSurfaces: surfaceBelow and surfaceTopIn answer
// alike everywhere): the same objects in the same order, placed alike, of types with the same meshes. An
// edit of fields only (a footprint, a warm brush, the global snow) keeps the support, so the instances
// resting on it need not be settled again.
bool sameRestSurfaces(const EnvScene& a, const EnvScene& b);

}  // namespace ug
