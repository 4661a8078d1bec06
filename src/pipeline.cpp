// Pipeline: runs the stages of one call in order — read points, condition, tetrahedralize, grow, fill
// holes — and hands the results over in the caller's point indexing.
#include "pipeline.h"

#include <algorithm>

#include "core/point_input.h"
#include "core/progress_span.h"
#include "core/status.h"
#include "delaunay/point_conditioning.h"
#include "delaunay/tetgen_backend.h"
#include "delaunay/tetrahedralization.h"
#include "grow/region_growing.h"
#include "growth_snapshots.h"
#include "holes/hole_filling.h"
#include "surface/surface.h"

namespace dbrg {
namespace {

// Reads, checks and conditions the caller's points; the raw copy is released before returning. Each step
// reports its share of DBRG_STAGE_VALIDATE, the renumbering last, up to 1.
dbrg_status prepare_points(const dbrg_points* points, Context& context, ConditionedPoints& conditioned) {
    const double start = seconds_now();
    DBRG_PROPAGATE(context.report(DBRG_STAGE_VALIDATE, 0.0));
    Array<double> xyz(context.memory);
    DBRG_PROPAGATE(read_points(points, context, xyz));
    DBRG_PROPAGATE(condition_points(xyz.data(), points->count, context, conditioned));
    xyz.release();
    DBRG_PROPAGATE(renumber_spatially(conditioned, context));
    context.stats.input_points = static_cast<uint32_t>(points->count);
    context.stats.unique_points = conditioned.size();
    context.stats.duplicates_merged = conditioned.duplicates_merged;
    context.stats.seconds_validate = seconds_now() - start;
    return DBRG_OK;
}

dbrg_status tetrahedralize(const ConditionedPoints& conditioned, Context& context, Tetrahedralization& delaunay) {
    return build_tetrahedralization(context.params.backend, conditioned.coordinates.data(), conditioned.size(), context,
                                    delaunay);
}

// Which components to turn over: the closed ones (no boundary half-edge) whose signed volume is negative.
dbrg_status find_inward_components(const Surface& surface, const ConditionedPoints& points, const ProgressSpan& progress,
                                   Array<uint32_t>& face_component, Array<uint8_t>& flip) {
    Context& context = progress.context();
    const uint32_t components = surface.label_components(face_component);
    if (components == NO_FACE) return context.fail_out_of_memory();
    Array<double> volume(context.memory);
    Array<uint8_t> open(context.memory);
    if (!volume.resize(components, 0.0) || !open.resize(components, 0) || !flip.resize(components, 0)) {
        return context.fail_out_of_memory();
    }
    for (uint32_t f = 0; f < surface.face_count(); ++f) {
        DBRG_PROPAGATE(progress.report_at(f, surface.face_count()));
        const uint32_t k = face_component[f];
        if (k == NO_FACE) continue;
        for (uint32_t i = 0; i < 3; ++i) open[k] |= surface.is_boundary(3 * f + i) ? 1 : 0;
        const Vec3 a = load_vec3(points.point(surface.corner(f, 0)));
        const Vec3 b = load_vec3(points.point(surface.corner(f, 1)));
        const Vec3 c = load_vec3(points.point(surface.corner(f, 2)));
        volume[k] += dot(a, cross(b, c));
    }
    for (uint32_t k = 0; k < components; ++k) flip[k] = !open[k] && volume[k] < 0;
    context.stats.components = components;
    return DBRG_OK;
}

// Triangles in the caller's indices, closed components turned outward, and the boundary loops.
dbrg_status emit_surface(const Surface& surface, const ConditionedPoints& conditioned, Context& context,
                         SurfaceResult& result) {
    const ProgressSpan progress(context, DBRG_STAGE_OUTPUT);
    DBRG_PROPAGATE(progress.report(0, 1));
    const uint32_t faces = surface.face_count();
    Array<uint32_t> face_component(context.memory);
    Array<uint8_t> flip(context.memory);
    DBRG_PROPAGATE(find_inward_components(surface, conditioned, progress.part(0.0, 0.4), face_component, flip));
    if (!result.triangles.reserve(3 * size_t(surface.live_face_count()))) return context.fail_out_of_memory();
    const ProgressSpan writing = progress.part(0.4, 0.7), tracing = progress.part(0.7, 0.9), counting = progress.part(0.9, 1.0);
    for (uint32_t f = 0; f < faces; ++f) {
        DBRG_PROPAGATE(writing.report_at(f, faces));
        if (surface.face_removed(f)) continue;
        const bool turn = flip[face_component[f]] != 0;
        result.triangles.push_back(conditioned.input_index[surface.corner(f, 0)]);
        result.triangles.push_back(conditioned.input_index[surface.corner(f, turn ? 2 : 1)]);
        result.triangles.push_back(conditioned.input_index[surface.corner(f, turn ? 1 : 2)]);
    }
    // Boundary loops: from a boundary half-edge u->v, the loop continues with the half-edge that leaves
    // v's fan. (Only closed components are turned over, and they have no loops.)
    Array<uint8_t> visited(context.memory);
    if (!visited.resize(3 * size_t(faces), 0) || !result.loop_offsets.push_back(0)) return context.fail_out_of_memory();
    uint32_t boundary_edges = 0;
    for (uint32_t start = 0; start < 3 * faces; ++start) {
        DBRG_PROPAGATE(tracing.report_at(start, 3 * size_t(faces)));
        if (!surface.is_boundary(start) || visited[start]) continue;
        uint32_t h = start;
        do {
            visited[h] = 1;
            ++boundary_edges;
            if (!result.loop_vertices.push_back(conditioned.input_index[surface.origin(h)])) return context.fail_out_of_memory();
            h = surface.fan_exit(h);
        } while (h != start);
        if (!result.loop_offsets.push_back(static_cast<uint32_t>(result.loop_vertices.size()))) {
            return context.fail_out_of_memory();
        }
    }
    uint32_t vertices_used = 0;
    for (uint32_t v = 0; v < surface.vertex_count(); ++v) {
        DBRG_PROPAGATE(counting.report_at(v, surface.vertex_count()));
        vertices_used += surface.is_used(v) ? 1 : 0;
    }
    context.stats.triangles = surface.live_face_count();
    context.stats.vertices_used = vertices_used;
    context.stats.boundary_edges = boundary_edges;
    context.stats.boundary_loops = static_cast<uint32_t>(result.loop_offsets.size() - 1);
    return DBRG_OK;
}

} // namespace

dbrg_status reconstruct_surface(const dbrg_points* points, Context& context, SurfaceResult& result) {
    ConditionedPoints conditioned(context.memory);
    DBRG_PROPAGATE(prepare_points(points, context, conditioned));

    Surface surface(context.memory);
    {
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
            HoleFiller filler(delaunay, surface, grower, context);
            DBRG_PROPAGATE(filler.fill());
            context.stats.seconds_fill_holes = seconds_now() - start;
        }
    }

