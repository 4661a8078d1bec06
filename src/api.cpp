// The C ABI boundary: argument checks, status codes and result objects. The only file with extern "C".
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <algorithm>
#include <new>

#include "core/c_enum.h"
#include "core/params.h"
#include "points/point_input.h"
#include "points/point_conditioning.h"
#include "pipeline.h"
#include "tiles/tiled_reconstruction.h"

using namespace dbrg;

namespace {

// The sizes of dbrg_params that released headers have: 0.1.0 ended before the snapshot fields, 0.2.0 and
// 0.3.0 before the cleaning fields.
const size_t PARAMS_V0_1_SIZE = offsetof(dbrg_params, snapshot);
const size_t PARAMS_V0_2_SIZE = offsetof(dbrg_params, cleaning);

bool known_params_size(size_t size) {
    return size == PARAMS_V0_1_SIZE || size == PARAMS_V0_2_SIZE || size == sizeof(dbrg_params);
}

void write_message(char* message, size_t capacity, const char* text) {
    if (message && capacity > 0) snprintf(message, capacity, "%s", text);
}

// Copies the caller's parameters over the defaults, honouring a struct_size from an older header.
dbrg_status read_params(const dbrg_params* given, dbrg_params& params, char* message, size_t capacity) {
    fill_default_params(params);
    if (!given) return DBRG_OK;
    const dbrg_status status = dbrg_params_validate(given, message, capacity);
    if (status != DBRG_OK) return status;
    memcpy(&params, given, given->struct_size < sizeof params ? given->struct_size : sizeof params);
    params.struct_size = sizeof params;
    return DBRG_OK;
}

// Allocates a result object of type T (a ResultBase) from the caller's allocator.
template <class T>
T* create_result(const dbrg_params& params) {
    Memory bootstrap(params.allocator);
    void* block = bootstrap.allocate(sizeof(T));
    return block ? new (block) T(params.allocator) : nullptr;
}

template <class T>
void destroy_result(T* result) {
    if (!result) return;
    Memory bootstrap(result->allocator_copy_valid ? &result->allocator_copy : nullptr);
    result->~T();
    bootstrap.release(result, sizeof(T));
}

// Starts a call that hands back a result object: reads the parameters and creates the object, which
// carries the parameter problem if there is one. NULL when the object itself cannot be allocated.
template <class Result>
Result* open_result(const dbrg_params* given, dbrg_params& params) {
    char message[256];
    const dbrg_status status = read_params(given, params, message, sizeof message);
    if (status != DBRG_OK) fill_default_params(params);  // bad params may carry a bad allocator
    Result* result = create_result<Result>(params);
    if (result && status != DBRG_OK) result->record(status, message);
    return result;
}

// A successful result that leaves most points out is almost always a parameter set too tight: say so,
// since nothing else would (the status is DBRG_OK). Empty when the surface uses at least half the points.
void left_out_warning(const dbrg_stats& stats, const dbrg_params& params, char* text, size_t capacity) {
    text[0] = '\0';
    if (stats.vertices_used >= stats.unique_points / 2) return;
    const int length = snprintf(text, capacity, "warning: only %u of %u distinct points are in the surface",
                                stats.vertices_used, stats.unique_points);
    if (stats.rejected_boundary > 0 && length > 0 && size_t(length) < capacity) {
        snprintf(text + length, capacity - size_t(length),
                 "; the open-surface test refused %llu candidates (boundary_factor %g is tight; the default is 3)",
                 static_cast<unsigned long long>(stats.rejected_boundary), params.boundary_factor);
    }
}

} // namespace

// Result objects hold their arrays in a Memory built on the caller's allocator, so they outlive the call,
// and the status and message of the call that made them.
struct ResultBase {
    explicit ResultBase(const dbrg_allocator* allocator)
        : allocator_copy(allocator ? *allocator : dbrg_allocator{}), allocator_copy_valid(allocator != nullptr),
          memory(allocator) {
        message[0] = '\0';
    }
    void record(dbrg_status outcome, const char* text) {
        status = outcome;
        snprintf(message, sizeof message, "%s", text);
    }
    dbrg_allocator allocator_copy;
    bool allocator_copy_valid;
    Memory memory;
    dbrg_status status = DBRG_OK;
    char message[256];
};

