#include "env/env_effects.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/hash.h"
#include "core/parallel.h"
#include "env/snow.h"
#include "env/snow_joints.h"

namespace ug {

namespace {

// ---- identity of objects and fields (for reuse and dirty regions) ------------------------------------------

void hashPlacement(Hasher* h, const EnvPlacement& p) {
    h->add(p.t.x), h->add(p.t.y), h->add(p.t.z), h->add(p.c), h->add(p.s), h->add(p.scale), h->add(p.yaw_deg);
}

void hashSettings(Hasher* h, const EnvObject& o) {
    h->add(uint32_t(o.snow.mode));
    h->add(o.snow.max_face_angle_deg), h->add(o.snow.d0_m), h->add(o.snow.target_edge_m);
    h->add(uint32_t(o.icicles.enabled)), h->add(uint32_t(o.icicles.automatic_anchors));
    h->add(o.icicles.spacing_m), h->add(o.icicles.max_length_m), h->add(o.icicles.length_per_degree_m);
    h->add(uint64_t(o.icicles.anchors.size()));
    for (glm::vec3 a : o.icicles.anchors) h->add(a.x), h->add(a.y), h->add(a.z);
}

bool sameSettings(const EnvObject& a, const EnvObject& b) {
    return a.type == b.type && a.snow.mode == b.snow.mode && a.snow.max_face_angle_deg == b.snow.max_face_angle_deg &&
           a.snow.d0_m == b.snow.d0_m && a.snow.target_edge_m == b.snow.target_edge_m &&
           a.icicles.enabled == b.icicles.enabled && a.icicles.automatic_anchors == b.icicles.automatic_anchors &&
           a.icicles.spacing_m == b.icicles.spacing_m && a.icicles.max_length_m == b.icicles.max_length_m &&
           a.icicles.length_per_degree_m == b.icicles.length_per_degree_m && a.icicles.anchors == b.icicles.anchors;
}

bool sameObject(const EnvObject& a, const EnvObject& b) { return sameSettings(a, b) && a.placement == b.placement; }

uint64_t objectKey(const EnvObject& o) {
    Hasher h;
    h.add(o.type);
    hashPlacement(&h, o.placement);
    hashSettings(&h, o);
    return h.value();
}

void hashPrimitive(Hasher* h, const Primitive& p) {
    h->add(uint32_t(p.kind)), h->add(p.weight), h->add(p.radius_m), h->add(p.end_radius_m), h->add(p.disc_radius_m);
    for (glm::vec3 v : {p.center_m, p.end_m, p.normal, p.half_extents_m}) h->add(v.x), h->add(v.y), h->add(v.z);
}

uint64_t fieldKey(const EnvWorldField& f) {
    Hasher h;
    h.add(uint32_t(f.channel)), h.add(uint32_t(f.everywhere)), h.add(f.value);
    if (!f.everywhere) hashPrimitive(&h, f.shape);
    hashPlacement(&h, f.owner);
    return h.value();
}

// The column over a box that its effects read: shelter looks up it (slanting back along the snowfall, so
// widened by the drift up to the scene's top) and icicle clearance down it.
Bounds column(const EnvScene& scene, const Bounds& b) {
    const float rise = std::max(0.0f, scene.objectBounds().hi.z - b.lo.z);
    const float pad = 2.0f * kShelterCellM + scene.shelterDrift() * (std::isfinite(rise) ? rise : 0.0f);
    return Bounds{glm::vec3(b.lo.x - pad, b.lo.y - pad, -INFINITY), glm::vec3(b.hi.x + pad, b.hi.y + pad, INFINITY)};
}

bool meetsAny(const Bounds& b, const std::vector<Bounds>& boxes) {
    for (const Bounds& d : boxes)
        if (overlaps(b, d)) return true;
    return false;
}

// ---- signatures and classes ----------------------------------------------------------------------------

struct Signature {
    float v[kSignaturePoints][4];
};

Signature signatureOf(const EnvScene& scene, size_t object) {
    const EnvObject& o = scene.objects()[object];
    const Bounds3& b = scene.types()[o.type].bounds;
    glm::vec3 pts[kSignaturePoints];
    int k = 0;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) {
                const glm::vec3 f(0.1f + 0.4f * float(x), 0.1f + 0.4f * float(y), z == 0 ? 0.25f : 0.95f);
                pts[k++] = o.placement.toWorld(b.min + (b.max - b.min) * f);
            }
    // The centre shelter ray only: a ninth of the cost, and the comparison needs no soft edges.
    Signature s;
    for (int i = 0; i < kSignaturePoints; ++i) {
        EnvSample e = scene.channels(pts[i]);
        e.shelter = scene.shelterCentre(pts[i]);
        s.v[i][0] = e.snow * e.openness();
        s.v[i][1] = e.icicles;
        s.v[i][2] = e.temperature;
        s.v[i][3] = e.humidity;
    }
    return s;
}

float distance2(const Signature& a, const Signature& b) {
    double sum = 0.0;
    for (int i = 0; i < kSignaturePoints; ++i)
        for (int c = 0; c < 4; ++c) {
            const double d = double(a.v[i][c]) - double(b.v[i][c]);
            sum += d * d;
        }
    return float(sum / kSignaturePoints);
}

bool inRegion(const EnvEffectsOptions& opt, glm::vec3 p) { return !opt.region || contains(*opt.region, p); }

// A local field placed by something else (a footprint, a lamp's warmth) that reaches into an object's
// bounds while being too small for the signature to see: its 18 points lie 0.4 of the bounds apart, so
// a field narrower than 0.6 of them across (the gaps' diagonal) can fall between them, and the object
// took the snow of one without it (Montmartre's footprints vanished from the pavement). Wider fields (a
// wheel track down the street) meet a point wherever they lie. Fields of the snow's own channels only
// (leaves, grass and trash feed the scattered effects); an object's own fields (a lamppost's warmth on
// itself) are alike in every copy. Kept as the field seen from the object, so two objects touched alike
// (lampposts standing where their facades repeat) still share.
struct SmallFieldTouch {
    EnvChannel channel;
    float value;
    Primitive shape;                  // in the owner's space
    glm::vec3 local_a, local_b;       // the shape's centre and end in the object's space
    float turn_deg, scale;            // the owner's yaw and scale relative to the object's
};

constexpr float kTouchSameM = 1e-4f;  // where two objects see a field within this, they see the same

bool sameTouch(const SmallFieldTouch& a, const SmallFieldTouch& b) {
    const Primitive &p = a.shape, &q = b.shape;
    return a.channel == b.channel && a.value == b.value && a.turn_deg == b.turn_deg && a.scale == b.scale &&
           p.kind == q.kind && p.weight == q.weight && p.radius_m == q.radius_m && p.end_radius_m == q.end_radius_m &&
           p.normal == q.normal && p.disc_radius_m == q.disc_radius_m && p.half_extents_m == q.half_extents_m &&
           glm::length(a.local_a - b.local_a) <= kTouchSameM && glm::length(a.local_b - b.local_b) <= kTouchSameM;
}

bool sameTouches(const std::vector<SmallFieldTouch>& a, const std::vector<SmallFieldTouch>& b) {
    if (a.size() != b.size()) return false;
    for (size_t k = 0; k < a.size(); ++k)
        if (!sameTouch(a[k], b[k])) return false;
    return true;
}

// Per object, the small fields of others touching it, in field order.
std::vector<std::vector<SmallFieldTouch>> smallFieldTouches(const EnvScene& scene) {
    std::vector<std::vector<SmallFieldTouch>> touches(scene.objects().size());
    std::vector<uint32_t> last_field(scene.objects().size(), UINT32_MAX);  // the grid may list an object twice
    for (uint32_t fi = 0; fi < scene.fields().size(); ++fi) {
        const EnvWorldField& f = scene.fields()[fi];
        if (f.everywhere || f.channel == EnvChannel::Leaves || f.channel == EnvChannel::Grass ||
            f.channel == EnvChannel::Trash)
            continue;
        const glm::vec3 field_size = f.bounds.hi - f.bounds.lo;
        scene.forObjectsNearXY(f.bounds, [&](uint32_t o) {
            const EnvObject& obj = scene.objects()[o];
            if (last_field[o] == fi || f.owner_object == o || !overlaps(f.bounds, obj.bounds)) return;
            const glm::vec3 size = obj.bounds.hi - obj.bounds.lo;
            if (!(field_size.x < 0.6f * size.x || field_size.y < 0.6f * size.y)) return;
            last_field[o] = fi;
            const glm::vec3 a = obj.placement.toLocal(f.owner.toWorld(f.shape.center_m));
            const glm::vec3 b = obj.placement.toLocal(f.owner.toWorld(f.shape.end_m));
            touches[o].push_back({f.channel, f.value, f.shape, a, b, f.owner.yaw_deg - obj.placement.yaw_deg,
                                  f.owner.scale / obj.placement.scale});
        });
    }
    return touches;
}

// Greedy clustering in tree order (the same for the whole scene and every region).
void formClasses(const EnvScene& scene, const std::vector<Signature>& sig,
                 const std::vector<std::vector<SnowSegment>>& joints, const EnvEffectsOptions& opt, EnvEffects* out) {
    const std::vector<std::vector<SmallFieldTouch>> touches = smallFieldTouches(scene);
    const auto& objects = scene.objects();
    const float threshold = scene.desc().sharing_threshold;
    // Shelter rays fanned about the snowfall turn with the object as the offsets on their grid do not.
    // Their shelter steps by ninths anywhere over metres, which no signature certifies: a jointed object
    // then gets its own snow (one sharing another's met its neighbour at a step across their joint, a
    // crack; Montmartre's cobbles showed dashes of them). Others share as with one direction: their
    // snow meets no one's.
    const bool fanned = scene.desc().snow_spread_deg > 0.0f;
    const bool vertical = scene.desc().snow_direction == glm::vec3(0.0f, 0.0f, -1.0f) && !fanned;
    out->class_of.assign(objects.size(), UINT32_MAX);
    std::vector<std::vector<uint32_t>> by_type(scene.types().size());  // class ids per type
    for (uint32_t o = 0; o < objects.size(); ++o) {
        uint32_t found = UINT32_MAX;
        // Its own class, which no one else joins either.
        const bool alone = threshold < 0.0f || (fanned && !joints[o].empty());
        if (!alone)
            for (uint32_t c : by_type[objects[o].type]) {
                const EnvObject& first = objects[out->classes[c].first];
                // With slanting snow an object's effects depend on its turn too.
                const bool same_turn = vertical || (first.placement.c == objects[o].placement.c &&
                                                    first.placement.s == objects[o].placement.s);
                if (sameSettings(first, objects[o]) && first.placement.scale == objects[o].placement.scale && same_turn &&
                    joints[out->classes[c].first] == joints[o] && sameTouches(touches[out->classes[c].first], touches[o]) &&
                    distance2(sig[out->classes[c].first], sig[o]) <= threshold) {
                    found = c;
                    break;
                }
            }
        if (found == UINT32_MAX) {
            found = uint32_t(out->classes.size());
            EffectClass c;
            c.type = objects[o].type;
            c.first = o;
            out->classes.push_back(std::move(c));
            if (!alone) by_type[objects[o].type].push_back(found);
        }
        out->class_of[o] = found;
        if (inRegion(opt, objects[o].placement.t)) out->classes[found].members.push_back(o);
    }
}

// ---- one class's effects --------------------------------------------------------------------------------

bool classSnow(const EnvScene& scene, const EnvObject& o, std::vector<SnowSegment> bridged, const EnvQuery& env,
               TriangleMesh* out, std::string* error) {
    const EnvObjectType& type = scene.types()[o.type];
    SnowSettings s = objectSnowSettings(scene, o);
    s.bridged_borders = std::move(bridged);
    SnowCover cover;
    const Bounds3& b = type.bounds;
    bool ok = true;
    switch (o.snow.mode) {
    case SnowMode::None: return true;
    case SnowMode::Geometry: ok = buildGeometrySnow(*type.mesh, s, env, &cover, error); break;
    case SnowMode::Box: {
        const SnowBox box = snowBoxOf(type);
        ok = buildBoxSnow(box.center, box.half_extents, s, env, &cover, error);
        break;
    }
    case SnowMode::Cylinder:
        ok = buildCylinderSnow(glm::vec3((b.min.x + b.max.x) * 0.5f, (b.min.y + b.max.y) * 0.5f, b.min.z),
                               0.5f * std::max(b.max.x - b.min.x, b.max.y - b.min.y), b.max.z - b.min.z, s, env,
                               &cover, error);
        break;
    case SnowMode::Sphere:
        ok = buildSphereSnow((b.min + b.max) * 0.5f, 0.5f * std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z}),
                             s, env, &cover, error);
        break;
    }
    if (!ok) return false;
    *out = std::move(cover.mesh);
    return true;
}

