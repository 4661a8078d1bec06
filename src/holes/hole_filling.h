// Hole filling: closes the holes that region growing left where every candidate was invalid with ear
// triangles over each hole's own vertices, enlarging a hole that cannot be filled validly and trying again
// (paper §5), once a second growing pass has closed what Delaunay triangles can (RegionGrower::regrow_holes);
// then removes small handles.
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), section 5.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/pi.h"
#include "core/progress_span.h"
#include "core/vec3.h"
#include "grow/boundary_causes.h"
#include "grow/surface_geometry.h"
#include "holes/face_journal.h"
#include "surface/surface.h"

namespace dbrg {

struct SurfaceTopology;

// Where the passes of hole filling start in DBRG_STAGE_FILL_HOLES's progress, each ending where the next
// starts (about their shares of the time on large inputs): Delaunay triangles over the holes
// (RegionGrower::regrow_holes) from 0, ears, removing the islands that enlarging cut off, small handles,
// putting back the points passed over (PointInsertion), and the flips growing deferred
// (RegionGrower::flip_deferred) up to 1.
constexpr double FILL_PROGRESS_EARS = 0.05;
constexpr double FILL_PROGRESS_ISLANDS = 0.25;
constexpr double FILL_PROGRESS_HANDLES = 0.55;
constexpr double FILL_PROGRESS_POINTS = 0.93;
constexpr double FILL_PROGRESS_FLIPS = 0.97;
// Removing small handles goes in rounds, the first taking the first half of the pass's progress and each
// later one half of what is left. Where the parts of a round start in its share, each ending where the
// next starts: measuring the topology from 0, the spanning tree, the cotree, the short cycles, the cuts.
constexpr double HANDLES_PROGRESS_TREE = 0.3;
constexpr double HANDLES_PROGRESS_COTREE = 0.45;
constexpr double HANDLES_PROGRESS_CYCLES = 0.6;
constexpr double HANDLES_PROGRESS_CUTS = 0.8;

class HoleFiller {
public:
    // `points`: x, y, z triples by vertex id (the tetrahedralization's that S was grown over, or any).
    // `causes` says why growing left each boundary half-edge open; it is read at every step, so it may
    // change in between (regrowing adds faces with causes of their own).
    HoleFiller(const double* points, Surface& surface, const BoundaryCauses& causes, Context& context);

    // Loops through a vertex marked in `fixed` (NULL: none) are no holes: a fixed vertex's fan is complete
    // outside the points at hand (RegionGrower::grow_from), so such a loop is where they end.
    void keep_fixed(const uint8_t* fixed) { fixed_ = fixed; }

    // Counts the holes (is_hole) into context.stats.holes_found; `found` tells whether there are any.
    dbrg_status find_holes(bool& found);

    // Fills every hole of at most params.max_hole_edges edges that can be filled validly with ears,
    // leaving the open-surface boundaries (§4) alone, reporting to `ears`, then removes the islands that
    // enlarging holes cut off, reporting to `islands`. Fills the other hole fields of context.stats.
    dbrg_status fill_with_ears(const ProgressSpan& ears, const ProgressSpan& islands);

    // Topological noise removal: cuts components along short non-separating cycles and fills both
    // sides (small_handles.cpp). Reports to `progress`. Fills the handle fields of context.stats.
    dbrg_status remove_small_handles(const ProgressSpan& progress);

private:
    // How often a hole may be enlarged by removing its boundary triangles before it is left open. Where
    // growing folded the surface over a hole (a pleat: the faces around it overlap it, so every ear turns
    // over), the fold reaches two to four rings out: random points on a sphere leave 1 to 23 holes with
    // two enlargements and none at 100k-500k points with four (docs/benchmarks.md, "Holes in random samples").
    static constexpr uint32_t MAX_ENLARGEMENTS = 4;
    // Enlargements after this many must leave the hole one loop: one that cuts the surface apart (a band of
    // faces across a thin part removed) would fill each side on its own, cutting the part off.
    static constexpr uint32_t SPLITTING_ENLARGEMENTS = 2;
    static_assert(SPLITTING_ENLARGEMENTS <= MAX_ENLARGEMENTS, "the enlargements that may split are among all");

    // Components smaller than this that hole filling leaves apart from the rest are removed (as in growing).
    static constexpr uint32_t MIN_ISLAND_FACES = 16;

    // A hole that cannot be filled within theta_sliver is tried once more with this limit: at a sharp tip (a
    // horn, an ear) the only triangles over the hole's vertices fold more sharply than theta_sliver allows,
    // and a closed surface is worth a sharp fold there. Folding back completely is still refused.
    static constexpr double LAST_RESORT_FOLD_ANGLE = 175.0 * PI / 180.0;

    dbrg_status cut_handle(const uint32_t* cycle, size_t length, const ProgressSpan& progress, SurfaceTopology& before,
                           bool& removed);
    double length_between(uint32_t a, uint32_t b) const;

