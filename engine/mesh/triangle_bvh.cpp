// Binned-SAH BVH over triangles for exact nearest-hit ray casts (see the header for the contract).
#include "mesh/triangle_bvh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace ug {
namespace {

constexpr int kBins = 16;
constexpr int kMaxTraversalDepth = 128;
// Past this depth every split is a median split, so the depth stays below kMaxTraversalDepth whatever
// the SAH does on degenerate input (log2(2^32 triangles) = 32 more levels at most).
constexpr int kMedianSplitDepth = 64;
constexpr float kInf = std::numeric_limits<float>::infinity();
// Levels split before the subtrees below are built in parallel (up to 2^(kParallelDepth - 1) of them).
constexpr int kParallelDepth = 7;

// Moller-Trumbore: distance along d to the triangle (a, a + e1, a + e2), or a value <= 0 / NaN / +inf
// for a miss. note: not inlined, so the brute force and the BVH run the very same instructions (a
// compiler may contract a*b+c into a fused multiply-add differently in two inlined copies, which would
// break the bit-exact equality the header promises).
[[gnu::noinline]] float rayTriangle(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a,
                                    const glm::vec3& e1, const glm::vec3& e2) {
    const glm::vec3 pv = glm::cross(d, e2);
    const float det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-20f) return kInf;
    const float inv = 1.0f / det;
    const glm::vec3 tv = o - a;
    const float u = glm::dot(tv, pv) * inv;
    if (u < 0.0f || u > 1.0f) return kInf;
    const glm::vec3 qv = glm::cross(tv, e1);
    const float v = glm::dot(d, qv) * inv;
    if (v < 0.0f || u + v > 1.0f) return kInf;
    return glm::dot(e2, qv) * inv;
}

float area(const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct Item {
    glm::vec3 lo, hi;
    float centroid[3];
    uint32_t tri;
};

}  // namespace

float rayHitBruteForce(const TriangleMesh& mesh, const glm::vec3& o, const glm::vec3& d) {
    float best = kInf;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const float dist = rayTriangle(o, d, a, mesh.positions[mesh.indices[t + 1]] - a,
                                       mesh.positions[mesh.indices[t + 2]] - a);
        if (dist > 0.0f && dist < best) best = dist;
    }
    return best;
}

