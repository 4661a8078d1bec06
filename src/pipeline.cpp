// Pipeline: runs the stages of one call in order — read points, condition, tetrahedralize, grow, fill
// holes; or, for points all in one plane, triangulate in the plane and grow — and hands the results over in
// the caller's point indexing.
#include "pipeline.h"

#include <math.h>
#include <string.h>

#include "points/point_input.h"
#include "core/progress_span.h"
#include "core/status.h"
#include "delaunay/backend.h"
#include "delaunay/canonical_order.h"
#include "points/point_cleaning.h"
#include "points/point_conditioning.h"
#include "delaunay/tetrahedralization.h"
#include "grow/region_growing.h"
#include "growth_snapshots.h"
#include "holes/hole_filling.h"
#include "holes/point_insertion.h"
#include "planar/planar_delaunay.h"
#include "planar/planar_growing.h"
#include "surface/surface.h"

namespace dbrg {
namespace {

// Reads, checks and conditions the caller's points; the raw copy is released before returning, copied into
// `kept_copy` first when there is one. Each step reports its share of DBRG_STAGE_VALIDATE, the renumbering last, up to 1.
dbrg_status prepare_points(const dbrg_points* points, Context& context, ConditionedPoints& conditioned,
                           Array<double>* kept_copy = nullptr) {
    const double start = seconds_now();
    DBRG_PROPAGATE(context.report(DBRG_STAGE_VALIDATE, 0.0));
    Array<double> xyz(context.memory);
    DBRG_PROPAGATE(copy_caller_points(points, context, xyz));
    DBRG_PROPAGATE(condition_points(xyz.data(), points->count, context, conditioned));
    if (kept_copy) {
        if (!kept_copy->resize(xyz.size())) return context.fail_out_of_memory();
        memcpy(kept_copy->data(), xyz.data(), xyz.size() * sizeof(double));
    }
    xyz.release();
    DBRG_PROPAGATE(renumber_spatially(conditioned, context));
    context.stats.input_points = static_cast<uint32_t>(points->count);
    context.stats.unique_points = conditioned.size();
    context.stats.duplicates_merged = conditioned.duplicates_merged;
    context.stats.seconds_validate = seconds_now() - start;
    return DBRG_OK;
}

// Cleans the points unless the caller turned cleaning off. For output_smoothed, `result.smoothed_points`
// holds the caller's points on entry; it is left with every point standing for a distinct point at its
// smoothed position, in the caller's coordinates, or emptied when nothing was smoothed.
dbrg_status clean(ConditionedPoints& conditioned, Context& context, SurfaceResult& result) {
    if (context.params.cleaning == DBRG_CLEANING_OFF) return DBRG_OK;
    const double start = seconds_now();
    DBRG_PROPAGATE(clean_points(conditioned, context, result.outliers));
    context.stats.unique_points = conditioned.size();
    context.stats.seconds_clean = seconds_now() - start;
    if (context.stats.points_smoothed == 0) {
        result.smoothed_points.release();
    } else if (!result.smoothed_points.empty()) {
        for (uint32_t v = 0; v < conditioned.size(); ++v) {
            for (int a = 0; a < 3; ++a) {
                result.smoothed_points[3 * size_t(conditioned.input_index[v]) + a] =
                    ldexp(conditioned.point(v)[a], -conditioned.scale_exponent) + conditioned.origin[a];
            }
        }
    }
    return DBRG_OK;
}

dbrg_status tetrahedralize(const ConditionedPoints& conditioned, Context& context, Tetrahedralization& delaunay) {
    return build_tetrahedralization(context.params.backend, conditioned.coordinates.data(), conditioned.size(),
                                    conditioned.order, context, delaunay);
}

// The flat path: the 2-D Delaunay triangulation of the points in their plane, grown with the same border
// rule. Its triangles are all Delaunay and its region has no handles, and nothing of it is a hole the border
// rule has not already judged: hole filling, the flips and the handle search have nothing to do.
dbrg_status grow_flat_surface(const ConditionedPoints& conditioned, Context& context, Surface& surface) {
    double start = seconds_now();
    PlanarTriangulation triangulation(context.memory);
    DBRG_PROPAGATE(triangulation.build(conditioned.coordinates.data(), conditioned.size(), context,
                                       ProgressSpan(context, DBRG_STAGE_DELAUNAY)));
    context.stats.seconds_delaunay = seconds_now() - start;
    start = seconds_now();
    PlanarGrower grower(triangulation, surface, context);
    DBRG_PROPAGATE(grower.grow(ProgressSpan(context, DBRG_STAGE_GROW)));
    context.stats.seconds_grow = seconds_now() - start;
    GrowthSnapshots snapshots(conditioned, context);
    return snapshots.finish(surface);
}

// A caller index with no conditioned vertex of its own.
const uint32_t NO_VERTEX = UINT32_MAX;

// The seeds and fixed flags, given by caller index, by conditioned vertex: a face with a merged duplicate
// that does not stand for its copies is dropped (it has no vertex of its own).
dbrg_status to_vertex_indexing(const ConditionedPoints& conditioned, size_t count, const uint32_t* seeds,
                               size_t seed_count, const uint8_t* fixed, Context& context,
                               Array<uint32_t>& seed_vertices, Array<uint8_t>& fixed_flags) {
    Array<uint32_t> vertex_of(context.memory);
    if (!vertex_of.resize(count, NO_VERTEX)) return context.fail_out_of_memory();
    for (uint32_t v = 0; v < conditioned.size(); ++v) vertex_of[conditioned.input_index[v]] = v;
    if (!seed_vertices.reserve(3 * seed_count)) return context.fail_out_of_memory();
    for (size_t i = 0; i < seed_count; ++i) {
        uint32_t corners[3];
        bool known = true;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t index = seeds[3 * i + k];
            corners[k] = index < count ? vertex_of[index] : NO_VERTEX;
            known = known && corners[k] != NO_VERTEX;
        }
        for (uint32_t k = 0; known && k < 3; ++k) seed_vertices.push_back(corners[k]);
    }
    if (!fixed) return DBRG_OK;
    if (!fixed_flags.resize(conditioned.size(), 0)) return context.fail_out_of_memory();
    for (uint32_t v = 0; v < conditioned.size(); ++v) fixed_flags[v] = fixed[conditioned.input_index[v]] ? 1 : 0;
    return DBRG_OK;
}

} // namespace

