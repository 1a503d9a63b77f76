// BlobTree density fields (Ghost Tile §5 and §6.1: "Primitives are combinated together using blending
// and Boolean operators as described in [WGG99]. Finally, density fields are modified by computing the
// difference with the other solid objects in the scene such as the tree and the terrain").
//
// Beyond the paper: docs/architecture.md makes instantiation a pure function, so field values must not
// depend on who evaluated them. Hence:
//   - one evaluation routine (evalPoint) behind every public entry point, scalar or batched, full or per
//     tile, value only or with gradient (a template flag only adds the gradient arithmetic);
//   - a fixed child order (sums are not associative in floating point);
//   - tile lists that prune without changing a bit: a primitive whose support misses the tile evaluates
//     to exactly +0 there (primitive_eval.h returns +0, never weight * 0), so
//       * in a Blend it is dropped: the running sum starts at +0 and x + (+0) == x for every x != -0, and
//         a sum that starts at +0 never becomes -0 under round-to-nearest;
//       * in a Union / Intersection it is replaced by an explicit zero child (kZeroChild) at its place,
//         with runs of them collapsed: the fold keeps the first of equal values (strict comparisons), so
//         a run of identical zeros acts as one, and ties break the same way as in the full tree;
//       * in a Difference the first child keeps a zero in its place, later ones are dropped (a
//         subtrahend only acts when it is > 0);
//     and a node left with no real child is itself exactly +0 (every operator of +0 children gives +0),
//     so its parent treats it like a left-out primitive.
#include "field/density_field.h"

#include <cassert>
#include <cmath>
#include <string>

#include "field/primitive_eval.h"

