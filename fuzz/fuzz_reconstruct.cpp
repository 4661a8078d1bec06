// Fuzz target: dbrg_reconstruct on produced points and parameters (in and outside their valid ranges).
// Checks that the status is the one the input calls for; that a successful mesh is an oriented manifold
// over valid, canonical indices whose boundary loops are its boundary edges; that nothing leaks and the
// allocator contract holds on every path, with an allocation failure or a cancellation injected at a
// chosen step; and that reversing the input order, changing its layout or scaling it keeps the result.
#include <math.h>
#include <string.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/pi.h"
#include "dbrg/dbrg.h"
#include "exact_geometry.h"
#include "fuzz_check.h"
#include "fuzz_input.h"
#include "measure/mesh_report.h"
#include "point_producer.h"
#include "support/counting_allocator.h"

using namespace dbrg;
using namespace dbrg::fuzz;

namespace {

// Bugs show on small sets (the ones found so far had 6 to 74 points); small inputs run many times faster.
const size_t MAX_POINTS = 600;
const double NAN_VALUE = __builtin_nan("");
const double INF_VALUE = __builtin_inf();

const double SLIVER_ANGLES[] = {5 * PI / 6, 2.0, 3.1, PI / 2 + 1e-12, PI - 1e-12, PI / 2, PI, 0.0, -2.0, NAN_VALUE, INF_VALUE};
const double BOUNDARY_FACTORS[] = {3.0, 0.0, 1.5, 100.0, 1.0 + 0x1p-52, 1e300, 1.0, 0.5, -3.0, NAN_VALUE, INF_VALUE};
const uint32_t HOLE_EDGES[] = {64, 3, 4, 1000, UINT32_MAX, 2, 0};
const uint32_t COMPONENTS[] = {64, 1, 2, UINT32_MAX, 0};
const uint32_t ENUM_VALUES[] = {0, 1, 0, 1, 2, UINT32_MAX};
const uint32_t THREADS[] = {1, 0, 2, 4};
const uint32_t SNAPSHOT_COUNTS[] = {0, 0, 1, 3, 64, UINT32_MAX};
// Ours, a newer caller's, a 0.1.0 caller's (without the snapshot fields), and three sizes no version has.
const size_t STRUCT_SIZES[] = {sizeof(dbrg_params), sizeof(dbrg_params), sizeof(dbrg_params) + 8,
                               offsetof(dbrg_params, snapshot), offsetof(dbrg_params, snapshot) - 8,
                               offsetof(dbrg_params, snapshot) + 4, 0};

enum class Fault { none, fail_one_allocation, fail_allocations_from, cancel };
enum class Variant { none, reversed, relaid, rescaled };
enum class Mangle { none, short_stride, bad_type, null_data, lying_count, overflowing_stride };

std::string status_text(dbrg_status got, dbrg_status expected) {
    return std::string("got ") + dbrg_status_string(got) + ", expected " + dbrg_status_string(expected);
}

// Progress reports: arguments checked, and a cancellation at the chosen call.
struct ProgressProbe {
    uint64_t calls = 0;
    uint64_t cancel_at = 0;  // 0: never
    bool cancelled = false;

    static int report(void* user, dbrg_stage stage, double fraction) {
        ProgressProbe& self = *static_cast<ProgressProbe*>(user);
        FUZZ_CHECK(stage >= DBRG_STAGE_VALIDATE && stage <= DBRG_STAGE_CLEAN);
        FUZZ_CHECK(fraction >= 0.0 && fraction <= 1.0);
        FUZZ_CHECK_WHY(!self.cancelled, "the progress callback was called again after it cancelled");
        if (++self.calls == self.cancel_at) self.cancelled = true;
        return self.cancelled ? 1 : 0;
    }
};

// Checks every growth snapshot: at most the count asked for, triangles over the caller's points, the share
// of points reached within [0, 1] (it may fall: removing a pinch gives points back).
struct SnapshotProbe {
    size_t point_count = 0;
    uint32_t calls = 0;

