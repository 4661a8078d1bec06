// Planar growing: region growing for a flat input. Grows an oriented manifold region S over the triangles
// of the points' 2-D Delaunay triangulation, smallest first, with the border rule of the 3-D grower: a
// triangle whose radius exceeds boundary_factor times the mean radius r_a of S's faces (over all of S or
// around the edge, as params.boundary_mean says) spans an opening of the region and is left out. A triangle's
// radius here is that of the smallest circle around it (its circumradius unless it is obtuse), so that the
// slivers along a sampled outline are kept (see triangle_radius).
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface reconstruction
// from unorganized points", Computer-Aided Design 37 (2005), sections 3 and 4, in one plane: every
// candidate lies in the plane of its neighbours, so the dihedral-angle tests and the smoothness order of
// the 3-D grower have nothing to decide, and the triangles, all Delaunay already, need no flips.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "grow/candidate_queue.h"
#include "planar/planar_delaunay.h"
#include "surface/surface.h"

namespace dbrg {

class PlanarGrower {
public:
    // S's faces keep the triangulation's triangle ids in Surface::face_tet.
    PlanarGrower(const PlanarTriangulation& triangulation, Surface& surface, Context& context);

    // Grows S from a median-sized triangle, then from further seeds (in order of radius, each passing the
    // border rule against the triangles grown so far) while unused points can start a component of their own,
    // up to params.max_components. Vertices still pinched when a component stops growing keep their largest
    // fan (Surface::remove_pinches); components of fewer than 16 faces beside a larger one are removed. Every
    // face is counter-clockwise seen from the plane normal whose largest component is positive. Reports
    // DBRG_STAGE_GROW progress to `progress`; fills candidates_evaluated, rejected_boundary,
    // pinch_faces_removed and components of context.stats.
    dbrg_status grow(const ProgressSpan& progress);

private:
    dbrg_status grow_component(const ProgressSpan& progress);
    dbrg_status drain_queue(const ProgressSpan& progress);
    bool passes_boundary_test(const Candidate& candidate) const;
    double triangle_radius(uint32_t t) const;
    dbrg_status propose(uint32_t halfedge);
    dbrg_status add_triangle(uint32_t t, const FaceCheck& check);
    dbrg_status postpone(Candidate candidate);
    dbrg_status resolve_pinches();

    const PlanarTriangulation& triangulation_;
    Surface& surface_;
    Context& context_;
    CandidateQueue queue_;
    Array<Candidate> postponed_;  // set aside once, retried when the queue runs dry
    double radius_sum_ = 0;       // triangle_radius over the faces of S, for the global mean r_a
};

} // namespace dbrg
