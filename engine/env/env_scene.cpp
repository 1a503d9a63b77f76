#include "env/env_scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "field/primitive.h"
#include "mesh/mesh_loader.h"

namespace ug {

namespace {

constexpr float kDegToRad = 0.017453292519943295f;

// An upper bound of a field's value over a world box, far tighter than its peak for the boxes a tile
// asks about (a tree's 8 m leaf field seen from a 25 cm tile): value·K(d_min, R), d_min the distance from
// the box (placed in the owner's space) to the AABB of the skeleton, which no point of the skeleton is
// nearer than. Kinds without a small skeleton (half-spaces, terrain kinds) are bounded by their weight.
float fieldBoundIn(const EnvWorldField& f, const Bounds& box) {
    const float peak = std::max(0.0f, f.value);
    if (f.everywhere || peak == 0.0f) return peak;
    const Primitive& sh = f.shape;
    glm::vec3 lo = sh.center_m, hi = sh.center_m;
    float radius = sh.radius_m;
    switch (sh.kind) {
        case PrimitiveKind::Point: break;
        case PrimitiveKind::Segment:
            lo = glm::min(lo, sh.end_m);
            hi = glm::max(hi, sh.end_m);
            radius = std::max(sh.radius_m, sh.end_radius_m);
            break;
        case PrimitiveKind::Disc:
            lo -= glm::vec3(sh.disc_radius_m);
            hi += glm::vec3(sh.disc_radius_m);
            break;
        case PrimitiveKind::Box:
            lo -= sh.half_extents_m;
            hi += sh.half_extents_m;
            break;
        default: return peak;
    }
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a])) return peak;
    glm::vec3 blo(std::numeric_limits<float>::infinity()), bhi(-std::numeric_limits<float>::infinity());
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z);
        const glm::vec3 l = f.owner.toLocal(c);
        blo = glm::min(blo, l);
        bhi = glm::max(bhi, l);
    }
    const glm::vec3 gap = glm::max(glm::vec3(0.0f), glm::max(lo - bhi, blo - hi));
    // Shortened a little against the rounding of the placed corners and of K's own evaluation.
    const float d = std::max(0.0f, glm::length(gap) * (1.0f - 1e-4f) - 1e-5f);
    if (d >= radius) return 0.0f;
    const float q = 1.0f - d * d / (radius * radius);
    return peak * q * q * q;
}

// Primitive bounds mapped through a placement: the local box's corners placed, then their AABB (a turn
// about Z of an AABB stays within the placed corners' AABB; the scale and translation are exact).
Bounds placedBounds(const Bounds& local, const EnvPlacement& pl) {
    if (local.empty()) return local;
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(local.lo[a]) || !std::isfinite(local.hi[a])) return Bounds::everything();
    Bounds out;
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c((k & 1) ? local.hi.x : local.lo.x, (k & 2) ? local.hi.y : local.lo.y,
                          (k & 4) ? local.hi.z : local.lo.z);
        const glm::vec3 w = pl.toWorld(c);
        out.lo = glm::min(out.lo, w);
        out.hi = glm::max(out.hi, w);
    }
    // Rounding of the placed corners: pad by a few ulps of the coordinates.
    const glm::vec3 pad = glm::max(glm::abs(out.lo), glm::abs(out.hi)) * 4e-7f + glm::vec3(1e-6f);
    out.lo -= pad;
    out.hi += pad;
    return out;
}

void applyOverrides(const EffectOverrides& o, SnowEffectDesc* snow, IcicleEffectDesc* ice) {
    if (o.snow_mode) snow->mode = *o.snow_mode;
    if (o.snow_max_face_angle_deg) snow->max_face_angle_deg = *o.snow_max_face_angle_deg;
    if (o.snow_d0_m) snow->d0_m = *o.snow_d0_m;
    if (o.snow_target_edge_m) snow->target_edge_m = *o.snow_target_edge_m;
    if (o.icicles_enabled) ice->enabled = *o.icicles_enabled;
    if (o.icicle_spacing_m) ice->spacing_m = *o.icicle_spacing_m;
    if (o.icicle_max_length_m) ice->max_length_m = *o.icicle_max_length_m;
}

// The inherited state while walking the tree: the overrides from the root down (nearest last).
struct WalkState {
    EnvPlacement placement;
    std::vector<const EffectOverrides*> overrides;
    bool under_lod = false;  // an LOD node above supplies the fields of this subtree
};