struct dbrg_mesh : ResultBase {
    explicit dbrg_mesh(const dbrg_allocator* allocator) : ResultBase(allocator), surface(memory) {
        memset(&stats, 0, sizeof stats);
        stats.struct_size = sizeof stats;
    }
    SurfaceResult surface;
    uint32_t point_count = 0;
    dbrg_stats stats;
};

struct dbrg_tile_mesh : ResultBase {
    explicit dbrg_tile_mesh(const dbrg_allocator* allocator)
        : ResultBase(allocator), triangles(memory), dropped(memory), outliers(memory) {
        memset(&stats, 0, sizeof stats);
        stats.struct_size = sizeof stats;
    }
    Array<uint64_t> triangles;  // global ids
    Array<uint64_t> dropped;    // a seam stitch's: indices into its faces
    Array<uint64_t> outliers;   // a tile's: global ids of its core's outliers
    dbrg_stats stats;
};

struct dbrg_tetrahedralization : ResultBase {
    explicit dbrg_tetrahedralization(const dbrg_allocator* allocator) : ResultBase(allocator), result(memory) {}
    TetrahedraResult result;
};

namespace {

// Copies `from` into the caller's stats, up to its struct_size.
dbrg_status copy_stats(const dbrg_stats& from, dbrg_stats& to) {
    const size_t size = to.struct_size < sizeof from ? to.struct_size : sizeof from;
    memcpy(&to, &from, size);
    to.struct_size = size;
    return DBRG_OK;
}

// The caller's global ids `wanted` as indices into its `count` points with ids `ids` (count, one past the
// last index, for an id not among them).
dbrg_status local_indices(const uint64_t* ids, size_t count, const uint64_t* wanted, size_t wanted_count,
                          Context& context, Array<uint32_t>& local) {
    struct IdIndex {
        uint64_t id;
        uint32_t index;
    };
    Array<IdIndex> by_id(context.memory);
    if (!by_id.resize(count) || !local.resize(wanted_count)) return context.fail_out_of_memory();
    for (size_t i = 0; i < count; ++i) by_id[i] = IdIndex{ids[i], static_cast<uint32_t>(i)};
    std::sort(by_id.begin(), by_id.end(), [](const IdIndex& a, const IdIndex& b) { return a.id < b.id; });
    for (size_t i = 0; i < wanted_count; ++i) {
        const IdIndex* at = std::lower_bound(by_id.begin(), by_id.end(), wanted[i],
                                             [](const IdIndex& e, uint64_t id) { return e.id < id; });
        local[i] = at != by_id.end() && at->id == wanted[i] ? at->index : static_cast<uint32_t>(count);
    }
    return DBRG_OK;
}

// dbrg_mesh_assemble's outliers, checked against its `count` points: sorted, each once, into `left_out`.
dbrg_status read_outliers(const uint32_t* outliers, size_t outlier_count, size_t count, Context& context,
                          Array<uint32_t>& left_out) {
    if (outlier_count > 0 && !outliers) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "outliers is NULL with an outlier_count of %zu", outlier_count);
    }
    if (!left_out.reserve(outlier_count)) return context.fail_out_of_memory();
    for (size_t i = 0; i < outlier_count; ++i) {
        if (outliers[i] >= count) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "outlier %zu is the index %u, past the %zu points", i,
                                outliers[i], count);
        }
        left_out.push_back(outliers[i]);
    }
    std::sort(left_out.begin(), left_out.end());
    left_out.shrink(static_cast<size_t>(std::unique(left_out.begin(), left_out.end()) - left_out.begin()));
    return DBRG_OK;
}

// Reads a dbrg_tiling's axis and spacing, checked.
dbrg_status read_tiling(const dbrg_tiling* tiling, Context& context, int& axis, double& spacing) {
    if (!tiling) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "tiling is NULL");
    if (tiling->struct_size < sizeof(dbrg_tiling)) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "tiling->struct_size is %zu; this library needs %zu",
                            tiling->struct_size, sizeof(dbrg_tiling));
    }
    if (tiling->axis > 2) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "tiling->axis is %u; 0, 1 or 2", tiling->axis);
    if (!(tiling->spacing > 0 && tiling->spacing < HUGE_VAL)) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "tiling->spacing is %g; a positive finite length", tiling->spacing);
    }
    axis = static_cast<int>(tiling->axis);
    spacing = tiling->spacing;
    return DBRG_OK;
}

