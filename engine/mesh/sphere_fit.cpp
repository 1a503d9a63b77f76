// Collision sphere sets for detail models (Ghost Tile §4.3, Figure 8: "input objects approximated by
// unions of spheres"). The paper cites variational fitting [WSL*06] and medial spheres [SKS12]; we use
// the medial idea in its simplest robust form, a set-cover over surface samples:
//
//  1. Sample the surface densely (area-uniform, stratified along the triangle list).
//  2. At every sample p with outward normal n, the largest ball tangent at p that holds no sample
//     strictly inside ("shrinking ball") has radius
//         r(p) = min over samples q with m.(q - p) > 0 of |q - p|^2 / (2 m.(q - p)),   m = -n,
//     which is the exact solution of |p + r m - q| = r for the binding q; no iteration is needed.
//     Such balls approximate the inner medial axis: they stay inside a closed mesh, so the union is
//     tight. When no sample binds (open or inverted surface) we take r = 0.
//  3. Each candidate is the ball at p + r m with radius max(r, tolerance): thin parts (a leaf blade, a
//     needle, r ~ half the thickness) get balls of about the tolerance, so they need many small
//     spheres, as in the paper's leaves and branches, instead of a few balls bulging off the surface.
//  4. Greedy set cover (lazy, exact greedy): repeatedly take the candidate that covers the most still
//     uncovered samples; a sample is covered when its distance to the ball's surface is within the fit
//     tolerance. If max_spheres is reached first, each uncovered sample grows its nearest sphere just
//     enough, so coverage of the samples always holds (report.radii_grown).
//
// Coverage between samples: the distance to a union of balls is 1-Lipschitz, so a point within h of a
// covered sample is within (fit tolerance + h). We fit to 0.70 of the asked tolerance and then check
// fresh, independent sample sets, adding any of their points beyond 0.80 of the tolerance to the sample
// set and covering them (up to kRepairRounds rounds). A last set, again independent, measures what we
// report.
//
// Cost (scanned models of millions of triangles, up to kMaxSurfaceSamples samples). Every step above
// is done with a spatial index instead of all pairs, and each index answers exactly what the all-pairs
// loop would (same float expressions, conservative pruning), so the spheres are bit for bit those of
// the plain algorithm:
//   - the ray to the opposite face (step 2): TriangleBvh, O(log triangles) per sample;
//   - the shrinking ball (step 2): a k-d tree over the samples, searched inside the current ball, which
//     shrinks as binding samples are found;
//   - the set cover (step 4): the same k-d tree with an uncovered count per node, so a candidate's gain
//     counts whole subtrees inside its ball at once (O(n) memory instead of n^2 coverage bits);
//   - distances to the union (repair rounds, growth, report): a small tree over the spheres.
// All parallel loops write per-index slots, so the result does not depend on the thread count.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <queue>

#include "core/hash.h"
#include "core/parallel.h"
#include "mesh/detail_model.h"
#include "mesh/triangle_bvh.h"

namespace ug {
namespace {

constexpr float kFitToleranceFraction = 0.70f;     // fit below the asked tolerance (see above)
constexpr float kRepairToleranceFraction = 0.80f;  // check-set points beyond this join the fit set
constexpr int kRepairRounds = 6;
constexpr float kBulgeFraction = 0.5f;  // medial balls may stand this much (x tolerance) off the surface
constexpr int kCoarsenAttempts = 4;
constexpr uint64_t kRepairSeedSalt = 0x5e11'0c4e'c4ull;
constexpr uint64_t kReportSeedSalt = 0x0e90'47ull;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr size_t kParallelChunk = 64;

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

// ---- progress and cancellation ----

// Maps the fit's stages onto [0, 1] and forwards rising fractions to the caller's callback, from the
// calling thread only (worker 0 of parallelFor is the calling thread).
class Progress {
public:
    Progress(const std::function<void(float)>& callback, const std::atomic<bool>* cancel)
        : callback_(callback), cancel_(cancel) {}

    bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }
    // The current stage spans [lo, hi] of the whole; at() reports a fraction of the stage.
    void stage(double lo, double hi) {
        lo_ = lo;
        hi_ = hi;
        at(0.0);
    }
    double lo() const { return lo_; }
    double hi() const { return hi_; }
    void at(double fraction_of_stage) {
        if (!callback_) return;
        const float f = float(std::min(1.0, lo_ + (hi_ - lo_) * std::clamp(fraction_of_stage, 0.0, 1.0)));
        if (f > last_) {
            last_ = f;
            callback_(f);
        }
    }
    void done() {
        if (callback_ && last_ < 1.0f) {
            last_ = 1.0f;
            callback_(1.0f);
        }
    }

private:
    const std::function<void(float)>& callback_;
    const std::atomic<bool>* cancel_;
    double lo_ = 0.0, hi_ = 0.0;
    float last_ = -1.0f;
};

// parallelFor over [0, count) with progress from the calling thread and a cancel check per chunk.
// Returns false when cancelled (some indices were then not visited).
bool forEachIndex(size_t count, int threads, Progress* progress, const std::function<void(size_t)>& body) {
    std::atomic<size_t> done{0};
    std::atomic<bool> stop{false};
    parallelFor(count, threads, kParallelChunk, [&](size_t begin, size_t end, int worker) {
        for (size_t i = begin; i < end; i += kParallelChunk) {
            if (stop.load(std::memory_order_relaxed)) return;
            const size_t block_end = std::min(end, i + kParallelChunk);
            for (size_t k = i; k < block_end; ++k) body(k);
            const size_t so_far = done.fetch_add(block_end - i, std::memory_order_relaxed) + (block_end - i);
            if (worker == 0) {
                if (progress->cancelled()) stop.store(true);
                progress->at(double(so_far) / double(count));
            }
        }
    });
    return !stop.load() && !progress->cancelled();
}

// ---- area-uniform sampling ----

// The cumulative area table of a mesh, built once and drawn from many times (every repair round and
// the report draw fresh sets): O(triangles) once, O(log triangles) per sample.
class SurfaceSampler {
public:
    explicit SurfaceSampler(const TriangleMesh& mesh) : mesh_(mesh), cumulative_(mesh.triangleCount()) {
        double total = 0.0;
        for (size_t t = 0; t < cumulative_.size(); ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                            b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
            total += std::isfinite(area) ? area : 0.0;
            cumulative_[t] = total;
        }
        total_ = total;
    }

    void sample(uint32_t count, uint64_t seed, std::vector<glm::vec3>* points,
                std::vector<glm::vec3>* normals) const {
        assert(points);
        points->clear();
        if (normals) normals->clear();
        const size_t tri_count = cumulative_.size();
        if (!(total_ > 0.0) || count == 0) return;
        points->reserve(count);
        if (normals) normals->reserve(count);
        for (uint32_t i = 0; i < count; ++i) {
            // Stratified along the cumulative area: sample i falls in the i-th of `count` equal slices, so
            // the set has no large holes along the triangle order (triangles are usually spatially coherent).
            const double u = (double(i) + unitDouble(hashWords(seed, i, 0))) / double(count) * total_;
            size_t t =
                size_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), u) - cumulative_.begin());
            t = std::min(t, tri_count - 1);
            // Never land on a zero-area triangle: go back to the first triangle of the run with this
            // cumulative value (the one with area), by binary search rather than a walk.
            t = size_t(
                std::lower_bound(cumulative_.begin(), cumulative_.begin() + ptrdiff_t(t), cumulative_[t]) -
                cumulative_.begin());
            const glm::vec3 a = mesh_.positions[mesh_.indices[3 * t]],
                            b = mesh_.positions[mesh_.indices[3 * t + 1]],
                            c = mesh_.positions[mesh_.indices[3 * t + 2]];
            float r1 = std::sqrt(unitFloat(hashWords(seed, i, 1)));
            const float r2 = unitFloat(hashWords(seed, i, 2));
            points->push_back(a * (1.0f - r1) + b * (r1 * (1.0f - r2)) + c * (r1 * r2));
            if (normals) {
                const glm::vec3 n = glm::cross(b - a, c - a);
                const float len = glm::length(n);
                normals->push_back(len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f));
            }
        }
    }

private:
    const TriangleMesh& mesh_;
    std::vector<double> cumulative_;
    double total_ = 0.0;
};

// ---- k-d tree over points ----

// Median splits on the longest box axis, leaves of at most kLeafPoints; points are stored in tree order
// so every subtree is one contiguous range. Deterministic: ties in the split coordinate go by index.
class PointTree {
public:
    static constexpr uint32_t kLeafPoints = 8;
    struct Node {
        glm::vec3 lo, hi;
        uint32_t begin, end;  // range in tree order
        uint32_t left;        // 0 = leaf; else the left child (the right is left + 1)
        uint32_t uncovered;   // set cover bookkeeping: uncovered points in the subtree
    };

    explicit PointTree(const std::vector<glm::vec3>& points) : index(points.size()) {
        const size_t n = points.size();
        for (size_t i = 0; i < n; ++i) index[i] = uint32_t(i);
        if (n == 0) return;
        struct Task {
            uint32_t node, begin, end;
        };
        nodes.reserve(2 * (n / kLeafPoints) + 2);
        nodes.push_back(Node{});
        std::vector<Task> tasks = {{0, 0, uint32_t(n)}};
        while (!tasks.empty()) {
            const Task task = tasks.back();
            tasks.pop_back();
            glm::vec3 lo(kInf), hi(-kInf);
            for (uint32_t k = task.begin; k < task.end; ++k) {
                lo = glm::min(lo, points[index[k]]);
                hi = glm::max(hi, points[index[k]]);
            }
            Node node{lo, hi, task.begin, task.end, 0, task.end - task.begin};
            if (task.end - task.begin > kLeafPoints) {
                const glm::vec3 e = hi - lo;
                const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
                const uint32_t mid = task.begin + (task.end - task.begin) / 2;
                std::nth_element(index.begin() + task.begin, index.begin() + mid, index.begin() + task.end,
                                 [&](uint32_t a, uint32_t b) {
                                     return points[a][axis] < points[b][axis] ||
                                            (points[a][axis] == points[b][axis] && a < b);
                                 });
                node.left = uint32_t(nodes.size());
                nodes.push_back(Node{});
                nodes.push_back(Node{});
                tasks.push_back({node.left + 1, mid, task.end});
                tasks.push_back({node.left, task.begin, mid});
            }
            nodes[task.node] = node;
        }
        pos.resize(n);
        for (size_t k = 0; k < n; ++k) pos[k] = points[index[k]];
    }