class TreeExpander {
public:
    TreeExpander(const EnvironmentDesc& desc, const std::vector<EnvObjectType>& types, const std::string& name,
                 std::vector<EnvObject>* objects, std::vector<EnvWorldField>* fields, std::string* error)
        : desc_(desc), types_(types), name_(name), objects_(objects), fields_(fields), error_(error) {}

    // Counts the objects the tree expands into (references followed) before any is made, refusing cycles,
    // unknown groups and counts over kMaxEnvObjects.
    bool count(const EnvNode& n, const std::string& where, int depth, std::vector<std::string>* stack, size_t* total) {
        if (depth > kMaxEnvTreeDepth) return fail(where, "the tree (references followed) is deeper than " +
                                                             std::to_string(kMaxEnvTreeDepth) + " levels");
        switch (n.kind) {
        case EnvNodeKind::Object:
            if (++*total > kMaxEnvObjects)
                return fail(where, "the tree expands to more than " + std::to_string(kMaxEnvObjects) + " objects");
            return true;
        case EnvNodeKind::Reference: {
            const NamedEnvGroup* g = group(n.target);
            if (!g) return fail(where + "/ref", "no group named \"" + n.target + "\" in /environment/groups");
            if (std::find(stack->begin(), stack->end(), n.target) != stack->end())
                return fail(where + "/ref", "reference cycle: group \"" + n.target + "\" refers back to itself");
            stack->push_back(n.target);
            const bool ok = count(g->group, "/environment/groups/" + n.target, depth + 1, stack, total);
            stack->pop_back();
            return ok;
        }
        case EnvNodeKind::Group:
        case EnvNodeKind::Lod:
            for (size_t i = 0; i < n.children.size(); ++i)
                if (!count(n.children[i], childPointer(n, where, i), depth + 1, stack, total)) return false;
            return true;
        }
        return true;
    }

    void expand(const EnvNode& n, const std::string& where, const WalkState& parent) {
        WalkState st = parent;
        st.placement = parent.placement.compose(EnvPlacement::of(n.transform));
        if (!n.overrides.empty()) st.overrides.push_back(&n.overrides);
        const bool lod = n.kind == EnvNodeKind::Lod && desc_.use_lod_nodes;
        // An LOD node's own fields stand for its subtree; below it, nothing else emits.
        if (!parent.under_lod) addFields(n.fields, st.placement);
        if (lod) st.under_lod = true;
        switch (n.kind) {
        case EnvNodeKind::Object: {
            const EnvObjectType& type = types_[n.type];
            EnvObject o;
            o.type = n.type;
            o.placement = st.placement;
            o.snow = type.desc.snow;
            o.icicles = type.desc.icicles;
            for (const EffectOverrides* ov : st.overrides) applyOverrides(*ov, &o.snow, &o.icicles);
            o.bounds = placedBounds(Bounds{type.bounds.min, type.bounds.max}, o.placement);
            o.where = where;
            objects_->push_back(std::move(o));
            if (!parent.under_lod) addFields(type.desc.fields, st.placement, uint32_t(objects_->size() - 1));
            return;
        }
        case EnvNodeKind::Reference:
            expand(group(n.target)->group, "/environment/groups/" + n.target, st);
            return;
        case EnvNodeKind::Group:
        case EnvNodeKind::Lod:
            for (size_t i = 0; i < n.children.size(); ++i) expand(n.children[i], childPointer(n, where, i), st);
            return;
        }
    }

private:
    bool fail(const std::string& where, const std::string& reason) {
        *error_ = name_ + ": " + where + ": " + reason;
        return false;
    }
    static std::string childPointer(const EnvNode& n, const std::string& where, size_t i) {
        return where + (n.kind == EnvNodeKind::Lod ? "/lod" : "/group") + "/children/" + std::to_string(i);
    }
    const NamedEnvGroup* group(const std::string& name) const {
        for (const NamedEnvGroup& g : desc_.groups)
            if (g.name == name) return &g;
        return nullptr;
    }
    void addFields(const std::vector<EnvFieldDesc>& fields, const EnvPlacement& owner, uint32_t owner_object = UINT32_MAX) {
        for (const EnvFieldDesc& f : fields) {
            EnvWorldField w;
            w.channel = f.channel;
            w.everywhere = f.everywhere;
            w.value = f.value;
            w.shape = f.shape;
            w.owner = owner;
            w.owner_object = owner_object;
            w.bounds = f.everywhere ? Bounds::everything() : placedBounds(primitiveBounds(f.shape, nullptr), owner);
            fields_->push_back(w);
        }
    }

