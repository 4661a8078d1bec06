// Planar growing: region growing over a 2-D Delaunay triangulation with the border rule (see planar_growing.h).
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface reconstruction
// from unorganized points", Computer-Aided Design 37 (2005), sections 3 and 4.
#include "planar/planar_growing.h"

#include <math.h>

#include <algorithm>

#include "core/status.h"
#include "grow/surface_geometry.h"
#include "grow/triangle_geometry.h"

namespace dbrg {
namespace {

// Growing reports its progress every this many candidates taken from the queue.
const uint32_t REPORT_CANDIDATES = 1024;

// As in the 3-D grower: a later seed must grow this many faces to count as an object of its own; fewer are
// stray points, removed at the end if they stay apart.
const uint32_t MIN_SEEDED_COMPONENT_FACES = 16;

// Every candidate continues its neighbours flat: the 3-D grower's smoothness order has nothing to rank, and
// the queue orders by radius alone.
const double FLAT = 1.0;

struct SeedTriangle {
    float radius;  // triangle_radius, compared at float precision as the 3-D candidates are: congruent triangles tie
    uint32_t triangle;
};

} // namespace

PlanarGrower::PlanarGrower(const PlanarTriangulation& triangulation, Surface& surface, Context& context)
    : triangulation_(triangulation), surface_(surface), context_(context), queue_(context.memory), postponed_(context.memory) {}

// The radius of the smallest circle around the triangle: its circumradius, or half its longest side when
// that side's angle is obtuse. A sliver between three neighbouring samples of an outline has a circumradius
// many times the spacing although it spans no more than two of their gaps; measured by its circumradius the
// border rule would cut it from every jittered outline (the planar tests lose 2 to 5 % of the reference's
// triangles so, most of them on the outline). An opening's triangles still measure at least half its width.
double PlanarGrower::triangle_radius(uint32_t t) const {
    const double* corners[3] = {triangulation_.point(triangulation_.triangle_vertex(t, 0)),
                                triangulation_.point(triangulation_.triangle_vertex(t, 1)),
                                triangulation_.point(triangulation_.triangle_vertex(t, 2))};
    double side[3];  // squared, opposite each corner
    for (int i = 0; i < 3; ++i) side[i] = squared_length(load_vec3(corners[(i + 1) % 3]) - load_vec3(corners[(i + 2) % 3]));
    const int longest = side[0] >= side[1] && side[0] >= side[2] ? 0 : (side[1] >= side[2] ? 1 : 2);
    if (side[longest] >= side[(longest + 1) % 3] + side[(longest + 2) % 3]) return 0.5 * sqrt(side[longest]);
    return circumradius(corners[0], corners[1], corners[2]);
}

dbrg_status PlanarGrower::grow(const ProgressSpan& progress) {
    DBRG_PROPAGATE(progress.report(0, 1));
    const uint32_t triangles = triangulation_.finite_triangle_count();
    if (!surface_.reset(triangulation_.vertex_count()) || !surface_.reserve_faces(triangles)) {
        return context_.fail_out_of_memory();
    }
    // Seeds: every finite triangle in order of radius (ties to the smaller slot, a function of the
    // coordinates). The first is the median one, a typical triangle of the sampling: the smallest may be far
    // below the spacing, and the border rule measured against it alone would stop growing at once.
    Array<SeedTriangle> seeds(context_.memory);
    if (!seeds.reserve(triangles)) return context_.fail_out_of_memory();
    for (uint32_t t = 0; t < triangulation_.slot_count(); ++t) {
        if (triangulation_.triangle_is_finite(t)) seeds.push_back(SeedTriangle{static_cast<float>(triangle_radius(t)), t});
    }
    std::sort(seeds.begin(), seeds.end(), [](const SeedTriangle& a, const SeedTriangle& b) {
        return a.radius != b.radius ? a.radius < b.radius : a.triangle < b.triangle;
    });
    const size_t median = seeds.size() / 2;
    std::rotate(seeds.begin(), seeds.begin() + median, seeds.begin() + median + 1);

    const double factor = context_.params.boundary_factor;
    uint32_t components = 0;
    for (const SeedTriangle& seed : seeds) {
        if (components >= context_.params.max_components) break;
        const uint32_t t = seed.triangle;
        bool unused = true;
        for (uint32_t lv = 0; lv < 3; ++lv) unused = unused && !surface_.is_used(triangulation_.triangle_vertex(t, lv));
        if (!unused) continue;
        const uint32_t faces_before = surface_.live_face_count();
        if (factor > 0 && faces_before > 0 && seed.radius > factor * radius_sum_ / faces_before) continue;
        DBRG_PROPAGATE(add_triangle(t, surface_.check_face(triangulation_.triangle_vertex(t, 0),
                                                           triangulation_.triangle_vertex(t, 1),
                                                           triangulation_.triangle_vertex(t, 2))));
        DBRG_PROPAGATE(grow_component(progress));
        DBRG_PROPAGATE(resolve_pinches());
        if (components == 0 || surface_.live_face_count() >= faces_before + MIN_SEEDED_COMPONENT_FACES) ++components;
    }
    seeds.release();
    queue_.release();
    postponed_.release();
    Array<uint32_t> removed(context_.memory);
    if (!surface_.remove_small_components(MIN_SEEDED_COMPONENT_FACES, removed)) return context_.fail_out_of_memory();
    context_.stats.pinch_faces_removed += static_cast<uint32_t>(removed.size());
    context_.stats.components = components;  // the output stage recounts
    return progress.report(1, 1);
}

dbrg_status PlanarGrower::grow_component(const ProgressSpan& progress) {
    // Postponed candidates get one more chance each time the queue runs dry.
    for (;;) {
        DBRG_PROPAGATE(drain_queue(progress));
        if (postponed_.empty()) return DBRG_OK;
        for (const Candidate& c : postponed_) {
            if (!queue_.push(c)) return context_.fail_out_of_memory();
        }
        postponed_.clear();
    }
}

dbrg_status PlanarGrower::drain_queue(const ProgressSpan& progress) {
    dbrg_stats& stats = context_.stats;
    const uint32_t triangles = triangulation_.finite_triangle_count();
    uint32_t taken = 0;
    while (!queue_.empty()) {
        if (++taken % REPORT_CANDIDATES == 0) DBRG_PROPAGATE(progress.report(surface_.live_face_count(), triangles));
        const Candidate c = queue_.pop();
        if (!surface_.is_boundary(c.halfedge)) continue;  // covered since it was queued
        ++stats.candidates_evaluated;
        const uint32_t t = c.tet;
        const FaceCheck check = surface_.check_face(triangulation_.triangle_vertex(t, 0), triangulation_.triangle_vertex(t, 1),
                                                    triangulation_.triangle_vertex(t, 2));
        // Triangles of one planar triangulation, all counter-clockwise, can give an edge no third face and no
        // opposite orientation, and a vertex inside S has every triangle around it in S already: only pinches,
        // where two fronts meet at a vertex, need a verdict.
        if (check.verdict != FaceCheck::valid) continue;
        // Touching S at a vertex alone pinches it: needed where two fronts meet, but only once nothing better is left.
        if (check.pinches > 0 && !c.postponed) {
            DBRG_PROPAGATE(postpone(c));
            continue;
        }
        if (!passes_boundary_test(c)) {
            if (!c.postponed) {
                DBRG_PROPAGATE(postpone(c));
            } else {
                ++stats.rejected_boundary;
            }
            continue;
        }
        DBRG_PROPAGATE(add_triangle(t, check));
    }
    return DBRG_OK;
}

dbrg_status PlanarGrower::postpone(Candidate c) {
    c.postponed = 1;
    return postponed_.push_back(c) ? DBRG_OK : context_.fail_out_of_memory();
}

// §4: a candidate much larger than the triangles of S spans an opening of the region.
bool PlanarGrower::passes_boundary_test(const Candidate& c) const {
    const double factor = context_.params.boundary_factor;
    if (factor == 0) return true;
    const auto radius = [&](uint32_t f) { return triangle_radius(surface_.face_tet(f)); };
    const double mean = context_.params.boundary_mean == DBRG_BOUNDARY_MEAN_GLOBAL
                            ? radius_sum_ / surface_.live_face_count()
                            : mean_radius_at_ends(surface_, c.halfedge, radius);
    return c.radius <= factor * mean;
}


// Queues the triangle across boundary half-edge `halfedge` of S, if it is finite: S's faces keep the corner
// order of their triangles, so half-edge 3 f + i runs opposite corner i + 2 of triangle face_tet(f).
dbrg_status PlanarGrower::propose(uint32_t halfedge) {
    const uint32_t face = Surface::face_of(halfedge);
    const uint32_t across = triangulation_.triangle_adjacent(surface_.face_tet(face), (halfedge % 3 + 2) % 3);
    if (!triangulation_.triangle_is_finite(across)) return DBRG_OK;  // a hull edge
    uint32_t apex = PLANAR_INFINITE_VERTEX;
    for (uint32_t lv = 0; lv < 3; ++lv) {
        const uint32_t v = triangulation_.triangle_vertex(across, lv);
        if (v != surface_.origin(halfedge) && v != surface_.target(halfedge)) apex = v;
    }
    Candidate c;
    c.set_smoothness(FLAT, 0);  // every candidate alike: the order is the radius's
    c.radius = triangle_radius(across);
    c.halfedge = halfedge;
    c.apex = apex;
    c.tet = across;
    c.postponed = 0;
    return queue_.push(c) ? DBRG_OK : context_.fail_out_of_memory();
}

// Inserts triangle t into S and queues the triangles across its new boundary edges.
dbrg_status PlanarGrower::add_triangle(uint32_t t, const FaceCheck& check) {
    const uint32_t f = surface_.add_face(triangulation_.triangle_vertex(t, 0), triangulation_.triangle_vertex(t, 1),
                                         triangulation_.triangle_vertex(t, 2), t, check);
    if (f == NO_FACE) return context_.fail_out_of_memory();
    radius_sum_ += triangle_radius(t);
    for (uint32_t h = 3 * f; h < 3 * f + 3; ++h) {
        if (surface_.is_boundary(h)) DBRG_PROPAGATE(propose(h));
    }
    return DBRG_OK;
}

// Vertices still pinched when a component stops growing keep their largest fan.
dbrg_status PlanarGrower::resolve_pinches() {
    Array<uint32_t> removed(context_.memory);
    if (!surface_.remove_pinches(removed)) return context_.fail_out_of_memory();
    for (uint32_t f : removed) radius_sum_ -= triangle_radius(surface_.face_tet(f));
    context_.stats.pinch_faces_removed += static_cast<uint32_t>(removed.size());
    return DBRG_OK;
}

} // namespace dbrg
