// What incremental re-growth (StrandRegrower, strand_growth.h) keeps of a growth to grow the edited scene
// again: every point with the step that placed it, every strand with its parent and children, and every
// step's moves (the proposal and whether it was refused) in the order of that step's active strands.
// Points, strands born and moves are appended in step order, so a step's share of each is a range.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/large_pages.h"
#include "particles/particle_scene.h"

namespace ug {

// Gives `array` room for exactly n entries if it has less, written once so that its pages are in memory
// before a growth fills them (not faulted in one by one as it does), and empties it. An array with room
// already is left as it is.
template <typename Array>
void warmArrayExactly(Array& array, size_t n) {
    if (array.capacity() >= n) return;
    array.clear();
    array.resize(n);
    array.clear();
}

// As warmArrayExactly, for arrays whose size varies a little from one growth to the next: an array
// without room for n gets room for a quarter more, so that it does not grow again each time.
template <typename Array>
void warmArray(Array& array, size_t n) {
    if (array.capacity() < n) warmArrayExactly(array, n + n / 4);
}

// warmArray(array, like.size()) for each pair (array, like) of the arguments.
template <typename Array, typename Like, typename... Rest>
void warmEachLike(Array& array, const Like& like, Rest&&... rest) {
    warmArray(array, like.size());
    if constexpr (sizeof...(rest) > 0) warmEachLike(std::forward<Rest>(rest)...);
}

struct GrowthRecord {
    // Points, as the growth placed them: a strand is the chain of prev links (kNoPoint at a root).
    LargeVector<glm::vec3> point_pos;  // swapped with the growth's own arrays (large_pages.h)
    LargeVector<uint32_t> point_prev, point_strand;
    std::vector<uint32_t> step_points;  // [t]: the first point placed at step t (t = 0: the seeds); one past the last step ends it
    // Strands: the parent (-1 for a root) and the first of a split's children (kNoPoint if none; they
    // have consecutive ids).
    std::vector<int32_t> strand_parent;
    std::vector<uint32_t> strand_first_child;
    std::vector<uint32_t> step_strands;  // [t]: the first strand born at step t (t = 0: the roots)
    // Moves of step t: entries [step_moves[t], step_moves[t + 1]), one per strand active at t, by id.
    std::vector<uint32_t> step_moves;
    // A fur ball's are tens of megabytes each, as the points' (large_pages.h).
    LargeVector<uint32_t> move_strand;
    LargeVector<uint32_t> move_from;  // the point the move leaves
    LargeVector<glm::vec3> move_pos, move_dir;
    LargeVector<int32_t> move_cutter;
    LargeVector<uint8_t> move_blocked, move_still;

    static constexpr uint32_t kNoPoint = 0xffffffffu;

    // Empties every array, keeping its memory for the next growth.
    void clear() {
        const auto clearAll = [](auto&... arrays) { (arrays.clear(), ...); };
        clearAll(point_pos, point_prev, point_strand, step_points, strand_parent, strand_first_child, step_strands,
                 step_moves, move_strand, move_from, move_pos, move_dir, move_cutter, move_blocked, move_still);
    }
    // Gives every array room for as many entries as `other`'s (warmArray), the points' for exactly
    // `point_room` (a growth reserves that much before it places any);
    // empties the record. A growth appends to the steps' and the moves' arrays; the points' and the
    // strands' are swapped with its workspace's, which the growth after it fills.
    void warmLike(const GrowthRecord& other, size_t point_room) {
        clear();
        warmArrayExactly(point_pos, point_room);
        warmArrayExactly(point_prev, point_room);
        warmArrayExactly(point_strand, point_room);
        warmEachLike(step_points, other.step_points, strand_parent, other.strand_parent, strand_first_child,
                     other.strand_first_child, step_strands, other.step_strands, step_moves, other.step_moves,
                     move_strand, other.move_strand, move_from, other.move_from, move_pos, other.move_pos, move_dir,
                     other.move_dir, move_cutter, other.move_cutter, move_blocked, other.move_blocked, move_still,
                     other.move_still);
    }

    // Range helpers that read past the recorded steps as empty (the growth ended early: no active strand).
    uint32_t stepBegin(const std::vector<uint32_t>& starts, uint32_t step) const {
        return step < starts.size() ? starts[step] : starts.back();
    }
    uint32_t stepEnd(const std::vector<uint32_t>& starts, uint32_t step) const { return stepBegin(starts, step + 1); }
};

// How the attractors of an edited scene differ from the recorded one's, step by step. A trial's fitness
// can change only through an attractor that changed: wherever such an attractor's distance is beyond its
// radius of influence, old and new alike, its term is charge·radius, the same bits, so a strand whose
// trials all lie out there moves as before. A charge that changes at a step, or a radius of influence that
// changes or is 0 (everywhere), changes every trial's sum at that step: every strand is proposed again.
class AttractorEdit {
public:
    AttractorEdit(const std::vector<Attractor>& before, const std::vector<Attractor>& after, float step_length_m);

    // Whether every strand must be proposed again at `step`.
    bool everywhereAt(uint32_t step) const;
    // Whether a move from p0 (any trial within one step length of it) can see a changed term at `step`;
    // call only when !everywhereAt(step).
    bool reaches(glm::vec3 p0) const;

private:
    const std::vector<Attractor>& before_;
    const std::vector<Attractor>& after_;
    std::vector<uint32_t> moved_;   // changed attractors whose term changes only within their radius
    std::vector<uint32_t> global_;  // changed attractors whose term changes everywhere
    float margin_m_;                // a step length and then some, against rounding
};

// How the cutters of an edited scene differ from the recorded one's (as many of them). A cutter clips a
// move only where g crosses its threshold along it, and g is 1-Lipschitz (a signed distance), so a move
// from p0 can meet a changed cutter, old or new, only where |g(p0) - threshold| is within a step: a strand
// farther from every changed cutter moves as recorded. A move that a changed cutter clips (whose action may
// have changed too) parts from its record.
class CutterEdit {
public:
    CutterEdit(const std::vector<Cutter>& before, const std::vector<Cutter>& after, float step_length_m);

    // Whether a move from p0 can meet a changed cutter.
    bool reaches(glm::vec3 p0) const;
    // Whether cutter `index` (-1: none) changed.
    bool changed(int32_t index) const { return index >= 0 && changed_[size_t(index)]; }

private:
    const std::vector<Cutter>& before_;
    const std::vector<Cutter>& after_;
    std::vector<uint8_t> changed_;  // per cutter
    std::vector<uint32_t> list_;    // the changed ones
    float margin_m_;
};

// Whether a growth of `after` can start from a record of `before`: everything but the attractors (places,
// shapes, charges) and the cutters (places, thresholds, sides, actions) is the same (generators, terrain,
// the walk, the solids, the number of attractors and of cutters).
bool regrowable(const ParticleScene& before, const ParticleScene& after);

}  // namespace ug