    const EnvironmentDesc& desc_;
    const std::vector<EnvObjectType>& types_;
    const std::string& name_;
    std::vector<EnvObject>* objects_;
    std::vector<EnvWorldField>* fields_;
    std::string* error_;
};

bool loadType(const EnvTypeDesc& desc, size_t index, const std::string& base_dir, const std::string& name,
              EnvObjectType* out, std::string* error) {
    namespace fs = std::filesystem;
    const std::string where = name + ": /environment/types/" + std::to_string(index) + "/mesh: ";
    fs::path path(desc.mesh_path);
    if (path.is_relative() && !base_dir.empty()) path = fs::path(base_dir) / path;
    auto mesh = std::make_shared<TriangleMesh>();
    if (!loadMeshFile(path.lexically_normal().string(), mesh.get(), error)) {
        *error = where + *error;
        return false;
    }
    if (desc.y_up) convertYUpToZUp(mesh.get());
    if (desc.scale != 1.0f) scaleMesh(mesh.get(), desc.scale);
    if (!validateMesh(*mesh, error)) {
        *error = where + path.string() + ": " + *error;
        return false;
    }
    computeNormals(mesh.get());
    out->desc = desc;
    out->bounds = meshBounds(*mesh);
    out->spans = std::make_shared<HeightSpanMap>(*mesh);
    out->mesh = std::move(mesh);
    return true;
}

}  // namespace

EnvPlacement EnvPlacement::of(const EnvTransform& tr) {
    EnvPlacement p;
    p.t = tr.translation;
    p.yaw_deg = tr.yaw_deg;
    p.c = std::cos(tr.yaw_deg * kDegToRad);
    p.s = std::sin(tr.yaw_deg * kDegToRad);
    p.scale = tr.scale;
    return p;
}

EnvPlacement EnvPlacement::compose(const EnvPlacement& child) const {
    EnvPlacement out;
    out.t = toWorld(child.t);
    out.c = c * child.c - s * child.s;
    out.s = s * child.c + c * child.s;
    out.scale = scale * child.scale;
    out.yaw_deg = yaw_deg + child.yaw_deg;
    return out;
}

glm::vec3 EnvPlacement::toWorld(glm::vec3 p) const {
    const glm::vec3 q = p * scale;
    return glm::vec3(c * q.x - s * q.y, s * q.x + c * q.y, q.z) + t;
}

glm::vec3 EnvPlacement::toLocal(glm::vec3 p) const {
    const glm::vec3 d = p - t;
    return glm::vec3(c * d.x + s * d.y, -s * d.x + c * d.y, d.z) / scale;
}

namespace {

// The shelter rays' drifts per metre of rise: the snowfall's for the centre ray (4); the other 8 about
// the cone of half-angle spread_deg around it (drift offsets of tan(spread), exact for snow falling
// straight down), as four opposite pairs on two rings (radius 1 and 0.55 of the cone's, 45 degrees
// apart, turned 11.25 degrees off the axes). Opposite pairs keep the set centred on the snowfall, and
// no two rays share a drift across or along a wall on the axes: a lee fades in nine steps, not three.
std::array<glm::vec2, 9> shelterRaySlopes(glm::vec2 slope, float spread_deg) {
    std::array<glm::vec2, 9> out;
    out.fill(slope);
    if (!(spread_deg > 0.0f)) return out;
    const float radius = std::tan(glm::radians(spread_deg));
    int m = 0;
    for (int k = 0; k < 9; ++k) {
        if (k == 4) continue;
        const float a = glm::radians(11.25f + 45.0f * float(m));
        out[size_t(k)] = slope + radius * (m % 2 ? 0.55f : 1.0f) * glm::vec2(std::cos(a), std::sin(a));
        ++m;
    }
    return out;
}

}  // namespace

