// Edge flips inside the grown surface S towards the smaller Delaunay balls. Where S crosses a Delaunay
// tetrahedron through two of its faces, the other two span the same four outer edges. The candidate
// order of growing sees one edge at a time, and where the four corners are nearly on a circle (a flat
// sliver: both diagonals of a quadrilateral are Delaunay edges) its choice between the two pairs is close
// to arbitrary. The flips take the pair with the smaller Delaunay balls instead (the size advancing-front
// reconstruction ranks candidates by): mostly the Delaunay diagonal of the quadrilateral.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "delaunay/tetrahedralization.h"
#include "surface/surface.h"

namespace dbrg {

// Called after every face added to S with the share of points S has reached (tests check S after every
// step; the pipeline takes snapshots). A status other than DBRG_OK stops the stage with it.
using StepObserver = dbrg_status (*)(void* user, const Surface& surface, double points_reached);

class EdgeFlipper {
public:
    EdgeFlipper(const Tetrahedralization& delaunay, Surface& surface, Context& context);

    void observe_steps(StepObserver observer, void* user) {
        observer_ = observer;
        observer_user_ = user;
    }

    // Visits every interior edge of S once, flipping where decide() says so and then visiting the four
    // outer edges of the flipped pair again. Edges with a corner on the boundary of S are remembered for
    // flip_deferred. `radius_sum`, the sum of the circumradii of S's faces, follows the flips. Reports
    // to `progress`.
    dbrg_status flip_all(double& radius_sum, const ProgressSpan& progress);

    // Visits the remembered edges again, and the edges of every face added since flip_all: for after hole
    // filling, which closes the boundary those edges waited on and changes what is around them. Reports
    // to `progress`.
    dbrg_status flip_deferred(const ProgressSpan& progress);

    enum class Decision { keep, defer, flip };
    // What a visit would do with the edge of `halfedge` now: flip it to the other two faces of tetrahedron
    // `tet` when that shrinks the larger of the two Delaunay balls, folds no sharper than theta_sliver and
    // loses no smoothness; defer it when that is undecided only because a corner is on the boundary of S
    // (flipping there could change the topology); otherwise keep it.
    Decision decide(uint32_t halfedge, uint32_t& tet) const;

    uint32_t flip_count() const { return flips_; }

private:
    dbrg_status visit(uint32_t halfedge, double& radius_sum);
    dbrg_status flip(uint32_t halfedge, uint32_t tet, double& radius_sum);
    uint32_t tet_with_corners(uint32_t tet, uint32_t a, uint32_t b, uint32_t c, uint32_t d) const;
    uint32_t fourth_corner(uint32_t tet, uint32_t u, uint32_t v, uint32_t w) const;
    double ball_radius(uint32_t u, uint32_t v, uint32_t w, uint32_t tet) const;

    const Tetrahedralization& delaunay_;
    Surface& surface_;
    Context& context_;
    double cos_sliver_;
    Array<uint32_t> deferred_;  // a half-edge of each edge deferred
    Array<uint32_t> revisit_;   // half-edges whose neighbourhood a flip changed, to be visited again
    uint32_t flips_ = 0;
    uint32_t faces_after_flip_all_ = 0;  // faces from this id on were added later (hole filling)
    StepObserver observer_ = nullptr;
    void* observer_user_ = nullptr;
};

} // namespace dbrg