dbrg_status fill_holes(const Tetrahedralization& delaunay, Surface& surface, RegionGrower& grower, Context& context) {
    const ProgressSpan stage(context, DBRG_STAGE_FILL_HOLES);
    DBRG_PROPAGATE(stage.report(0, 1));
    HoleFiller filler(delaunay.points(), surface, grower.boundary_causes(), context);
    bool holes = false;
    DBRG_PROPAGATE(filler.find_holes(holes));
    if (holes) {
        // Delaunay triangles first, as growing would attach them: S has changed around the holes since
        // their edges were last examined. Then ears over what is left.
        DBRG_PROPAGATE(grower.regrow_holes(stage.part(0, FILL_PROGRESS_EARS)));
        DBRG_PROPAGATE(filler.fill_with_ears(stage.part(FILL_PROGRESS_EARS, FILL_PROGRESS_ISLANDS),
                                             stage.part(FILL_PROGRESS_ISLANDS, FILL_PROGRESS_HANDLES)));
    }
    DBRG_PROPAGATE(filler.remove_small_handles(stage.part(FILL_PROGRESS_HANDLES, FILL_PROGRESS_POINTS)));
    PointInsertion insertion(delaunay, surface, context);
    DBRG_PROPAGATE(insertion.insert_left_out(stage.part(FILL_PROGRESS_POINTS, FILL_PROGRESS_FLIPS)));
    // Growing's flips passed over the edges with a corner on a hole's rim: the holes are closed, and what is
    // around the filled holes has changed.
    DBRG_PROPAGATE(grower.flip_deferred(stage.part(FILL_PROGRESS_FLIPS, 1)));
    return stage.report(1, 1);
}

dbrg_status reconstruct_surface(const dbrg_points* points, Context& context, SurfaceResult& result) {
    ConditionedPoints conditioned(context.memory);
    const bool keep_copy = context.params.output_smoothed && context.params.cleaning != DBRG_CLEANING_OFF;
    DBRG_PROPAGATE(prepare_points(points, context, conditioned, keep_copy ? &result.smoothed_points : nullptr));
    DBRG_PROPAGATE(clean(conditioned, context, result));

    Surface surface(context.memory);
    if (conditioned.flat) {
        // A flat set needs no tetrahedra, but a backend this build lacks is refused whatever the points.
        DBRG_PROPAGATE(check_backend(context.params.backend, context));
        DBRG_PROPAGATE(grow_flat_surface(conditioned, context, surface));
    } else {
        // The tetrahedralization and the grower's tables live until hole filling is done: their memory is
        // given back before the output is allocated.
        Tetrahedralization delaunay(context.memory);
        DBRG_PROPAGATE(tetrahedralize(conditioned, context, delaunay));

        double start = seconds_now();
        RegionGrower grower(delaunay, surface, context);
        GrowthSnapshots snapshots(conditioned, context);
        snapshots.attach(grower);
        DBRG_PROPAGATE(grower.grow());
        context.stats.seconds_grow = seconds_now() - start;
        DBRG_PROPAGATE(snapshots.finish(surface));

        if (context.params.fill_holes) {
            start = seconds_now();
            DBRG_PROPAGATE(fill_holes(delaunay, surface, grower, context));
            context.stats.seconds_fill_holes = seconds_now() - start;
        }
    }

    const double start = seconds_now();
    DBRG_PROPAGATE(emit_surface(surface, conditioned, context, result));
    context.stats.seconds_output = seconds_now() - start;
    return context.memory.failed() ? context.fail_out_of_memory() : context.report(DBRG_STAGE_OUTPUT, 1.0);
}