bool compileEnvScene(const EnvironmentDesc& desc, const std::string& base_dir, const std::string& name,
                     std::shared_ptr<const HeightField> terrain, EnvScene* out, std::string* error,
                     const EnvScene* previous) {
    if (!(desc.snow_spread_deg >= 0.0f && desc.snow_spread_deg <= kMaxSnowSpreadDeg))
        return *error = name + ": /environment/snow_spread_deg: must be in [0, " +
                        std::to_string(int(kMaxSnowSpreadDeg)) + "]",
               false;
    EnvScene scene;
    scene.desc_ = desc;
    scene.ray_slopes_ = shelterRaySlopes(scene.snowSlope(), desc.snow_spread_deg);
    for (glm::vec2 s : scene.ray_slopes_) scene.shelter_drift_ = std::max(scene.shelter_drift_, glm::length(s));
    scene.terrain_ = std::move(terrain);
    scene.types_.resize(desc.types.size());
    for (size_t t = 0; t < desc.types.size(); ++t) {
        const EnvTypeDesc& d = desc.types[t];
        const EnvObjectType* same = nullptr;
        if (previous)
            for (const EnvObjectType& old : previous->types())
                if (old.desc.mesh_path == d.mesh_path && old.desc.scale == d.scale && old.desc.y_up == d.y_up) same = &old;
        if (same) {
            scene.types_[t] = *same;
            scene.types_[t].desc = d;
        } else if (!loadType(d, t, base_dir, name, &scene.types_[t], error)) {
            return false;
        }
    }
    TreeExpander tree(desc, scene.types_, name, &scene.objects_, &scene.fields_, error);
    size_t total = 0;
    std::vector<std::string> stack;
    for (size_t i = 0; i < desc.roots.size(); ++i)
        if (!tree.count(desc.roots[i], "/environment/tree/" + std::to_string(i), 0, &stack, &total)) return false;
    for (const NamedEnvGroup& g : desc.groups) {  // a cycle among groups no tree node uses is still an error
        stack.assign(1, g.name);
        size_t unused = 0;
        if (!tree.count(g.group, "/environment/groups/" + g.name, 1, &stack, &unused)) return false;
    }
    scene.objects_.reserve(total);
    for (size_t i = 0; i < desc.roots.size(); ++i)
        tree.expand(desc.roots[i], "/environment/tree/" + std::to_string(i), WalkState{});
    for (const EnvFieldDesc& f : desc.global_fields) {
        EnvWorldField w;
        w.channel = f.channel;
        w.everywhere = f.everywhere;
        w.value = f.value;
        w.shape = f.shape;
        w.bounds = f.everywhere ? Bounds::everything() : primitiveBounds(f.shape, nullptr);
        scene.fields_.push_back(w);
    }
    if (scene.fields_.size() > kMaxEnvFields)
        return *error = name + ": /environment: " + std::to_string(scene.fields_.size()) +
                        " fields after expansion exceed the limit of " + std::to_string(kMaxEnvFields),
               false;
    for (const EnvObject& o : scene.objects_) {
        scene.object_bounds_.lo = glm::min(scene.object_bounds_.lo, o.bounds.lo);
        scene.object_bounds_.hi = glm::max(scene.object_bounds_.hi, o.bounds.hi);
    }
    scene.buildIndex();
    *out = std::move(scene);
    return true;
}

// ---- indexes ---------------------------------------------------------------------------------------------