    std::vector<Node> nodes;
    std::vector<uint32_t> index;  // tree order -> original index
    std::vector<glm::vec3> pos;   // points in tree order
};

// Squared distance from c to the nearest and the farthest point of a box. note: the per-component
// differences and the sum are formed as glm::dot(q - c, q - c) forms them for a point q, and float
// rounding is monotone, so "farthest <= x" implies every point's own float test passes and "nearest >
// x" that every one fails: whole subtrees are decided without a point-by-point check. The callers
// still keep a relative margin of kBoxMargin, in case a compiler contracts one of the two forms into
// fused multiply-adds and not the other.
constexpr float kBoxMargin = 1e-5f;
inline float nearestSquared(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& c) {
    // At most one of the two terms is non-zero per component (lo <= hi).
    const glm::vec3 d = glm::max(lo - c, glm::vec3(0.0f)) + glm::max(c - hi, glm::vec3(0.0f));
    return glm::dot(d, d);
}
inline float farthestSquared(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& c) {
    const glm::vec3 d = glm::max(glm::abs(lo - c), glm::abs(hi - c));
    return glm::dot(d, d);
}

// Step 2's r(p), from a start radius r_start: samples with f(q) = |q - p|^2 / (2 m.(q - p)) < r_start
// lower it, results >= r_start come back as r_start. f(q) < r exactly when q lies strictly inside the
// ball B(p + r m, r), and that ball shrinks (the balls are nested, all tangent at p) as binding samples
// are found, so the search only opens subtrees that meet the current ball; subtrees nearest its centre
// go first, where the binding sample usually is. Returns early once r < stop_below.
//
// Exactness: every visited sample runs the all-pairs loop's float expression. A sample whose float
// f(q) is below r lies within r (1 + 24 eps) of the float centre plus the centre's own rounding (the
// cancellation in m.(q - p) adds at most 14 eps r |q - p| to |q - c|^2, and |q - p| < 2 r), so the
// pruning margin of 2e-5 r plus `slack` never drops a binding sample.
float shrinkingBallRadius(const PointTree& tree, const glm::vec3& p, const glm::vec3& m, float r_start,
                          float slack, float stop_below) {
    float r = r_start;
    if (tree.nodes.empty()) return r;
    struct Entry {
        uint32_t node;
        float r;  // r when the node was found to meet the ball; unchanged since: no need to test again
    };
    Entry stack[128];
    int sp = 0;
    stack[sp++] = {0, -1.0f};
    glm::vec3 c = p + r * m;
    float reach = r * (1.0f + 2e-5f) + slack, reach2 = reach * reach;
    while (sp > 0) {
        const Entry e = stack[--sp];
        const PointTree::Node& node = tree.nodes[e.node];
        if (e.r != r && nearestSquared(node.lo, node.hi, c) > reach2) continue;
        if (node.left == 0) {
            const float r_before = r;
            for (uint32_t k = node.begin; k < node.end; ++k) {
                const glm::vec3 d = tree.pos[k] - p;
                const float along = glm::dot(m, d);
                if (along <= 0.0f) continue;
                r = std::min(r, glm::dot(d, d) / (2.0f * along));
            }
            if (r < stop_below) return r;
            if (r != r_before) {
                c = p + r * m;
                reach = r * (1.0f + 2e-5f) + slack;
                reach2 = reach * reach;
            }
            continue;
        }
        const uint32_t a = node.left, b = node.left + 1;
        const float da = nearestSquared(tree.nodes[a].lo, tree.nodes[a].hi, c);
        const float db = nearestSquared(tree.nodes[b].lo, tree.nodes[b].hi, c);
        const bool a_first = da <= db;
        assert(sp + 2 <= 128);
        if ((a_first ? db : da) <= reach2) stack[sp++] = {a_first ? b : a, r};
        if ((a_first ? da : db) <= reach2) stack[sp++] = {a_first ? a : b, r};
    }
    return r;
}

// The set cover's view of the points to cover: which are still uncovered, counted per subtree.
class CoverState {
public:
    explicit CoverState(const std::vector<glm::vec3>& points) : tree_(points), covered_(points.size(), 0) {}

    size_t uncovered() const { return tree_.nodes.empty() ? 0 : tree_.nodes[0].uncovered; }