// The caller's points in ascending order of their ids, `sorted` (3 doubles each), and `faces` (global ids)
// as indices into them. `order[k]` is the caller's index of sorted point k.
dbrg_status sort_by_id(const Array<double>& xyz, const uint64_t* ids, const uint64_t* faces, size_t face_count,
                       Context& context, Array<uint32_t>& order, Array<double>& sorted, Array<uint32_t>& local_faces) {
    const size_t count = xyz.size() / 3;
    Array<uint64_t> sorted_ids(context.memory);
    if (!order.resize(count) || !sorted.resize(3 * count) || !sorted_ids.resize(count) ||
        !local_faces.resize(3 * face_count)) {
        return context.fail_out_of_memory();
    }
    for (size_t i = 0; i < count; ++i) order[i] = static_cast<uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return ids[a] < ids[b]; });
    for (size_t k = 0; k < count; ++k) {
        sorted_ids[k] = ids[order[k]];
        if (k > 0 && sorted_ids[k] == sorted_ids[k - 1]) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "point_ids repeats the id %llu",
                                static_cast<unsigned long long>(sorted_ids[k]));
        }
        for (int a = 0; a < 3; ++a) sorted[3 * k + a] = xyz[3 * size_t(order[k]) + a];
    }
    for (size_t i = 0; i < 3 * face_count; ++i) {
        const uint64_t* at = std::lower_bound(sorted_ids.begin(), sorted_ids.end(), faces[i]);
        if (at == sorted_ids.end() || *at != faces[i]) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "face %zu uses the id %llu, which is not among point_ids",
                                i / 3, static_cast<unsigned long long>(faces[i]));
        }
        local_faces[i] = static_cast<uint32_t>(at - sorted_ids.begin());
        if (i % 3 == 2 && (local_faces[i] == local_faces[i - 1] || local_faces[i] == local_faces[i - 2] ||
                           local_faces[i - 1] == local_faces[i - 2])) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "face %zu repeats a corner", i / 3);
        }
    }
    return DBRG_OK;
}

// A call that hands back a dbrg_tile_mesh: `work(context, triangles, mesh)` writes triangles as indices
// into `points`, handed back as their global ids, and (a stitch) the indices of the faces it drops or (a
// tile) its outliers into `mesh`. A surface needs 4 points; a stitch (`any_count`) takes fewer, and has
// nothing to grow then.
template <class Work>
dbrg_status run_tile_call(const dbrg_points* points, const uint64_t* ids, const dbrg_params* given,
                          dbrg_tile_mesh** out, bool any_count, const Work& work) {
    if (!out) return DBRG_ERR_INVALID_ARGUMENT;
    dbrg_params params;
    dbrg_tile_mesh* mesh = *out = open_result<dbrg_tile_mesh>(given, params);
    if (!mesh) return DBRG_ERR_OUT_OF_MEMORY;
    if (mesh->status != DBRG_OK) return mesh->status;
    MemoryMeter meter;
    Context context(params);
    context.memory.count_in(&meter);
    mesh->memory.count_in(&meter);
    const double start = seconds_now();
    dbrg_status status = DBRG_OK;
    if (!points || (!ids && points->count > 0)) {
        status = context.fail(DBRG_ERR_INVALID_ARGUMENT, !points ? "points is NULL" : "point_ids is NULL");
    } else {
        status = any_count ? check_not_too_many_points(points->count, context) : check_point_count(points->count, context);
    }
    Array<uint32_t> triangles(context.memory);
    if (status == DBRG_OK) status = work(context, triangles, *mesh);
    if (status != DBRG_OK) {
        mesh->dropped.release();
        mesh->outliers.release();
    }
    if (status == DBRG_OK && !mesh->triangles.reserve(triangles.size())) status = context.fail_out_of_memory();
    if (status == DBRG_OK) {
        for (uint32_t v : triangles) mesh->triangles.push_back(ids[v]);
    }
    triangles.release();
    mesh->memory.count_in(nullptr);
    mesh->stats = context.stats;
    mesh->stats.seconds_total = seconds_now() - start;
    mesh->stats.peak_bytes = meter.peak;
    mesh->record(status, status == DBRG_OK ? "" : context.message());
    return status;
}

