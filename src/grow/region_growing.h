// Region growing: extracts an oriented manifold surface S from the Delaunay tetrahedralization by
// attaching, one at a time, the most credible candidate triangle of S's boundary (paper §3 and §4).
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), sections 3 and 4.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "core/vec3.h"
#include "delaunay/tetrahedralization.h"
#include "grow/boundary_causes.h"
#include "grow/candidate_queue.h"
#include "grow/edge_flips.h"
#include "surface/surface.h"

namespace dbrg {

// Where the passes of RegionGrower::grow() start in DBRG_STAGE_GROW's progress, each ending where the next
// starts (about their shares of the time on large inputs): growing S from 0, removing islands, flipping edges.
constexpr double GROW_PROGRESS_ISLANDS = 0.92;
constexpr double GROW_PROGRESS_FLIPS = 0.94;
// Where regrow_holes's growing starts in its share of progress, after looking for the holes' edges.
constexpr double REGROW_PROGRESS_GROWING = 0.5;

class RegionGrower {
public:
    RegionGrower(const Tetrahedralization& delaunay, Surface& surface, Context& context);

    // Grows S from the highest point, then from further seeds while unused points can start a
    // component of their own (up to params.max_components), removes islands, then flips edges inside S to
    // the smaller Delaunay balls (EdgeFlipper::flip_all). Reports DBRG_STAGE_GROW progress, growing S as
    // the share of the faces of a closed surface through all points that it has. Fills the growing fields
    // of context.stats.
    dbrg_status grow();

    // Grows S from a given partial surface instead of seeds of its own: `seed_count` faces, 3 corners each
    // in `seeds` (counter-clockwise, consistently oriented), are put into S first (those that do not fit
    // it as a manifold are skipped), then growing runs from their boundary edges and the edges are flipped,
    // as in grow(). No new face uses a vertex marked in `fixed` (NULL: none): a fixed vertex's fan is
    // complete outside these points. Adds nothing where the seeds leave no front. Reports DBRG_STAGE_GROW
    // progress.
    dbrg_status grow_from(const uint32_t* seeds, size_t seed_count, const uint8_t* fixed);

    // Gives every boundary edge left unresolved (a hole) a fresh pass over all its candidates: S has
    // changed around it since it was last examined. The first step of hole filling (§5): Delaunay
    // triangles before ears. Here the open-surface test (§4) weighs each candidate against the faces
    // around its edge's ends rather than the whole surface: inside a hole, the triangles at hand set the
    // scale, while the mean over the surface refuses the ordinary triangles of an unevenly sampled closed
    // object's sparse parts. The faces it adds are marked FACE_FILLED. Adds context.stats.hole_triangles_delaunay.
    // Reports to `progress`.
    dbrg_status regrow_holes(const ProgressSpan& progress);

    // Flips the edges that growing's flips passed over because a corner was on the boundary of S, and
    // those around the faces added since: the last step of hole filling, once the holes are closed.
    dbrg_status flip_deferred(const ProgressSpan& progress) { return flipper_.flip_deferred(progress); }
    const EdgeFlipper& edge_flips() const { return flipper_; }

    // Called after every face added to S, flips included (see StepObserver).
    void observe_steps(StepObserver observer, void* user) {
        observer_ = observer;
        observer_user_ = user;
        flipper_.observe_steps(observer, user);
    }

    // Why each boundary half-edge is on the boundary, for hole filling; faces added by anything but this
    // grower count as unresolved.
    const BoundaryCauses& boundary_causes() const { return causes_; }

private:
    // The examinations' verdict on a candidate; FaceCheck::Verdict is the topological part of it.
    enum class CandidateVerdict { valid, pinch, edge_nonmanifold, orientation, bowtie, dihedral, fixed };

    dbrg_status start_surface();
    dbrg_status grow_component(const ProgressSpan& progress);
    dbrg_status drain_queue(const ProgressSpan& progress);
    dbrg_status report_grown(const ProgressSpan& progress) const;
    double smallest_seed(uint32_t vertex, uint32_t corners[3], uint32_t& tet) const;
    bool find_seed(uint32_t vertex, uint32_t corners[3], uint32_t& tet) const;
    bool measure_typical_seed();
    uint32_t tet_with_face(uint32_t a, uint32_t b, uint32_t c) const;
    bool select_candidate(uint32_t halfedge, const CandidateRank* after, Candidate& out) const;
    CandidateVerdict examine(const Candidate& candidate, double& smoothness, FaceCheck& check) const;
    CandidateVerdict examine_again(const Candidate& candidate, double& smoothness, FaceCheck& check) const;
    bool passes_boundary_test(const Candidate& candidate) const;
    CandidateRank rank(const Candidate& candidate) const;
    dbrg_status propose(uint32_t halfedge, const CandidateRank* after);
    // `check`, when given, is what surface_.check_face(a, b, c) returned with the surface as it is now.
    dbrg_status add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const FaceCheck* check = nullptr);
    dbrg_status postpone(Candidate candidate);
    bool enqueue(const Candidate& candidate);
    void release_queues();
    dbrg_status reject(const Candidate& candidate, CandidateVerdict verdict);
    dbrg_status report_step() const;
    dbrg_status try_seed(uint32_t vertex, Array<uint32_t>& removed, const ProgressSpan& progress);
    dbrg_status resolve_pinches(Array<uint32_t>& removed);
    dbrg_status remove_islands(const ProgressSpan& progress);

    const Tetrahedralization& delaunay_;
    Surface& surface_;
    Context& context_;
    double cos_sliver_;

    CandidateQueue queue_;
    Array<Candidate> postponed_;     // set aside once, retried when the queue runs dry
    BoundaryCauses causes_;          // of the half-edges of the faces growing added
    uint32_t components_ = 0;        // seeds that grew into a surface of their own
    StepObserver observer_ = nullptr;
    void* observer_user_ = nullptr;
    double radius_sum_ = 0;          // over the faces of S, for the global mean r_a
    double typical_seed_ = HUGE_VAL; // r_a before S has faces: the median seed radius of a sample of points
    // What examine answered for the last candidates proposed, and S's edit count then. About half of the
    // candidates taken from the queue were proposed for the face added just before, with S as it is.
    struct Examined {
        uint32_t halfedge = NO_HALFEDGE, apex = 0, edits = 0;
        CandidateVerdict verdict = CandidateVerdict::valid;
        double smoothness = 0;
        FaceCheck check;
    };
    static constexpr uint32_t EXAMINED_KEPT = 4;  // the proposals of one face and a rejection's
    Examined examined_[EXAMINED_KEPT];
    uint32_t examined_next_ = 0;
    bool local_boundary_test_ = false;  // regrow_holes: §4 against the faces around the edge
    uint8_t new_face_flags_ = 0;        // FACE_* bits of the faces added: FACE_FILLED in regrow_holes
    const uint8_t* fixed_ = nullptr;    // grow_from: vertices no new face may use
    EdgeFlipper flipper_;
};

} // namespace dbrg