    // Uncovered points q with glm::dot(q - c, q - c) <= reach2 (the all-pairs test, exactly).
    size_t gain(const glm::vec3& c, float reach2) const {
        if (tree_.nodes.empty()) return 0;
        size_t g = 0;
        uint32_t stack[128];
        int sp = 0;
        stack[sp++] = 0;
        while (sp > 0) {
            const PointTree::Node& node = tree_.nodes[stack[--sp]];
            if (node.uncovered == 0 || nearestSquared(node.lo, node.hi, c) > reach2 * (1.0f + kBoxMargin))
                continue;
            if (farthestSquared(node.lo, node.hi, c) <= reach2 * (1.0f - kBoxMargin)) {
                g += node.uncovered;
                continue;
            }
            if (node.left == 0) {
                for (uint32_t k = node.begin; k < node.end; ++k) {
                    const glm::vec3 d = tree_.pos[k] - c;
                    if (!covered_[k] && glm::dot(d, d) <= reach2) ++g;
                }
                continue;
            }
            assert(sp + 2 <= 128);
            stack[sp++] = node.left + 1;
            stack[sp++] = node.left;
        }
        return g;
    }

    // Marks what gain(c, reach2) counts as covered; returns how many.
    size_t take(const glm::vec3& c, float reach2) { return tree_.nodes.empty() ? 0 : take(0, c, reach2); }

    // Original indices of the uncovered points, ascending.
    std::vector<size_t> uncoveredIndices() const {
        std::vector<size_t> out;
        for (size_t k = 0; k < covered_.size(); ++k)
            if (!covered_[k]) out.push_back(tree_.index[k]);
        std::sort(out.begin(), out.end());
        return out;
    }

private:
    size_t take(uint32_t id, const glm::vec3& c, float reach2) {
        PointTree::Node& node = tree_.nodes[id];
        if (node.uncovered == 0 || nearestSquared(node.lo, node.hi, c) > reach2 * (1.0f + kBoxMargin))
            return 0;
        size_t taken = 0;
        if (farthestSquared(node.lo, node.hi, c) <= reach2 * (1.0f - kBoxMargin)) {
            taken = node.uncovered;
            coverAll(id);
            return taken;
        }
        if (node.left == 0) {
            for (uint32_t k = node.begin; k < node.end; ++k) {
                const glm::vec3 d = tree_.pos[k] - c;
                if (!covered_[k] && glm::dot(d, d) <= reach2) {
                    covered_[k] = 1;
                    ++taken;
                }
            }
        } else {
            const uint32_t left = node.left;  // note: `node` stays valid, nodes never reallocate here
            taken = take(left, c, reach2) + take(left + 1, c, reach2);
        }
        node.uncovered -= uint32_t(taken);
        return taken;
    }
    void coverAll(uint32_t id) {
        PointTree::Node& node = tree_.nodes[id];
        if (node.uncovered == 0) return;
        node.uncovered = 0;
        if (node.left == 0) {
            for (uint32_t k = node.begin; k < node.end; ++k) covered_[k] = 1;
            return;
        }
        coverAll(node.left);
        coverAll(node.left + 1);
    }

    PointTree tree_;
    std::vector<uint8_t> covered_;  // tree order
};

// ---- distances to the union of spheres ----

// A small bounding-box tree over the spheres (rebuilt whenever the set grows; radii may grow in place).
// nearest() returns exactly what the loop over all spheres returns: the smallest gap |p - c| - r, ties
// to the lowest index. Pruning: a box that holds a sphere is never farther than the sphere's surface.
class SphereIndex {
public:
    SphereIndex(const std::vector<Sphere>& spheres, float slack) : spheres_(spheres), slack_(slack) {
        const size_t n = spheres_.size();
        if (n == 0) return;
        std::vector<uint32_t> order(n);
        for (size_t i = 0; i < n; ++i) order[i] = uint32_t(i);
        leaf_of_.assign(n, 0);
        struct Task {
            uint32_t node, parent, begin, end;
        };
        nodes_.push_back(Node{});
        std::vector<Task> tasks = {{0, kNone, 0, uint32_t(n)}};
        while (!tasks.empty()) {
            const Task task = tasks.back();
            tasks.pop_back();
            Node node;
            node.parent = task.parent;
            if (task.end - task.begin <= kLeafSpheres) {
                node.count = task.end - task.begin;
                for (uint32_t k = 0; k < node.count; ++k) {
                    node.items[k] = order[task.begin + k];
                    leaf_of_[node.items[k]] = task.node;
                }
                nodes_[task.node] = node;
                refit(task.node);
                continue;
            }
            glm::vec3 lo(kInf), hi(-kInf);
            for (uint32_t k = task.begin; k < task.end; ++k) {
                lo = glm::min(lo, spheres_[order[k]].center);
                hi = glm::max(hi, spheres_[order[k]].center);
            }
            const glm::vec3 e = hi - lo;
            const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
            const uint32_t mid = task.begin + (task.end - task.begin) / 2;
            std::nth_element(order.begin() + task.begin, order.begin() + mid, order.begin() + task.end,
                             [&](uint32_t a, uint32_t b) {
                                 const float ca = spheres_[a].center[axis], cb = spheres_[b].center[axis];
                                 return ca < cb || (ca == cb && a < b);
                             });
            node.left = uint32_t(nodes_.size());
            nodes_[task.node] = node;
            nodes_.push_back(Node{});
            nodes_.push_back(Node{});
            // Children are done before their parent's box is needed: boxes are filled bottom-up below.
            tasks.push_back({node.left + 1, task.node, mid, task.end});
            tasks.push_back({node.left, task.node, task.begin, mid});
        }
        for (size_t i = nodes_.size(); i-- > 0;)  // children always follow their parent
            if (nodes_[i].count == 0) {
                nodes_[i].lo = glm::min(nodes_[nodes_[i].left].lo, nodes_[nodes_[i].left + 1].lo);
                nodes_[i].hi = glm::max(nodes_[nodes_[i].left].hi, nodes_[nodes_[i].left + 1].hi);
            }
    }