namespace {

struct Box {
    glm::vec3 lo{kInf}, hi{-kInf};
    void add(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void add(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
};

// One node to build: items [begin, end) with their box and the box of their centroids.
struct Task {
    uint32_t node, begin, end;
    int depth;
    Box box, centroids;
};

glm::vec3 centroidOf(const Item& it) {
    return glm::vec3(it.centroid[0], it.centroid[1], it.centroid[2]);
}

// Splits a task's items in place (binned SAH, median split as the fallback) and returns the two child
// tasks (their `node` left unset), or false when the task is a leaf. The children's boxes come out of
// the bins, so each level costs one binning pass and one partition pass over its items.
bool splitTask(std::vector<Item>& items, const Task& task, Task* left, Task* right) {
    const uint32_t count = task.end - task.begin;
    if (count <= TriangleBvh::kMaxLeafTriangles) return false;
    const glm::vec3 cext = task.centroids.hi - task.centroids.lo;
    const int axis = cext.x >= cext.y && cext.x >= cext.z ? 0 : (cext.y >= cext.z ? 1 : 2);
    *left = Task{0, task.begin, 0, task.depth + 1, {}, {}};
    *right = Task{0, 0, task.end, task.depth + 1, {}, {}};
    if (cext[axis] > 0.0f && task.depth < kMedianSplitDepth) {
        struct Bin {
            Box box, centroids;
            uint32_t count = 0;
        };
        Bin bins[kBins];
        const float lo = task.centroids.lo[axis], scale = float(kBins) / cext[axis];
        auto binOf = [&](const Item& it) {
            return std::min(kBins - 1, std::max(0, int((it.centroid[axis] - lo) * scale)));
        };
        for (uint32_t i = task.begin; i < task.end; ++i) {
            Bin& b = bins[binOf(items[i])];
            b.box.lo = glm::min(b.box.lo, items[i].lo);
            b.box.hi = glm::max(b.box.hi, items[i].hi);
            b.centroids.add(centroidOf(items[i]));
            ++b.count;
        }
        float right_area[kBins];
        uint32_t right_count[kBins];
        Box r;
        uint32_t rc = 0;
        for (int b = kBins - 1; b > 0; --b) {
            r.add(bins[b].box);
            rc += bins[b].count;
            right_area[b] = area(r.lo, r.hi);
            right_count[b] = rc;
        }
        Box l;
        uint32_t lc = 0;
        float best_cost = kInf;
        int best_split = -1;
        for (int b = 1; b < kBins; ++b) {  // split before bin b
            l.add(bins[b - 1].box);
            lc += bins[b - 1].count;
            if (lc == 0 || right_count[b] == 0) continue;
            const float cost = area(l.lo, l.hi) * float(lc) + right_area[b] * float(right_count[b]);
            if (cost < best_cost) {
                best_cost = cost;
                best_split = b;
            }
        }
        if (best_split > 0) {
            Item* split = std::partition(items.data() + task.begin, items.data() + task.end,
                                         [&](const Item& it) { return binOf(it) < best_split; });
            left->end = right->begin = uint32_t(split - items.data());
            for (int b = 0; b < kBins; ++b) {
                Task* side = b < best_split ? left : right;
                side->box.add(bins[b].box);
                side->centroids.add(bins[b].centroids);
            }
            return true;
        }
    }
    // Median split (all centroids in one bin, or too deep): by centroid, ties by triangle index, so the
    // halves are well defined.
    const uint32_t mid = task.begin + count / 2;
    std::nth_element(items.begin() + task.begin, items.begin() + mid, items.begin() + task.end,
                     [&](const Item& x, const Item& y) {
                         return x.centroid[axis] < y.centroid[axis] ||
                                (x.centroid[axis] == y.centroid[axis] && x.tri < y.tri);
                     });
    left->end = right->begin = mid;
    for (Task* side : {left, right})
        for (uint32_t i = side->begin; i < side->end; ++i) {
            side->box.lo = glm::min(side->box.lo, items[i].lo);
            side->box.hi = glm::max(side->box.hi, items[i].hi);
            side->centroids.add(centroidOf(items[i]));
        }
    return true;
}

}  // namespace

TriangleBvh::TriangleBvh(const TriangleMesh& mesh, int threads) {
    const size_t n = mesh.triangleCount();
    if (n == 0) return;
    assert(n < size_t(std::numeric_limits<uint32_t>::max()) / 2);
    std::vector<Item> items(n);
    parallelFor(n, threads, 1 << 14, [&](size_t begin, size_t end, int) {
        for (size_t t = begin; t < end; ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                            b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            Item& it = items[t];
            it.lo = glm::min(a, glm::min(b, c));
            it.hi = glm::max(a, glm::max(b, c));
            for (int k = 0; k < 3; ++k) it.centroid[k] = 0.5f * (it.lo[k] + it.hi[k]);
            it.tri = uint32_t(t);
        }
    });
    Task root{0, 0, uint32_t(n), 1, {}, {}};
    for (const Item& it : items) {
        root.box.lo = glm::min(root.box.lo, it.lo);
        root.box.hi = glm::max(root.box.hi, it.hi);
        root.centroids.add(centroidOf(it));
    }
    // Padding: a few hundred ulps of the largest coordinate, far above any rounding in the slab test.
    const glm::vec3 mag = glm::max(glm::abs(root.box.lo), glm::abs(root.box.hi));
    slack_ = 1e-5f * (std::max(mag.x, std::max(mag.y, mag.z)) +
                      std::max(1e-30f, glm::length(root.box.hi - root.box.lo)));

    // Builds the subtree of `task` into `nodes` (task.node is its slot there), depth first.
    auto buildSubtree = [&](Task first, std::vector<Node>* nodes, int* max_depth) {
        std::vector<Task> tasks = {first};
        while (!tasks.empty()) {
            const Task task = tasks.back();
            tasks.pop_back();
            *max_depth = std::max(*max_depth, task.depth);
            Node& node = (*nodes)[task.node];
            node.lo = task.box.lo - slack_;
            node.hi = task.box.hi + slack_;
            Task left, right;
            if (!splitTask(items, task, &left, &right)) {
                node.first = task.begin;
                node.count = task.end - task.begin;
                continue;
            }
            node.first = left.node = uint32_t(nodes->size());
            node.count = 0;
            right.node = left.node + 1;
            nodes->resize(nodes->size() + 2);  // note: `node` is not used past this point
            tasks.push_back(right);
            tasks.push_back(left);
        }
    };

    // The top kParallelDepth levels are split here, breadth first; the subtrees below them are built in
    // parallel, each into its own array, then appended in a fixed order. The cut does not depend on the
    // thread count, so neither does the tree.
    nodes_.reserve(2 * (n / 2 + 1));
    nodes_.push_back(Node{});
    std::vector<Task> frontier = {root}, subtrees;
    while (!frontier.empty()) {
        std::vector<Task> next;
        for (const Task& task : frontier) {
            if (task.depth >= kParallelDepth) {
                subtrees.push_back(task);
                continue;
            }
            depth_ = std::max(depth_, task.depth);
            Node& node = nodes_[task.node];
            node.lo = task.box.lo - slack_;
            node.hi = task.box.hi + slack_;
            Task left, right;
            if (!splitTask(items, task, &left, &right)) {
                node.first = task.begin;
                node.count = task.end - task.begin;
                continue;
            }
            node.first = left.node = uint32_t(nodes_.size());
            node.count = 0;
            right.node = left.node + 1;
            nodes_.resize(nodes_.size() + 2);
            next.push_back(left);
            next.push_back(right);
        }
        frontier = std::move(next);
    }
    std::vector<std::vector<Node>> local(subtrees.size());
    std::vector<int> local_depth(subtrees.size(), 0);
    parallelFor(subtrees.size(), threads, 1, [&](size_t begin, size_t end, int) {
        for (size_t s = begin; s < end; ++s) {
            Task task = subtrees[s];
            task.node = 0;
            local[s].reserve(2 * ((task.end - task.begin) / 2 + 1));
            local[s].resize(1);
            buildSubtree(task, &local[s], &local_depth[s]);
        }
    });
    for (size_t s = 0; s < subtrees.size(); ++s) {
        // Local node 0 goes to the subtree's slot; local node i > 0 to offset + i - 1.
        const uint32_t offset = uint32_t(nodes_.size());
        auto place = [&](Node node) {
            if (node.count == 0) node.first = offset + node.first - 1;
            return node;
        };
        nodes_[subtrees[s].node] = place(local[s][0]);
        for (size_t i = 1; i < local[s].size(); ++i) nodes_.push_back(place(local[s][i]));
        depth_ = std::max(depth_, local_depth[s]);
        std::vector<Node>().swap(local[s]);
    }
    assert(depth_ < kMaxTraversalDepth);
    tris_.resize(n);
    parallelFor(n, threads, 1 << 14, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            const uint32_t* idx = &mesh.indices[3 * size_t(items[i].tri)];
            const glm::vec3 a = mesh.positions[idx[0]];
            tris_[i] = Tri{a, mesh.positions[idx[1]] - a, mesh.positions[idx[2]] - a};
        }
    });
}

