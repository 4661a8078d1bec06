// Point conditioning: exact power-of-two rescaling, lexicographic order, duplicate merging and the
// degeneracy checks (too few, collinear) and the flatness test that choose how the points are triangulated.
#include "points/point_conditioning.h"

#include <math.h>

#include <algorithm>

#include "core/parallel.h"
#include "core/progress_span.h"
#include "core/status.h"
#include "core/vec3.h"
#include "points/point_input.h"
#include "points/spatial_sort.h"
#include "predicates/affine_checks.h"
#include "predicates/predicates.h"

namespace dbrg {
namespace {

// True when a - b is representable, i.e. the subtraction rounds nothing (Knuth's two-difference:
// the rounding error of a - b, computed without it being contracted into an FMA).
bool subtraction_is_exact(double a, double b) {
    const double difference = a - b;
    const double b_virtual = a - difference;
    const double a_virtual = difference + b_virtual;
    const double b_round = b_virtual - b;
    const double a_round = a - a_virtual;
    return a_round + b_round == 0.0;
}

// The translation for one axis into `origin`: the minimum rounded down to a multiple of 2^exponent (so that
// it has few significant bits), kept only if it is exact for every coordinate on the axis, 0 otherwise.
dbrg_status exact_origin(const double* xyz, size_t count, int axis, double minimum, int exponent,
                         const ProgressSpan& progress, double& origin) {
    origin = 0.0;
    const double units = floor(ldexp(minimum, -exponent));
    if (!isfinite(units)) return DBRG_OK;
    const double candidate = ldexp(units, exponent);
    if (!isfinite(candidate) || candidate == 0.0) return DBRG_OK;
    for (size_t i = 0; i < count; ++i) {
        DBRG_PROPAGATE(progress.report_at(i, count));
        if (!subtraction_is_exact(xyz[3 * i + axis], candidate)) return DBRG_OK;
    }
    origin = candidate;
    return DBRG_OK;
}

// The exact predicates need every coordinate to be a multiple of 2^-200 (so no product of differences
// underflows): rounding to that grid moves a point by at most 2^-201 of the cloud's extent, which merges
// only points that no double-precision computation on the whole cloud could tell apart anyway.
// Products with powers of two instead of ldexp calls, exact here: |x| <= 1, and a double of 2^52 or more is
// already an integer.
double snap_to_predicate_grid(double x) {
    const double units = x * 0x1p200;
    return (fabs(units) < 0x1p52 ? nearbyint(units) : units) * 0x1p-200;
}

struct IndexedPoint {
    double p[3];
    uint32_t index;
};

// Coordinates compared with ==, like the sort: -0.0 and 0.0 are one point.
bool same_point(const IndexedPoint& a, const IndexedPoint& b) {
    return a.p[0] == b.p[0] && a.p[1] == b.p[1] && a.p[2] == b.p[2];
}

// Points between two progress reports in the degeneracy checks: on collinear or coplanar points every
// predicate needs exact arithmetic, about a microsecond.
constexpr uint32_t RANK_STEP = 1u << 14;

// Finds the first point after the lexicographically smallest two that makes them non-collinear, and
// then one that is not coplanar with the three. Sets `rank` to the number of affinely independent points
// found (2, 3 or 4).
dbrg_status affine_rank(const ConditionedPoints& points, const ProgressSpan& progress, int& rank) {
    PredicateCounters counters;
    const uint32_t n = points.size();
    const double* a = points.point(0);
    const double* b = points.point(n - 1);  // the two lexicographic extremes are distinct
    // Both searches may run through every point: each has half of the span.
    uint32_t c = 1;
    for (; c + 1 < n && points_collinear(a, b, points.point(c), counters); ++c) {
        if (c % RANK_STEP == 0) DBRG_PROPAGATE(progress.report(c, 2 * size_t(n)));
    }
    rank = 2;
    if (c + 1 >= n) return DBRG_OK;
    rank = 4;
    for (uint32_t d = 1; d + 1 < n; ++d) {
        if (d % RANK_STEP == 0) DBRG_PROPAGATE(progress.report(n + size_t(d), 2 * size_t(n)));
        if (orient3d(a, b, points.point(c), points.point(d), counters) != 0) return DBRG_OK;
    }
    rank = 3;
    return DBRG_OK;
}

// The largest distance of a point from the line through the two lexicographic extremes, as a share of their
// distance. For points meant to lie on one line but rounded off it, this is a few units in the last place:
// exactly coplanar, yet a user would call them collinear, and the message should say so.
double spread_off_line(const ConditionedPoints& points) {
    const uint32_t n = points.size();
    const Vec3 a = load_vec3(points.point(0)), direction = load_vec3(points.point(n - 1)) - a;
    const double length_squared = dot(direction, direction);
    double largest = 0;
    for (uint32_t i = 1; i + 1 < n; ++i) {
        const Vec3 off = cross(load_vec3(points.point(i)) - a, direction);
        largest = std::max(largest, dot(off, off));
    }
    return sqrt(largest) / length_squared;
}

// Spread off the line below which coplanar points are reported as collinear but for rounding.
const double ROUNDING_SPREAD = 1e-9;

} // namespace

namespace {

dbrg_status condition(const double* xyz, size_t count, const ProgressSpan& progress, ConditionedPoints& out) {
    Context& context = progress.context();
    out.coordinates.clear();
    out.input_index.clear();
    out.duplicates_merged = 0;
    out.scale_exponent = 0;
    out.origin[0] = out.origin[1] = out.origin[2] = 0.0;
    out.flat = false;
    DBRG_PROPAGATE(check_point_count(count, context));

    // Each pass has a share of the progress roughly as its time on a large input.
    double lo[3], hi[3];
    DBRG_PROPAGATE(bounding_box(xyz, count, progress.part(0.0, 0.05), lo, hi));
    // The extent may overflow to infinity (coordinates near +-DBL_MAX); measure half of it then.
    double extent = 0.0;
    bool halved = false;
    for (int k = 0; k < 3; ++k) extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
    if (isinf(extent)) {
        extent = 0.0;
        halved = true;
        for (int k = 0; k < 3; ++k) extent = 0.5 * hi[k] - 0.5 * lo[k] > extent ? 0.5 * hi[k] - 0.5 * lo[k] : extent;
    }
    if (extent == 0.0) {
        return context.fail(DBRG_ERR_TOO_FEW_POINTS, "all %zu points are equal: 1 distinct point; at least 4 are needed",
                            count);
    }
    int exponent = 0;
    frexp(extent, &exponent);  // extent = f * 2^exponent with f in [0.5, 1)
    if (halved) ++exponent;
    out.scale_exponent = -exponent;
    for (int k = 0; k < 3; ++k) {
        DBRG_PROPAGATE(exact_origin(xyz, count, k, lo[k], exponent, progress.part(0.05 + 0.02 * k, 0.07 + 0.02 * k),
                                    out.origin[k]));
    }

    // The transformed points with their input index, sorted by coordinates, then by the caller's
    // coordinates, then by index: the first of a group of equal points is the one with the smallest caller
    // coordinates (several distinct ones may round to one grid point), and among exact copies the one with
    // the smallest index. So the representative never depends on the input order.
    const uint32_t parts = part_count(context.params.threads, count, MIN_POINTS_PER_THREAD);
    Array<IndexedPoint> sorted(context.memory);
    Array<IndexedPoint> scratch(context.memory);
    if (!sorted.resize(count) || (sort_needs_scratch(count, parts) && !scratch.resize(count))) {
        return context.fail_out_of_memory();
    }
    // The scaling as a product where 2^scale_exponent is a normal double: both round the exact product once.
    const bool scale_by_product = out.scale_exponent >= -1022 && out.scale_exponent <= 1023;
    const double scale = scale_by_product ? ldexp(1.0, out.scale_exponent) : 0.0;
    DBRG_PROPAGATE(progress.part(0.11, 0.2).for_each_step(count, parts, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            IndexedPoint& q = sorted[i];
            for (int k = 0; k < 3; ++k) {
                const double shifted = xyz[3 * i + k] - out.origin[k];
                q.p[k] = snap_to_predicate_grid(scale_by_product ? shifted * scale : ldexp(shifted, out.scale_exponent));
            }
            q.index = static_cast<uint32_t>(i);
        }
    }));
    DBRG_PROPAGATE(progress.part(0.2, 0.85).sort(sorted.data(), count, scratch.data(), parts,
                                                 [xyz](const IndexedPoint& a, const IndexedPoint& b) {
        for (int k = 0; k < 3; ++k) {
            if (a.p[k] != b.p[k]) return a.p[k] < b.p[k];
        }
        for (int k = 0; k < 3; ++k) {
            const double u = xyz[3 * size_t(a.index) + k], v = xyz[3 * size_t(b.index) + k];
            if (u != v) return u < v;
        }
        return a.index < b.index;
    }));
    scratch.release();