    // (gap, index) of the sphere whose surface is nearest to p (negative gap: inside). With
    // `stop_inside`, returns as soon as some gap <= 0 is found (the distance to the union is then 0).
    std::pair<float, size_t> nearest(const glm::vec3& p, bool stop_inside) const {
        float best = kInf;
        size_t best_index = 0;
        if (nodes_.empty()) return {best, best_index};
        uint32_t stack[128];
        int sp = 0;
        stack[sp++] = 0;
        while (sp > 0) {
            const Node& node = nodes_[stack[--sp]];
            if (std::sqrt(nearestSquared(node.lo, node.hi, p)) > best + slack_) continue;
            if (node.count > 0) {
                for (uint32_t k = 0; k < node.count; ++k) {
                    const Sphere& s = spheres_[node.items[k]];
                    const float gap = glm::length(p - s.center) - s.radius;
                    if (gap < best || (gap == best && node.items[k] < best_index)) {
                        best = gap;
                        best_index = node.items[k];
                    }
                }
                if (stop_inside && best <= 0.0f) return {best, best_index};
                continue;
            }
            const Node& a = nodes_[node.left];
            const Node& b = nodes_[node.left + 1];
            const bool a_first = nearestSquared(a.lo, a.hi, p) <= nearestSquared(b.lo, b.hi, p);
            assert(sp + 2 <= 128);
            stack[sp++] = a_first ? node.left + 1 : node.left;
            stack[sp++] = a_first ? node.left : node.left + 1;
        }
        return {best, best_index};
    }

    // distanceToSphereUnion(spheres, p), exactly.
    float distance(const glm::vec3& p) const {
        const float gap = nearest(p, true).first;
        return gap <= 0.0f ? 0.0f : gap;
    }

    // Sphere i's radius grew (never shrinks): its boxes up to the root grow with it.
    void grown(size_t i) {
        for (uint32_t id = leaf_of_[i]; id != kNone; id = nodes_[id].parent) {
            if (nodes_[id].count > 0) {
                refit(id);
            } else {
                nodes_[id].lo = glm::min(nodes_[id].lo, nodes_[nodes_[id].left].lo);
                nodes_[id].lo = glm::min(nodes_[id].lo, nodes_[nodes_[id].left + 1].lo);
                nodes_[id].hi = glm::max(nodes_[id].hi, nodes_[nodes_[id].left].hi);
                nodes_[id].hi = glm::max(nodes_[id].hi, nodes_[nodes_[id].left + 1].hi);
            }
        }
    }

private:
    static constexpr uint32_t kLeafSpheres = 4;
    static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
    struct Node {
        glm::vec3 lo{kInf}, hi{-kInf};
        uint32_t left = 0, parent = kNone, count = 0;  // count > 0: leaf with items[0, count)
        uint32_t items[kLeafSpheres] = {};
    };
    void refit(uint32_t id) {
        Node& node = nodes_[id];
        node.lo = glm::vec3(kInf);
        node.hi = glm::vec3(-kInf);
        for (uint32_t k = 0; k < node.count; ++k) {
            const Sphere& s = spheres_[node.items[k]];
            node.lo = glm::min(node.lo, s.center - s.radius);
            node.hi = glm::max(node.hi, s.center + s.radius);
        }
    }

    const std::vector<Sphere>& spheres_;
    float slack_;
    std::vector<Node> nodes_;
    std::vector<uint32_t> leaf_of_;
};

// ---- the fit ----

struct FitContext {
    const TriangleBvh& bvh;
    Bounds3 box;
    float tolerance_m, fit_tolerance_m;
    float slack;  // rounding allowance of the indexes: a few hundred ulps of the largest coordinate
    int threads;
    Progress* progress;
};

