// Candidate queue: the priority queue Q of candidate triangles ct(e), most credible first (paper §3.1.3).
#pragma once

#include <math.h>
#include <stdint.h>

#include "core/array.h"

namespace dbrg {

// The order in which the Delaunay triangles around a boundary edge are its candidates (§3.1.2): smallest
// circumradius first. Circumradii of congruent triangles (a lattice, a cube's faces) differ only by rounding,
// so they are compared at float precision, and equal ones go to the triangle that turns least from the
// surface, then to the smaller apex id: a total order, and a function of the coordinates only.
struct CandidateRank {
    float radius;
    double turn;         // cosine of the dihedral angle with the edge's face in S
    uint32_t apex;
};

inline bool precedes(const CandidateRank& a, const CandidateRank& b) {
    if (a.radius != b.radius) return a.radius < b.radius;
    if (a.turn != b.turn) return a.turn > b.turn;
    return a.apex < b.apex;
}

// Local smooth degrees in the same step of this size count as equal in the queue's order. On a dense sample
// of a smooth surface nearly every candidate turns less than a degree from its neighbours (median 0.28
// degrees on 200,000 random points of a sphere), so nearly every LSD lies within 2^-13 of 1 and their exact
// values order the candidates at random. The front then grows like invasion percolation: porous, its open
// edges about 40 % of the faces grown, each step at an arbitrary place in memory. Among equals the queue
// prefers the candidate with more faces of S around it (it closes a notch instead of lengthening the front),
// then the smaller circumradius (a point under a flat Delaunay tetrahedron is reached before the big face
// above it is taken). 2^-13 is the cosine of 0.9 degrees; 2^-12 (1.3 degrees) changed the simulated scans (a
// loop left open on one), 2^-13 and 2^-14 did not, and 2^-13 reaches more samples (docs/benchmarks.md).
constexpr double SMOOTHNESS_TIE = 1.0 / 8192;

// The candidate triangle of one boundary half-edge u->v of S: the Delaunay triangle (v, u, apex). 32 bytes:
// the queue holds one per half-edge on the fronts, and those covered since until it next compacts.
struct Candidate {
    double smoothness;        // local smooth degree LSD: mean cosine of the dihedral angles with its neighbours in S
    double radius;            // circumradius r(t)
    uint32_t halfedge;        // the boundary half-edge of S it attaches to
    uint32_t apex;            // its third vertex
    uint32_t tet;             // a Delaunay tetrahedron that has it as a face
    int16_t smoothness_tier;  // smoothness in steps of SMOOTHNESS_TIE, rounded down
    uint8_t neighbours;       // faces of S it shares an edge with
    uint8_t postponed;        // 1 once it has been set aside for a retry

    // Sets the LSD and what ranks it: its tier and the faces of S the candidate shares an edge with.
    void set_smoothness(double lsd, uint8_t faces_around) {
        smoothness = lsd;
        // Below -1 (no cosine is) or NaN: the lowest tier.
        smoothness_tier = lsd >= -1 ? static_cast<int16_t>(floor(lsd / SMOOTHNESS_TIE)) : INT16_MIN;
        neighbours = faces_around;
    }
};
static_assert(sizeof(Candidate) == 32, "a queue entry fills half a cache line");

// Higher smoothness tier first, then more neighbours in S, the smaller circumradius, the higher exact
// smoothness, and vertex and half-edge ids, which depend only on coordinates, so the order is deterministic.
inline bool more_credible(const Candidate& a, const Candidate& b) {
    if (a.smoothness_tier != b.smoothness_tier) return a.smoothness_tier > b.smoothness_tier;
    if (a.neighbours != b.neighbours) return a.neighbours > b.neighbours;
    if (a.radius != b.radius) return a.radius < b.radius;
    if (a.smoothness != b.smoothness) return a.smoothness > b.smoothness;
    if (a.apex != b.apex) return a.apex < b.apex;
    return a.halfedge < b.halfedge;
}

// A binary max-heap of candidates over an Array.
class CandidateQueue {
public:
    explicit CandidateQueue(Memory& memory) : heap_(memory) {}

    bool empty() const { return heap_.empty(); }
    size_t size() const { return heap_.size(); }

    // True when the next push has to grow the heap's memory.
    bool full() const { return heap_.size() == heap_.capacity(); }
    size_t capacity() const { return heap_.capacity(); }
    // Makes room for `capacity` entries. Returns false on allocation failure.
    bool reserve(size_t capacity) { return heap_.reserve(capacity); }
    // Gives the heap's memory back; the queue must be empty.
    void release() { heap_.release(); }

    // Drops the entries for which stale(entry) is true and restores the heap order in linear time. Pops
    // return the remaining entries in the same order as before: more_credible is a total order.
    template <class Stale>
    void remove_if(Stale&& stale) {
        size_t kept = 0;
        for (size_t i = 0; i < heap_.size(); ++i) {
            if (!stale(heap_[i])) heap_[kept++] = heap_[i];
        }
        heap_.shrink(kept);
        for (size_t i = kept / 2; i-- > 0;) sift_down(i);
    }

    // Returns false on allocation failure.
    bool push(const Candidate& candidate) {
        if (!heap_.push_back(candidate)) return false;
        size_t i = heap_.size() - 1;
        while (i > 0) {
            const size_t parent = (i - 1) / 2;
            if (!more_credible(heap_[i], heap_[parent])) break;
            swap_entries(i, parent);
            i = parent;
        }
        return true;
    }

    Candidate pop() {
        const Candidate top = heap_[0];
        heap_[0] = heap_.back();
        heap_.pop_back();
        sift_down(0);
        return top;
    }

private:
    void sift_down(size_t i) {
        const size_t n = heap_.size();
        for (;;) {
            const size_t left = 2 * i + 1, right = left + 1;
            size_t best = i;
            if (left < n && more_credible(heap_[left], heap_[best])) best = left;
            if (right < n && more_credible(heap_[right], heap_[best])) best = right;
            if (best == i) break;
            swap_entries(i, best);
            i = best;
        }
    }

    void swap_entries(size_t i, size_t j) {
        const Candidate t = heap_[i];
        heap_[i] = heap_[j];
        heap_[j] = t;
    }

    Array<Candidate> heap_;
};

} // namespace dbrg