void EnvScene::buildIndex() {
    // Fields: global ones (unbounded in every axis) apart; a median-split BVH over the others.
    std::vector<uint32_t> local;
    global_ids_.clear();
    for (uint32_t i = 0; i < fields_.size(); ++i) {
        const Bounds& b = fields_[i].bounds;
        bool finite = !b.empty();
        for (int a = 0; a < 3 && finite; ++a) finite = std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]);
        (finite ? local : global_ids_).push_back(i);
    }
    nodes_.clear();
    leaf_ids_.clear();
    if (!local.empty()) {
        struct Task {
            uint32_t node, begin, end;
        };
        nodes_.push_back({});
        std::vector<Task> tasks = {{0, 0, uint32_t(local.size())}};
        while (!tasks.empty()) {
            const Task t = tasks.back();
            tasks.pop_back();
            Bounds box;
            for (uint32_t k = t.begin; k < t.end; ++k) {
                box.lo = glm::min(box.lo, fields_[local[k]].bounds.lo);
                box.hi = glm::max(box.hi, fields_[local[k]].bounds.hi);
            }
            nodes_[t.node].box = box;
            if (t.end - t.begin <= 4) {
                nodes_[t.node].first = uint32_t(leaf_ids_.size());
                nodes_[t.node].count = t.end - t.begin;
                std::vector<uint32_t> ids(local.begin() + t.begin, local.begin() + t.end);
                std::sort(ids.begin(), ids.end());
                leaf_ids_.insert(leaf_ids_.end(), ids.begin(), ids.end());
                continue;
            }
            const glm::vec3 ext = box.hi - box.lo;
            const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
            const uint32_t mid = (t.begin + t.end) / 2;
            std::nth_element(local.begin() + t.begin, local.begin() + mid, local.begin() + t.end,
                             [&](uint32_t a, uint32_t b) {
                                 const float ca = fields_[a].bounds.lo[axis] + fields_[a].bounds.hi[axis];
                                 const float cb = fields_[b].bounds.lo[axis] + fields_[b].bounds.hi[axis];
                                 return ca < cb || (ca == cb && a < b);
                             });
            const uint32_t left = uint32_t(nodes_.size());
            nodes_.push_back({});
            nodes_.push_back({});
            nodes_[t.node].first = left;
            nodes_[t.node].count = 0;
            tasks.push_back({left, t.begin, mid});
            tasks.push_back({left + 1, mid, t.end});
        }
    }
    // Objects: a uniform XY grid of about 4 objects per cell.
    grid_ids_.clear();
    grid_first_.clear();
    grid_nx_ = grid_ny_ = 0;
    if (objects_.empty()) return;
    // Every object's bounds are padded by the shelter rays' 3 x 3 spread; the grid covers the padded bounds.
    const glm::vec2 lo = glm::vec2(object_bounds_.lo) - kShelterCellM, hi = glm::vec2(object_bounds_.hi) + kShelterCellM;
    const float area = std::max((hi.x - lo.x) * (hi.y - lo.y), 1e-4f);
    grid_cell_ = std::max(std::sqrt(area * 4.0f / float(objects_.size())), 0.25f);
    grid_origin_ = lo;
    grid_nx_ = std::min(4096, int((hi.x - lo.x) / grid_cell_) + 1);
    grid_ny_ = std::min(4096, int((hi.y - lo.y) / grid_cell_) + 1);
    grid_cell_ = std::max((hi.x - lo.x) / float(grid_nx_), (hi.y - lo.y) / float(grid_ny_)) * 1.0001f + 1e-6f;
    const size_t cells = size_t(grid_nx_) * size_t(grid_ny_);
    std::vector<uint32_t> count(cells + 1, 0);
    auto range = [&](const Bounds& b, int* i0, int* i1, int* j0, int* j1) {
        const float pad = kShelterCellM;
        *i0 = std::clamp(int((b.lo.x - pad - grid_origin_.x) / grid_cell_), 0, grid_nx_ - 1);
        *i1 = std::clamp(int((b.hi.x + pad - grid_origin_.x) / grid_cell_), 0, grid_nx_ - 1);
        *j0 = std::clamp(int((b.lo.y - pad - grid_origin_.y) / grid_cell_), 0, grid_ny_ - 1);
        *j1 = std::clamp(int((b.hi.y + pad - grid_origin_.y) / grid_cell_), 0, grid_ny_ - 1);
    };
    for (const EnvObject& o : objects_) {
        int i0, i1, j0, j1;
        range(o.bounds, &i0, &i1, &j0, &j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) ++count[size_t(j) * grid_nx_ + i + 1];
    }
    for (size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
    grid_first_ = count;
    grid_ids_.resize(grid_first_[cells]);
    for (uint32_t k = 0; k < objects_.size(); ++k) {
        int i0, i1, j0, j1;
        range(objects_[k].bounds, &i0, &i1, &j0, &j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) grid_ids_[count[size_t(j) * grid_nx_ + i]++] = k;
    }
}

void EnvScene::fieldsAt(glm::vec3 p, std::vector<uint32_t>* out) const {
    out->assign(global_ids_.begin(), global_ids_.end());
    if (!nodes_.empty()) {
        uint32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (!contains(n.box, p)) continue;
            if (n.count > 0) {
                for (uint32_t k = n.first; k < n.first + n.count; ++k)
                    if (contains(fields_[leaf_ids_[k]].bounds, p)) out->push_back(leaf_ids_[k]);
            } else if (top + 2 <= 128) {
                stack[top++] = n.first;
                stack[top++] = n.first + 1;
            }
        }
    }
    std::sort(out->begin(), out->end());
}

void EnvScene::fieldsMeeting(const Bounds& box, std::vector<uint32_t>* out) const {
    out->assign(global_ids_.begin(), global_ids_.end());
    if (!nodes_.empty()) {
        thread_local std::vector<uint32_t> stack;
        stack.assign(1, 0);
        while (!stack.empty()) {
            const Node& node = nodes_[stack.back()];
            stack.pop_back();
            if (!overlaps(node.box, box)) continue;
            if (node.count > 0) {
                for (uint32_t k = node.first; k < node.first + node.count; ++k)
                    if (overlaps(fields_[leaf_ids_[k]].bounds, box)) out->push_back(leaf_ids_[k]);
            } else {
                stack.push_back(node.first);
                stack.push_back(node.first + 1);
            }
        }
    }
    std::sort(out->begin(), out->end());
}

