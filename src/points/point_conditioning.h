// Point conditioning: turns the caller's finite points into the distinct, well-scaled, coordinate-ordered
// point set that the tetrahedralization and the surface work on.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "points/spatial_sort.h"

namespace dbrg {

struct ConditionedPoints {
    explicit ConditionedPoints(Memory& memory) : coordinates(memory), input_index(memory) {}

    // x, y, z of each distinct point, translated by `origin` and scaled by 2^scale_exponent so the
    // largest extent lies in [0.5, 1), then rounded to a multiple of 2^-200 as the exact predicates
    // require. Sorted lexicographically by (x, y, z): vertex ids therefore depend on the coordinates only,
    // never on the caller's order. The translation and scaling are exact; the rounding moves a point by
    // at most 2^-201 of the extent, so only points closer than that to each other are merged.
    Array<double> coordinates;
    // For each distinct point, the caller index standing for the input points merged into it: the one
    // with the smallest caller coordinates, the smallest index among exact copies.
    Array<uint32_t> input_index;
    // Per axis: the bounding box's minimum corner rounded down to a multiple of 2^-scale_exponent, or
    // 0 on an axis where subtracting that would round some coordinate. The translation is only there
    // to keep coordinates small; exactness matters more.
    double origin[3] = {0, 0, 0};
    int scale_exponent = 0;
    uint32_t duplicates_merged = 0;
    PointOrder order = PointOrder::any;  // hilbert once renumber_spatially has run
    // All points lie exactly in one plane (as orient3d decides) and not on one line: a surface, but no
    // volume to tetrahedralize.
    bool flat = false;

    uint32_t size() const { return static_cast<uint32_t>(input_index.size()); }
    const double* point(uint32_t v) const { return coordinates.data() + 3 * static_cast<size_t>(v); }
};

// Where conditioning's share of DBRG_STAGE_VALIDATE's progress ends (it begins after reading the points,
// at VALIDATE_READ_SHARE) and the renumbering's begins.
constexpr double VALIDATE_CONDITION_END = 0.8;

// Conditions `count` finite points given as x, y, z triples. Merges points that are equal after the
// transform. Coplanar points are conditioned like any others, with out.flat set. Fails with
// DBRG_ERR_TOO_FEW_POINTS (fewer than 4 distinct points) or DBRG_ERR_DEGENERATE_INPUT (all collinear, or
// coplanar but on one line up to rounding), each with a message saying how many distinct points there were,
// or DBRG_ERR_CANCELLED; `out` is then left empty. Reports DBRG_STAGE_VALIDATE progress from
// VALIDATE_READ_SHARE to VALIDATE_CONDITION_END.
dbrg_status condition_points(const double* xyz, size_t count, Context& context, ConditionedPoints& out);
// The same, reporting to `progress` (the cleaning stage conditions the points it keeps again).
dbrg_status condition_points(const double* xyz, size_t count, const ProgressSpan& progress, ConditionedPoints& out);

// Where a volume is needed (tetrahedra): DBRG_ERR_DEGENERATE_INPUT, with a message saying how many of the
// `count` points given were distinct, when `points` are flat; DBRG_OK otherwise.
dbrg_status refuse_flat(const ConditionedPoints& points, size_t count, Context& context);

// Renumbers conditioned points along a Hilbert curve, so that points close in space are close in memory
// for the tetrahedralization and region growing that follow. The numbering stays a function of the
// coordinates alone (the curve over the bounding box; ties by lexicographic order), so results still do
// not depend on the caller's order. Reports DBRG_STAGE_VALIDATE progress from VALIDATE_CONDITION_END to 1.
// Returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED (with the message set).
dbrg_status renumber_spatially(ConditionedPoints& points, Context& context);
dbrg_status renumber_spatially(ConditionedPoints& points, const ProgressSpan& progress);

} // namespace dbrg