std::vector<IcicleInstance> classIcicles(const EnvScene& scene, const EnvObject& o, const EnvQuery& env) {
    if (!o.icicles.enabled) return {};
    const EnvObjectType& type = scene.types()[o.type];
    IcicleSettings s;
    s.automatic_anchors = o.icicles.automatic_anchors;
    s.anchors = o.icicles.anchors;
    s.spacing_m = o.icicles.spacing_m / o.placement.scale;
    s.max_length_m = o.icicles.max_length_m / o.placement.scale;
    s.length_per_degree_m = o.icicles.length_per_degree_m / o.placement.scale;
    const std::vector<IcicleAnchor> anchors = findIcicleAnchors(*type.mesh, s);
    if (anchors.empty()) return {};
    std::vector<glm::vec3> at(anchors.size());
    for (size_t k = 0; k < anchors.size(); ++k) at[k] = anchors[k].position;
    std::vector<EnvSample> e(anchors.size());
    env(at.data(), at.size(), e.data());
    // Icicles need meltwater: the surface over the drip edge (the roof over its eave, the seat over its
    // front edge) must be open to the sky; the bench under the shelter's roof does not drip. A closed
    // anchor gets no clearance, so no icicle.
    std::vector<float> clearance(anchors.size());
    const float eps = 0.005f / o.placement.scale;
    for (size_t k = 0; k < anchors.size(); ++k) {
        const float top = std::max(at[k].z, type.spans->surfaceAboveNear(at[k], eps)) + 2.0f * eps;
        const bool fed = scene.shelter(o.placement.toWorld(glm::vec3(at[k].x, at[k].y, top))) >= 0.5f;
        clearance[k] = fed ? scene.clearanceBelow(o.placement.toWorld(at[k])) / o.placement.scale : 0.0f;
    }
    return placeIcicles(anchors, e, clearance, s);
}