    const double start = seconds_now();
    DBRG_PROPAGATE(emit_surface(surface, conditioned, context, result));
    context.stats.seconds_output = seconds_now() - start;
    return context.memory.failed() ? context.fail_out_of_memory() : context.report(DBRG_STAGE_OUTPUT, 1.0);
}

dbrg_status tetrahedralize_points(const dbrg_points* points, Context& context, TetrahedraResult& result) {
    ConditionedPoints conditioned(context.memory);
    DBRG_PROPAGATE(prepare_points(points, context, conditioned));
    Tetrahedralization delaunay(context.memory);
    DBRG_PROPAGATE(tetrahedralize(conditioned, context, delaunay));
    const ProgressSpan progress(context, DBRG_STAGE_OUTPUT);
    DBRG_PROPAGATE(progress.report(0, 1));

    // Finite tetrahedra are numbered in the order of their canonical corners (counting sort by the first,
    // then the few that share it by the other three), and written with their corners in that order: the
    // output is the same whichever slots construction left them in (threads leave them in other slots).
    const uint32_t slots = delaunay.tet_slots();
    const auto corners = [&](uint32_t t, uint32_t local[4], uint32_t vertex[4]) {
        delaunay.canonical_corners(t, local);
        for (uint32_t i = 0; i < 4; ++i) vertex[i] = delaunay.tet_vertex(t, local[i]);
    };
    Array<uint32_t> bucket_end(context.memory);  // per smallest corner
    Array<uint32_t> order(context.memory);
    Array<uint32_t> number(context.memory);
    if (!bucket_end.resize(size_t(delaunay.vertex_count()) + 1, 0) || !number.resize(slots, DBRG_NO_NEIGHBOR)) {
        return context.fail_out_of_memory();
    }
    // The first canonical corner is the smallest vertex: the counting sort needs no more than that.
    const auto smallest = [&](uint32_t t) {
        return std::min(std::min(delaunay.tet_vertex(t, 0), delaunay.tet_vertex(t, 1)),
                        std::min(delaunay.tet_vertex(t, 2), delaunay.tet_vertex(t, 3)));
    };
    // A vertex's bucket takes about a microsecond to sort, a tetrahedron's corners a few hundred nanoseconds
    // to put in canonical order: those loops report more often than every STEP_ITEMS.
    const ProgressSpan counting = progress.part(0.0, 0.1), ordering = progress.part(0.1, 0.2),
                       sorting = progress.part(0.2, 0.6), numbering = progress.part(0.6, 0.65),
                       writing = progress.part(0.65, 1.0);
    const size_t VERTICES_PER_REPORT = 1 << 14, TETS_PER_REPORT = 1 << 16;
    uint32_t local[4], vertex[4], finite = 0;
    for (uint32_t t = 0; t < slots; ++t) {
        DBRG_PROPAGATE(counting.report_at(t, slots));
        if (delaunay.tet_is_free(t) || !delaunay.tet_is_finite(t)) continue;
        ++bucket_end[smallest(t) + 1];
        ++finite;
    }
    for (size_t v = 1; v < bucket_end.size(); ++v) bucket_end[v] += bucket_end[v - 1];
    if (!order.resize(finite)) return context.fail_out_of_memory();
    for (uint32_t t = 0; t < slots; ++t) {
        DBRG_PROPAGATE(ordering.report_at(t, slots));
        if (delaunay.tet_is_free(t) || !delaunay.tet_is_finite(t)) continue;
        order[bucket_end[smallest(t)]++] = t;  // bucket_end[v] ends as the end of v's bucket
    }
    // Within a bucket, by the other three corners, each tetrahedron's computed once.
    struct Keyed {
        uint32_t rest[3];
        uint32_t slot;
    };
    Array<Keyed> bucket(context.memory);
    for (size_t v = 0, begin = 0; v < delaunay.vertex_count(); begin = bucket_end[v++]) {
        DBRG_PROPAGATE(sorting.report_at(v, delaunay.vertex_count(), VERTICES_PER_REPORT));
        bucket.clear();
        for (size_t i = begin; i < bucket_end[v]; ++i) {
            corners(order[i], local, vertex);
            if (!bucket.push_back(Keyed{{vertex[1], vertex[2], vertex[3]}, order[i]})) return context.fail_out_of_memory();
        }
        std::sort(bucket.begin(), bucket.end(), [](const Keyed& x, const Keyed& y) {
            return std::lexicographical_compare(x.rest, x.rest + 3, y.rest, y.rest + 3);
        });
        for (size_t i = begin; i < bucket_end[v]; ++i) order[i] = bucket[i - begin].slot;
    }
    for (uint32_t i = 0; i < finite; ++i) {
        DBRG_PROPAGATE(numbering.report_at(i, finite));
        number[order[i]] = i;
    }
    // Not filled first: that would touch every page in one go, between two reports; written in order,
    // they are touched a step at a time.
    if (!result.tets.reserve(4 * size_t(finite)) || !result.adjacency.reserve(4 * size_t(finite))) {
        return context.fail_out_of_memory();
    }
    result.tets.resize_unwritten(4 * size_t(finite));
    result.adjacency.resize_unwritten(4 * size_t(finite));
    for (uint32_t i = 0; i < finite; ++i) {
        DBRG_PROPAGATE(writing.report_at(i, finite, TETS_PER_REPORT));
        corners(order[i], local, vertex);
        for (uint32_t k = 0; k < 4; ++k) {
            result.tets[4 * size_t(i) + k] = conditioned.input_index[vertex[k]];
            result.adjacency[4 * size_t(i) + k] = number[delaunay.tet_adjacent(order[i], local[k])];
        }
    }
    result.unique_points = conditioned.size();
    return context.report(DBRG_STAGE_OUTPUT, 1.0);
}

} // namespace dbrg
