// Candidate queue: the priority queue Q of candidate triangles ct(e), most credible first (paper §3.1.3).
#pragma once

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

// The candidate triangle of one boundary half-edge u->v of S: the Delaunay triangle (v, u, apex). 32 bytes:
// the queue holds one per half-edge on the fronts, and those covered since until it next compacts.
struct Candidate {
    double smoothness;   // local smooth degree LSD: mean cosine of the dihedral angles with its neighbours in S
    double radius;       // circumradius r(t)
    uint32_t halfedge;   // the boundary half-edge of S it attaches to
    uint32_t apex;       // its third vertex
    uint32_t tet;        // a Delaunay tetrahedron that has it as a face
    uint8_t postponed;   // 1 once it has been set aside for a retry
};

// Higher smoothness first, then the smaller circumradius, then vertex and half-edge ids, which depend only
// on coordinates, so the order is deterministic.
inline bool more_credible(const Candidate& a, const Candidate& b) {
    if (a.smoothness != b.smoothness) return a.smoothness > b.smoothness;
    if (a.radius != b.radius) return a.radius < b.radius;
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