namespace ug {

const char* fieldOpName(FieldOp op) {
    switch (op) {
        case FieldOp::Blend: return "blend";
        case FieldOp::Union: return "union";
        case FieldOp::Intersection: return "intersection";
        case FieldOp::Difference: return "difference";
    }
    return "unknown";
}

namespace {

using field_detail::Sample;
using field_detail::sampleValue;

bool isTerrain(const Primitive& pr) {
    return pr.kind == PrimitiveKind::TerrainLayer || pr.kind == PrimitiveKind::TerrainSolid;
}

inline const HeightField* heightFieldOf(const DensityField& f, const Primitive& pr) {
    return isTerrain(pr) ? f.height_fields[pr.height_field].get() : nullptr;
}

// An External primitive's support and positive part come from its field (external_field.h).
Bounds primitiveBoundsOf(const DensityField& f, const Primitive& pr) {
    if (pr.kind == PrimitiveKind::External) return f.externals[pr.external]->bounds();
    return primitiveBounds(pr, heightFieldOf(f, pr));
}

Bounds primitivePositiveBoundsOf(const DensityField& f, const Primitive& pr, const Bounds& box) {
    if (pr.kind != PrimitiveKind::External) return primitivePositiveBoundsIn(pr, heightFieldOf(f, pr), box);
    if (!(pr.weight > 0.0f) || box.empty()) return Bounds{};
    const Bounds b = intersect(f.externals[pr.external]->positiveBoundsIn(box), box);
    return b.empty() ? Bounds{} : b;
}

// A batch's External values, evaluated together before its points are (evalBatch): the k-th point's
// value of primitive `primitive` is values[slot * count + k]. Thread-local because the evaluation routine
// below runs one batch at a time per thread.
struct ExternalBatch {
    const DensityField* field = nullptr;
    std::vector<uint32_t> primitive;  // External primitives of the batch, in the order of `values`
    std::vector<float> values;
    size_t count = 0, k = 0;
};
thread_local ExternalBatch* t_external_batch = nullptr;

template <bool kGrad>
inline Sample<kGrad> externalSample(const DensityField& f, const Primitive& pr, glm::vec3 p) {
    float v;
    const ExternalBatch* b = t_external_batch;
    size_t slot = 0;
    if (b && b->field == &f) {
        const uint32_t index = uint32_t(&pr - f.primitives.data());
        while (slot < b->primitive.size() && b->primitive[slot] != index) ++slot;
    }
    if (b && b->field == &f && slot < b->primitive.size())
        v = b->values[slot * b->count + b->k];
    else
        v = f.externals[pr.external]->value(p);
    // +0 stays +0 (a left-out External must give the same bits as one evaluated outside its support).
    return Sample<kGrad>(v == 0.0f ? 0.0f : pr.weight * v);
}

template <bool kGrad>
inline Sample<kGrad> childSample(const DensityField& f, const Sample<kGrad>* slots, uint32_t ref, glm::vec3 p,
                                 field_detail::HeightCache* cache) {
    if (ref == kZeroChild) return Sample<kGrad>(0.0f);
    if (ref & kPrimitiveChildBit) {
        const Primitive& pr = f.primitives[ref & ~kPrimitiveChildBit];
        if (pr.kind == PrimitiveKind::External) return externalSample<kGrad>(f, pr, p);
        return field_detail::evalPrimitive<kGrad>(pr, heightFieldOf(f, pr), p, cache);
    }
    return slots[ref];
}

template <bool kGrad>
inline Sample<kGrad> evalNode(const DensityField& f, FieldOp op, const uint32_t* refs, uint32_t count,
                              const Sample<kGrad>* slots, glm::vec3 p, field_detail::HeightCache* cache) {
    using S = Sample<kGrad>;
    switch (op) {
        case FieldOp::Blend: {
            S acc(0.0f);
            for (uint32_t i = 0; i < count; ++i) acc += childSample<kGrad>(f, slots, refs[i], p, cache);
            return acc;
        }
        case FieldOp::Union: {
            if (count == 0) return S(0.0f);
            S best = childSample<kGrad>(f, slots, refs[0], p, cache);
            for (uint32_t i = 1; i < count; ++i) {
                const S c = childSample<kGrad>(f, slots, refs[i], p, cache);
                if (sampleValue(c) > sampleValue(best)) best = c;
            }
            return best;
        }
        case FieldOp::Intersection: {
            if (count == 0) return S(0.0f);
            S best = childSample<kGrad>(f, slots, refs[0], p, cache);
            for (uint32_t i = 1; i < count; ++i) {
                const S c = childSample<kGrad>(f, slots, refs[i], p, cache);
                if (sampleValue(c) < sampleValue(best)) best = c;
            }
            return best;
        }
        case FieldOp::Difference: {
            if (count == 0) return S(0.0f);
            S acc = childSample<kGrad>(f, slots, refs[0], p, cache);
            // Nothing to carve where a <= 0: keep a and skip the solids (most points a tile tests lie
            // outside a thin layer, so this saves the terrain solid's evaluation there).
            if (!(sampleValue(acc) > 0.0f)) return acc;
            for (uint32_t i = 1; i < count; ++i) {
                const S c = childSample<kGrad>(f, slots, refs[i], p, cache);
                if (sampleValue(c) > 0.0f) acc -= c;
            }
            return acc;
        }
    }
    return S(0.0f);
}

// The single evaluation routine. slots has one entry per field node.
template <bool kGrad>
inline Sample<kGrad> evalPoint(const DensityField& f, const TileFieldList* list, Sample<kGrad>* slots, glm::vec3 p) {
    field_detail::HeightCache cache;
    if (!list) {
        if (f.root == kNoNode) return Sample<kGrad>(0.0f);
        for (uint32_t n = 0; n <= f.root; ++n) {
            const FieldNode& node = f.nodes[n];
            slots[n] =
                evalNode<kGrad>(f, node.op, f.children.data() + node.first_child, node.child_count, slots, p, &cache);
        }
        return slots[f.root];
    }
    if (!list->root_live) return Sample<kGrad>(0.0f);
    for (const TileNode& node : list->nodes)
        slots[node.node] =
            evalNode<kGrad>(f, node.op, list->children.data() + node.first_child, node.child_count, slots, p, &cache);
    return slots[f.root];
}

constexpr size_t kInlineSlots = 64;

template <bool kGrad, typename Out>
void evalBatch(const DensityField& f, const TileFieldList* list, const glm::vec3* points, size_t count, Out* out) {
    using S = Sample<kGrad>;
    S inline_slots[kInlineSlots];
    S* slots = inline_slots;
    if (f.nodes.size() > kInlineSlots) {
        thread_local std::vector<S> big;
        if (big.size() < f.nodes.size()) big.resize(f.nodes.size());
        slots = big.data();
    }
    if (f.externals.empty() || count < 2) {
        for (size_t k = 0; k < count; ++k) out[k] = evalPoint<kGrad>(f, list, slots, points[k]);
        return;
    }
    // External terms first, for the whole batch (the same bits as one by one: value() is pure).
    thread_local ExternalBatch batch;
    batch.field = &f;
    batch.primitive.clear();
    batch.count = count;
    auto consider = [&](uint32_t i) {
        if (f.primitives[i].kind == PrimitiveKind::External) batch.primitive.push_back(i);
    };
    if (list) {
        for (uint32_t i : list->primitives) consider(i);
    } else {
        for (uint32_t i = 0; i < f.primitives.size(); ++i) consider(i);
    }
    batch.values.resize(batch.primitive.size() * count);
    for (size_t slot = 0; slot < batch.primitive.size(); ++slot)
        f.externals[f.primitives[batch.primitive[slot]].external]->valueBatch(points, count,
                                                                               batch.values.data() + slot * count);
    ExternalBatch* previous = t_external_batch;
    t_external_batch = &batch;
    for (size_t k = 0; k < count; ++k) {
        batch.k = k;
        out[k] = evalPoint<kGrad>(f, list, slots, points[k]);
    }
    t_external_batch = previous;
}

}  // namespace

// ---- building --------------------------------------------------------------------------------------

uint32_t addPrimitive(DensityField* field, const Primitive& primitive) {
    assert(field && field->primitives.size() < kPrimitiveChildBit - 1);
    field->primitives.push_back(primitive);
    return uint32_t(field->primitives.size() - 1);
}

uint32_t addNode(DensityField* field, FieldOp op, std::span<const uint32_t> child_refs) {
    assert(field && field->nodes.size() < kPrimitiveChildBit - 1);
    FieldNode node;
    node.op = op;
    node.first_child = uint32_t(field->children.size());
    node.child_count = uint32_t(child_refs.size());
    for (uint32_t ref : child_refs) {
        assert(ref != kZeroChild);
        assert(isPrimitiveChild(ref) ? childIndex(ref) < field->primitives.size() : ref < field->nodes.size());
        field->children.push_back(ref);
    }
    field->nodes.push_back(node);
    return uint32_t(field->nodes.size() - 1);
}

uint32_t addExternal(DensityField* field, std::shared_ptr<const ExternalField> external) {
    assert(field && external);
    field->externals.push_back(std::move(external));
    return uint32_t(field->externals.size() - 1);
}

uint32_t addHeightField(DensityField* field, std::shared_ptr<const HeightField> height_field) {
    assert(field && height_field && !height_field->empty());
    field->height_fields.push_back(std::move(height_field));
    return uint32_t(field->height_fields.size() - 1);
}

bool addPolyline(DensityField* field, std::span<const glm::vec4> vertices_m, float weight, uint32_t* out_ref,
                 std::string* error) {
    assert(field && out_ref);
    auto fail = [&](const std::string& what) {
        if (error) *error = "polyline: " + what;
        return false;
    };
    if (vertices_m.size() < 2)
        return fail("needs at least 2 vertices, got " + std::to_string(vertices_m.size()));
    if (!std::isfinite(weight)) return fail("weight is not finite");
    for (size_t k = 0; k < vertices_m.size(); ++k) {
        const glm::vec4 v = vertices_m[k];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            return fail("vertex " + std::to_string(k) + " position is not finite");
        if (!std::isfinite(v.w) || !(v.w > 0.0f))
            return fail("vertex " + std::to_string(k) + " radius must be finite and > 0");
    }
    std::vector<uint32_t> refs;
    refs.reserve(vertices_m.size() - 1);
    for (size_t k = 0; k + 1 < vertices_m.size(); ++k) {
        const glm::vec4 a = vertices_m[k], b = vertices_m[k + 1];
        refs.push_back(primitiveChild(addPrimitive(field, makeCone(glm::vec3(a), a.w, glm::vec3(b), b.w, weight))));
    }
    // weight * max K == max(weight * K) for weight >= 0 and min(weight * K) for weight < 0.
    *out_ref = nodeChild(addNode(field, weight < 0.0f ? FieldOp::Intersection : FieldOp::Union, refs));
    return true;
}

DensityField makeBlendField(std::span<const Primitive> primitives) {
    DensityField field;
    std::vector<uint32_t> refs;
    refs.reserve(primitives.size());
    for (const Primitive& p : primitives) refs.push_back(primitiveChild(addPrimitive(&field, p)));
    field.root = addNode(&field, FieldOp::Blend, refs);
    return field;
}

DensityField makeBlendField(std::initializer_list<Primitive> primitives) {
    return makeBlendField(std::span<const Primitive>(primitives.begin(), primitives.size()));
}

void subtractSolids(DensityField* field, std::span<const Primitive> solids) {
    assert(field);
    if (solids.empty() || field->root == kNoNode) return;
    std::vector<uint32_t> refs;
    refs.reserve(solids.size());
    for (const Primitive& p : solids) {
        assert(!isTerrain(p) || p.height_field < field->height_fields.size());
        refs.push_back(primitiveChild(addPrimitive(field, p)));
    }
    const uint32_t solid = addNode(field, FieldOp::Union, refs);
    const uint32_t pair[2] = {nodeChild(field->root), nodeChild(solid)};
    field->root = addNode(field, FieldOp::Difference, pair);
}

void subtractSolids(DensityField* field, std::initializer_list<Primitive> solids) {
    subtractSolids(field, std::span<const Primitive>(solids.begin(), solids.size()));
}

bool validate(const DensityField& f, std::string* error) {
    auto fail = [&](const std::string& what) {
        if (error) *error = what;
        return false;
    };
    for (size_t i = 0; i < f.height_fields.size(); ++i)
        if (!f.height_fields[i] || f.height_fields[i]->empty())
            return fail("height field " + std::to_string(i) + ": missing or empty");
    if (f.primitives.size() >= kPrimitiveChildBit - 1) return fail("too many primitives");
    if (f.nodes.size() >= kPrimitiveChildBit - 1) return fail("too many nodes");
    for (size_t i = 0; i < f.externals.size(); ++i)
        if (!f.externals[i]) return fail("external field " + std::to_string(i) + ": missing");
    for (size_t i = 0; i < f.primitives.size(); ++i) {
        if (!validatePrimitive(f.primitives[i], i, f.height_fields.size(), error)) return false;
        if (f.primitives[i].kind == PrimitiveKind::External && f.primitives[i].external >= f.externals.size())
            return fail("primitive " + std::to_string(i) + " (external): external " +
                        std::to_string(f.primitives[i].external) + " is out of range (" +
                        std::to_string(f.externals.size()) + " external fields)");
    }
    for (size_t n = 0; n < f.nodes.size(); ++n) {
        const FieldNode& node = f.nodes[n];
        const std::string where = "node " + std::to_string(n) + " (" + fieldOpName(node.op) + "): ";
        if (int(node.op) > int(FieldOp::Difference))
            return fail("node " + std::to_string(n) + ": operator " + std::to_string(int(node.op)) + " is unknown");
        if (uint64_t(node.first_child) + node.child_count > f.children.size())
            return fail(where + "children [" + std::to_string(node.first_child) + ", +" +
                        std::to_string(node.child_count) + ") run past the " + std::to_string(f.children.size()) +
                        " child references");
        for (uint32_t c = 0; c < node.child_count; ++c) {
            const uint32_t ref = f.children[node.first_child + c];
            const std::string child = "child " + std::to_string(c) + " ";
            if (ref == kZeroChild) return fail(where + child + "is a tile-list zero placeholder");
            if (isPrimitiveChild(ref)) {
                if (childIndex(ref) >= f.primitives.size())
                    return fail(where + child + "refers to primitive " + std::to_string(childIndex(ref)) +
                                " of " + std::to_string(f.primitives.size()));
            } else if (ref >= n) {
                return fail(where + child + "refers to node " + std::to_string(ref) +
                            ", which does not come before it");
            }
        }
    }
    if (f.root != kNoNode && f.root >= f.nodes.size())
        return fail("root " + std::to_string(f.root) + " is not one of the " + std::to_string(f.nodes.size()) +
                    " nodes");
    return true;
}

// ---- evaluating --------------------------------------------------------------------------------------

float evaluate(const DensityField& field, glm::vec3 p_m) {
    float out;
    evalBatch<false>(field, nullptr, &p_m, 1, &out);
    return out;
}

glm::vec4 evaluateWithGradient(const DensityField& field, glm::vec3 p_m) {
    glm::vec4 out;
    evalBatch<true>(field, nullptr, &p_m, 1, &out);
    return out;
}

void evaluateBatch(const DensityField& field, const TileFieldList* list, const glm::vec3* points_m, size_t count,
                   float* out) {
    assert(count == 0 || (points_m && out));
    evalBatch<false>(field, list, points_m, count, out);
}

void evaluateBatchWithGradient(const DensityField& field, const TileFieldList* list, const glm::vec3* points_m,
                               size_t count, glm::vec4* out) {
    assert(count == 0 || (points_m && out));
    evalBatch<true>(field, list, points_m, count, out);
}

void buildTileList(const DensityField& f, const Bounds& box, TileFieldList* out, const TileFieldList* parent) {
    assert(out);
    out->box = box;
    out->primitives.clear();
    out->nodes.clear();
    out->children.clear();
    out->node_live.assign(f.nodes.size(), 0);
    out->root_live = false;

    auto primitiveLive = [&](uint32_t i) {
        return overlaps(primitiveBoundsOf(f, f.primitives[i]), box);
    };
    if (parent) {
        for (uint32_t i : parent->primitives)
            if (primitiveLive(i)) out->primitives.push_back(i);
    } else {
        for (uint32_t i = 0; i < f.primitives.size(); ++i)
            if (primitiveLive(i)) out->primitives.push_back(i);
    }

    // Appends the pruned node (see the top of this file for why each rule keeps the bits).
    auto emit = [&](uint32_t node_index, FieldOp op, const uint32_t* refs, uint32_t count) {
        const uint32_t first = uint32_t(out->children.size());
        bool any_live = false;
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t ref = refs[i];
            bool live = false;
            if (ref == kZeroChild) {
                live = false;
            } else if (ref & kPrimitiveChildBit) {
                live = primitiveLive(childIndex(ref));
            } else {
                live = out->node_live[ref] != 0;
            }
            if (live) {
                out->children.push_back(ref);
                any_live = true;
                continue;
            }
            const bool keep_zero =
                op == FieldOp::Union || op == FieldOp::Intersection || (op == FieldOp::Difference && i == 0);
            const bool after_zero = out->children.size() > first && out->children.back() == kZeroChild;
            if (keep_zero && !after_zero) out->children.push_back(kZeroChild);
        }
        if (!any_live) {  // exactly +0 everywhere in the box
            out->children.resize(first);
            return;
        }
        out->nodes.push_back(TileNode{node_index, op, first, uint32_t(out->children.size()) - first});
        out->node_live[node_index] = 1;
    };