    static int take(void* user, const uint32_t* triangles, uint32_t triangle_count, double points_reached) {
        SnapshotProbe& self = *static_cast<SnapshotProbe*>(user);
        ++self.calls;
        FUZZ_CHECK(points_reached >= 0.0 && points_reached <= 1.0);
        for (size_t i = 0; i < 3 * size_t(triangle_count); ++i) FUZZ_CHECK(triangles[i] < self.point_count);
        return 0;
    }
};

// Stores any int in an enum field, as a C caller may: the library must check it without undefined behaviour.
template <class Enum>
void store_enum(Enum& field, uint32_t value) {
    static_assert(sizeof field == sizeof value, "C enums are int-sized");
    memcpy(&field, &value, sizeof value);
}

dbrg_params produce_params(FuzzInput& input) {
    dbrg_params params;
    dbrg_params_init(&params);
    params.sliver_angle = input.flag() ? input.pick(SLIVER_ANGLES) : PI / 2 + PI / 2 * (input.byte() + 1) / 257.0;
    params.boundary_factor = input.pick(BOUNDARY_FACTORS);
    store_enum(params.boundary_mean, input.pick(ENUM_VALUES));
    params.fill_holes = input.flag();
    params.max_hole_edges = input.pick(HOLE_EDGES);
    params.max_components = input.pick(COMPONENTS);
    store_enum(params.backend, input.pick(ENUM_VALUES));
    params.threads = input.pick(THREADS);
    params.snapshot_count = input.pick(SNAPSHOT_COUNTS);
    params.struct_size = input.pick(STRUCT_SIZES);
    return params;
}

// Breaks one argument rule, `amount` saying by how much; the points themselves stay as produced.
void mangle_points(Mangle mangle, uint32_t amount, dbrg_points& points) {
    switch (mangle) {
    case Mangle::none: break;
    case Mangle::short_stride: points.stride_bytes = 3 * (points.type == DBRG_FLOAT32 ? 4 : 8) - 1 - amount % 8; break;
    case Mangle::bad_type: store_enum(points.type, 2 + amount % 100); break;
    case Mangle::null_data: points.data = nullptr; break;
    // The buffer holds only the produced points: reading any further is a bug the sanitizers catch.
    case Mangle::lying_count: points.count = DBRG_MAX_POINTS + 1 + amount; break;
    case Mangle::overflowing_stride: points.stride_bytes = SIZE_MAX / 2 + 1; break;
    }
}

// For each point, the smallest index of a point at the same place: what the library returns for merged duplicates.
std::vector<uint32_t> canonical_indices(const std::vector<double>& xyz) {
    std::map<std::array<double, 3>, uint32_t> first;
    std::vector<uint32_t> canonical(xyz.size() / 3);
    for (uint32_t i = 0; i < canonical.size(); ++i) {
        canonical[i] = first.emplace(std::array<double, 3>{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, i).first->second;
    }
    return canonical;
}

// The status the input calls for when no fault is injected. `flexible` is set when the coordinates are not
// on the grid: then rounding in the library's scaling may merge more points than exact equality does, and
// coplanarity is not judged here, so TOO_FEW_POINTS and DEGENERATE_INPUT are acceptable instead of OK or of
// UNSUPPORTED (a backend this build lacks, which the library reports after those).
dbrg_status expected_status(const PointSet& set, const dbrg_points& points, Mangle mangle, const dbrg_params* params,
                            const std::vector<uint32_t>& canonical, bool& flexible) {
    flexible = false;
    if (params) {
        const dbrg_status status = dbrg_params_validate(params, nullptr, 0);
        if (status != DBRG_OK) return status;
    }
    switch (mangle) {
    case Mangle::none: break;
    case Mangle::short_stride:
    case Mangle::bad_type: return DBRG_ERR_INVALID_ARGUMENT;
    case Mangle::null_data:
        if (points.count > 0) return DBRG_ERR_INVALID_ARGUMENT;
        break;
    case Mangle::lying_count: return DBRG_ERR_TOO_MANY_POINTS;
    case Mangle::overflowing_stride:
        if (points.count > 1) return DBRG_ERR_TOO_MANY_POINTS;  // 2 * 2^63 bytes do not fit in a size_t
        break;
    }
    if (!set.finite) return DBRG_ERR_NON_FINITE_INPUT;
    size_t distinct = 0;
    for (uint32_t i = 0; i < canonical.size(); ++i) distinct += canonical[i] == i;
    if (distinct < 4) return DBRG_ERR_TOO_FEW_POINTS;
    if (set.on_grid) {
        std::vector<IntPoint> grid(set.count());
        for (size_t i = 0; i < grid.size(); ++i) grid[i] = {set.grid[3 * i], set.grid[3 * i + 1], set.grid[3 * i + 2]};
        // Coplanar points are a flat surface; collinear ones are no surface.
        if (all_collinear(grid.data(), grid.size())) return DBRG_ERR_DEGENERATE_INPUT;
    } else {
        flexible = true;
    }
    const dbrg_backend backend = params ? params->backend : DBRG_BACKEND_BUILTIN;
#ifndef DBRG_HAVE_TETGEN
    if (backend == DBRG_BACKEND_TETGEN) return DBRG_ERR_UNSUPPORTED;
#else
    (void)backend;
#endif
    return DBRG_OK;
}

// The properties every successful result must have.
void check_result(const dbrg_mesh* mesh, const PointSet& set, const std::vector<uint32_t>& canonical) {
    const uint32_t count = dbrg_mesh_triangle_count(mesh);
    const uint32_t* triangles = dbrg_mesh_triangles(mesh);
    FUZZ_CHECK(dbrg_mesh_point_count(mesh) == set.count());
    // A success says nothing, or warns exactly when the surface leaves more than half the points out.
    dbrg_stats stats;
    stats.struct_size = sizeof stats;
    FUZZ_CHECK(dbrg_mesh_stats(mesh, &stats) == DBRG_OK);
    const bool most_left_out = stats.vertices_used < stats.unique_points / 2;
    FUZZ_CHECK(most_left_out ? strncmp(dbrg_mesh_message(mesh), "warning: ", 9) == 0
                             : strcmp(dbrg_mesh_message(mesh), "") == 0);
    // No check that there are triangles: the API does not promise any.
    FUZZ_CHECK((count > 0) == (triangles != nullptr));

    io::MeshData data;
    data.positions = set.xyz;
    data.triangles.assign(triangles, triangles + 3 * size_t(count));
    data.has_faces = true;
    for (size_t i = 0; i < data.triangles.size(); ++i) {
        const uint32_t v = data.triangles[i];
        FUZZ_CHECK_WHY(v < set.count(), "a triangle index is out of range");
        FUZZ_CHECK_WHY(canonical[v] == v, "a merged duplicate is not represented by its smallest input index");
        FUZZ_CHECK_WHY(v != data.triangles[i / 3 * 3 + (i + 1) % 3], "a triangle repeats a corner");
    }
    measure::MeshReport report;
    FUZZ_CHECK(measure::make_mesh_report(data, report).ok);
    FUZZ_CHECK(report.edges_nonmanifold == 0);
    FUZZ_CHECK(report.vertices_nonmanifold == 0);
    FUZZ_CHECK(report.oriented);
    FUZZ_CHECK(report.duplicate_faces == 0);
    // The report's zero-area test is exact only where coordinate arithmetic is: on the grid.
    if (set.on_grid) FUZZ_CHECK(report.degenerate_faces == 0);

    // Each loop step is a boundary edge in its triangle's direction, and every boundary edge is one step.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < data.triangles.size(); t += 3) {
        for (size_t i = 0; i < 3; ++i) ++directed[{data.triangles[t + i], data.triangles[t + (i + 1) % 3]}];
    }
    uint64_t steps = 0;
    const uint32_t loops = dbrg_mesh_boundary_loop_count(mesh);
    for (uint32_t loop = 0; loop < loops; ++loop) {
        uint32_t length = 0;
        const uint32_t* vertices = dbrg_mesh_boundary_loop(mesh, loop, &length);
        FUZZ_CHECK(vertices != nullptr && length >= 3);
        for (uint32_t i = 0; i < length; ++i) {
            const uint32_t u = vertices[i], v = vertices[(i + 1) % length];
            const std::pair<uint32_t, uint32_t> step(u, v), back(v, u);
            FUZZ_CHECK_WHY(directed.count(step) == 1 && directed.count(back) == 0, "a loop step is not a boundary edge");
            FUZZ_CHECK_WHY(directed[step]-- == 1, "a boundary edge is in two loop steps");
            ++steps;
        }
    }
    FUZZ_CHECK(dbrg_mesh_boundary_loop(mesh, loops, nullptr) == nullptr);
    FUZZ_CHECK(steps == report.edges_boundary);
    FUZZ_CHECK(loops == report.boundary_loops);

    FUZZ_CHECK(stats.input_points == set.count());
    FUZZ_CHECK(stats.unique_points + stats.duplicates_merged == stats.input_points);
    FUZZ_CHECK(stats.triangles == count);
    FUZZ_CHECK(stats.boundary_loops == loops);
    FUZZ_CHECK(stats.boundary_edges == report.edges_boundary);
    FUZZ_CHECK(stats.vertices_used == report.vertices);
}

std::vector<uint32_t> triangles_of(const dbrg_mesh* mesh) {
    const uint32_t* triangles = dbrg_mesh_triangles(mesh);
    return std::vector<uint32_t>(triangles, triangles + 3 * size_t(dbrg_mesh_triangle_count(mesh)));
}

// Triangles as canonical point numbers (through `original`, the input position of each point), each
// rotated to start at its smallest number, the list sorted: comparable across input orders.
std::vector<std::array<uint32_t, 3>> comparable(const std::vector<uint32_t>& triangles, const std::vector<uint32_t>& original,
                                                const std::vector<uint32_t>& canonical) {
    std::vector<std::array<uint32_t, 3>> out;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        std::array<uint32_t, 3> corners;
        for (size_t i = 0; i < 3; ++i) corners[i] = canonical[original[triangles[t + i]]];
        std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
        out.push_back(corners);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Reconstructs `set` under another order, layout or scale, which must not change the result; `choice`
// picks the layout or the scale.
void check_variant(Variant variant, uint32_t choice, const PointSet& set, const dbrg_params* params,
                   const std::vector<uint32_t>& reference, const std::vector<uint32_t>& canonical) {
    const size_t n = set.count();
    std::vector<uint32_t> original(n);
    for (uint32_t i = 0; i < n; ++i) original[i] = i;
    std::vector<double> xyz = set.xyz;
    test::PointLayout layout = set.layout();
    switch (variant) {
    case Variant::none: return;
    case Variant::reversed:
        for (size_t i = 0; i < n; ++i) {
            original[i] = static_cast<uint32_t>(n - 1 - i);
            std::copy_n(&set.xyz[3 * (n - 1 - i)], 3, &xyz[3 * i]);
        }
        break;
    case Variant::relaid: {
        bool float_exact = true;
        for (double x : xyz) float_exact = float_exact && static_cast<double>(static_cast<float>(x)) == x;
        layout.type = float_exact && layout.type == DBRG_FLOAT64 ? DBRG_FLOAT32 : DBRG_FLOAT64;
        layout.padding = choice % 16;
        layout.offset = choice / 16 % 8;
        break;
    }
    case Variant::rescaled: {
        // Exact on the grid while the values stay normal floats: steps below 2^7, step sizes 2^-120 .. 2^112.
        if (!set.on_grid) return;
        const int exponent = set.exponent + static_cast<int>(choice % 241) - 120;
        if (exponent < -120 || exponent > 112) return;
        for (double& x : xyz) x = ldexp(x, exponent - set.exponent);
        break;
    }
    }
    const test::StoredPoints other(xyz, layout);
    dbrg_mesh* mesh = nullptr;
    const dbrg_status status = dbrg_reconstruct(&other.points(), params, &mesh);
    FUZZ_CHECK_WHY(status == DBRG_OK, status_text(status, DBRG_OK).c_str());
    const std::vector<uint32_t> triangles = triangles_of(mesh);
    dbrg_mesh_destroy(mesh);
    if (variant == Variant::reversed) {
        std::vector<uint32_t> identity(n);
        for (uint32_t i = 0; i < n; ++i) identity[i] = i;
        FUZZ_CHECK_WHY(comparable(triangles, original, canonical) == comparable(reference, identity, canonical),
                       "the same points in reverse order give other triangles");
    } else {
        FUZZ_CHECK_WHY(triangles == reference, "another layout or a power-of-two scale changes the triangles");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzInput input(data, size);
    const uint8_t control = input.byte();
    const int params_mode = control & 3;  // 0: NULL, 1: defaults, 2 and 3: produced
    const Fault fault = static_cast<Fault>((control >> 2) & 3);
    const Variant variant = static_cast<Variant>((control >> 4) & 3);
    const Mangle mangle = (control & 0x40) ? static_cast<Mangle>(1 + input.below(5)) : Mangle::none;
    const uint64_t fault_step = 1 + input.below(1024);
    const uint32_t mangle_amount = mangle == Mangle::none ? 0 : input.u32();
    const uint32_t variant_choice = variant == Variant::none ? 0 : input.byte();

    dbrg_params params;
    if (params_mode >= 2) {
        params = produce_params(input);
    } else {
        dbrg_params_init(&params);
    }
    test::CountingAllocator allocator;
    ProgressProbe progress;
    params.allocator = allocator.get();
    params.progress = ProgressProbe::report;
    params.progress_user = &progress;
    if (fault == Fault::cancel) progress.cancel_at = fault_step;
    if (fault == Fault::fail_one_allocation || fault == Fault::fail_allocations_from) {
        allocator.fail_at(fault_step, fault == Fault::fail_allocations_from);
    }
    const dbrg_params* given = params_mode == 0 ? nullptr : &params;

    const PointSet set = produce_points(input, MAX_POINTS);
    dbrg_points points = set.points();
    SnapshotProbe snapshots;
    snapshots.point_count = points.count;
    params.snapshot = SnapshotProbe::take;
    params.snapshot_user = &snapshots;
    // A caller of 0.1.0 (a struct without the snapshot fields) gets none, and nobody more than the limit.
    const uint32_t snapshots_asked = params.struct_size > offsetof(dbrg_params, snapshot)
                                         ? std::min(params.snapshot_count, DBRG_MAX_SNAPSHOTS)
                                         : 0;
    mangle_points(mangle, mangle_amount, points);
    // NaN has no place in an ordered map; sets with one are judged before duplicates matter.
    const std::vector<uint32_t> canonical = set.finite ? canonical_indices(set.xyz) : std::vector<uint32_t>();
    bool flexible = false;
    const dbrg_status expected = expected_status(set, points, mangle, given, canonical, flexible);

    dbrg_mesh* mesh = nullptr;
    const dbrg_status status = dbrg_reconstruct(&points, given, &mesh);
    const std::string why = status_text(status, expected);
    FUZZ_CHECK_WHY(status != DBRG_ERR_INTERNAL, dbrg_mesh_message(mesh));
    if (allocator.refused() > 0) {
        FUZZ_CHECK_WHY(status == DBRG_ERR_OUT_OF_MEMORY, why.c_str());
    } else if (progress.cancelled) {
        FUZZ_CHECK_WHY(status == DBRG_ERR_CANCELLED, why.c_str());
    } else {
        // Off the grid, rounding may leave too few points or a degenerate set, which the library reports
        // before it asks for a backend it lacks.
        const bool acceptable = status == expected ||
            (flexible && (expected == DBRG_OK || expected == DBRG_ERR_UNSUPPORTED) &&
             (status == DBRG_ERR_TOO_FEW_POINTS || status == DBRG_ERR_DEGENERATE_INPUT));
        FUZZ_CHECK_WHY(acceptable, why.c_str());
    }
    FUZZ_CHECK_WHY(snapshots.calls <= snapshots_asked, "more snapshots than asked for");
    if (status == DBRG_OK && snapshots_asked > 0) FUZZ_CHECK_WHY(snapshots.calls >= 1, "no snapshot at the end of growing");
    if (mangle == Mangle::lying_count) FUZZ_CHECK_WHY(allocator.largest_request() < 4096, "a lying count made the library allocate");

    // Out of memory before the result object exists is the one case without one.
    FUZZ_CHECK(mesh != nullptr || status == DBRG_ERR_OUT_OF_MEMORY);
    if (mesh) {
        FUZZ_CHECK(dbrg_mesh_status(mesh) == status);
        if (status == DBRG_OK) {
            check_result(mesh, set, canonical);
        } else {
            FUZZ_CHECK(dbrg_mesh_triangle_count(mesh) == 0 && dbrg_mesh_triangles(mesh) == nullptr);
            FUZZ_CHECK(dbrg_mesh_boundary_loop_count(mesh) == 0);
            FUZZ_CHECK(strlen(dbrg_mesh_message(mesh)) > 0);
        }
    }
    const std::vector<uint32_t> reference = status == DBRG_OK ? triangles_of(mesh) : std::vector<uint32_t>();
    dbrg_mesh_destroy(mesh);
    FUZZ_CHECK_WHY(allocator.live_blocks() == 0 && allocator.live_bytes() == 0, "memory leaked through the caller's allocator");
    FUZZ_CHECK_WHY(allocator.contract_violations() == 0, "a block was given back with the wrong size");

    if (status == DBRG_OK && fault == Fault::none) {
        allocator.fail_at(0);
        check_variant(variant, variant_choice, set, given, reference, canonical);
        FUZZ_CHECK(allocator.live_blocks() == 0 && allocator.contract_violations() == 0);
    }
    return 0;
}
