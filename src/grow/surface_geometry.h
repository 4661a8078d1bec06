// The geometry of a face of the surface S, from its points: those of the tetrahedralization it was grown
// over, or any other array of them with a point(v) (PointTriples). Recomputed rather than stored: cheaper
// in memory, and exact copies of what growing computed. And the share of the points S has reached.
#pragma once

#include <stdint.h>

#include "core/vec3.h"
#include "delaunay/tetrahedralization.h"
#include "grow/triangle_geometry.h"
#include "surface/surface.h"

namespace dbrg {

// Points by vertex id from x, y, z triples, for surfaces with no tetrahedralization behind them (an
// assembled tiled mesh).
struct PointTriples {
    const double* xyz;
    const double* point(uint32_t v) const { return xyz + 3 * size_t(v); }
};

template <class Points>
Vec3 face_normal(const Points& points, const Surface& surface, uint32_t f) {
    return triangle_normal(points.point(surface.corner(f, 0)), points.point(surface.corner(f, 1)),
                           points.point(surface.corner(f, 2)));
}

template <class Points>
double face_radius(const Points& points, const Surface& surface, uint32_t f) {
    return circumradius(points.point(surface.corner(f, 0)), points.point(surface.corner(f, 1)),
                        points.point(surface.corner(f, 2)));
}

// The mean of radius(f) over the faces around both ends of `halfedge` (of a pinched end, its first fan's):
// the local scale the open-surface test (§4) can weigh a candidate against.
template <class FaceRadius>
double mean_radius_at_ends(const Surface& surface, uint32_t halfedge, const FaceRadius& radius) {
    double sum = 0;
    uint32_t count = 0;
    for (uint32_t end : {surface.origin(halfedge), surface.target(halfedge)}) {
        surface.walk_fan(surface.vertex_halfedge(end), [&](uint32_t h) {
            sum += radius(Surface::face_of(h));
            ++count;
        });
    }
    return sum / count;
}

// The share of the points S has now (pinch removal may give some back): what step observers are told.
inline double points_reached(const Tetrahedralization& delaunay, const Surface& surface) {
    return double(surface.used_vertex_count()) / delaunay.vertex_count();
}

} // namespace dbrg