    if (f.root == kNoNode) return;
    if (parent) {
        if (!parent->root_live) return;
        for (const TileNode& node : parent->nodes)
            emit(node.node, node.op, parent->children.data() + node.first_child, node.child_count);
    } else {
        for (uint32_t n = 0; n <= f.root; ++n) {
            const FieldNode& node = f.nodes[n];
            emit(n, node.op, f.children.data() + node.first_child, node.child_count);
        }
    }
    out->root_live = out->node_live[f.root] != 0;
}

TileFieldList buildTileList(const DensityField& field, const Bounds& box) {
    TileFieldList list;
    buildTileList(field, box, &list);
    return list;
}

Bounds positiveBounds(const DensityField& f) {
    if (f.root == kNoNode) return Bounds{};
    std::vector<Bounds> node_bounds(f.root + 1);
    auto childBounds = [&](uint32_t ref) {
        if (isPrimitiveChild(ref)) {
            const Primitive& pr = f.primitives[childIndex(ref)];
            return pr.weight > 0.0f ? primitiveBoundsOf(f, pr) : Bounds{};
        }
        return node_bounds[ref];
    };
    for (uint32_t n = 0; n <= f.root; ++n) {
        const FieldNode& node = f.nodes[n];
        const uint32_t* refs = f.children.data() + node.first_child;
        Bounds b;
        switch (node.op) {
            case FieldOp::Blend:
            case FieldOp::Union:
                for (uint32_t i = 0; i < node.child_count; ++i) b = unite(b, childBounds(refs[i]));
                break;
            case FieldOp::Intersection:
                if (node.child_count == 0) break;
                b = Bounds::everything();
                for (uint32_t i = 0; i < node.child_count; ++i) b = intersect(b, childBounds(refs[i]));
                if (b.empty()) b = Bounds{};
                break;
            case FieldOp::Difference:
                if (node.child_count > 0) b = childBounds(refs[0]);
                break;
        }
        node_bounds[n] = b;
    }
    return node_bounds[f.root];
}