    const ProgressSpan counting = progress.part(0.85, 0.88), copying = progress.part(0.88, 0.95);
    size_t distinct = 1;
    for (size_t i = 1; i < count; ++i) {
        DBRG_PROPAGATE(counting.report_at(i, count));
        distinct += !same_point(sorted[i], sorted[i - 1]);
    }
    if (!out.coordinates.reserve(3 * distinct) || !out.input_index.reserve(distinct)) {
        return context.fail_out_of_memory();
    }
    for (size_t i = 0; i < count; ++i) {
        DBRG_PROPAGATE(copying.report_at(i, count));
        if (i > 0 && same_point(sorted[i], sorted[i - 1])) continue;
        out.coordinates.push_back(sorted[i].p[0]);
        out.coordinates.push_back(sorted[i].p[1]);
        out.coordinates.push_back(sorted[i].p[2]);
        out.input_index.push_back(sorted[i].index);
    }
    out.duplicates_merged = static_cast<uint32_t>(count - distinct);
    sorted.release();

    if (distinct < 4) {
        return context.fail(DBRG_ERR_TOO_FEW_POINTS, "%zu points given but only %zu distinct; at least 4 are needed",
                            count, distinct);
    }
    int rank = 0;
    DBRG_PROPAGATE(affine_rank(out, progress.part(0.95, 1.0), rank));
    if (rank == 2) {
        return context.fail(DBRG_ERR_DEGENERATE_INPUT, "all %zu distinct points (of %zu given) are collinear",
                            distinct, count);
    }
    if (rank == 3 && spread_off_line(out) < ROUNDING_SPREAD) {
        return context.fail(DBRG_ERR_DEGENERATE_INPUT,
                            "all %zu distinct points (of %zu given) are coplanar: they lie on one line but for rounding",
                            distinct, count);
    }
    out.flat = rank == 3;
    return progress.report(1, 1);
}

} // namespace

