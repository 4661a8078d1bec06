// Surface: the growing triangulated surface S (paper §2.2) as an array-based half-edge structure that
// can only ever hold an oriented 2-manifold with boundary.
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), section 2.2.
#pragma once

#include <stdint.h>

#include "core/array.h"

namespace dbrg {

constexpr uint32_t NO_HALFEDGE = UINT32_MAX;
constexpr uint32_t NO_FACE = UINT32_MAX;

// Half-edge h = 3 f + i of face f runs from corner i to corner (i + 1) % 3; next and prev are implicit,
// so a face costs its three corners, its three twins and the tetrahedron it was taken from.
//
// Invariant kept by every mutation: the faces around each vertex form a single fan (no bow-tie), every
// edge has at most two faces, and two faces on an edge traverse it in opposite directions. A vertex on
// the boundary therefore has exactly one outgoing and one incoming boundary half-edge, and
// vertex_halfedge() of a boundary vertex is its outgoing boundary half-edge.
class Surface {
public:
    explicit Surface(Memory& memory);

    // Prepares per-vertex storage for vertices 0 .. vertex_count - 1. Returns false on allocation failure.
    bool reset(uint32_t vertex_count);

    uint32_t face_count() const { return static_cast<uint32_t>(corners_.size() / 3); }
    uint32_t vertex_count() const { return static_cast<uint32_t>(vertex_halfedge_.size()); }

    static uint32_t face_of(uint32_t h) { return h / 3; }
    static uint32_t next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
    static uint32_t prev(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
    uint32_t origin(uint32_t h) const { return corners_[h]; }
    uint32_t target(uint32_t h) const { return corners_[next(h)]; }
    uint32_t twin(uint32_t h) const { return twins_[h]; }
    bool is_boundary(uint32_t h) const { return twins_[h] == NO_HALFEDGE; }
    uint32_t corner(uint32_t f, uint32_t i) const { return corners_[3 * size_t(f) + i]; }
    uint32_t face_tet(uint32_t f) const { return tets_[f]; }

    // An outgoing half-edge of v (its outgoing boundary half-edge when v is on the boundary), or
    // NO_HALFEDGE when v has no face.
    uint32_t vertex_halfedge(uint32_t v) const { return vertex_halfedge_[v]; }
    bool is_used(uint32_t v) const { return vertex_halfedge_[v] != NO_HALFEDGE; }
    // True when v has faces and its fan is open.
    bool is_boundary_vertex(uint32_t v) const {
        return vertex_halfedge_[v] != NO_HALFEDGE && is_boundary(vertex_halfedge_[v]);
    }

    // The next outgoing half-edge of origin(h) turning one way around the vertex, or NO_HALFEDGE at the
    // boundary. Starting from vertex_halfedge(v) it visits every outgoing half-edge of v.
    uint32_t rotate(uint32_t h) const { return twins_[prev(h)]; }

    // The half-edge from a to b, or NO_HALFEDGE. O(degree of a).
    uint32_t find_halfedge(uint32_t a, uint32_t b) const;

    // Adds face (a, b, c), counter-clockwise, remembering tetrahedron `tet`. Links it with the existing
    // boundary half-edges b->a, c->b, a->c. The caller must have checked (can_add_face) that the result
    // stays an oriented manifold. Returns the face id, or NO_FACE on allocation failure.
    uint32_t add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet);

    // Removes faces first_face .. face_count() - 1, which must share no edge or vertex with earlier faces
    // (a component grown last). Returns how many vertices that frees.
    uint32_t truncate(uint32_t first_face);

    // Checks every invariant above from scratch. On failure writes a sentence into message.
    bool validate(char* message, size_t message_capacity) const;

private:
    void link_twins(uint32_t h);
    void update_vertex_halfedge(uint32_t h);

    Array<uint32_t> corners_;          // 3 per face
    Array<uint32_t> twins_;            // 3 per face
    Array<uint32_t> tets_;             // 1 per face
    Array<uint32_t> vertex_halfedge_;  // 1 per vertex
};

} // namespace dbrg