Bounds positiveBoundsIn(const DensityField& f, const TileFieldList& list) {
    if (!list.root_live) return Bounds{};
    // Bounds of the list's live nodes, indexed like list.nodes (children come before parents).
    std::vector<Bounds> node_bounds(list.nodes.size());
    std::vector<uint32_t> slot_of_node;  // field node -> index in list.nodes
    slot_of_node.assign(f.nodes.size(), kNoNode);
    auto childBounds = [&](uint32_t ref) {
        if (ref == kZeroChild) return Bounds{};
        if (isPrimitiveChild(ref)) {
            const Primitive& pr = f.primitives[childIndex(ref)];
            return primitivePositiveBoundsOf(f, pr, list.box);
        }
        return node_bounds[slot_of_node[ref]];
    };
    for (size_t k = 0; k < list.nodes.size(); ++k) {
        const TileNode& node = list.nodes[k];
        slot_of_node[node.node] = uint32_t(k);
        const uint32_t* refs = list.children.data() + node.first_child;
        Bounds b;
        switch (node.op) {
            case FieldOp::Blend:
            case FieldOp::Union:
                for (uint32_t i = 0; i < node.child_count; ++i) b = unite(b, childBounds(refs[i]));
                break;
            case FieldOp::Intersection:
                if (node.child_count == 0) break;
                b = list.box;
                for (uint32_t i = 0; i < node.child_count; ++i) b = intersect(b, childBounds(refs[i]));
                if (b.empty()) b = Bounds{};
                break;
            case FieldOp::Difference:
                if (node.child_count > 0) b = childBounds(refs[0]);
                break;
        }
        node_bounds[k] = b;
    }
    return node_bounds[slot_of_node[f.root]];
}

}  // namespace ug