// A call that hands back a dbrg_mesh: `work(context, surface)` fills the surface and context.stats.
template <class Work>
dbrg_status run_mesh_call(const dbrg_points* points, const dbrg_params* given, dbrg_mesh** out_mesh, const Work& work) {
    if (!out_mesh) return DBRG_ERR_INVALID_ARGUMENT;
    dbrg_params params;
    dbrg_mesh* mesh = *out_mesh = open_result<dbrg_mesh>(given, params);
    if (!mesh) return DBRG_ERR_OUT_OF_MEMORY;
    if (mesh->status != DBRG_OK) return mesh->status;
    MemoryMeter meter;  // the working memory and the result's together: the pipeline frees the one before the other grows
    Context context(params);
    context.memory.count_in(&meter);
    mesh->memory.count_in(&meter);
    const double start = seconds_now();
    const dbrg_status status = work(context, mesh->surface);
    if (status != DBRG_OK) mesh->surface = SurfaceResult(mesh->memory);
    mesh->memory.count_in(nullptr);
    mesh->point_count = status == DBRG_OK ? static_cast<uint32_t>(points->count) : 0;
    mesh->stats = context.stats;
    mesh->stats.seconds_total = seconds_now() - start;
    mesh->stats.peak_bytes = meter.peak;
    char warning[sizeof mesh->message];
    if (status == DBRG_OK) left_out_warning(mesh->stats, params, warning, sizeof warning);
    mesh->record(status, status == DBRG_OK ? warning : context.message());
    return status;
}

} // namespace