// Steps 2-4 above: appends spheres to `spheres` until every point of `points` is within
// `fit_tolerance_m` of the union (growing radii once `max_spheres` is reached). `medial_points` is every
// sample known on the surface; the shrinking balls are bound by them. Returns true if radii were grown.
// The progress stage set by the caller is spent here. False in `*ok` when cancelled.
bool coverPoints(const FitContext& fc, const std::vector<glm::vec3>& medial_points,
                 const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                 uint32_t max_spheres, float bulge_m, std::vector<Sphere>* spheres, bool* ok) {
    *ok = true;
    const size_t n = points.size();
    if (n == 0) return false;
    const glm::vec3 extent = fc.box.max - fc.box.min;
    const float max_radius_m = 0.5f * std::max(extent.x, std::max(extent.y, extent.z));
    const glm::vec3 lo = fc.box.min - glm::vec3(fc.tolerance_m), hi = fc.box.max + glm::vec3(fc.tolerance_m);
    Progress& progress = *fc.progress;
    const double stage_lo = progress.lo(), stage_hi = progress.hi();
    auto sub = [&](double a, double b) {
        progress.stage(stage_lo + (stage_hi - stage_lo) * a, stage_lo + (stage_hi - stage_lo) * b);
    };

    // Candidate balls, one per point (a slot per index keeps the result thread-count independent).
    sub(0.0, 0.05);
    const PointTree medial_tree(medial_points);
    std::vector<Sphere> cand(n);
    sub(0.05, 0.65);
    *ok = forEachIndex(n, fc.threads, &progress, [&](size_t i) {
        const glm::vec3 p = points[i], m = -normals[i];
        // Samples are sparser than a leaf is thick, so a ball bound only by samples can slip through
        // a thin part; the ray along m to the opposite face bounds it by half the local thickness.
        const float half_thickness = 0.5f * fc.bvh.rayHit(p + 1e-6f * max_radius_m * m, m);
        // r = min(shrinking ball, half_thickness), where a shrinking ball that nothing binds below
        // max_radius_m counts as 0 (open or inverted surface here). The ray is cast first: its bound
        // starts the search with a small ball, and only when no sample binds below it is a second,
        // early-out search needed to tell "bound below max_radius_m" from "nothing binds".
        const float start = std::min(max_radius_m, half_thickness);
        float r = shrinkingBallRadius(medial_tree, p, m, start, fc.slack, -1.0f);
        if (!(r < start) &&
            !(start < max_radius_m &&
              shrinkingBallRadius(medial_tree, p, m, max_radius_m, fc.slack, max_radius_m) < max_radius_m))
            r = 0.0f;
        r = std::min(r, half_thickness);
        glm::vec3 c = p + r * m;
        // A centre off the model's box means the ball sits in the outside (inverted normals):
        // fall back to a tolerance-sized ball on the sample, which always covers it.
        if (!(glm::all(glm::greaterThanEqual(c, lo)) && glm::all(glm::lessThanEqual(c, hi)))) {
            r = 0.0f;
            c = p;
        }
        cand[i] = Sphere{c, std::max(r + bulge_m, fc.tolerance_m)};
    });
    if (!*ok) return false;

    // Point j is covered by candidate i when glm::dot(points[j] - c_i, ...) <= reach_i^2.
    std::vector<float> reach2(n);
    for (size_t i = 0; i < n; ++i) {
        const float reach = cand[i].radius + fc.fit_tolerance_m;
        reach2[i] = reach * reach;
    }
    sub(0.65, 0.85);
    CoverState state(points);
    std::vector<size_t> initial_gain(n);
    *ok = forEachIndex(n, fc.threads, &progress,
                       [&](size_t i) { initial_gain[i] = state.gain(cand[i].center, reach2[i]); });
    if (!*ok) return false;

    // Lazy greedy: gains only shrink, so a popped entry whose fresh gain still beats the next stored
    // (upper-bound) gain is the true maximum. Ties go to the lower index (determinism).
    sub(0.85, 1.0);
    using Entry = std::pair<size_t, size_t>;  // (gain, n - index): larger is better
    std::vector<Entry> entries(n);
    for (size_t i = 0; i < n; ++i) entries[i] = {initial_gain[i], n - i};
    std::priority_queue<Entry> heap(std::less<Entry>(), std::move(entries));
    size_t pops = 0;
    while (state.uncovered() > 0 && spheres->size() < max_spheres && !heap.empty()) {
        if (++pops % 256 == 0) {
            if (progress.cancelled()) return *ok = false;
            progress.at(1.0 - double(state.uncovered()) / double(n));
        }
        const Entry top = heap.top();
        heap.pop();
        const size_t i = n - top.second;
        const size_t gain = state.gain(cand[i].center, reach2[i]);
        if (gain == 0) continue;
        if (!heap.empty() && Entry{gain, top.second} < heap.top()) {
            heap.push({gain, top.second});
            continue;
        }
        spheres->push_back(cand[i]);
        [[maybe_unused]] const size_t taken = state.take(cand[i].center, reach2[i]);
        assert(taken == gain);
    }
    if (state.uncovered() == 0) return false;

    // Bound hit: every uncovered point grows its nearest sphere (by gap to the surface) just enough.
    if (spheres->empty()) {  // max_spheres >= 1 by contract
        spheres->push_back(cand[0]);
        state.take(cand[0].center, reach2[0]);
    }
    bool grown = false;
    SphereIndex index(*spheres, fc.slack);
    for (size_t j : state.uncoveredIndices()) {
        const auto [best_gap, best] = index.nearest(points[j], false);
        if (best_gap > fc.fit_tolerance_m) {
            Sphere& s = (*spheres)[best];
            // note: growing to half the fit tolerance (not to it) leaves room for the points between
            // samples, which the grown sphere must also reach.
            s.radius = glm::length(points[j] - s.center) - 0.5f * fc.fit_tolerance_m;
            index.grown(best);
            grown = true;
        }
    }
    return grown;
}