dbrg_status grow_from_surface(const dbrg_points* points, const uint32_t* seeds, size_t seed_count,
                              const uint8_t* fixed, Context& context, SurfaceResult& result) {
    ConditionedPoints conditioned(context.memory);
    DBRG_PROPAGATE(prepare_points(points, context, conditioned));
    DBRG_PROPAGATE(refuse_flat(conditioned, points->count, context));
    Array<uint32_t> seed_vertices(context.memory);
    Array<uint8_t> fixed_flags(context.memory);
    DBRG_PROPAGATE(to_vertex_indexing(conditioned, points->count, seeds, seed_count, fixed, context,
                                      seed_vertices, fixed_flags));
    Surface surface(context.memory);
    {
        Tetrahedralization delaunay(context.memory);
        DBRG_PROPAGATE(tetrahedralize(conditioned, context, delaunay));
        double start = seconds_now();
        RegionGrower grower(delaunay, surface, context);
        DBRG_PROPAGATE(grower.grow_from(seed_vertices.data(), seed_vertices.size() / 3,
                                        fixed_flags.empty() ? nullptr : fixed_flags.data()));
        context.stats.seconds_grow = seconds_now() - start;
        start = seconds_now();
        const ProgressSpan stage(context, DBRG_STAGE_FILL_HOLES);
        HoleFiller filler(delaunay.points(), surface, grower.boundary_causes(), context);
        filler.keep_fixed(fixed_flags.empty() ? nullptr : fixed_flags.data());
        bool holes = false;
        DBRG_PROPAGATE(filler.find_holes(holes));
        if (holes) {
            DBRG_PROPAGATE(grower.regrow_holes(stage.part(0, FILL_PROGRESS_EARS)));
            DBRG_PROPAGATE(filler.fill_with_ears(stage.part(FILL_PROGRESS_EARS, FILL_PROGRESS_ISLANDS),
                                                 stage.part(FILL_PROGRESS_ISLANDS, FILL_PROGRESS_POINTS)));
        }
        PointInsertion insertion(delaunay, surface, context);
        insertion.keep_fixed(fixed_flags.empty() ? nullptr : fixed_flags.data());
        DBRG_PROPAGATE(insertion.insert_left_out(stage.part(FILL_PROGRESS_POINTS, FILL_PROGRESS_FLIPS)));
        DBRG_PROPAGATE(grower.flip_deferred(stage.part(FILL_PROGRESS_FLIPS, 1)));
        context.stats.seconds_fill_holes = seconds_now() - start;
    }
    DBRG_PROPAGATE(emit_surface(surface, conditioned, context, result));
    return context.memory.failed() ? context.fail_out_of_memory() : context.report(DBRG_STAGE_OUTPUT, 1.0);
}

dbrg_status tetrahedralize_points(const dbrg_points* points, Context& context, TetrahedraResult& result) {
    ConditionedPoints conditioned(context.memory);
    DBRG_PROPAGATE(prepare_points(points, context, conditioned));
    DBRG_PROPAGATE(refuse_flat(conditioned, points->count, context));
    Tetrahedralization delaunay(context.memory);
    DBRG_PROPAGATE(tetrahedralize(conditioned, context, delaunay));
    const ProgressSpan progress(context, DBRG_STAGE_OUTPUT);
    DBRG_PROPAGATE(progress.report(0, 1));
    DBRG_PROPAGATE(write_canonical_tetrahedra(delaunay, conditioned.input_index.data(), progress, result.tets,
                                              result.adjacency));
    result.unique_points = conditioned.size();
    return context.report(DBRG_STAGE_OUTPUT, 1.0);
}

} // namespace dbrg