extern "C" {

DBRG_API uint32_t dbrg_version_number(void) { return DBRG_VERSION_NUMBER; }

DBRG_API const char* dbrg_version_string(void) { return DBRG_VERSION_STRING; }

DBRG_API const char* dbrg_status_string(dbrg_status status) {
    switch (c_enum_value(status)) {
    case DBRG_OK: return "DBRG_OK";
    case DBRG_ERR_INVALID_ARGUMENT: return "DBRG_ERR_INVALID_ARGUMENT";
    case DBRG_ERR_INVALID_PARAMETER: return "DBRG_ERR_INVALID_PARAMETER";
    case DBRG_ERR_NON_FINITE_INPUT: return "DBRG_ERR_NON_FINITE_INPUT";
    case DBRG_ERR_TOO_FEW_POINTS: return "DBRG_ERR_TOO_FEW_POINTS";
    case DBRG_ERR_DEGENERATE_INPUT: return "DBRG_ERR_DEGENERATE_INPUT";
    case DBRG_ERR_TOO_MANY_POINTS: return "DBRG_ERR_TOO_MANY_POINTS";
    case DBRG_ERR_OUT_OF_MEMORY: return "DBRG_ERR_OUT_OF_MEMORY";
    case DBRG_ERR_CANCELLED: return "DBRG_ERR_CANCELLED";
    case DBRG_ERR_UNSUPPORTED: return "DBRG_ERR_UNSUPPORTED";
    case DBRG_ERR_INTERNAL: return "DBRG_ERR_INTERNAL";
    }
    return "DBRG_STATUS_UNKNOWN";
}

DBRG_API dbrg_status dbrg_params_init_sized(dbrg_params* params, size_t struct_size) {
    if (!params || !(known_params_size(struct_size) || struct_size > sizeof(dbrg_params))) return DBRG_ERR_INVALID_ARGUMENT;
    dbrg_params defaults;
    fill_default_params(defaults);
    const size_t filled = struct_size < sizeof defaults ? struct_size : sizeof defaults;
    defaults.struct_size = filled;
    memcpy(params, &defaults, filled);
    return DBRG_OK;
}

DBRG_API dbrg_status dbrg_params_validate(const dbrg_params* params, char* message, size_t capacity) {
    write_message(message, capacity, "");
    if (!params) {
        write_message(message, capacity, "params is NULL");
        return DBRG_ERR_INVALID_ARGUMENT;
    }
    if (!known_params_size(params->struct_size)) {
        char text[200];
        snprintf(text, sizeof text,
                 "params->struct_size is %zu; this library (%s) knows sizes %zu, %zu and %zu: call dbrg_params_init first",
                 params->struct_size, DBRG_VERSION_STRING, PARAMS_V0_1_SIZE, PARAMS_V0_2_SIZE, sizeof(dbrg_params));
        write_message(message, capacity, text);
        return DBRG_ERR_INVALID_ARGUMENT;
    }
    // Checked as the library will use them: the caller's bytes over the defaults, never past its struct.
    dbrg_params effective;
    fill_default_params(effective);
    memcpy(&effective, params, params->struct_size);
    const char* problem = find_parameter_problem(effective);
    if (!problem) return DBRG_OK;
    write_message(message, capacity, problem);
    return DBRG_ERR_INVALID_PARAMETER;
}

DBRG_API dbrg_status dbrg_points_validate(const dbrg_points* points, const dbrg_allocator* allocator, char* message,
                                          size_t capacity) {
    dbrg_params params;
    fill_default_params(params);
    params.allocator = allocator;
    Context context(params);
    Array<double> xyz(context.memory);
    dbrg_status status = copy_caller_points(points, context, xyz);
    if (status == DBRG_OK) {
        ConditionedPoints conditioned(context.memory);
        status = condition_points(xyz.data(), points->count, context, conditioned);
    }
    write_message(message, capacity, status == DBRG_OK ? "" : context.message());
    return status;
}

DBRG_API dbrg_status dbrg_reconstruct(const dbrg_points* points, const dbrg_params* given, dbrg_mesh** out_mesh) {
    return run_mesh_call(points, given, out_mesh, [&](Context& context, SurfaceResult& surface) {
        return reconstruct_surface(points, context, surface);
    });
}

DBRG_API void dbrg_mesh_destroy(dbrg_mesh* mesh) { destroy_result(mesh); }

DBRG_API dbrg_status dbrg_mesh_status(const dbrg_mesh* mesh) { return mesh ? mesh->status : DBRG_ERR_INVALID_ARGUMENT; }

DBRG_API const char* dbrg_mesh_message(const dbrg_mesh* mesh) { return mesh ? mesh->message : ""; }

DBRG_API uint32_t dbrg_mesh_point_count(const dbrg_mesh* mesh) { return mesh ? mesh->point_count : 0; }

DBRG_API uint32_t dbrg_mesh_triangle_count(const dbrg_mesh* mesh) {
    return mesh ? static_cast<uint32_t>(mesh->surface.triangles.size() / 3) : 0;
}

DBRG_API const uint32_t* dbrg_mesh_triangles(const dbrg_mesh* mesh) {
    return mesh && !mesh->surface.triangles.empty() ? mesh->surface.triangles.data() : nullptr;
}

DBRG_API const uint8_t* dbrg_mesh_face_flags(const dbrg_mesh* mesh) {
    return mesh && !mesh->surface.face_flags.empty() ? mesh->surface.face_flags.data() : nullptr;
}

DBRG_API uint32_t dbrg_mesh_boundary_loop_count(const dbrg_mesh* mesh) {
    return mesh && !mesh->surface.loop_offsets.empty() ? static_cast<uint32_t>(mesh->surface.loop_offsets.size() - 1) : 0;
}

DBRG_API const uint32_t* dbrg_mesh_boundary_loop(const dbrg_mesh* mesh, uint32_t loop, uint32_t* out_count) {
    if (out_count) *out_count = 0;
    if (loop >= dbrg_mesh_boundary_loop_count(mesh)) return nullptr;
    const uint32_t begin = mesh->surface.loop_offsets[loop];
    if (out_count) *out_count = mesh->surface.loop_offsets[loop + 1] - begin;
    return mesh->surface.loop_vertices.data() + begin;
}

DBRG_API const uint32_t* dbrg_mesh_outliers(const dbrg_mesh* mesh, uint32_t* out_count) {
    const uint32_t count = mesh ? static_cast<uint32_t>(mesh->surface.outliers.size()) : 0;
    if (out_count) *out_count = count;
    return count > 0 ? mesh->surface.outliers.data() : nullptr;
}

DBRG_API const double* dbrg_mesh_smoothed_points(const dbrg_mesh* mesh) {
    return mesh && !mesh->surface.smoothed_points.empty() ? mesh->surface.smoothed_points.data() : nullptr;
}

DBRG_API dbrg_status dbrg_mesh_stats(const dbrg_mesh* mesh, dbrg_stats* stats) {
    if (!mesh || !stats || stats->struct_size < sizeof(size_t)) return DBRG_ERR_INVALID_ARGUMENT;
    return copy_stats(mesh->stats, *stats);
}

DBRG_API dbrg_status dbrg_reconstruct_tiled(const dbrg_points* points, uint32_t tile_count, const dbrg_params* given,
                                            dbrg_mesh** out_mesh) {
    return run_mesh_call(points, given, out_mesh, [&](Context& context, SurfaceResult& surface) {
        return reconstruct_tiled(points, tile_count, context, surface);
    });
}

DBRG_API dbrg_status dbrg_reconstruct_tile(const dbrg_points* points, const uint64_t* point_ids, const double* core_low,
                                           const double* core_high, const dbrg_params* given, dbrg_tile_mesh** out) {
    return run_tile_call(points, point_ids, given, out, false, [&](Context& context, Array<uint32_t>& triangles,
                                                                   dbrg_tile_mesh& mesh) {
        if (!core_low || !core_high) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "core_low or core_high is NULL");
        TileCore core;
        for (int axis = 0; axis < 3; ++axis) {
            core.low[axis] = core_low[axis];
            core.high[axis] = core_high[axis];
        }
        Array<uint32_t> outliers(context.memory);
        DBRG_PROPAGATE(reconstruct_tile(points, core, context, triangles, outliers));
        if (!mesh.outliers.reserve(outliers.size())) return context.fail_out_of_memory();
        for (uint32_t v : outliers) mesh.outliers.push_back(point_ids[v]);
        std::sort(mesh.outliers.begin(), mesh.outliers.end());  // the ids need not ascend with the points
        return DBRG_OK;
    });
}