// ---- terrain snow ---------------------------------------------------------------------------------------

struct ChunkRange {
    int ix0 = 0, ix1 = -1, iy0 = 0, iy1 = -1;
};

ChunkRange terrainChunks(const HeightField& hf) {
    const glm::vec2 lo = hf.origin();
    const glm::vec2 hi = lo + glm::vec2(float(hf.width() - 1), float(hf.height() - 1)) * hf.cellSize();
    ChunkRange r;
    r.ix0 = int(std::floor(lo.x / kTerrainSnowChunkM));
    r.iy0 = int(std::floor(lo.y / kTerrainSnowChunkM));
    r.ix1 = int(std::ceil(hi.x / kTerrainSnowChunkM)) - 1;
    r.iy1 = int(std::ceil(hi.y / kTerrainSnowChunkM)) - 1;
    return r;
}

Bounds chunkBounds(const HeightField& hf, int ix, int iy) {
    const glm::vec2 lo = hf.origin();
    const glm::vec2 hi = lo + glm::vec2(float(hf.width() - 1), float(hf.height() - 1)) * hf.cellSize();
    Bounds b;
    b.lo = glm::vec3(std::max(lo.x, float(ix) * kTerrainSnowChunkM), std::max(lo.y, float(iy) * kTerrainSnowChunkM),
                     hf.minHeight() - 1.0f);
    b.hi = glm::vec3(std::min(hi.x, float(ix + 1) * kTerrainSnowChunkM), std::min(hi.y, float(iy + 1) * kTerrainSnowChunkM),
                     hf.maxHeight() + 1.0f);
    return b;
}