    bool is_open_boundary(uint32_t halfedge) const;
    // How many of the loop's boundary half-edges the open-surface test (§4) left.
    uint32_t count_open_edges(const Array<uint32_t>& loop) const;
    // A loop that the open-surface test made but that is this short is a hole all the same: a real border
    // is long, while a short loop marks a jump in sampling density (as in CAD tessellations).
    static constexpr uint32_t SHORT_LOOP_EDGES = 16;
    // Holes of at most this many edges that could not be filled are tried once more without a corner of at
    // most MAX_DROPPED_FAN faces (fill_without_a_corner): a vertex that growing pulled across the hole.
    static constexpr uint32_t MAX_CORNER_DROPPING_EDGES = 8;
    static constexpr uint32_t MAX_DROPPED_FAN = 4;
    // Whether the boundary loop `loop` (its half-edges in order) is a hole (§5) rather than a real border.
    // Each edge says why growing stopped there: its candidate was refused as too large (§4), or every
    // candidate was invalid (§3.2.1). A loop is one thing or the other, so its edges vote: at a real border
    // nearly every edge sees only large triangles beyond it, while where a closed surface comes closer to
    // itself than the sample spacing (a deep crease, a neck) a minority of a hole's edges see triangles
    // across the gap large enough for §4. A loop that §4 made is still a hole when it is short, or when
    // the opening it bounds is narrow next to the triangles around it (is_narrow): §4 compares each
    // candidate with the mean over the whole surface, which on an unevenly sampled closed object refuses
    // the ordinary triangles of its sparse parts.
    bool is_hole(const Array<uint32_t>& loop) const;
    // §4's test for the loop as a whole, against the triangles at hand: whether the opening's width (twice
    // its area over its perimeter: the radius of a round one, half the width of a long crack) is at most
    // boundary_factor times the mean circumradius of the faces along the loop.
    bool is_narrow(const Array<uint32_t>& loop) const;
    // The boundary half-edges of the loop through `start`, in order; false when it is longer than
    // max_hole_edges, or when it is a border (is_hole).
    bool collect_hole(uint32_t start, Array<uint32_t>& loop) const;
    uint32_t count_holes() const;
    bool through_fixed(const Array<uint32_t>& loop) const;
    // Fills the hole through the boundary half-edge from u to v within the sliver fold limit, and where
    // that fails once more at LAST_RESORT_FOLD_ANGLE; a failed attempt is undone. Enlarges the hole at
    // most `enlargements` times per attempt.
    dbrg_status fill_within_fold_limits(uint32_t u, uint32_t v, uint32_t enlargements, FaceJournal& journal,
                                        bool& filled);
    // Fills the hole through `start`, enlarging it (§5) at most `enlargements` more times.
    dbrg_status fill_hole(uint32_t start, uint32_t enlargements, FaceJournal& journal, bool& filled);
    // The hole of `edges` edges through the boundary half-edge from u to v, which ears and enlarging could
    // not fill: fills it without one of its corners of at most MAX_DROPPED_FAN faces, where that works.
    dbrg_status fill_without_a_corner(uint32_t u, uint32_t v, uint32_t edges, FaceJournal& journal, bool& filled);
    dbrg_status clip_ears(Array<uint32_t>& corners, FaceJournal& journal, bool& filled);
    bool ear_is_valid(uint32_t apex, uint32_t previous, uint32_t next, bool closes_hole) const;
    dbrg_status enlarge(const Array<uint32_t>& loop, FaceJournal& journal, Array<uint32_t>& new_starts);
    // Whether the boundary half-edges `starts` all lie on one loop of at most max_hole_edges edges (a longer
    // one is not filled anyway). False also when out of memory.
    bool on_one_loop(const Array<uint32_t>& starts) const;
    dbrg_status remove_and_record(uint32_t face, FaceJournal& journal);
    bool record_removed(uint32_t face, FaceJournal& journal) const;
    dbrg_status undo(FaceJournal& journal, size_t position);
    // Adds face (a, b, c) with FACE_* bits `flags`, recording it in `journal` when there is one.
    dbrg_status add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const uint8_t* causes, uint8_t flags,
                         FaceJournal* journal);
    Vec3 vertex_normal(uint32_t v) const;

    const PointTriples points_;
    Surface& surface_;
    const BoundaryCauses& causes_;
    Context& context_;
    double cos_fold_limit_ = 1;  // ears folding at this cosine or below are refused
    // Faces restored after a failed attempt get new ids; their open-surface edges stay marked here.
    Array<uint8_t> restored_open_;  // per half-edge of faces added by this stage, from added_base_ on
    uint32_t added_base_ = 0;
    const uint8_t* fixed_ = nullptr;
    bool filling_cut_ = false;  // the loops being filled were cut open by remove_small_handles: never borders
    uint32_t handles_removed_ = 0;
    uint32_t handle_triangles_removed_ = 0;
    uint32_t handle_triangles_added_ = 0;
};

} // namespace dbrg