DBRG_API dbrg_status dbrg_grow_from_surface(const dbrg_points* points, const uint64_t* point_ids,
                                            const uint64_t* seed_triangles, size_t seed_count, const uint8_t* fixed,
                                            const dbrg_params* given, dbrg_tile_mesh** out) {
    return run_tile_call(points, point_ids, given, out, false, [&](Context& context, Array<uint32_t>& triangles,
                                                                   dbrg_tile_mesh&) {
        if (seed_count > 0 && !seed_triangles) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "seed_triangles is NULL with a seed_count of %zu",
                                seed_count);
        }
        if (seed_count > SIZE_MAX / 3) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "seed_count is too large");
        Array<uint32_t> seeds(context.memory);
        DBRG_PROPAGATE(local_indices(point_ids, points->count, seed_triangles, 3 * seed_count, context, seeds));
        SurfaceResult surface(context.memory);
        DBRG_PROPAGATE(grow_from_surface(points, seeds.data(), seed_count, fixed, context, surface));
        triangles.swap(surface.triangles);
        return DBRG_OK;
    });
}

DBRG_API dbrg_status dbrg_tiling_plan(const dbrg_points* points, uint32_t tile_count, const dbrg_params* given,
                                      dbrg_tiling* tiling, double* walls, char* message, size_t capacity) {
    dbrg_params params;
    dbrg_status status = read_params(given, params, message, capacity);
    if (status != DBRG_OK) return status;
    Context context(params);
    if (!tiling || (tile_count > 1 && !walls)) {
        status = context.fail(DBRG_ERR_INVALID_ARGUMENT, !tiling ? "tiling is NULL" : "walls is NULL with a tile_count of %u",
                              tile_count);
    } else if (tiling->struct_size < sizeof(dbrg_tiling)) {
        status = context.fail(DBRG_ERR_INVALID_ARGUMENT, "tiling->struct_size is %zu; this library needs %zu",
                              tiling->struct_size, sizeof(dbrg_tiling));
    }
    Array<double> xyz(context.memory);
    if (status == DBRG_OK) status = copy_caller_points(points, context, xyz);
    if (status == DBRG_OK) status = check_point_count(points->count, context);
    TilingPlan plan(context.memory);
    if (status == DBRG_OK) status = plan_tiling(xyz.data(), points->count, tile_count, context, plan);
    if (status == DBRG_OK) {
        tiling->axis = static_cast<uint32_t>(plan.axis);
        tiling->wall_count = static_cast<uint32_t>(plan.walls.size());
        tiling->spacing = plan.spacing;
        tiling->halo = HALO_SPACINGS * plan.spacing;
        tiling->seam_reach = (STRIP_SPACINGS + MARGIN_SPACINGS) * plan.spacing;
        for (size_t w = 0; w < plan.walls.size(); ++w) walls[w] = plan.walls[w];
    }
    write_message(message, capacity, status == DBRG_OK ? "" : context.message());
    return status;
}

