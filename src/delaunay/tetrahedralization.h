// Tetrahedralization: the compact tetrahedron store of a 3D Delaunay tetrahedralization and the queries
// region growing needs (tetrahedra around a vertex; triangles around an edge are in edge_ring.h).
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "points/spatial_sort.h"
#include "predicates/predicates.h"

namespace dbrg {

constexpr uint32_t NO_TET = UINT32_MAX;
// The vertex at infinity: every convex-hull face has an infinite tetrahedron behind it.
constexpr uint32_t INFINITE_VERTEX = UINT32_MAX;
// Tetrahedron slots are numbered below this: adjacency packs the neighbour in the upper 30 bits.
constexpr uint32_t MAX_TET_SLOTS = 1u << 30;
// A local index (0 to 3) that names no vertex or face of a tetrahedron.
constexpr uint32_t NO_LOCAL_INDEX = 4;

// Local numbering: face lf of a tetrahedron is the face opposite its local vertex lf. Finite
// tetrahedra are positively oriented: orient3d(v0, v1, v2, v3) > 0. In an infinite tetrahedron the
// infinite vertex is always local vertex 3, so face 3 is its convex-hull face, and the orientation
// is the one it would have if the infinite vertex were a point far outside the hull:
// orient3d(v0, v1, v2, q) > 0 for a point q beyond that hull face.

// Face lf as three local vertices in the order that makes (face, lf) an even permutation of
// (0, 1, 2, 3): orient3d(face, v_lf) then has the sign of the tetrahedron.
constexpr uint32_t FACE_VERTEX[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

// The vertices of the infinite tetrahedron behind face lf of the finite tetrahedron `finite`: the
// face with its orientation reversed, so that a point beyond it sees it positively, then the
// infinite vertex.
inline void infinite_tet_behind(const uint32_t finite[4], uint32_t lf, uint32_t behind[4]) {
    behind[0] = finite[FACE_VERTEX[lf][1]];
    behind[1] = finite[FACE_VERTEX[lf][0]];
    behind[2] = finite[FACE_VERTEX[lf][2]];
    behind[3] = INFINITE_VERTEX;
}

// The tetrahedra with their vertices and neighbours, in the local numbering above.
class Tetrahedralization {
public:
    explicit Tetrahedralization(Memory& memory);

    // Computes the Delaunay tetrahedralization of `count` distinct points (x, y, z triples that stay
    // alive and unchanged as long as this object is used). Reports DBRG_STAGE_SORT and
    // DBRG_STAGE_DELAUNAY progress; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY, DBRG_ERR_CANCELLED,
    // DBRG_ERR_TOO_FEW_POINTS, DBRG_ERR_TOO_MANY_POINTS or DBRG_ERR_DEGENERATE_INPUT (with the message
    // set on the context). On failure the object is left empty. Writes context.stats.seconds_sort,
    // seconds_delaunay (insertion only) and tetrahedra, and adds `counters` to the predicate_* fields.
    // The tetrahedra are a function of the coordinates only; on one thread (context.params.threads 1, or
    // a small input) the same point array in any memory also gives the same slots in the same order,
    // while threads inserting at once leave them in other slots (canonical_corners and the pipeline's
    // output order do not depend on slots). The points are read in place, so numbering them along a
    // space-filling curve first (renumber_spatially, as the pipeline does) keeps neighbours close in memory.
    // `order` says how the points are numbered, when the caller knows (see BrioOrder::prepare).
    dbrg_status build(const double* points, uint32_t count, Context& context, PointOrder order = PointOrder::any);

    // Empties the object and gives its memory back.
    void clear();

    uint32_t vertex_count() const { return vertex_count_; }
    const double* point(uint32_t v) const { return points_ + 3 * static_cast<size_t>(v); }
    const double* points() const { return points_; }

    // Tetrahedra are numbered 0 .. tet_slots() - 1; some slots are free (deleted and not reused).
    uint32_t tet_slots() const { return static_cast<uint32_t>(vertices_.size() / 4); }
    bool tet_is_free(uint32_t t) const { return vertices_[4 * size_t(t)] == FREE_MARK; }
    bool tet_is_finite(uint32_t t) const { return vertices_[4 * size_t(t) + 3] != INFINITE_VERTEX; }
    uint32_t finite_tet_count() const { return finite_tets_; }

    uint32_t tet_vertex(uint32_t t, uint32_t lv) const { return vertices_[4 * size_t(t) + lv]; }
    // The tetrahedron across face lf of t (never NO_TET in a finished tetrahedralization).
    uint32_t tet_adjacent(uint32_t t, uint32_t lf) const { return adjacency_[4 * size_t(t) + lf] >> 2; }
    // The local index, in tet_adjacent(t, lf), of the face shared with t.
    uint32_t tet_adjacent_face(uint32_t t, uint32_t lf) const { return adjacency_[4 * size_t(t) + lf] & 3u; }
    // The local index of vertex v in t, or NO_LOCAL_INDEX when t does not contain v.
    uint32_t tet_local_index(uint32_t t, uint32_t v) const;
    // The local indices of t's corners in a canonical order: the smallest vertex id first, then the
    // smallest of the other three, by an even permutation (so with t's orientation). How construction
    // happened to number the corners does not show in it.
    void canonical_corners(uint32_t t, uint32_t local[4]) const;

    // Some tetrahedron (finite or infinite) that contains vertex v.
    uint32_t vertex_tet(uint32_t v) const { return vertex_tet_[v]; }

    // Appends to `tets` every tetrahedron (finite or infinite) that contains vertex v. `tets` is
    // cleared first. Returns false on allocation failure.
    bool tets_around_vertex(uint32_t v, Array<uint32_t>& tets) const;

    // Checks adjacency symmetry, the orientation of every finite tetrahedron, the local Delaunay
    // property of every interior face (exact, with the same perturbation as construction), the
    // convexity of the hull and the Euler characteristic. On failure writes a sentence into message.
    bool validate(char* message, size_t message_capacity) const;

    // How the predicates were decided during build.
    PredicateCounters counters;

    static constexpr uint32_t FREE_MARK = UINT32_MAX - 1;

private:
    // Records one incident tetrahedron per vertex, the first slot that has it (vertex_tet_ holds NO_TET
    // for a vertex in none). Returns false on allocation failure.
    bool index_vertex_tets();

    const double* points_ = nullptr;
    uint32_t vertex_count_ = 0;
    uint32_t finite_tets_ = 0;
    Array<uint32_t> vertices_;   // 4 per tetrahedron
    Array<uint32_t> adjacency_;  // 4 per tetrahedron: neighbour << 2 | its local face
    Array<uint32_t> vertex_tet_; // one incident tetrahedron per vertex
    friend class DelaunayBuilder;
    friend class TetgenImporter;
};

} // namespace dbrg