size_t EnvScene::candidateFieldCount(const Bounds& box) const {
    std::vector<uint32_t> ids;
    fieldsMeeting(box, &ids);
    return ids.size();
}

long EnvScene::objectCellAt(float x, float y) const {
    if (grid_nx_ == 0) return -1;
    const float fx = (x - grid_origin_.x) / grid_cell_, fy = (y - grid_origin_.y) / grid_cell_;
    if (!(fx >= 0.0f && fy >= 0.0f && fx < float(grid_nx_) && fy < float(grid_ny_))) return -1;
    return long(int(fy)) * grid_nx_ + long(int(fx));
}

std::span<const uint32_t> EnvScene::objectsAt(float x, float y) const {
    const long c = objectCellAt(x, y);
    if (c < 0) return {};
    return {grid_ids_.data() + grid_first_[size_t(c)], grid_first_[size_t(c) + 1] - grid_first_[size_t(c)]};
}

// ---- evaluation ------------------------------------------------------------------------------------------

EnvSample EnvScene::accumulate(glm::vec3 p, const uint32_t* ids, size_t n) const {
    float sum[kEnvChannelCount] = {};
    float alpha = 1.0f;
    for (size_t k = 0; k < n; ++k) {
        const EnvWorldField& f = fields_[ids[k]];
        const float v = f.everywhere ? f.value : primitiveValue(f.shape, nullptr, f.owner.toLocal(p));
        if (f.channel == EnvChannel::Occlusion)
            alpha *= 1.0f - v;
        else
            sum[size_t(f.channel)] += v;
    }
    EnvSample e;
    e.snow = sum[size_t(EnvChannel::Snow)];
    e.icicles = sum[size_t(EnvChannel::Icicles)];
    e.leaves = sum[size_t(EnvChannel::Leaves)];
    e.grass = sum[size_t(EnvChannel::Grass)];
    e.trash = sum[size_t(EnvChannel::Trash)];
    e.occlusion = std::clamp(alpha, 0.0f, 1.0f);
    e.humidity = sum[size_t(EnvChannel::Humidity)];
    e.temperature = sum[size_t(EnvChannel::Temperature)];
    return e;
}

EnvSample EnvScene::channels(glm::vec3 p) const {
    thread_local std::vector<uint32_t> ids;  // millions of calls per scattered layer: no allocation each
    fieldsAt(p, &ids);
    return accumulate(p, ids.data(), ids.size());
}

void EnvScene::ShelterCandidates::begin(size_t objects, size_t cells) {
    ids.clear();
    if (round_of.size() < objects) round_of.resize(objects, 0);
    if (cell_round_of.size() < cells) cell_round_of.resize(cells, 0);
    if (++round == 0) {  // wrapped: no mark may equal a later round by accident
        std::fill(round_of.begin(), round_of.end(), 0u);
        std::fill(cell_round_of.begin(), cell_round_of.end(), 0u);
        round = 1;
    }
}

void EnvScene::shelterCandidates(glm::vec3 p, glm::vec2 slope, ShelterCandidates* out) const {
    // The objects of the grid cells along the ray's drift, up to the top of the scene.
    const float rise = std::max(0.0f, object_bounds_.hi.z - p.z);
    const float drift = glm::length(slope);
    const int steps = drift > 0.0f ? int(std::ceil(2.0f * drift * rise / grid_cell_)) : 0;
    for (int k = 0; k <= steps; ++k) {
        const glm::vec2 at = glm::vec2(p) + slope * (rise * float(k) / float(std::max(steps, 1)));
        // A ray takes two steps a cell, and a fan's rays start in one: each cell's list is read once.
        const long c = objectCellAt(at.x, at.y);
        if (c < 0 || out->cell_round_of[size_t(c)] == out->round) continue;
        out->cell_round_of[size_t(c)] = out->round;
        for (uint32_t i = grid_first_[size_t(c)]; i < grid_first_[size_t(c) + 1]; ++i) {
            const uint32_t o = grid_ids_[i];
            // Listed once, if it can reach above p and keeps things off.
            if (out->round_of[o] == out->round || objects_[o].bounds.hi.z <= p.z + kShelterEpsM ||
                !types_[objects_[o].type].desc.shelters)
                continue;
            out->round_of[o] = out->round;
            out->ids.push_back(o);
        }
    }
}