dbrg_status condition_points(const double* xyz, size_t count, Context& context, ConditionedPoints& out) {
    return condition_points(xyz, count, ProgressSpan(context, DBRG_STAGE_VALIDATE, VALIDATE_READ_SHARE, VALIDATE_CONDITION_END),
                            out);
}

dbrg_status condition_points(const double* xyz, size_t count, const ProgressSpan& progress, ConditionedPoints& out) {
    const dbrg_status status = condition(xyz, count, progress, out);
    if (status != DBRG_OK) {
        out.coordinates.release();  // a failed call leaves nothing behind
        out.input_index.release();
    }
    return status;
}

dbrg_status refuse_flat(const ConditionedPoints& points, size_t count, Context& context) {
    if (!points.flat) return DBRG_OK;
    return context.fail(DBRG_ERR_DEGENERATE_INPUT, "all %u distinct points (of %zu given) are coplanar", points.size(),
                        count);
}

dbrg_status renumber_spatially(ConditionedPoints& points, Context& context) {
    return renumber_spatially(points, ProgressSpan(context, DBRG_STAGE_VALIDATE, VALIDATE_CONDITION_END, 1.0));
}

dbrg_status renumber_spatially(ConditionedPoints& points, const ProgressSpan& progress) {
    Context& context = progress.context();
    const uint32_t n = points.size();
    Array<uint32_t> order(context.memory);
    Array<double> coordinates(context.memory);
    Array<uint32_t> input_index(context.memory);
    DBRG_PROPAGATE(hilbert_order(points.coordinates.data(), n, progress.part(0.0, 0.9), order));
    if (!coordinates.resize(3 * size_t(n)) || !input_index.resize(n)) return context.fail_out_of_memory();
    const uint32_t parts = part_count(context.params.threads, n, MIN_POINTS_PER_THREAD);
    DBRG_PROPAGATE(progress.part(0.9, 1.0).for_each_step(n, parts, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            for (int k = 0; k < 3; ++k) coordinates[3 * i + k] = points.coordinates[3 * size_t(order[i]) + k];
            input_index[i] = points.input_index[order[i]];
        }
    }));
    points.coordinates.swap(coordinates);
    points.input_index.swap(input_index);
    points.order = PointOrder::hilbert;
    return DBRG_OK;
}

} // namespace dbrg