float maxDistance(const FitContext& fc, const std::vector<Sphere>& spheres,
                  const std::vector<glm::vec3>& points) {
    SphereIndex index(spheres, fc.slack);
    std::vector<float> d(points.size());
    parallelFor(points.size(), fc.threads, 1024, [&](size_t begin, size_t end, int) {
        for (size_t j = begin; j < end; ++j) d[j] = index.distance(points[j]);
    });
    float worst = 0.0f;
    for (float v : d) worst = std::max(worst, v);
    return worst;
}

}  // namespace

float distanceToSphereUnion(const std::vector<Sphere>& spheres, const glm::vec3& p) {
    float best = std::numeric_limits<float>::infinity();
    for (const Sphere& s : spheres) best = std::min(best, glm::length(p - s.center) - s.radius);
    return std::max(best, 0.0f);
}

void sampleSurface(const TriangleMesh& mesh, uint32_t count, uint64_t seed, std::vector<glm::vec3>* points,
                   std::vector<glm::vec3>* normals) {
    SurfaceSampler(mesh).sample(count, seed, points, normals);
}

bool validateSphereFitSettings(const SphereFitSettings& settings, std::string* error) {
    if (settings.max_spheres < 1 || settings.max_spheres > kMaxFitSpheres)
        return fail(error, "fit.max_spheres = " + std::to_string(settings.max_spheres) + " is outside [1, " +
                               std::to_string(kMaxFitSpheres) + "]");
    if (!std::isfinite(settings.tolerance_m) || settings.tolerance_m < 0.0f)
        return fail(error,
                    "fit.tolerance_m = " + std::to_string(settings.tolerance_m) + " must be finite and >= 0");
    if (settings.tolerance_m == 0.0f &&
        !(std::isfinite(settings.tolerance_rel) && settings.tolerance_rel > 0.0f))
        return fail(error, "fit.tolerance_rel = " + std::to_string(settings.tolerance_rel) +
                               " must be finite and > 0 when fit.tolerance_m is 0");
    if (settings.surface_samples < kMinSurfaceSamples)
        return fail(error, "fit.surface_samples = " + std::to_string(settings.surface_samples) +
                               " is below the minimum of " + std::to_string(kMinSurfaceSamples));
    if (settings.surface_samples > kMaxSurfaceSamples)
        return fail(error, "fit.surface_samples = " + std::to_string(settings.surface_samples) +
                               " exceeds the limit of " + std::to_string(kMaxSurfaceSamples));
    return true;
}