float EnvScene::shelterRays(glm::vec3 p, bool centre_only) const {
    // The 9 rays start within kShelterCellM of p on each axis (the grid pads every object by that much) and
    // drift by their slope per metre of rise.
    bool covered[9] = {};
    const int rays = centre_only ? 1 : 9;
    int open = rays;
    const bool fanned = !centre_only && desc_.snow_spread_deg > 0.0f;
    const float drift = fanned ? shelter_drift_ : glm::length(ray_slopes_[4]);
    // Whether a ray is covered does not depend on the order the objects are tried in.
    thread_local ShelterCandidates candidates;
    candidates.begin(objects_.size(), size_t(grid_nx_) * size_t(grid_ny_));
    if (fanned) {
        for (glm::vec2 slope : ray_slopes_) shelterCandidates(p, slope, &candidates);
    } else {
        shelterCandidates(p, ray_slopes_[4], &candidates);
    }
    for (uint32_t o : candidates.ids) {
        const EnvObject& obj = objects_[o];
        const float reach = kShelterCellM + drift * std::max(0.0f, obj.bounds.hi.z - p.z);
        if (obj.bounds.hi.z <= p.z + kShelterEpsM || p.x < obj.bounds.lo.x - reach || p.x > obj.bounds.hi.x + reach ||
            p.y < obj.bounds.lo.y - reach || p.y > obj.bounds.hi.y + reach)
            continue;
        const EnvObjectType& type = types_[obj.type];
        const glm::vec3 local = obj.placement.toLocal(p);
        // The world offsets (i, j) * cell and the drifts turned into the object's space.
        const float inv = kShelterCellM / obj.placement.scale;
        const glm::vec2 ex(obj.placement.c * inv, -obj.placement.s * inv);  // world +X in object space
        const glm::vec2 ey(obj.placement.s * inv, obj.placement.c * inv);   // world +Y
        const float eps = kShelterEpsM / obj.placement.scale;
        const auto toObject = [&](glm::vec2 slope) {
            return glm::vec2(obj.placement.c * slope.x + obj.placement.s * slope.y,
                             -obj.placement.s * slope.x + obj.placement.c * slope.y);
        };
        // One direction turned once for every ray; fanned rays each turn their own.
        const glm::vec2 snowfall_local = toObject(ray_slopes_[4]);
        for (int k = 0; k < rays; ++k) {
            if (covered[k]) continue;
            const int ray = centre_only ? 4 : k;  // 4: the centre of the 3 x 3
            const float i = float(ray % 3 - 1), j = float(ray / 3 - 1);
            const glm::vec2 local_slope = fanned ? toObject(ray_slopes_[size_t(ray)]) : snowfall_local;
            const glm::vec3 q(local.x + i * ex.x + j * ey.x, local.y + i * ex.y + j * ey.y, local.z);
            if (type.spans->coveredAlong(q, local_slope, eps, type.bounds.min.z, type.bounds.max.z)) {
                covered[k] = true;
                --open;
            }
        }
        if (open == 0) break;
    }
    return float(open) / float(rays);
}

glm::vec2 EnvScene::snowSlope() const {
    const glm::vec3 up = -desc_.snow_direction;  // back along the snowfall
    return glm::vec2(up.x, up.y) / up.z;
}

float EnvScene::clearanceBelow(glm::vec3 p) const {
    float floor_z = -std::numeric_limits<float>::infinity();
    if (terrain_ && !terrain_->empty()) floor_z = terrain_->sample(p.x, p.y);
    for (uint32_t o : objectsAt(p.x, p.y)) {
        const EnvObject& obj = objects_[o];
        if (!contains(Bounds{glm::vec3(obj.bounds.lo.x, obj.bounds.lo.y, -INFINITY),
                             glm::vec3(obj.bounds.hi.x, obj.bounds.hi.y, p.z)},
                      p))
            continue;
        const float below = types_[obj.type].spans->highestBelow(obj.placement.toLocal(p), kShelterEpsM / obj.placement.scale);
        if (below > -std::numeric_limits<float>::infinity())
            floor_z = std::max(floor_z, obj.placement.toWorld(glm::vec3(0.0f, 0.0f, below)).z);
    }
    return p.z - floor_z;
}

