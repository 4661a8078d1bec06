// The ring of tetrahedra around a Delaunay edge, whose triangles through the edge are region growing's
// candidates (paper §3.1.2) for a boundary edge of S: the one walk around an edge of the tetrahedralization.
#pragma once

#include <stdint.h>

#include "delaunay/tetrahedralization.h"

namespace dbrg {
namespace edge_ring_detail {

// One tetrahedron of the ring around an edge (u, v), read at once: its two vertices other than u and v,
// their local indices, and its four neighbours.
struct RingTet {
    uint32_t others[2];
    uint32_t local[2];
    uint32_t adjacent[4];
};

inline RingTet read_ring_tet(const Tetrahedralization& delaunay, uint32_t t, uint32_t u, uint32_t v) {
    RingTet r;
    uint32_t vertex[4];
    for (uint32_t i = 0; i < 4; ++i) vertex[i] = delaunay.tet_vertex(t, i);
    for (uint32_t i = 0; i < 4; ++i) r.adjacent[i] = delaunay.tet_adjacent(t, i);
    uint32_t n = 0;
    for (uint32_t lv = 0; lv < 4; ++lv) {
        if (vertex[lv] != u && vertex[lv] != v) {
            r.others[n] = vertex[lv];
            r.local[n++] = lv;
        }
    }
    return r;
}

} // namespace edge_ring_detail

// Calls emit(apex, tet) once for each Delaunay triangle (u, v, apex) around the edge (u, v), where `start`
// is a tetrahedron with corners u and v: the ring of tetrahedra that share the edge is turned one way from
// `start`, and each is emitted with the apex of the triangle it shares with the next one that way. apex
// may be INFINITE_VERTEX (a hull edge). The pairs come in no cyclic order: finding the next tetrahedron
// waits on a cache miss, so the ring is walked from both sides of `start` at once, two of those misses in
// flight together, and each tetrahedron's neighbours are read together with its vertices rather than after.
template <class Emit>
void walk_edge_ring(const Tetrahedralization& delaunay, uint32_t start, uint32_t u, uint32_t v, Emit&& emit) {
    using namespace edge_ring_detail;
    // Forward: tetrahedron tf, whose apex is the vertex other than the one it shares with the previous
    // tetrahedron. The first has no previous one: its apex is others[0] unless that is the infinite vertex,
    // so the walk starts as if it came from there.
    RingTet f = read_ring_tet(delaunay, start, u, v);
    uint32_t tf = start, previous_apex = INFINITE_VERTEX;
    const uint32_t first = f.others[0] == previous_apex ? 1 : 0;
    // Backward: tetrahedron tb, entered through the face that holds `entered`, its apex in the forward order.
    uint32_t tb = f.adjacent[f.local[first]], entered = f.others[1 - first];
    RingTet b = read_ring_tet(delaunay, tb, u, v);
    for (;;) {
        const uint32_t k = f.others[0] == previous_apex ? 1 : 0;
        emit(f.others[k], tf);
        if (tf == tb) return;  // the sides met on one tetrahedron
        const uint32_t next_f = f.adjacent[f.local[1 - k]];
        emit(entered, tb);
        if (next_f == tb) return;  // the sides met between two tetrahedra
        const uint32_t j = b.others[0] == entered ? 0 : 1;
        const uint32_t next_b = b.adjacent[b.local[j]];
        previous_apex = f.others[k];
        entered = b.others[1 - j];
        tf = next_f;
        tb = next_b;
        f = read_ring_tet(delaunay, tf, u, v);
        if (tb != tf) b = read_ring_tet(delaunay, tb, u, v);
    }
}

} // namespace dbrg