DBRG_API dbrg_status dbrg_seam_stitch(const dbrg_points* points, const uint64_t* point_ids, const uint64_t* faces,
                                      size_t face_count, const dbrg_tiling* tiling, double wall,
                                      const dbrg_params* given, dbrg_tile_mesh** out) {
    return run_tile_call(points, point_ids, given, out, true,
                         [&](Context& context, Array<uint32_t>& triangles, dbrg_tile_mesh& mesh) {
        int axis;
        double spacing;
        DBRG_PROPAGATE(read_tiling(tiling, context, axis, spacing));
        if (!(fabs(wall) < HUGE_VAL)) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "wall is %g; a finite position", wall);
        if (face_count > 0 && !faces) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "faces is NULL with a face_count of %zu", face_count);
        }
        if (face_count > UINT32_MAX / 3) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "face_count is too large");
        Array<double> xyz(context.memory), sorted(context.memory);
        const dbrg_status read = copy_caller_points(points, context, xyz);
        if (read != DBRG_OK && read != DBRG_ERR_TOO_FEW_POINTS) return read;  // fewer than 4 are copied, and fine
        Array<uint32_t> order(context.memory), local_faces(context.memory);
        DBRG_PROPAGATE(sort_by_id(xyz, point_ids, faces, face_count, context, order, sorted, local_faces));
        xyz.release();
        Array<uint32_t> seam_dropped(context.memory);
        DBRG_PROPAGATE(stitch_seam(sorted.data(), points->count, local_faces.data(), face_count, axis, wall, spacing,
                                   context, seam_dropped, triangles));
        for (uint32_t& v : triangles) v = order[v];  // back to the caller's indexing
        if (!mesh.dropped.reserve(seam_dropped.size())) return context.fail_out_of_memory();
        for (uint32_t f : seam_dropped) mesh.dropped.push_back(f);
        return DBRG_OK;
    });
}

DBRG_API dbrg_status dbrg_mesh_assemble(const dbrg_points* points, const uint32_t* triangles, size_t triangle_count,
                                        const uint32_t* outliers, size_t outlier_count, const dbrg_params* given,
                                        dbrg_mesh** out_mesh) {
    return run_mesh_call(points, given, out_mesh, [&](Context& context, SurfaceResult& surface) {
        Array<double> xyz(context.memory);
        DBRG_PROPAGATE(copy_caller_points(points, context, xyz));
        DBRG_PROPAGATE(check_point_count(points->count, context));
        if (triangle_count > 0 && !triangles) {
            return context.fail(DBRG_ERR_INVALID_ARGUMENT, "triangles is NULL with a triangle_count of %zu",
                                triangle_count);
        }
        if (triangle_count > UINT32_MAX / 3) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "triangle_count is too large");
        Array<uint32_t> mesh(context.memory);
        if (!mesh.resize(3 * triangle_count)) return context.fail_out_of_memory();
        for (size_t i = 0; i < 3 * triangle_count; ++i) {
            if (triangles[i] >= points->count) {
                return context.fail(DBRG_ERR_INVALID_ARGUMENT, "triangle %zu uses the index %u, past the %zu points",
                                    i / 3, triangles[i], points->count);
            }
            mesh[i] = triangles[i];
            // A surface has no such face (it would corrupt the surface's fans).
            if (i % 3 == 2 && (mesh[i] == mesh[i - 1] || mesh[i] == mesh[i - 2] || mesh[i - 1] == mesh[i - 2])) {
                return context.fail(DBRG_ERR_INVALID_ARGUMENT, "triangle %zu repeats a corner", i / 3);
            }
        }
        Array<uint32_t> left_out(context.memory);
        DBRG_PROPAGATE(read_outliers(outliers, outlier_count, points->count, context, left_out));
        context.stats.input_points = static_cast<uint32_t>(points->count);
        context.stats.unique_points = static_cast<uint32_t>(points->count);
        return assemble_tiles(xyz, mesh, left_out, context, surface);
    });
}

DBRG_API void dbrg_tile_mesh_destroy(dbrg_tile_mesh* mesh) { destroy_result(mesh); }

DBRG_API const uint64_t* dbrg_tile_mesh_outliers(const dbrg_tile_mesh* mesh, uint64_t* out_count) {
    const uint64_t count = mesh ? mesh->outliers.size() : 0;
    if (out_count) *out_count = count;
    return count > 0 ? mesh->outliers.data() : nullptr;
}

DBRG_API dbrg_status dbrg_tile_mesh_status(const dbrg_tile_mesh* mesh) {
    return mesh ? mesh->status : DBRG_ERR_INVALID_ARGUMENT;
}

