// Edge flips inside the grown surface S towards the smaller Delaunay balls (see edge_flips.h).
#include "grow/edge_flips.h"

#include <math.h>

#include <algorithm>

#include "core/status.h"
#include "grow/surface_geometry.h"
#include "grow/triangle_geometry.h"

namespace dbrg {
namespace {

// Progress is reported every this many faces or edges visited: at most a few milliseconds of visits.
constexpr size_t REPORT_VISITS = 1 << 12;

} // namespace

EdgeFlipper::EdgeFlipper(const Tetrahedralization& delaunay, Surface& surface, Context& context)
    : delaunay_(delaunay),
      surface_(surface),
      context_(context),
      cos_sliver_(cos(context.params.sliver_angle)),
      deferred_(context.memory),
      revisit_(context.memory) {}

dbrg_status EdgeFlipper::flip_all(double& radius_sum, const ProgressSpan& progress) {
    // Faces the flips add are not visited from here: their outer edges are visited again by visit(), and
    // their inner edge stays, as flipping it back would make the balls larger again.
    const uint32_t faces = surface_.face_count();
    for (uint32_t f = 0; f < faces; ++f) {
        DBRG_PROPAGATE(progress.report_at(f, faces, REPORT_VISITS));
        for (uint32_t h = 3 * f; h < 3 * f + 3 && !surface_.face_removed(f); ++h) {
            const uint32_t twin = surface_.twin(h);
            if (twin != NO_HALFEDGE && h < twin) DBRG_PROPAGATE(visit(h, radius_sum));
        }
    }
    revisit_.release();
    faces_after_flip_all_ = surface_.face_count();
    return DBRG_OK;
}

dbrg_status EdgeFlipper::flip_deferred(const ProgressSpan& progress) {
    // No sum of radii to keep from here on: the open-surface test is done with.
    double radius_sum = 0;
    Array<uint32_t> edges(context_.memory);
    edges.swap(deferred_);
    // Progress counts the listed edges, then the faces.
    const uint32_t faces = surface_.face_count();
    const size_t items = edges.size() + (faces - faces_after_flip_all_);
    size_t item = 0;
    const auto report_item = [&]() { return progress.report_at(item++, items, REPORT_VISITS); };
    for (uint32_t h : edges) {
        DBRG_PROPAGATE(report_item());
        DBRG_PROPAGATE(visit(h, radius_sum));
    }
    // The edges of the faces added since flip_all, once each: the rims of the holes that filling closed
    // (boundary edges while growing, so never deferred), and deferred edges whose faces filling removed
    // and put back under new ids (their listed ids are stale).
    for (uint32_t f = faces_after_flip_all_; f < faces; ++f) {
        DBRG_PROPAGATE(report_item());
        for (uint32_t h = 3 * f; h < 3 * f + 3 && !surface_.face_removed(f); ++h) {
            const uint32_t twin = surface_.twin(h);
            if (twin != NO_HALFEDGE && (h < twin || Surface::face_of(twin) < faces_after_flip_all_)) {
                DBRG_PROPAGATE(visit(h, radius_sum));
            }
        }
    }
    // Edges deferred again are on a boundary that nothing closes any more.
    deferred_.release();
    revisit_.release();
    return DBRG_OK;
}

// Each flip replaces two faces by two whose larger Delaunay ball is smaller than the larger of the two it
// removes, so the radii of S, sorted, decrease, and the flips and the visits they cause come to an end.
dbrg_status EdgeFlipper::visit(uint32_t halfedge, double& radius_sum) {
    revisit_.clear();
    if (!revisit_.push_back(halfedge)) return context_.fail_out_of_memory();
    while (!revisit_.empty()) {
        const uint32_t h = revisit_.back();
        revisit_.pop_back();
        if (surface_.face_removed(Surface::face_of(h))) continue;  // flipped since it was listed
        uint32_t tet = NO_TET;
        const Decision decision = decide(h, tet);
        if (decision == Decision::defer && !deferred_.push_back(h)) return context_.fail_out_of_memory();
        if (decision != Decision::flip) continue;
        // The faces across the four outer edges stay; their dihedral angles with the pair change.
        const uint32_t twin = surface_.twin(h);
        for (uint32_t outer : {Surface::prev(h), Surface::next(h), Surface::next(twin), Surface::prev(twin)}) {
            if (!revisit_.push_back(surface_.twin(outer))) return context_.fail_out_of_memory();
        }
        DBRG_PROPAGATE(flip(h, tet, radius_sum));
    }
    return DBRG_OK;
}

EdgeFlipper::Decision EdgeFlipper::decide(uint32_t halfedge, uint32_t& tet) const {
    const uint32_t twin = surface_.twin(halfedge);
    if (twin == NO_HALFEDGE) return Decision::keep;
    const uint32_t face = Surface::face_of(halfedge), other = Surface::face_of(twin);
    const uint32_t a = surface_.origin(halfedge), b = surface_.target(halfedge);
    const uint32_t c = surface_.target(Surface::next(halfedge)), d = surface_.target(Surface::next(twin));
    // Cheapest first: most pairs are the Delaunay pair of their four corners already.
    const auto holds = [&](uint32_t x, uint32_t y, uint32_t z, uint32_t w) {
        return in_diametral_ball(delaunay_.point(x), delaunay_.point(y), delaunay_.point(z), delaunay_.point(w));
    };
    if (c == d || !(holds(a, b, c, d) || holds(b, a, d, c)) || holds(c, a, d, b) || holds(d, b, c, a)) {
        return Decision::keep;
    }
    // Either face may be an ear of hole filling (no tetrahedron): walk from the other one then, so that
    // both half-edges of an edge get the same decision.
    tet = surface_.face_tet(face) != NO_TET ? tet_with_corners(surface_.face_tet(face), a, b, c, d)
                                            : tet_with_corners(surface_.face_tet(other), b, a, d, c);
    if (tet == NO_TET) return Decision::keep;
    for (uint32_t corner : {a, b, c, d}) {
        if (surface_.is_boundary_vertex(corner) || surface_.is_pinched(corner)) return Decision::defer;
    }
    if (surface_.find_halfedge(c, d) != NO_HALFEDGE || surface_.find_halfedge(d, c) != NO_HALFEDGE) return Decision::keep;
    const double now = fmax(ball_radius(a, b, c, tet), ball_radius(b, a, d, tet));
    if (!(fmax(ball_radius(c, a, d, tet), ball_radius(d, b, c, tet)) < now)) return Decision::keep;
    // The fold test of §3.2.1 for the new faces (c, a, d) and (d, b, c), and no loss of smoothness: the sum
    // of the cosines of the dihedral angles at the pair's five edges (its inner edge and the outer edges
    // c->a, b->c of `face` and a->d, d->b of `other`) must not drop.
    const Vec3 old1 = face_normal(delaunay_, surface_, face), old2 = face_normal(delaunay_, surface_, other);
    const Vec3 new1 = triangle_normal(delaunay_.point(c), delaunay_.point(a), delaunay_.point(d));
    const Vec3 new2 = triangle_normal(delaunay_.point(d), delaunay_.point(b), delaunay_.point(c));
    double old_smoothness = dihedral_cosine(old1, old2), new_smoothness = dihedral_cosine(new1, new2);
    bool too_sharp = new_smoothness <= cos_sliver_;
    const uint32_t outer[4] = {Surface::prev(halfedge), Surface::next(halfedge), Surface::next(twin), Surface::prev(twin)};
    for (uint32_t k = 0; k < 4; ++k) {
        const Vec3 across = face_normal(delaunay_, surface_, Surface::face_of(surface_.twin(outer[k])));
        // c->a lies on new face (c, a, d), b->c on (d, b, c), a->d on (c, a, d) and d->b on (d, b, c).
        const double after = dihedral_cosine(k % 2 == 0 ? new1 : new2, across);
        old_smoothness += dihedral_cosine(k < 2 ? old1 : old2, across);
        new_smoothness += after;
        too_sharp = too_sharp || after <= cos_sliver_;
    }
    return too_sharp || new_smoothness < old_smoothness ? Decision::keep : Decision::flip;
}

dbrg_status EdgeFlipper::flip(uint32_t halfedge, uint32_t tet, double& radius_sum) {
    const uint32_t face = Surface::face_of(halfedge), other = Surface::face_of(surface_.twin(halfedge));
    const uint32_t a = surface_.origin(halfedge), b = surface_.target(halfedge);
    const uint32_t c = surface_.target(Surface::next(halfedge)), d = surface_.target(Surface::next(surface_.twin(halfedge)));
    radius_sum -= face_radius(delaunay_, surface_, face) + face_radius(delaunay_, surface_, other);
    // The new pair covers what the old one did: each is as invented as either face it replaces.
    const uint8_t flags = surface_.face_flags(face) | surface_.face_flags(other);
    if (!surface_.remove_face(face) || !surface_.remove_face(other)) return context_.fail_out_of_memory();
    const uint32_t added[2][3] = {{c, a, d}, {d, b, c}};
    for (const auto& corners : added) {
        // Valid: the two removed faces left a hole of four edges between closed fans, and c-d is no edge.
        const FaceCheck check = surface_.check_face(corners[0], corners[1], corners[2]);
        if (check.verdict != FaceCheck::valid || check.pinches > 0) {
            return context_.fail(DBRG_ERR_INTERNAL, "an edge flip left a face that does not fit");
        }
        const uint32_t f = surface_.add_face(corners[0], corners[1], corners[2], tet, check);
        if (f == NO_FACE) return context_.fail_out_of_memory();
        surface_.set_face_flags(f, flags);
        radius_sum += face_radius(delaunay_, surface_, f);
        if (observer_) DBRG_PROPAGATE(observer_(observer_user_, surface_, points_reached(delaunay_, surface_)));
    }
    ++flips_;
    return DBRG_OK;
}

// The tetrahedron with corners a, b, c, d, if it is t or t's neighbour across its face (a, b, c).
uint32_t EdgeFlipper::tet_with_corners(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t d) const {
    if (t == NO_TET) return NO_TET;
    const uint32_t lf = fourth_corner(t, a, b, c);
    if (delaunay_.tet_vertex(t, lf) == d) return t;
    const uint32_t neighbour = delaunay_.tet_adjacent(t, lf);
    return delaunay_.tet_vertex(neighbour, delaunay_.tet_adjacent_face(t, lf)) == d ? neighbour : NO_TET;
}

// The local index of the corner of tetrahedron t other than u, v and w (three of its corners).
uint32_t EdgeFlipper::fourth_corner(uint32_t t, uint32_t u, uint32_t v, uint32_t w) const {
    uint32_t lv = 0;
    while (lv < 3) {
        const uint32_t x = delaunay_.tet_vertex(t, lv);
        if (x != u && x != v && x != w) break;
        ++lv;
    }
    return lv;
}

// Radius of the Delaunay ball of the Delaunay triangle (u, v, w), a face of tetrahedron t: the smallest
// ball through u, v, w with no point inside. The balls through them that hold neither fourth corner of the
// two tetrahedra sharing the triangle are the empty ones, so it is the triangle's diametral ball when that
// holds neither, otherwise the circumscribed ball of the tetrahedron whose fourth corner it holds. Corners
// are taken in id order, so that a triangle or tetrahedron gets the same radius whichever way it is reached.
double EdgeFlipper::ball_radius(uint32_t u, uint32_t v, uint32_t w, uint32_t t) const {
    const uint32_t lf = fourth_corner(t, u, v, w);
    const uint32_t neighbour = delaunay_.tet_adjacent(t, lf);
    uint32_t fourth[2] = {delaunay_.tet_vertex(t, lf), delaunay_.tet_vertex(neighbour, delaunay_.tet_adjacent_face(t, lf))};
    uint32_t corners[4] = {u, v, w, 0};
    std::sort(corners, corners + 3);
    std::sort(fourth, fourth + 2);
    for (uint32_t d : fourth) {
        if (d == INFINITE_VERTEX) continue;  // sorted last
        if (!in_diametral_ball(delaunay_.point(corners[0]), delaunay_.point(corners[1]), delaunay_.point(corners[2]),
                               delaunay_.point(d))) {
            continue;
        }
        corners[3] = d;
        std::sort(corners, corners + 4);
        return tet_circumradius(delaunay_.point(corners[0]), delaunay_.point(corners[1]), delaunay_.point(corners[2]),
                                delaunay_.point(corners[3]));
    }
    return circumradius(delaunay_.point(corners[0]), delaunay_.point(corners[1]), delaunay_.point(corners[2]));
}

} // namespace dbrg