EnvScene::Support EnvScene::supportBelow(glm::vec3 p) const {
    Support s;
    if (terrain_ && !terrain_->empty()) {
        const float h = terrain_->sample(p.x, p.y);
        if (h <= p.z) s.z = h;
    }
    for (uint32_t o : objectsAt(p.x, p.y)) {
        const EnvObject& obj = objects_[o];
        if (!contains(Bounds{glm::vec3(obj.bounds.lo.x, obj.bounds.lo.y, -INFINITY),
                             glm::vec3(obj.bounds.hi.x, obj.bounds.hi.y, INFINITY)},
                      p) ||
            obj.bounds.lo.z > p.z)
            continue;
        bool inside = false;
        const float below = types_[obj.type].spans->supportBelow(obj.placement.toLocal(p), &inside);
        if (inside) {
            s.inside = true;
            s.object = o;
            return s;
        }
        if (!(below > -std::numeric_limits<float>::infinity())) continue;
        const float z = obj.placement.toWorld(glm::vec3(0.0f, 0.0f, below)).z;
        if (z > s.z) {
            s.z = z;
            s.object = o;
        }
    }
    return s;
}

float EnvScene::surfaceBelow(float x, float y, float z) const {
    const Support s = supportBelow(glm::vec3(x, y, z));
    return s.inside ? z : s.z;
}

float EnvScene::surfaceTopIn(glm::vec2 lo, glm::vec2 hi) const {
    float top = -std::numeric_limits<float>::infinity();
    if (terrain_ && !terrain_->empty()) top = terrain_->heightRange(lo, hi).y;
    forObjectsNearXY(Bounds{glm::vec3(lo, 0.0f), glm::vec3(hi, 0.0f)}, [&](uint32_t o) {
        const Bounds& b = objects_[o].bounds;
        if (b.hi.x >= lo.x && b.lo.x <= hi.x && b.hi.y >= lo.y && b.lo.y <= hi.y) top = std::max(top, b.hi.z);
    });
    return top;
}

bool sameRestSurfaces(const EnvScene& a, const EnvScene& b) {
    if (a.terrain() != b.terrain() || a.objects().size() != b.objects().size() || a.types().size() != b.types().size())
        return false;
    for (size_t t = 0; t < a.types().size(); ++t)
        if (a.types()[t].spans != b.types()[t].spans) return false;
    for (size_t o = 0; o < a.objects().size(); ++o) {
        const EnvObject& x = a.objects()[o];
        const EnvObject& y = b.objects()[o];
        if (x.type != y.type || !(x.placement == y.placement)) return false;
    }
    return true;
}

float EnvScene::channelBound(EnvChannel c, const Bounds& box) const {
    thread_local std::vector<uint32_t> ids;
    fieldsMeeting(box, &ids);
    float bound = 0.0f;
    for (uint32_t k : ids)
        if (fields_[k].channel == c) bound += fieldBoundIn(fields_[k], box);
    // The sum of the bounds, rounded like the sum of the values it bounds: a few ulps more.
    return bound > 0.0f ? bound * (1.0f + 1e-5f) : 0.0f;
}

EnvSample EnvScene::sample(glm::vec3 p) const {
    EnvSample e = channels(p);
    e.shelter = shelter(p);
    return e;
}

void EnvScene::channelsBatch(const glm::vec3* points, size_t n, EnvSample* out, uint32_t channels) const {
    if (n == 0) return;
    // The fields whose bounds meet the batch's box, in index order; per point those holding it, in the
    // same order channels() sums them: the same value bit for bit.
    Bounds box;
    for (size_t k = 0; k < n; ++k) {
        box.lo = glm::min(box.lo, points[k]);
        box.hi = glm::max(box.hi, points[k]);
    }
    thread_local std::vector<uint32_t> near, ids;
    fieldsMeeting(box, &near);
    if (channels != kAllEnvChannels)
        near.erase(std::remove_if(near.begin(), near.end(),
                                  [&](uint32_t f) { return !(envChannelBit(fields_[f].channel) & channels); }),
                   near.end());
    ids.reserve(near.size());
    for (size_t k = 0; k < n; ++k) {
        ids.clear();
        for (uint32_t f : near)
            if (contains(fields_[f].bounds, points[k])) ids.push_back(f);
        out[k] = accumulate(points[k], ids.data(), ids.size());
    }
}

void EnvScene::sampleBatch(const glm::vec3* points, size_t n, EnvSample* out) const {
    channelsBatch(points, n, out);
    for (size_t k = 0; k < n; ++k) out[k].shelter = shelter(points[k]);
}

EnvQuery EnvScene::objectQuery(size_t object) const {
    const EnvPlacement pl = objects_[object].placement;
    return [this, pl](const glm::vec3* points, size_t n, EnvSample* out) {
        std::vector<glm::vec3> world(n);
        for (size_t k = 0; k < n; ++k) world[k] = pl.toWorld(points[k]);
        sampleBatch(world.data(), n, out);
    };
}

}  // namespace ug
