// Tiled reconstruction: tiles reconstructed one after another, their owned triangles oriented together,
// the seam strips cut and regrown from the surface around them, and the whole assembled as one manifold
// (docs/tiles.md).
#include "tiles/tiled_reconstruction.h"

#include <math.h>

#include <algorithm>
#include <limits>

#include "core/status.h"
#include "pipeline.h"
#include "points/point_conditioning.h"
#include "points/point_input.h"
#include "points/spatial_sort.h"
#include "delaunay/tetrahedralization.h"
#include "holes/hole_filling.h"
#include "surface/surface.h"
#include "tiles/point_spacing.h"
#include "tiles/triangle_orientation.h"

namespace dbrg {
namespace {

const uint32_t NOT_IN_STRIP = UINT32_MAX;
// The stitches' share of DBRG_STAGE_FILL_HOLES's progress; the assembly's numbering of the points and its
// handle cut take the rest.
constexpr double STITCH_PROGRESS = 0.9;
constexpr double NUMBERING_PROGRESS = 0.92;

// The axis along which the box of the points is longest.
int longest_axis(const double* xyz, size_t count) {
    double low[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, high[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < count; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = std::min(low[axis], xyz[3 * i + axis]);
            high[axis] = std::max(high[axis], xyz[3 * i + axis]);
        }
    }
    int best = 0;
    for (int axis = 1; axis < 3; ++axis) best = high[axis] - low[axis] > high[best] - low[best] ? axis : best;
    return best;
}

// The inner walls of `tile_count` slabs along `axis` holding about equal numbers of points: quantiles of the
// coordinates. A wall closer than `min_width` to the previous one or to either end of the points is dropped
// (a slab thinner than the strips around its walls has no interior of its own), and so is a repeated one.
dbrg_status slab_walls(const double* xyz, size_t count, int axis, uint32_t tile_count, double min_width,
                       Context& context, Array<double>& walls) {
    Array<double> values(context.memory);
    if (!values.resize(count)) return context.fail_out_of_memory();
    for (size_t i = 0; i < count; ++i) values[i] = xyz[3 * i + axis];
    const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
    const double low = *lowest, high = *highest;
    // The order statistics at the walls' ranks, each selected among the values at or above the previous one.
    size_t selected = 0;
    for (uint32_t k = 1; k < tile_count; ++k) {
        const size_t rank = count * k / tile_count;
        std::nth_element(values.begin() + selected, values.begin() + rank, values.end());
        selected = rank;
        const double wall = values[rank];
        const double previous = walls.empty() ? low : walls[walls.size() - 1];
        if (!(wall - previous >= min_width && high - wall >= min_width)) continue;
        if (!walls.push_back(wall)) return context.fail_out_of_memory();
    }
    return DBRG_OK;
}

dbrg_points double_points(const Array<double>& xyz) {
    return dbrg_points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
}

// The parameters of one piece of the work (a tile, the stitch): the caller's without progress or snapshots.
dbrg_params piece_params(const dbrg_params& params) {
    dbrg_params piece = params;
    piece.progress = nullptr;
    piece.snapshot = nullptr;
    piece.snapshot_count = 0;
    return piece;
}

// total + piece, or the type's largest value where that would wrap (a run of billions of points).
template <class Count>
void add_counts(Count& total, Count piece) {
    total = total > std::numeric_limits<Count>::max() - piece ? std::numeric_limits<Count>::max() : total + piece;
}

// Reconstructs tile `k` of the slabs and appends its owned triangles and its core's outliers, in the caller's
// indexing, to `owned` and `outliers`.
dbrg_status run_tile(const Array<double>& xyz, int axis, const Array<double>& walls, uint32_t k, double halo,
                     Context& context, Array<uint32_t>& owned, Array<uint32_t>& outliers) {
    TileCore core;
    for (int a = 0; a < 3; ++a) {
        core.low[a] = -HUGE_VAL;
        core.high[a] = HUGE_VAL;
    }
    if (k > 0) core.low[axis] = walls[k - 1];
    if (k < walls.size()) core.high[axis] = walls[k];
    Array<double> tile_xyz(context.memory);
    Array<uint32_t> tile_index(context.memory);
    const size_t count = xyz.size() / 3;
    for (size_t i = 0; i < count; ++i) {
        const double x = xyz[3 * i + axis];
        if (x < core.low[axis] - halo || x >= core.high[axis] + halo) continue;
        if (!tile_index.push_back(static_cast<uint32_t>(i))) return context.fail_out_of_memory();
        for (int a = 0; a < 3; ++a) {
            if (!tile_xyz.push_back(xyz[3 * i + a])) return context.fail_out_of_memory();
        }
    }
    if (tile_index.size() < 4) return DBRG_OK;  // nothing to reconstruct; the stitch sees these points
    Context tile_context(piece_params(context.params));
    tile_context.memory.count_in(context.memory.meter());  // the call's peak includes the piece's
    Array<uint32_t> tile_owned(tile_context.memory), tile_outliers(tile_context.memory);
    const dbrg_points tile_points = double_points(tile_xyz);
    const dbrg_status status = reconstruct_tile(&tile_points, core, tile_context, tile_owned, tile_outliers);
    if (status != DBRG_OK) return context.fail(status, "tile %u: %s", k + 1, tile_context.message());
    add_piece_stats(tile_context.stats, context.stats);
    context.stats.tile_peak_bytes = std::max(context.stats.tile_peak_bytes, tile_context.memory.peak_bytes());
    if (!owned.reserve(owned.size() + tile_owned.size()) || !outliers.reserve(outliers.size() + tile_outliers.size())) {
        return context.fail_out_of_memory();
    }
    for (uint32_t v : tile_owned) owned.push_back(tile_index[v]);
    for (uint32_t v : tile_outliers) outliers.push_back(tile_index[v]);
    return DBRG_OK;
}

// Where a point lies from the wall being stitched.
enum Zone : uint8_t { FAR = 0, BAND = 1, STRIP = 2 };

// The zone of each of the `count` points `xyz` around `wall`: closer than the strip, within reach, or far.
dbrg_status zone_points(const double* xyz, size_t count, int axis, double wall, double spacing, Context& context,
                        Array<uint8_t>& zone) {
    const double strip = STRIP_SPACINGS * spacing, reach = strip + MARGIN_SPACINGS * spacing;
    if (!zone.resize(count, FAR)) return context.fail_out_of_memory();
    for (size_t i = 0; i < count; ++i) {
        const double d = fabs(xyz[3 * i + axis] - wall);
        zone[i] = d < strip ? STRIP : d < reach ? BAND : FAR;
    }
    return DBRG_OK;
}

// The faces of `mesh` (3 global indices each) a stitch of `wall` needs, and the points they and the wall
// need, as the stitch_seam contract says: the faces with a corner within reach of the wall or sharing a
// corner with a face that has one in the strip. `faces` receives their indices in `mesh`, `points` the
// points' global indices, ascending. The tiles' `outliers` join only as corners of those faces (a tile that
// kept one may have used it), never for being near the wall: the stitch would grow over them.
dbrg_status gather_seam(const Array<double>& xyz, const Array<uint32_t>& mesh, const Array<uint32_t>& outliers,
                        int axis, double wall, double spacing, Context& context, Array<uint32_t>& faces,
                        Array<uint32_t>& points) {
    const size_t count = xyz.size() / 3, face_count = mesh.size() / 3;
    Array<uint8_t> zone(context.memory);
    DBRG_PROPAGATE(zone_points(xyz.data(), count, axis, wall, spacing, context, zone));
    for (uint32_t v : outliers) zone[v] = FAR;
    // The corners of faces reaching into the strip join the band (marked 3: they widen nothing further).
    const uint8_t REACHED = 3;
    for (size_t f = 0; f < face_count; ++f) {
        const uint32_t* t = mesh.data() + 3 * f;
        if (zone[t[0]] != STRIP && zone[t[1]] != STRIP && zone[t[2]] != STRIP) continue;
        for (int i = 0; i < 3; ++i) zone[t[i]] = zone[t[i]] == FAR ? REACHED : zone[t[i]];
    }
    Array<uint8_t> wanted(context.memory);
    if (!wanted.resize(count, 0)) return context.fail_out_of_memory();
    for (size_t i = 0; i < count; ++i) wanted[i] = zone[i] == STRIP || zone[i] == BAND;
    for (size_t f = 0; f < face_count; ++f) {
        const uint32_t* t = mesh.data() + 3 * f;
        if (zone[t[0]] == FAR && zone[t[1]] == FAR && zone[t[2]] == FAR) continue;
        if (!faces.push_back(static_cast<uint32_t>(f))) return context.fail_out_of_memory();
        for (int i = 0; i < 3; ++i) wanted[t[i]] = 1;
    }
    for (size_t i = 0; i < count; ++i) {
        if (wanted[i] && !points.push_back(static_cast<uint32_t>(i))) return context.fail_out_of_memory();
    }
    return DBRG_OK;
}

// Stitches `wall` on `mesh` (global indices) through stitch_seam: appends the indices in `mesh` of the faces
// it drops to `dropped` and the faces it adds, in global indices, to `added`.
dbrg_status stitch_wall(const Array<double>& xyz, const Array<uint32_t>& mesh, const Array<uint32_t>& outliers, int axis,
                        double wall, double spacing, Context& context, Array<uint32_t>& dropped, Array<uint32_t>& added) {
    Array<uint32_t> faces(context.memory), points(context.memory);
    DBRG_PROPAGATE(gather_seam(xyz, mesh, outliers, axis, wall, spacing, context, faces, points));
    // The gathered points and faces renumbered locally, in ascending global index as stitch_seam wants.
    Array<uint32_t> local(context.memory);
    Array<double> seam_xyz(context.memory);
    Array<uint32_t> seam_faces(context.memory);
    if (!local.resize(xyz.size() / 3, 0) || !seam_xyz.reserve(3 * points.size()) ||
        !seam_faces.reserve(3 * faces.size())) {
        return context.fail_out_of_memory();
    }
    for (size_t k = 0; k < points.size(); ++k) {
        local[points[k]] = static_cast<uint32_t>(k);
        for (int a = 0; a < 3; ++a) seam_xyz.push_back(xyz[3 * size_t(points[k]) + a]);
    }
    for (uint32_t f : faces) {
        for (int i = 0; i < 3; ++i) seam_faces.push_back(local[mesh[3 * size_t(f) + i]]);
    }
    local.release();
    Context stitch_context(piece_params(context.params));
    stitch_context.memory.count_in(context.memory.meter());  // the call's peak includes the piece's
    Array<uint32_t> seam_dropped(stitch_context.memory), seam_added(stitch_context.memory);
    const dbrg_status status = stitch_seam(seam_xyz.data(), points.size(), seam_faces.data(), faces.size(), axis,
                                           wall, spacing, stitch_context, seam_dropped, seam_added);
    if (status != DBRG_OK) return context.fail(status, "seam stitch: %s", stitch_context.message());
    add_piece_stats(stitch_context.stats, context.stats);
    context.stats.tile_peak_bytes = std::max(context.stats.tile_peak_bytes, stitch_context.memory.peak_bytes());
    if (!dropped.reserve(dropped.size() + seam_dropped.size()) || !added.reserve(added.size() + seam_added.size())) {
        return context.fail_out_of_memory();
    }
    for (uint32_t f : seam_dropped) dropped.push_back(faces[f]);
    for (uint32_t v : seam_added) added.push_back(points[v]);
    return DBRG_OK;
}

} // namespace

void add_piece_stats(const dbrg_stats& piece, dbrg_stats& total) {
    add_counts(total.tetrahedra, piece.tetrahedra);
    add_counts(total.candidates_evaluated, piece.candidates_evaluated);
    add_counts(total.rejected_edge_nonmanifold, piece.rejected_edge_nonmanifold);
    add_counts(total.rejected_orientation, piece.rejected_orientation);
    add_counts(total.rejected_bowtie, piece.rejected_bowtie);
    add_counts(total.rejected_dihedral, piece.rejected_dihedral);
    add_counts(total.rejected_boundary, piece.rejected_boundary);
    add_counts(total.holes_found, piece.holes_found);
    add_counts(total.holes_filled, piece.holes_filled);
    add_counts(total.holes_left_open, piece.holes_left_open);
    add_counts(total.hole_triangles_delaunay, piece.hole_triangles_delaunay);
    add_counts(total.hole_triangles_added, piece.hole_triangles_added);
    add_counts(total.hole_triangles_removed, piece.hole_triangles_removed);
    add_counts(total.handles_removed, piece.handles_removed);
    add_counts(total.points_inserted, piece.points_inserted);
    add_counts(total.pinch_faces_removed, piece.pinch_faces_removed);
    add_counts(total.predicate_calls, piece.predicate_calls);
    add_counts(total.predicate_filter_failures, piece.predicate_filter_failures);
    add_counts(total.predicate_perturbations, piece.predicate_perturbations);
    total.seconds_sort += piece.seconds_sort;
    total.seconds_delaunay += piece.seconds_delaunay;
    total.seconds_grow += piece.seconds_grow;
    total.seconds_fill_holes += piece.seconds_fill_holes;
    add_counts(total.near_duplicates_merged, piece.near_duplicates_merged);
    add_counts(total.points_smoothed, piece.points_smoothed);
    total.smoothing_iterations = std::max(total.smoothing_iterations, piece.smoothing_iterations);
    total.noise_level = std::max(total.noise_level, piece.noise_level);
    total.seconds_clean += piece.seconds_clean;
}

bool TileCore::contains(const double* p) const {
    for (int axis = 0; axis < 3; ++axis) {
        if (!(p[axis] >= low[axis] && p[axis] < high[axis])) return false;
    }
    return true;
}

bool TileCore::owns(const double* a, const double* b, const double* c) const {
    const double* corners[3] = {a, b, c};
    std::sort(corners, corners + 3,
              [](const double* p, const double* q) { return std::lexicographical_compare(p, p + 3, q, q + 3); });
    for (int axis = 0; axis < 3; ++axis) {
        const double centroid = (corners[0][axis] + corners[1][axis] + corners[2][axis]) / 3;
        if (!(centroid >= low[axis] && centroid < high[axis])) return false;
    }
    return true;
}

dbrg_status reconstruct_tile(const dbrg_points* points, const TileCore& core, Context& context,
                             Array<uint32_t>& owned, Array<uint32_t>& outliers) {
    SurfaceResult surface(context.memory);
    DBRG_PROPAGATE(reconstruct_surface(points, context, surface));
    Array<double> xyz(context.memory);
    DBRG_PROPAGATE(copy_caller_points(points, context, xyz));
    for (uint32_t v : surface.outliers) {
        if (core.contains(&xyz[3 * size_t(v)]) && !outliers.push_back(v)) return context.fail_out_of_memory();
    }
    for (size_t f = 0; f < surface.triangles.size() / 3; ++f) {
        const uint32_t* t = surface.triangles.data() + 3 * f;
        if (!core.owns(&xyz[3 * size_t(t[0])], &xyz[3 * size_t(t[1])], &xyz[3 * size_t(t[2])])) continue;
        for (int i = 0; i < 3; ++i) {
            const uint32_t v = t[i];
            if (!owned.push_back(v)) return context.fail_out_of_memory();
        }
    }
    return DBRG_OK;
}

dbrg_status plan_tiling(const double* xyz, size_t count, uint32_t tile_count, Context& context, TilingPlan& plan) {
    plan.walls.clear();
    DBRG_PROPAGATE(estimate_spacing(xyz, count, context, plan.spacing));
    plan.axis = longest_axis(xyz, count);
    if (tile_count <= 1 || !(plan.spacing > 0)) return DBRG_OK;
    return slab_walls(xyz, count, plan.axis, tile_count, MIN_SLAB_SPACINGS * plan.spacing, context, plan.walls);
}

dbrg_status stitch_seam(const double* xyz, size_t count, const uint32_t* faces, size_t face_count, int axis,
                        double wall, double spacing, Context& context, Array<uint32_t>& dropped,
                        Array<uint32_t>& added) {
    // The band: the points within reach of the wall, and the corners of the faces cut (a long face can
    // reach further where the sampling is uneven). The seeds: the other faces with a corner in the band.
    // The strip's points: the band and the seeds' other corners, which are fixed (their fans are complete
    // outside, far from the faces cut), numbered in the given (global id) order.
    Array<uint8_t> zone(context.memory);
    DBRG_PROPAGATE(zone_points(xyz, count, axis, wall, spacing, context, zone));
    const auto is_cut = [&](const uint32_t* t) {
        return zone[t[0]] == STRIP || zone[t[1]] == STRIP || zone[t[2]] == STRIP;
    };
    for (size_t f = 0; f < face_count; ++f) {
        const uint32_t* t = faces + 3 * f;
        if (!is_cut(t)) continue;
        for (int i = 0; i < 3; ++i) zone[t[i]] = zone[t[i]] == STRIP ? STRIP : BAND;
    }
    const auto is_seed = [&](const uint32_t* t) {
        return !is_cut(t) && (zone[t[0]] != FAR || zone[t[1]] != FAR || zone[t[2]] != FAR);
    };
    // The faces the stitch replaces, oriented alike: the tiles grew theirs each in its own orientation, and
    // the cut faces join the two sides where the tiles meet.
    Array<uint32_t> touched(context.memory);
    for (size_t f = 0; f < face_count; ++f) {
        const uint32_t* t = faces + 3 * f;
        if (!is_cut(t) && !is_seed(t)) continue;
        if (!dropped.push_back(static_cast<uint32_t>(f))) return context.fail_out_of_memory();
        for (int i = 0; i < 3; ++i) {
            if (!touched.push_back(t[i])) return context.fail_out_of_memory();
        }
    }
    DBRG_PROPAGATE(orient_triangles(touched, xyz, false, context));
    Array<uint32_t> local(context.memory);
    if (!local.resize(count, NOT_IN_STRIP)) return context.fail_out_of_memory();
    for (size_t i = 0; i < count; ++i) local[i] = zone[i] != FAR ? 0 : NOT_IN_STRIP;
    for (size_t f = 0; f < touched.size() / 3; ++f) {
        const uint32_t* t = touched.data() + 3 * f;
        if (!is_seed(t)) continue;
        for (int i = 0; i < 3; ++i) local[t[i]] = 0;
    }
    Array<uint32_t> strip_index(context.memory);
    Array<double> strip_xyz(context.memory);
    Array<uint8_t> fixed(context.memory);
    for (size_t i = 0; i < count; ++i) {
        if (local[i] == NOT_IN_STRIP) continue;
        local[i] = static_cast<uint32_t>(strip_index.size());
        if (!strip_index.push_back(static_cast<uint32_t>(i)) || !fixed.push_back(zone[i] == FAR ? 1 : 0)) {
            return context.fail_out_of_memory();
        }
        for (int a = 0; a < 3; ++a) {
            if (!strip_xyz.push_back(xyz[3 * i + a])) return context.fail_out_of_memory();
        }
    }
    Array<uint32_t> seeds(context.memory);
    for (size_t f = 0; f < touched.size() / 3; ++f) {
        const uint32_t* t = touched.data() + 3 * f;
        if (!is_seed(t)) continue;
        for (int i = 0; i < 3; ++i) {
            if (!seeds.push_back(local[t[i]])) return context.fail_out_of_memory();
        }
    }
    touched.release();
    local.release();
    zone.release();

    SurfaceResult grown(context.memory);
    const dbrg_points strip_points = double_points(strip_xyz);
    const dbrg_status status = grow_from_surface(&strip_points, seeds.data(), seeds.size() / 3, fixed.data(),
                                                 context, grown);
    const Array<uint32_t>* strip_faces = &grown.triangles;
    if (status == DBRG_ERR_TOO_FEW_POINTS || status == DBRG_ERR_DEGENERATE_INPUT) {
        strip_faces = &seeds;  // no volume to grow in: the seeds stay as they were
    } else if (status != DBRG_OK) {
        return status;
    }
    if (!added.reserve(added.size() + strip_faces->size())) return context.fail_out_of_memory();
    for (uint32_t v : *strip_faces) added.push_back(strip_index[v]);
    return DBRG_OK;
}

dbrg_status assemble_tiles(Array<double>& xyz, Array<uint32_t>& mesh, const Array<uint32_t>& outliers, Context& context,
                           SurfaceResult& result) {
    // Every pass below goes from face to neighbouring face. The caller's points may come in any order (those
    // of a shuffled cloud put a face's corners anywhere in memory), so they are numbered along the Hilbert
    // curve first, as a single call numbers its own, and the output hands the caller's numbering back.
    const uint32_t count = static_cast<uint32_t>(xyz.size() / 3);
    ConditionedPoints numbered(context.memory);
    DBRG_PROPAGATE(hilbert_order(xyz.data(), count,
                                 ProgressSpan(context, DBRG_STAGE_FILL_HOLES, STITCH_PROGRESS, NUMBERING_PROGRESS),
                                 numbered.input_index));
    {
        Array<uint32_t> vertex_of(context.memory);
        if (!vertex_of.resize(count) || !numbered.coordinates.resize(3 * size_t(count))) {
            return context.fail_out_of_memory();
        }
        for (uint32_t v = 0; v < count; ++v) {
            const uint32_t caller = numbered.input_index[v];
            vertex_of[caller] = v;
            for (int a = 0; a < 3; ++a) numbered.coordinates[3 * size_t(v) + a] = xyz[3 * size_t(caller) + a];
        }
        xyz.release();
        for (uint32_t& corner : mesh) corner = vertex_of[corner];
    }
    DBRG_PROPAGATE(orient_triangles(mesh, numbered.coordinates.data(), true, context));
    Surface surface(context.memory);
    if (!surface.reset(count) || !surface.reserve_faces(mesh.size() / 3)) return context.fail_out_of_memory();
    for (size_t f = 0; f < mesh.size() / 3; ++f) {
        const uint32_t a = mesh[3 * f], b = mesh[3 * f + 1], c = mesh[3 * f + 2];
        const FaceCheck check = surface.check_face(a, b, c);
        if (check.verdict != FaceCheck::valid) {
            ++context.stats.seam_faces_dropped;
            continue;
        }
        if (surface.add_face(a, b, c, NO_TET, check) == NO_FACE) return context.fail_out_of_memory();
    }
    mesh.release();
    Array<uint32_t> removed(context.memory);
    if (!surface.remove_pinches(removed)) return context.fail_out_of_memory();
    context.stats.seam_faces_dropped += static_cast<uint32_t>(removed.size());
    // The small-handle cut needs whole closed components, which no tile or strip holds: it runs here, over
    // the assembled surface, as a single call runs it over its own.
    if (context.params.fill_holes) {
        const BoundaryCauses none_recorded(context.memory);
        HoleFiller filler(numbered.coordinates.data(), surface, none_recorded, context);
        DBRG_PROPAGATE(
            filler.remove_small_handles(ProgressSpan(context, DBRG_STAGE_FILL_HOLES, NUMBERING_PROGRESS, 1.0)));
    }
    DBRG_PROPAGATE(emit_surface(surface, numbered, context, result));
    // Each tile judges the points of its core, from its own points; a neighbouring tile that kept such a
    // point may have joined it to a face it owns, and then it is no outlier of the mesh.
    Array<uint8_t> used(context.memory);
    if (!used.resize(count, 0) || !result.outliers.reserve(outliers.size())) return context.fail_out_of_memory();
    for (uint32_t v : result.triangles) used[v] = 1;
    for (uint32_t v : outliers) {
        if (!used[v]) result.outliers.push_back(v);
    }
    context.stats.outliers = static_cast<uint32_t>(result.outliers.size());
    context.stats.unique_points -= context.stats.outliers;
    return DBRG_OK;
}

dbrg_status reconstruct_tiled(const dbrg_points* points, uint32_t tile_count, Context& context, SurfaceResult& result) {
    context.stats.tiles = 1;
    if (tile_count <= 1) return reconstruct_surface(points, context, result);
    DBRG_PROPAGATE(context.report(DBRG_STAGE_VALIDATE, 0.0));
    Array<double> xyz(context.memory);
    DBRG_PROPAGATE(copy_caller_points(points, context, xyz));
    DBRG_PROPAGATE(check_point_count(points->count, context));
    const size_t count = points->count;
    TilingPlan plan(context.memory);
    DBRG_PROPAGATE(plan_tiling(xyz.data(), count, tile_count, context, plan));
    if (plan.walls.empty()) {
        xyz.release();
        return reconstruct_surface(points, context, result);
    }
    const Array<double>& walls = plan.walls;
    context.stats.tiles = static_cast<uint32_t>(walls.size() + 1);
    context.stats.input_points = static_cast<uint32_t>(count);
    context.stats.unique_points = static_cast<uint32_t>(count);

    Array<uint32_t> mesh(context.memory), outliers(context.memory);
    for (uint32_t k = 0; k < context.stats.tiles; ++k) {
        DBRG_PROPAGATE(context.report(DBRG_STAGE_GROW, double(k) / context.stats.tiles));
        DBRG_PROPAGATE(run_tile(xyz, plan.axis, walls, k, HALO_SPACINGS * plan.spacing, context, mesh, outliers));
    }
    // Every point lies in one core, so no outlier comes twice; the tiles come in order along the axis only.
    std::sort(outliers.begin(), outliers.end());
    // The even walls, then the odd ones: walls of one half are two slabs apart, farther than a stitch
    // reaches, so each stitch of a half sees the faces as they were before the half began, as on a cluster.
    for (size_t half = 0; half < 2; ++half) {
        Array<uint32_t> dropped(context.memory), added(context.memory);
        for (size_t w = half; w < walls.size(); w += 2) {
            const double stitched = double(w / 2 + half * ((walls.size() + 1) / 2)) / walls.size();
            DBRG_PROPAGATE(context.report(DBRG_STAGE_FILL_HOLES, STITCH_PROGRESS * stitched));
            DBRG_PROPAGATE(stitch_wall(xyz, mesh, outliers, plan.axis, walls[w], plan.spacing, context, dropped, added));
        }
        Array<uint8_t> drop(context.memory);
        if (!drop.resize(mesh.size() / 3, 0) || !mesh.reserve(mesh.size() + added.size())) {
            return context.fail_out_of_memory();
        }
        for (uint32_t f : dropped) drop[f] = 1;
        size_t kept = 0;
        for (size_t f = 0; f < mesh.size() / 3; ++f) {
            if (drop[f]) continue;
            for (int i = 0; i < 3; ++i) mesh[3 * kept + i] = mesh[3 * f + i];
            ++kept;
        }
        mesh.shrink(3 * kept);
        for (uint32_t v : added) mesh.push_back(v);
    }
    DBRG_PROPAGATE(assemble_tiles(xyz, mesh, outliers, context, result));
    return context.memory.failed() ? context.fail_out_of_memory() : context.report(DBRG_STAGE_OUTPUT, 1.0);
}

} // namespace dbrg