bool wantsTerrainSnow(const EnvScene& scene) {
    if (!scene.terrain() || scene.terrain()->empty() || !scene.desc().terrain.snow) return false;
    for (const EnvWorldField& f : scene.fields())
        if (f.channel == EnvChannel::Snow) return true;
    return false;
}

// ---- the whole computation ------------------------------------------------------------------------------

struct Reuse {
    const EnvEffects* previous = nullptr;
    const std::vector<Bounds>* dirty = nullptr;
};

bool run(const EnvScene& scene, const EnvEffectsOptions& opt, const Reuse& reuse, EnvEffects* out, std::string* error) {
    const auto& objects = scene.objects();
    EnvEffects fx;
    std::vector<Signature> sig(objects.size());
    // The previous result's computed classes by their source object.
    std::unordered_multimap<uint64_t, uint32_t> old_classes;
    if (reuse.previous)
        for (uint32_t c = 0; c < reuse.previous->classes.size(); ++c)
            if (reuse.previous->classes[c].computed) old_classes.emplace(objectKey(reuse.previous->classes[c].source), c);
    const std::vector<std::vector<SnowSegment>> joints = findSnowJoints(scene, opt.threads);
    auto previousOf = [&](uint32_t o) -> const EffectClass* {
        if (!reuse.previous || meetsAny(column(scene, objects[o].bounds), *reuse.dirty)) return nullptr;
        auto [a, b] = old_classes.equal_range(objectKey(objects[o]));
        for (auto it = a; it != b; ++it) {
            const EffectClass& old = reuse.previous->classes[it->second];
            if (sameObject(old.source, objects[o]) && old.snow_joints == joints[o]) return &old;
        }
        return nullptr;
    };
    parallelFor(objects.size(), opt.threads, 64, [&](size_t b, size_t e, int) {
        for (size_t o = b; o < e; ++o) sig[o] = signatureOf(scene, o);
    });
    formClasses(scene, sig, joints, opt, &fx);
    // Each class with members: reuse when its first object is unchanged and undisturbed, else compute.
    std::vector<std::string> errors(fx.classes.size());
    std::vector<char> failed(fx.classes.size(), 0);
    parallelFor(fx.classes.size(), opt.threads, 1, [&](size_t b, size_t e, int) {
        for (size_t c = b; c < e; ++c) {
            EffectClass& cls = fx.classes[c];
            if (cls.members.empty()) continue;
            cls.computed = true;
            cls.source = objects[cls.first];
            cls.snow_joints = joints[cls.first];
            if (const EffectClass* old = previousOf(cls.first)) {
                cls.snow = old->snow;
                cls.icicles = old->icicles;
                cls.reused = true;
                continue;
            }
            const EnvObject& first = objects[cls.first];
            const EnvQuery env = scene.objectQuery(cls.first);
            auto snow = std::make_shared<TriangleMesh>();
            if (!classSnow(scene, first, cls.snow_joints, env, snow.get(), &errors[c])) {
                failed[c] = 1;
                continue;
            }
            if (!snow->indices.empty()) cls.snow = std::move(snow);
            cls.icicles = classIcicles(scene, first, env);
        }
    });
    for (size_t c = 0; c < fx.classes.size(); ++c)
        if (failed[c]) {
            *error = objects[fx.classes[c].first].where + ": " + errors[c];
            return false;
        }
    // The terrain, chunk by chunk.
    if (wantsTerrainSnow(scene)) {
        const HeightField& hf = *scene.terrain();
        const ChunkRange r = terrainChunks(hf);
        for (int iy = r.iy0; iy <= r.iy1; ++iy)
            for (int ix = r.ix0; ix <= r.ix1; ++ix) {
                const Bounds b = chunkBounds(hf, ix, iy);
                if (!(b.lo.x < b.hi.x && b.lo.y < b.hi.y)) continue;
                if (inRegion(opt, glm::vec3(b.lo.x, b.lo.y, opt.region ? opt.region->lo.z : 0.0f)))
                    fx.terrain_snow.push_back(TerrainSnowChunk{ix, iy, nullptr, false});
            }
        std::vector<std::string> chunk_errors(fx.terrain_snow.size());
        std::vector<char> chunk_failed(fx.terrain_snow.size(), 0);
        const EnvQuery world = [&scene](const glm::vec3* p, size_t n, EnvSample* e) { scene.sampleBatch(p, n, e); };
        parallelFor(fx.terrain_snow.size(), opt.threads, 1, [&](size_t b, size_t e, int) {
            for (size_t k = b; k < e; ++k) {
                TerrainSnowChunk& ch = fx.terrain_snow[k];
                const Bounds box = chunkBounds(hf, ch.ix, ch.iy);
                if (reuse.previous && !meetsAny(column(scene, box), *reuse.dirty))
                    for (const TerrainSnowChunk& old : reuse.previous->terrain_snow)
                        if (old.ix == ch.ix && old.iy == ch.iy) {
                            ch.mesh = old.mesh;
                            ch.reused = true;
                        }
                if (ch.reused) continue;
                SnowSettings s;
                s.min_open = scene.snowMinOpen();
                SnowCover cover;
                if (!buildTerrainSnow(hf, box, scene.desc().terrain.snow_cell_m, s, world, &cover, &chunk_errors[k])) {
                    chunk_failed[k] = 1;
                    continue;
                }
                ch.mesh = std::make_shared<TriangleMesh>(std::move(cover.mesh));
            }
        });
        for (size_t k = 0; k < chunk_failed.size(); ++k)
            if (chunk_failed[k]) {
                *error = "/environment/terrain: " + chunk_errors[k];
                return false;
            }
    }
    // Statistics.
    EnvEffectsStats& st = fx.stats;
    for (const EffectClass& c : fx.classes) {
        if (!c.computed) continue;
        ++st.effect_computations;
        st.classes_reused += c.reused ? 1 : 0;
        st.objects += c.members.size();
        const uint64_t tris = c.snow ? c.snow->triangleCount() : 0;
        st.snow_triangles_unique += tris;
        st.snow_triangles += tris * c.members.size();
        st.icicles += uint64_t(c.icicles.size()) * c.members.size();
    }
    for (const TerrainSnowChunk& ch : fx.terrain_snow) {
        ++st.terrain_chunks;
        st.terrain_chunks_reused += ch.reused ? 1 : 0;
        const uint64_t tris = ch.mesh ? ch.mesh->triangleCount() : 0;
        st.snow_triangles += tris;
        st.snow_triangles_unique += tris;
    }
    *out = std::move(fx);
    return true;
}

}  // namespace