float TriangleBvh::rayHit(const glm::vec3& o, const glm::vec3& d) const {
    float best = kInf;
    if (nodes_.empty()) return best;
    glm::vec3 inv;
    bool flat[3];  // d has no component along this axis: the slab is a containment test
    for (int k = 0; k < 3; ++k) {
        flat[k] = d[k] == 0.0f;
        inv[k] = flat[k] ? 0.0f : 1.0f / d[k];
    }
    // Entry distance into a node's box, or +inf when the ray misses it or enters beyond `best`. The exit
    // is widened by 2 gamma(3) (Ize, "Robust BVH ray traversal", 2013) so rounding never culls a box
    // the ray grazes.
    auto entry = [&](const Node& node) {
        float tmin = 0.0f, tmax = kInf;
        for (int k = 0; k < 3; ++k) {
            if (flat[k]) {
                if (o[k] < node.lo[k] || o[k] > node.hi[k]) return kInf;
                continue;
            }
            float t0 = (node.lo[k] - o[k]) * inv[k], t1 = (node.hi[k] - o[k]) * inv[k];
            if (t0 > t1) std::swap(t0, t1);
            tmin = std::max(tmin, t0);
            tmax = std::min(tmax, t1);
        }
        if (tmin > tmax * (1.0f + 4.0f * std::numeric_limits<float>::epsilon()) || tmin > best + slack_)
            return kInf;
        return tmin;
    };
    // Stack entries keep their entry distance: a hit found in the nearer child can make the farther
    // one useless by the time it is popped.
    struct Entry {
        uint32_t node;
        float t;
    };
    Entry stack[kMaxTraversalDepth];
    int sp = 0;
    const float t_root = entry(nodes_[0]);
    if (t_root == kInf) return best;
    stack[sp++] = {0, t_root};
    while (sp > 0) {
        const Entry top = stack[--sp];
        if (top.t > best + slack_) continue;
        const Node& node = nodes_[top.node];
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const float dist = rayTriangle(o, d, tris_[i].a, tris_[i].e1, tris_[i].e2);
                if (dist > 0.0f && dist < best) best = dist;
            }
            continue;
        }
        const float tl = entry(nodes_[node.first]), tr = entry(nodes_[node.first + 1]);
        const bool left_first = tl <= tr;
        const Entry near{left_first ? node.first : node.first + 1, left_first ? tl : tr};
        const Entry far{left_first ? node.first + 1 : node.first, left_first ? tr : tl};
        if (far.t != kInf) stack[sp++] = far;
        if (near.t != kInf) stack[sp++] = near;
    }
    return best;
}

}  // namespace ug