bool fitSphereSet(const TriangleMesh& mesh, const SphereFitSettings& settings, std::vector<Sphere>* out,
                  SphereFitReport* report, std::string* error) {
    assert(out);
    if (!validateSphereFitSettings(settings, error)) return false;
    std::string why;
    if (!validateMesh(mesh, &why)) return fail(error, "mesh: " + why);

    const Bounds3 box = meshBounds(mesh);
    const glm::vec3 centre = 0.5f * (box.min + box.max);
    float bounding_radius_m = 0.0f;
    for (const glm::vec3& p : mesh.positions)
        bounding_radius_m = std::max(bounding_radius_m, glm::length(p - centre));
    const float tolerance_m =
        settings.tolerance_m > 0.0f ? settings.tolerance_m : settings.tolerance_rel * bounding_radius_m;
    if (!(tolerance_m > 0.0f) || !std::isfinite(tolerance_m))
        return fail(error, "mesh: degenerate (zero size), cannot derive a tolerance");

    // Stages of the progress bar, by typical cost: the BVH, the first attempt's cover and repair rounds;
    // later attempts (rare) split what is left, the report takes the last 3%.
    Progress progress(settings.progress, settings.cancel);
    const auto cancelled = [&] { return fail(error, "cancelled"); };
    progress.stage(0.0, 0.15);
    const TriangleBvh bvh(mesh, settings.threads);
    const SurfaceSampler sampler(mesh);
    if (progress.cancelled()) return cancelled();
    const glm::vec3 mag = glm::max(glm::abs(box.min), glm::abs(box.max));
    const float slack = 1e-5f * (std::max(mag.x, std::max(mag.y, mag.z)) + 2.0f * bounding_radius_m);
    const FitContext fc{
        bvh, box, tolerance_m, kFitToleranceFraction * tolerance_m, slack, settings.threads, &progress};

    std::vector<glm::vec3> points, normals;
    sampler.sample(settings.surface_samples, settings.seed, &points, &normals);
    if (points.empty()) return fail(error, "mesh: zero surface area");

    // Balls may stand kBulgeFraction * tolerance off the surface: each then covers much more of a smooth
    // surface, and stays within the tolerance band. If the count bound is still hit, coarser balls
    // (doubling the allowance) are tried before radii are grown point by point.
    std::vector<Sphere> spheres;
    bool grown = false;
    // Vertices join the samples: tips and corners (a grass blade's point) have too little area to be
    // sampled reliably but are where coverage fails first. A stride keeps big meshes cheap.
    {
        TriangleMesh with_normals;
        const std::vector<glm::vec3>* vertex_normals = &mesh.normals;
        if (mesh.normals.size() != mesh.positions.size()) {
            with_normals.positions = mesh.positions;
            with_normals.indices = mesh.indices;
            computeNormals(&with_normals);
            vertex_normals = &with_normals.normals;
        }
        const size_t stride = std::max<size_t>(1, mesh.positions.size() / settings.surface_samples);
        for (size_t v = 0; v < mesh.positions.size(); v += stride) {
            points.push_back(mesh.positions[v]);
            normals.push_back((*vertex_normals)[v]);
        }
    }
    const std::vector<glm::vec3> base_points = points, base_normals = normals;
    double attempt_lo = 0.15;
    for (int attempt = 0; attempt < kCoarsenAttempts; ++attempt) {
        const double attempt_hi =
            attempt + 1 < kCoarsenAttempts ? attempt_lo + 0.8 * (0.97 - attempt_lo) : 0.97;
        const double cover_hi = attempt_lo + 0.7 * (attempt_hi - attempt_lo);
        const float bulge_m = kBulgeFraction * float(1 << attempt) * tolerance_m;
        points = base_points;
        normals = base_normals;
        spheres.clear();
        bool ok = true;
        progress.stage(attempt_lo, cover_hi);
        grown = coverPoints(fc, points, points, normals, settings.max_spheres, bulge_m, &spheres, &ok);
        if (!ok) return cancelled();
        // Repair rounds: fresh independent samples that fall too far out are covered incrementally (the
        // spheres found so far stay), then join the sample set.
        for (int round = 0; round < kRepairRounds; ++round) {
            const double round_lo = cover_hi + (attempt_hi - cover_hi) * round / kRepairRounds;
            const double round_hi = cover_hi + (attempt_hi - cover_hi) * (round + 1) / kRepairRounds;
            progress.stage(round_lo, round_lo + 0.2 * (round_hi - round_lo));
            std::vector<glm::vec3> fresh, fresh_normals, bad, bad_normals;
            sampler.sample(2 * settings.surface_samples,
                           hashWords(settings.seed, kRepairSeedSalt, uint64_t(round)), &fresh,
                           &fresh_normals);
            std::vector<uint8_t> is_bad(fresh.size(), 0);
            {
                SphereIndex index(spheres, slack);
                ok = forEachIndex(fresh.size(), settings.threads, &progress, [&](size_t j) {
                    is_bad[j] = index.distance(fresh[j]) > kRepairToleranceFraction * tolerance_m;
                });
                if (!ok) return cancelled();
            }
            for (size_t j = 0; j < fresh.size(); ++j)
                if (is_bad[j]) {
                    bad.push_back(fresh[j]);
                    bad_normals.push_back(fresh_normals[j]);
                }
            if (bad.empty()) break;
            points.insert(points.end(), bad.begin(), bad.end());
            normals.insert(normals.end(), bad_normals.begin(), bad_normals.end());
            progress.stage(round_lo + 0.2 * (round_hi - round_lo), round_hi);
            grown |= coverPoints(fc, points, bad, bad_normals, settings.max_spheres, bulge_m, &spheres, &ok);
            if (!ok) return cancelled();
        }

        if (!grown) {
            grown = attempt > 0;  // a coarser pass than the first is a radius increase too
            break;
        }
        attempt_lo = attempt_hi;
    }
    progress.stage(0.97, 1.0);
    std::vector<glm::vec3> check_points;
    sampler.sample(settings.surface_samples, hashWords(settings.seed, kReportSeedSalt), &check_points,
                   nullptr);
    if (report) {
        *report = SphereFitReport{};
        report->tolerance_m = tolerance_m;
        report->max_sample_distance_m = maxDistance(fc, spheres, points);
        report->sphere_count = uint32_t(spheres.size());
        report->radii_grown = grown;
        report->max_check_distance_m = maxDistance(fc, spheres, check_points);
        report->check_sample_count = uint32_t(check_points.size());
    }
    *out = std::move(spheres);
    progress.done();
    return true;
}

}  // namespace ug