DBRG_API const char* dbrg_tile_mesh_message(const dbrg_tile_mesh* mesh) { return mesh ? mesh->message : ""; }

DBRG_API uint64_t dbrg_tile_mesh_triangle_count(const dbrg_tile_mesh* mesh) {
    return mesh ? mesh->triangles.size() / 3 : 0;
}

DBRG_API const uint64_t* dbrg_tile_mesh_triangles(const dbrg_tile_mesh* mesh) {
    return mesh && !mesh->triangles.empty() ? mesh->triangles.data() : nullptr;
}

DBRG_API const uint64_t* dbrg_tile_mesh_dropped(const dbrg_tile_mesh* mesh, uint64_t* out_count) {
    const uint64_t count = mesh ? mesh->dropped.size() : 0;
    if (out_count) *out_count = count;
    return count > 0 ? mesh->dropped.data() : nullptr;
}

DBRG_API dbrg_status dbrg_tile_mesh_stats(const dbrg_tile_mesh* mesh, dbrg_stats* stats) {
    if (!mesh || !stats || stats->struct_size < sizeof(size_t)) return DBRG_ERR_INVALID_ARGUMENT;
    return copy_stats(mesh->stats, *stats);
}

DBRG_API dbrg_status dbrg_stats_add_piece(dbrg_stats* total, const dbrg_stats* piece) {
    // Every caller has the fields of 0.5.0, which brought this function; a caller's struct may be shorter or
    // longer than this library's, and only what both hold is read and written.
    constexpr size_t FIRST_SIZE = offsetof(dbrg_stats, points_inserted) + sizeof(uint32_t);
    if (!total || !piece || total->struct_size < FIRST_SIZE || piece->struct_size < FIRST_SIZE) {
        return DBRG_ERR_INVALID_ARGUMENT;
    }
    dbrg_stats whole{}, part{};
    memcpy(&whole, total, std::min(total->struct_size, sizeof whole));
    memcpy(&part, piece, std::min(piece->struct_size, sizeof part));
    add_piece_stats(part, whole);
    whole.tile_peak_bytes = std::max(whole.tile_peak_bytes, part.peak_bytes);
    memcpy(total, &whole, std::min(total->struct_size, sizeof whole));
    return DBRG_OK;
}

DBRG_API dbrg_status dbrg_tetrahedralize(const dbrg_points* points, const dbrg_params* given,
                                         dbrg_tetrahedralization** out) {
    if (!out) return DBRG_ERR_INVALID_ARGUMENT;
    dbrg_params params;
    dbrg_tetrahedralization* tets = *out = open_result<dbrg_tetrahedralization>(given, params);
    if (!tets) return DBRG_ERR_OUT_OF_MEMORY;
    if (tets->status != DBRG_OK) return tets->status;
    Context context(params);
    const dbrg_status status = tetrahedralize_points(points, context, tets->result);
    if (status != DBRG_OK) tets->result = TetrahedraResult(tets->memory);
    tets->record(status, status == DBRG_OK ? "" : context.message());
    return status;
}

DBRG_API void dbrg_tetrahedralization_destroy(dbrg_tetrahedralization* tets) { destroy_result(tets); }

DBRG_API dbrg_status dbrg_tetrahedralization_status(const dbrg_tetrahedralization* tets) {
    return tets ? tets->status : DBRG_ERR_INVALID_ARGUMENT;
}

DBRG_API const char* dbrg_tetrahedralization_message(const dbrg_tetrahedralization* tets) {
    return tets ? tets->message : "";
}

DBRG_API uint32_t dbrg_tetrahedralization_tet_count(const dbrg_tetrahedralization* tets) {
    return tets ? static_cast<uint32_t>(tets->result.tets.size() / 4) : 0;
}

DBRG_API const uint32_t* dbrg_tetrahedralization_tets(const dbrg_tetrahedralization* tets) {
    return tets && !tets->result.tets.empty() ? tets->result.tets.data() : nullptr;
}

DBRG_API const uint32_t* dbrg_tetrahedralization_adjacency(const dbrg_tetrahedralization* tets) {
    return tets && !tets->result.adjacency.empty() ? tets->result.adjacency.data() : nullptr;
}

DBRG_API uint32_t dbrg_tetrahedralization_unique_point_count(const dbrg_tetrahedralization* tets) {
    return tets ? tets->result.unique_points : 0;
}

} // extern "C"
