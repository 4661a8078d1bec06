// Planar Delaunay: the 2-D Delaunay triangulation of points that all lie exactly in one plane of space (a
// flat input), built by incremental insertion with exact predicates, for the flat path of reconstruction.
//
// Based on: A. Bowyer, "Computing Dirichlet tessellations" and D. F. Watson, "Computing the n-dimensional
// Delaunay tessellation" (both 1981), in the plane, with an infinite vertex closing the convex hull.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "predicates/predicates.h"

namespace dbrg {

constexpr uint32_t NO_TRIANGLE = UINT32_MAX;
// The vertex at infinity: every convex-hull edge has an infinite triangle behind it.
constexpr uint32_t PLANAR_INFINITE_VERTEX = UINT32_MAX;

// Triangles are stored counter-clockwise as seen from the side the plane's normal points to, the normal
// taken with a positive component on normal_axis() (the axis of its largest component). An infinite
// triangle (x, y, infinity) has the outside of the hull to the left of x -> y. Cocircular points are decided
// by incircle3d_sos, the lifted-coordinate perturbation of the 3-D code, so the triangulation is a function
// of the coordinates alone.
class PlanarTriangulation {
public:
    explicit PlanarTriangulation(Memory& memory) : vertices_(memory), adjacent_(memory) {}

    // Triangulates n points (x, y, z each, kept by pointer until this object is gone) that are pairwise
    // distinct, exactly coplanar and not all collinear, inserted in the order given (a spatial order keeps the
    // walks short). Reports progress to `progress`; adds its predicate counts to context.stats. Returns DBRG_OK,
    // DBRG_ERR_OUT_OF_MEMORY, DBRG_ERR_CANCELLED, or DBRG_ERR_DEGENERATE_INPUT when all points are collinear.
    dbrg_status build(const double* coordinates, uint32_t n, Context& context, const ProgressSpan& progress);

    // Triangle slots, infinite and unused ones included.
    uint32_t slot_count() const { return static_cast<uint32_t>(vertices_.size() / 3); }
    uint32_t vertex_count() const { return vertex_count_; }
    uint32_t finite_triangle_count() const { return finite_triangles_; }
    bool triangle_is_live(uint32_t t) const { return vertices_[3 * size_t(t)] != FREE_SLOT; }
    bool triangle_is_finite(uint32_t t) const {
        return triangle_is_live(t) && vertices_[3 * size_t(t)] != PLANAR_INFINITE_VERTEX &&
               vertices_[3 * size_t(t) + 1] != PLANAR_INFINITE_VERTEX && vertices_[3 * size_t(t) + 2] != PLANAR_INFINITE_VERTEX;
    }
    uint32_t triangle_vertex(uint32_t t, uint32_t lv) const { return vertices_[3 * size_t(t) + lv]; }
    // The triangle across the edge opposite corner lv of t.
    uint32_t triangle_adjacent(uint32_t t, uint32_t lv) const { return adjacent_[3 * size_t(t) + lv]; }
    const double* point(uint32_t v) const { return coordinates_ + 3 * size_t(v); }
    // The axis of the plane normal's largest component; the normal is taken with that component positive.
    int normal_axis() const { return normal_axis_; }

    // Orientation of a, b, c in the plane: +1 counter-clockwise (as the triangles are stored), -1, or 0.
    int orient(const double* a, const double* b, const double* c, PredicateCounters& counters) const {
        return orient2d(a, b, c, (normal_axis_ + 1) % 3, (normal_axis_ + 2) % 3, counters);
    }

    // Checks adjacency symmetry, orientation and the (perturbed) empty-circle property of every edge. On
    // failure writes a sentence into message.
    bool validate(char* message, size_t message_capacity) const;

private:
    struct Scratch;

    bool in_conflict(uint32_t t, const double* p, PredicateCounters& counters) const;
    uint32_t locate(uint32_t start, const double* p, PredicateCounters& counters) const;
    dbrg_status insert(uint32_t v, uint32_t& near, Scratch& scratch, Context& context, PredicateCounters& counters);
    uint32_t new_triangle(uint32_t a, uint32_t b, uint32_t c);
    void link(uint32_t t, uint32_t lv, uint32_t neighbour) { adjacent_[3 * size_t(t) + lv] = neighbour; }
    uint32_t local_index_of(uint32_t t, uint32_t v) const;
    uint32_t local_index_of_neighbour(uint32_t t, uint32_t neighbour) const;

    const double* coordinates_ = nullptr;
    uint32_t vertex_count_ = 0;
    uint32_t finite_triangles_ = 0;
    int normal_axis_ = 2;
    // In the first vertex of a slot no triangle holds; never a vertex id (below DBRG_MAX_POINTS).
    static constexpr uint32_t FREE_SLOT = UINT32_MAX - 1;

    Array<uint32_t> vertices_;  // 3 per slot; FREE_SLOT in the first for a free slot
    Array<uint32_t> adjacent_;  // 3 per slot
};

} // namespace dbrg