bool computeEnvEffects(const EnvScene& scene, const EnvEffectsOptions& options, EnvEffects* out, std::string* error) {
    return run(scene, options, Reuse{}, out, error);
}

bool updateEnvEffects(const EnvScene& scene, const EnvEffects& previous, const std::vector<Bounds>& dirty,
                      const EnvEffectsOptions& options, EnvEffects* out, std::string* error) {
    return run(scene, options, Reuse{&previous, &dirty}, out, error);
}

std::vector<Bounds> envDirtyRegion(const EnvScene& before, const EnvScene& after) {
    std::vector<Bounds> dirty;
    // Another snowfall changes the shelter everywhere.
    if (before.desc().snow_direction != after.desc().snow_direction ||
        before.desc().snow_spread_deg != after.desc().snow_spread_deg)
        return {Bounds::everything()};
    auto diffObjects = [&](const EnvScene& a, const EnvScene& b) {
        std::unordered_multimap<uint64_t, uint32_t> keys;
        for (uint32_t o = 0; o < b.objects().size(); ++o) keys.emplace(objectKey(b.objects()[o]), o);
        for (const EnvObject& o : a.objects()) {
            bool found = false;
            auto [lo, hi] = keys.equal_range(objectKey(o));
            for (auto it = lo; it != hi && !found; ++it) found = sameObject(b.objects()[it->second], o);
            if (!found) dirty.push_back(o.bounds);
        }
    };
    auto diffFields = [&](const EnvScene& a, const EnvScene& b) {
        std::unordered_multimap<uint64_t, uint32_t> keys;
        for (uint32_t f = 0; f < b.fields().size(); ++f) keys.emplace(fieldKey(b.fields()[f]), f);
        for (const EnvWorldField& f : a.fields()) {
            if (keys.count(fieldKey(f)) == 0) dirty.push_back(f.bounds);
        }
    };
    diffObjects(before, after);
    diffObjects(after, before);
    diffFields(before, after);
    diffFields(after, before);
    return dirty;
}

}  // namespace ug
