// Planar Delaunay: incremental 2-D Delaunay triangulation of exactly coplanar points (see planar_delaunay.h).
//
// Based on: A. Bowyer, "Computing Dirichlet tessellations" and D. F. Watson, "Computing the n-dimensional
// Delaunay tessellation" (both 1981).
//
// Each point removes the triangles in conflict with it (a connected, star-shaped region) and joins the
// region's boundary edges to it. A finite triangle is in conflict when the point is inside its circumcircle,
// decided in the true plane by incircle3d_sos, which equals the 3-D insphere test with any point off the plane
// and perturbs cocircular cases by the points' lexicographic ranks. An infinite triangle (x, y, infinity) is
// in conflict when the point is strictly outside its hull edge, or on the edge's line strictly between x and
// y: the limit of its circle, a half-plane, with the points of the edge itself counted inside as they are for
// the finite triangle across it.
#include "planar/planar_delaunay.h"

#include <math.h>
#include <stdio.h>

#include "core/status.h"
#include "core/vec3.h"

namespace dbrg {
namespace {

// Insertions between two progress reports: a few milliseconds.
constexpr uint32_t REPORT_POINTS = 1u << 12;

// The axis of the largest component of the normal of the plane through the points, from the widest
// triangle found in two passes (the point farthest from the first, then the point farthest from their
// line); rounding only has to rank the components, which an off-axis plane does not need exactly.
int largest_normal_axis(const double* coordinates, uint32_t n) {
    const Vec3 a = load_vec3(coordinates);
    Vec3 b = a;
    double farthest = 0;
    for (uint32_t i = 1; i < n; ++i) {
        const Vec3 p = load_vec3(coordinates + 3 * size_t(i));
        const double d = squared_length(p - a);
        if (d > farthest) {
            farthest = d;
            b = p;
        }
    }
    Vec3 normal{0, 0, 0};
    double widest = 0;
    for (uint32_t i = 1; i < n; ++i) {
        const Vec3 candidate = cross(b - a, load_vec3(coordinates + 3 * size_t(i)) - a);
        const double w = squared_length(candidate);
        if (w > widest) {
            widest = w;
            normal = candidate;
        }
    }
    const double magnitude[3] = {fabs(normal.x), fabs(normal.y), fabs(normal.z)};
    int axis = 0;
    for (int k = 1; k < 3; ++k) axis = magnitude[k] > magnitude[axis] ? k : axis;
    return axis;
}

// The index of a vertex in per-vertex scratch arrays: the infinite vertex after the n finite ones.
inline uint32_t scratch_index(uint32_t v, uint32_t n) { return v == PLANAR_INFINITE_VERTEX ? n : v; }

} // namespace

// What one insertion collects before it changes anything: the triangles in conflict and the edges of the
// region they cover, each with the triangle outside it.
struct PlanarTriangulation::Scratch {
    explicit Scratch(Memory& memory)
        : stamp(memory), conflict(memory), cavity(memory), rim(memory), free_slots(memory), starting(memory) {}
    struct RimEdge {
        uint32_t x, y;           // counter-clockwise around the region
        uint32_t outside;        // the triangle across the edge, kept
        uint32_t outside_slot;   // the edge's local index in `outside`
    };
    Array<uint32_t> stamp;       // per slot: 1 + the last vertex tested against it
    Array<uint8_t> conflict;     // per slot: that test's answer
    Array<uint32_t> cavity;
    Array<RimEdge> rim;
    Array<uint32_t> free_slots;
    Array<uint32_t> starting;    // per vertex: the new triangle whose rim edge starts there
};

uint32_t PlanarTriangulation::local_index_of(uint32_t t, uint32_t v) const {
    for (uint32_t lv = 0; lv < 3; ++lv) {
        if (triangle_vertex(t, lv) == v) return lv;
    }
    return 3;
}

uint32_t PlanarTriangulation::local_index_of_neighbour(uint32_t t, uint32_t neighbour) const {
    for (uint32_t lv = 0; lv < 3; ++lv) {
        if (triangle_adjacent(t, lv) == neighbour) return lv;
    }
    return 3;
}

bool PlanarTriangulation::in_conflict(uint32_t t, const double* p, PredicateCounters& counters) const {
    const uint32_t infinite = local_index_of(t, PLANAR_INFINITE_VERTEX);
    if (infinite == 3) {
        return incircle3d_sos(point(triangle_vertex(t, 0)), point(triangle_vertex(t, 1)), point(triangle_vertex(t, 2)), p,
                              counters) > 0;
    }
    const double* x = point(triangle_vertex(t, (infinite + 1) % 3));
    const double* y = point(triangle_vertex(t, (infinite + 2) % 3));
    const int side = orient(x, y, p, counters);
    if (side != 0) return side > 0;
    // On the line: lexicographic order is monotone along a line, so p is between x and y exactly when it
    // compares the same way with both.
    return compare_points(x, p) == compare_points(p, y);
}

// A visibility walk from the finite triangle `start` to a triangle in conflict with p: the finite triangle
// that contains p (its closure), or the infinite triangle of a hull edge that p is strictly outside of.
// Walks in a Delaunay triangulation never cycle.
uint32_t PlanarTriangulation::locate(uint32_t start, const double* p, PredicateCounters& counters) const {
    uint32_t t = start;
    for (;;) {
        uint32_t next = NO_TRIANGLE;
        for (uint32_t lv = 0; lv < 3 && next == NO_TRIANGLE; ++lv) {
            const double* x = point(triangle_vertex(t, (lv + 1) % 3));
            const double* y = point(triangle_vertex(t, (lv + 2) % 3));
            if (orient(x, y, p, counters) < 0) next = triangle_adjacent(t, lv);
        }
        if (next == NO_TRIANGLE || !triangle_is_finite(next)) return next == NO_TRIANGLE ? t : next;
        t = next;
    }
}

uint32_t PlanarTriangulation::new_triangle(uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t t = slot_count();
    const uint32_t corners[3] = {a, b, c};
    for (uint32_t v : corners) {
        vertices_.push_back(v);
        adjacent_.push_back(NO_TRIANGLE);
    }
    return t;
}

dbrg_status PlanarTriangulation::insert(uint32_t v, uint32_t& near, Scratch& scratch, Context& context,
                                        PredicateCounters& counters) {
    const double* p = point(v);
    const uint32_t first = locate(near, p, counters);
    const uint32_t mark = v + 1;
    scratch.cavity.clear();
    scratch.rim.clear();
    if (!scratch.cavity.push_back(first)) return context.fail_out_of_memory();
    scratch.stamp[first] = mark;
    scratch.conflict[first] = 1;
    for (size_t i = 0; i < scratch.cavity.size(); ++i) {
        const uint32_t t = scratch.cavity[i];
        for (uint32_t lv = 0; lv < 3; ++lv) {
            const uint32_t n = triangle_adjacent(t, lv);
            if (scratch.stamp[n] != mark) {
                scratch.stamp[n] = mark;
                scratch.conflict[n] = in_conflict(n, p, counters) ? 1 : 0;
                if (scratch.conflict[n] && !scratch.cavity.push_back(n)) return context.fail_out_of_memory();
            }
            if (scratch.conflict[n]) continue;
            const Scratch::RimEdge edge{triangle_vertex(t, (lv + 1) % 3), triangle_vertex(t, (lv + 2) % 3), n,
                                        local_index_of_neighbour(n, t)};
            if (!scratch.rim.push_back(edge)) return context.fail_out_of_memory();
        }
    }
    for (uint32_t t : scratch.cavity) {
        vertices_[3 * size_t(t)] = FREE_SLOT;
        if (!scratch.free_slots.push_back(t)) return context.fail_out_of_memory();
    }
    // The region's rim is one cycle: each vertex on it starts one rim edge and ends another.
    const uint32_t n = vertex_count_;
    for (const Scratch::RimEdge& edge : scratch.rim) {
        uint32_t t;
        if (!scratch.free_slots.empty()) {
            t = scratch.free_slots.back();
            scratch.free_slots.pop_back();
            vertices_[3 * size_t(t)] = edge.x;
            vertices_[3 * size_t(t) + 1] = edge.y;
            vertices_[3 * size_t(t) + 2] = v;
        } else {
            t = new_triangle(edge.x, edge.y, v);
            if (!scratch.stamp.push_back(0) || !scratch.conflict.push_back(0)) return context.fail_out_of_memory();
        }
        link(t, 2, edge.outside);
        link(edge.outside, edge.outside_slot, t);
        scratch.starting[scratch_index(edge.x, n)] = t;
        if (edge.x != PLANAR_INFINITE_VERTEX && edge.y != PLANAR_INFINITE_VERTEX) near = t;
    }
    if (context.memory.failed()) return context.fail_out_of_memory();
    // (x, y, v) and (y, z, v) share the edge v - y: opposite x in the one, opposite z in the other.
    for (const Scratch::RimEdge& edge : scratch.rim) {
        const uint32_t t = scratch.starting[scratch_index(edge.x, n)];
        const uint32_t following = scratch.starting[scratch_index(edge.y, n)];
        link(t, 0, following);
        link(following, 1, t);
    }
    return DBRG_OK;
}

dbrg_status PlanarTriangulation::build(const double* coordinates, uint32_t n, Context& context, const ProgressSpan& progress) {
    coordinates_ = coordinates;
    vertex_count_ = n;
    vertices_.clear();
    adjacent_.clear();
    finite_triangles_ = 0;
    PredicateCounters counters;
    DBRG_PROPAGATE(progress.report(0, n));
    normal_axis_ = n >= 3 ? largest_normal_axis(coordinates, n) : 2;
    // The first triangle: the first two points and the first point off their line, turned counter-clockwise.
    uint32_t third = 2;
    int turn = 0;
    for (; third < n; ++third) {
        turn = orient(point(0), point(1), point(third), counters);
        if (turn != 0) break;
    }
    if (third >= n) return context.fail(DBRG_ERR_DEGENERATE_INPUT, "all %u distinct points are collinear", n);
    const uint32_t a = 0, b = turn > 0 ? 1 : third, c = turn > 0 ? third : 1;
    Scratch scratch(context.memory);
    const size_t slots = 2 * size_t(n) + 2;  // a triangulation with its hull closed by infinite triangles
    if (!vertices_.reserve(3 * slots) || !adjacent_.reserve(3 * slots) || !scratch.stamp.resize(4, 0) ||
        !scratch.conflict.resize(4, 0) || !scratch.starting.resize(size_t(n) + 1, NO_TRIANGLE)) {
        return context.fail_out_of_memory();
    }
    const uint32_t inside = new_triangle(a, b, c);
    const uint32_t across_a = new_triangle(c, b, PLANAR_INFINITE_VERTEX);
    const uint32_t across_b = new_triangle(a, c, PLANAR_INFINITE_VERTEX);
    const uint32_t across_c = new_triangle(b, a, PLANAR_INFINITE_VERTEX);
    link(inside, 0, across_a);
    link(inside, 1, across_b);
    link(inside, 2, across_c);
    link(across_a, 2, inside);
    link(across_b, 2, inside);
    link(across_c, 2, inside);
    // Around the hull: (c, b, inf) meets (b, a, inf) at b - inf, and so on.
    link(across_a, 0, across_c);
    link(across_c, 1, across_a);
    link(across_c, 0, across_b);
    link(across_b, 1, across_c);
    link(across_b, 0, across_a);
    link(across_a, 1, across_b);

    uint32_t near = inside;
    for (uint32_t v = 2; v < n; ++v) {
        if (v % REPORT_POINTS == 0) DBRG_PROPAGATE(progress.report(v, n));
        if (v == third) continue;
        DBRG_PROPAGATE(insert(v, near, scratch, context, counters));
    }
    for (uint32_t t = 0; t < slot_count(); ++t) finite_triangles_ += triangle_is_finite(t) ? 1 : 0;
    context.stats.predicate_calls += counters.calls;
    context.stats.predicate_filter_failures += counters.filter_failures;
    context.stats.predicate_perturbations += counters.perturbations;
    return progress.report(n, n);
}

bool PlanarTriangulation::validate(char* message, size_t capacity) const {
    PredicateCounters counters;
    for (uint32_t t = 0; t < slot_count(); ++t) {
        if (!triangle_is_live(t)) continue;
        for (uint32_t lv = 0; lv < 3; ++lv) {
            const uint32_t n = triangle_adjacent(t, lv);
            if (n >= slot_count() || !triangle_is_live(n)) {
                snprintf(message, capacity, "triangle %u has no live neighbour across its edge %u", t, lv);
                return false;
            }
            const uint32_t back = local_index_of_neighbour(n, t);
            const uint32_t x = triangle_vertex(t, (lv + 1) % 3), y = triangle_vertex(t, (lv + 2) % 3);
            if (back == 3 || triangle_vertex(n, (back + 1) % 3) != y || triangle_vertex(n, (back + 2) % 3) != x) {
                snprintf(message, capacity, "triangles %u and %u are not linked back through one edge", t, n);
                return false;
            }
            // Across each edge of a finite triangle the opposite vertex is outside its (perturbed) circle, and
            // behind a hull edge the finite triangle's apex is inside the hull.
            const uint32_t apex = triangle_vertex(n, back);
            if (triangle_is_finite(t) && apex != PLANAR_INFINITE_VERTEX && in_conflict(t, point(apex), counters)) {
                snprintf(message, capacity, "vertex %u is inside the circle of triangle %u", apex, t);
                return false;
            }
            if (!triangle_is_finite(t) && triangle_is_finite(n) && in_conflict(t, point(apex), counters)) {
                snprintf(message, capacity, "vertex %u is outside the hull edge of triangle %u", apex, t);
                return false;
            }
        }
        if (triangle_is_finite(t) &&
            orient(point(triangle_vertex(t, 0)), point(triangle_vertex(t, 1)), point(triangle_vertex(t, 2)), counters) <= 0) {
            snprintf(message, capacity, "triangle %u is not counter-clockwise", t);
            return false;
        }
    }
    return true;
}

} // namespace dbrg
