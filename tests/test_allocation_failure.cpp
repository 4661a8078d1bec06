// The caller's allocator and progress callback when things go wrong: refusing any one allocation of
// dbrg_reconstruct or dbrg_tetrahedralize, or every allocation from some point on, gives
// DBRG_ERR_OUT_OF_MEMORY; cancelling at any progress report gives DBRG_ERR_CANCELLED; either way nothing
// leaks and every block comes back with its size. Every pass of a stage reports inside its share of the
// stage's progress. Point counts beyond the limits fail before anything is allocated or read.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/splitmix64.h"
#include "dbrg/dbrg.h"
#include "delaunay_test_support.h"
#include "grow/region_growing.h"
#include "holes/hole_filling.h"
#include "samples/samples.h"
#include "support/counting_allocator.h"

using namespace dbrg;

namespace {

struct Input {
    std::string name;
    std::vector<double> xyz;
};

// A few hundred points each: sample shapes (hole filling runs on the open one), degenerate sets the
// library accepts, and sets it rejects after allocating.
std::vector<Input> inputs() {
    std::vector<Input> out;
    out.push_back({"sphere", samples::sample(samples::Shape::sphere, 200)});
    out.push_back({"torus", samples::sample(samples::Shape::torus, 250)});
    out.push_back({"hemisphere", samples::sample(samples::Shape::hemisphere, 150)});
    out.push_back({"cube", samples::sample(samples::Shape::cube, 200)});
    out.push_back({"random sphere (points put in by point insertion)", dbrg_test::random_sphere(300, 1)});
    out.push_back({"lattice 5x5x5", dbrg_test::lattice(5, 0.0, 0)});
    out.push_back({"lattice cube surface 6", dbrg_test::cube_surface_lattice(6)});
    std::vector<double> duplicated = samples::sample(samples::Shape::sphere, 150);
    duplicated.insert(duplicated.end(), duplicated.begin(), duplicated.begin() + 150);
    out.push_back({"sphere with duplicates", duplicated});
    std::vector<double> plane;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) plane.insert(plane.end(), {double(i), double(j), 0.5 * i - 0.25 * j});
    out.push_back({"coplanar (flat: reconstructed, no tetrahedra)", plane});
    std::vector<double> three(samples::sample(samples::Shape::sphere, 3));
    for (int copy = 0; copy < 5; ++copy) three.insert(three.end(), three.begin(), three.begin() + 9);
    out.push_back({"three distinct points (rejected)", three});
    return out;
}

// One call of an entry point, its status and what the result says.
struct Call {
    dbrg_status status;
    bool has_result;
    uint32_t elements;  // triangles or tetrahedra
};

enum class EntryPoint { reconstruct, tetrahedralize };

Call call(EntryPoint entry, const std::vector<double>& xyz, const dbrg_params& params) {
    const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    if (entry == EntryPoint::reconstruct) {
        dbrg_mesh* mesh = nullptr;
        const dbrg_status status = dbrg_reconstruct(&points, &params, &mesh);
        const Call result{status, mesh != nullptr, dbrg_mesh_triangle_count(mesh)};
        if (mesh) CHECK(dbrg_mesh_status(mesh) == status);
        dbrg_mesh_destroy(mesh);
        return result;
    }
    dbrg_tetrahedralization* tets = nullptr;
    const dbrg_status status = dbrg_tetrahedralize(&points, &params, &tets);
    const Call result{status, tets != nullptr, dbrg_tetrahedralization_tet_count(tets)};
    if (tets) CHECK(dbrg_tetrahedralization_status(tets) == status);
    dbrg_tetrahedralization_destroy(tets);
    return result;
}

std::string entry_name(EntryPoint entry) { return entry == EntryPoint::reconstruct ? "dbrg_reconstruct" : "dbrg_tetrahedralize"; }

void require_nothing_held(const test::CountingAllocator& allocator) {
    REQUIRE(allocator.live_blocks() == 0);
    REQUIRE(allocator.live_bytes() == 0);
    REQUIRE(allocator.contract_violations() == 0);
}

// Cancels at the chosen report and checks that no report follows.
struct Canceller {
    uint64_t calls = 0;
    uint64_t cancel_at = 0;  // 0: never
    uint64_t calls_after_cancel = 0;

    static int report(void* user, dbrg_stage, double) {
        Canceller& self = *static_cast<Canceller*>(user);
        if (self.cancel_at != 0 && self.calls >= self.cancel_at) ++self.calls_after_cancel;
        ++self.calls;
        return self.calls == self.cancel_at ? 1 : 0;
    }
};

const EntryPoint ENTRY_POINTS[] = {EntryPoint::reconstruct, EntryPoint::tetrahedralize};

// A share of a stage's progress, its ends excluded: where one pass of the stage reports.
struct Window {
    dbrg_stage stage;
    double from, to;
    bool holds(dbrg_stage s, double fraction) const { return s == stage && fraction > from && fraction < to; }
};

// Records the reports, and with an allocator the bytes it holds at each; cancels at the first one inside
// `cancel_in`, and with `stop_at_delaunay` at the first report of the Delaunay stage (nothing after that is
// watched).
struct StageWatcher {
    std::vector<std::pair<dbrg_stage, double>> reports;
    const test::CountingAllocator* allocator = nullptr;
    std::vector<size_t> live_bytes;
    Window cancel_in{DBRG_STAGE_VALIDATE, 1.0, 0.0};  // none
    bool stop_at_delaunay = true;

    static int report(void* user, dbrg_stage stage, double fraction) {
        StageWatcher& self = *static_cast<StageWatcher*>(user);
        self.reports.emplace_back(stage, fraction);
        if (self.allocator) self.live_bytes.push_back(self.allocator->live_bytes());
        return self.cancel_in.holds(stage, fraction) || (self.stop_at_delaunay && stage == DBRG_STAGE_DELAUNAY) ? 1 : 0;
    }

    size_t count_inside(const Window& window) const {
        size_t inside = 0;
        for (const auto& r : reports) inside += window.holds(r.first, r.second);
        return inside;
    }
};

} // namespace

TEST_CASE("refusing any one allocation, or all from one on, gives OUT_OF_MEMORY and leaks nothing") {
    for (const Input& input : inputs()) {
        for (EntryPoint entry : ENTRY_POINTS) {
            CAPTURE(input.name);
            CAPTURE(entry_name(entry));
            test::CountingAllocator allocator;
            dbrg_params params;
            dbrg_params_init(&params);
            params.allocator = allocator.get();
            const Call full = call(entry, input.xyz, params);
            require_nothing_held(allocator);
            const uint64_t requests = allocator.requests();
            REQUIRE(requests > 2);
            MESSAGE(input.name << ", " << entry_name(entry) << ": " << std::string(dbrg_status_string(full.status)) << " after "
                               << requests << " allocation requests");
            // Every single refusal; refusals from k on (memory running out for good) at every fourth k.
            for (bool persistent : {false, true}) {
                for (uint64_t k = 1; k <= requests; k += persistent ? 4 : 1) {
                    CAPTURE(persistent);
                    CAPTURE(k);
                    allocator.fail_at(k, persistent);
                    const Call failed = call(entry, input.xyz, params);
                    REQUIRE(failed.status == DBRG_ERR_OUT_OF_MEMORY);
                    REQUIRE(failed.elements == 0);
                    require_nothing_held(allocator);
                }
            }
        }
    }
}

TEST_CASE("cancelling at any progress report gives CANCELLED and leaks nothing") {
    for (const Input& input : inputs()) {
        for (EntryPoint entry : ENTRY_POINTS) {
            CAPTURE(input.name);
            CAPTURE(entry_name(entry));
            test::CountingAllocator allocator;
            Canceller canceller;
            dbrg_params params;
            dbrg_params_init(&params);
            params.allocator = allocator.get();
            params.progress = Canceller::report;
            params.progress_user = &canceller;
            call(entry, input.xyz, params);
            const uint64_t reports = canceller.calls;
            REQUIRE(reports > 0);
            for (uint64_t k = 1; k <= reports; ++k) {
                CAPTURE(k);
                canceller = Canceller{0, k, 0};
                const Call cancelled = call(entry, input.xyz, params);
                REQUIRE(cancelled.status == DBRG_ERR_CANCELLED);
                REQUIRE(cancelled.elements == 0);
                REQUIRE(canceller.calls == k);
                require_nothing_held(allocator);
            }
        }
    }
}

TEST_CASE("an input split among threads: refusals and cancelling while threads insert leak nothing") {
    // 40,000 points: most of the Delaunay insertion runs on two threads, which neither allocate nor report
    // (the calling thread reports for them, and stops them when the caller cancels). Cancelling at a sample
    // of the call's reports spread over all of it (every report is tried on one thread above: here each
    // try is a whole parallel tetrahedralization, which under the sanitizers costs seconds); refusing a
    // sample of its allocations, once or for good.
    const std::vector<double> xyz = samples::sample(samples::Shape::bumpy_sphere, 40000);
    test::CountingAllocator allocator;
    Canceller canceller;
    dbrg_params params;
    dbrg_params_init(&params);
    params.allocator = allocator.get();
    params.threads = 2;
    params.progress = Canceller::report;
    params.progress_user = &canceller;
    const Call full = call(EntryPoint::tetrahedralize, xyz, params);
    REQUIRE(full.status == DBRG_OK);
    require_nothing_held(allocator);
    const uint64_t requests = allocator.requests(), reports = canceller.calls;
    // While the other thread inserts its part, the calling thread reports as its points come in: how
    // often depends on the timing, so a run may report fewer times than the first one.
    const uint64_t SAMPLES = 24;
    uint64_t cancelled_runs = 0, tried = 0;
    for (uint64_t i = 0; i < SAMPLES; ++i) {
        const uint64_t k = 1 + (reports - 1) * i / (SAMPLES - 1);  // the first report to the last
        if (i > 0 && k == 1 + (reports - 1) * (i - 1) / (SAMPLES - 1)) continue;
        ++tried;
        CAPTURE(k);
        canceller = Canceller{0, k, 0};
        const Call cancelled = call(EntryPoint::tetrahedralize, xyz, params);
        require_nothing_held(allocator);
        if (canceller.calls < k) {
            REQUIRE(cancelled.status == DBRG_OK);
            continue;
        }
        REQUIRE(cancelled.status == DBRG_ERR_CANCELLED);
        REQUIRE(canceller.calls == k);
        ++cancelled_runs;
    }
    CHECK(cancelled_runs >= tried * 3 / 4);
    canceller = Canceller{};
    for (bool persistent : {false, true}) {
        for (uint64_t i = 0; i < SAMPLES; ++i) {
            const uint64_t k = 1 + requests * i / SAMPLES;
            CAPTURE(persistent);
            CAPTURE(k);
            allocator.fail_at(k, persistent);
            const Call failed = call(EntryPoint::tetrahedralize, xyz, params);
            REQUIRE(failed.status == DBRG_ERR_OUT_OF_MEMORY);
            require_nothing_held(allocator);
        }
    }
    CHECK(allocator.foreign_thread_calls() == 0);
}

TEST_CASE("point counts beyond the limits fail before anything is allocated or read") {
    // Four real points; the counts and strides below claim far more, which must never be read.
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const struct {
        const char* what;
        size_t count;
        size_t stride;
    } lies[] = {
        {"one more than DBRG_MAX_POINTS", DBRG_MAX_POINTS + 1, 3 * sizeof(double)},
        {"SIZE_MAX points", std::numeric_limits<size_t>::max(), 3 * sizeof(double)},
        {"count * stride overflows", 2, std::numeric_limits<size_t>::max() / 2 + 1},
        {"one point at a stride past the address space", 1, std::numeric_limits<size_t>::max() - 8},
        {"count * stride overflows at the limit", DBRG_MAX_POINTS, std::numeric_limits<size_t>::max() / 1024},
    };
    static_assert(DBRG_MAX_POINTS == 0x7fffffffu, "indices are 32-bit with UINT32_MAX reserved");
    for (const auto& lie : lies) {
        CAPTURE(lie.what);
        const dbrg_points points{xyz.data(), lie.count, lie.stride, DBRG_FLOAT64};
        test::CountingAllocator allocator;
        dbrg_params params;
        dbrg_params_init(&params);
        params.allocator = allocator.get();

        dbrg_mesh* mesh = nullptr;
        CHECK(dbrg_reconstruct(&points, &params, &mesh) == DBRG_ERR_TOO_MANY_POINTS);
        CHECK(std::string(dbrg_mesh_message(mesh)).find(std::to_string(lie.count)) != std::string::npos);
        dbrg_mesh_destroy(mesh);
        dbrg_tetrahedralization* tets = nullptr;
        CHECK(dbrg_tetrahedralize(&points, &params, &tets) == DBRG_ERR_TOO_MANY_POINTS);
        dbrg_tetrahedralization_destroy(tets);
        char message[256];
        CHECK(dbrg_points_validate(&points, allocator.get(), message, sizeof message) == DBRG_ERR_TOO_MANY_POINTS);
        CHECK(message[0] != '\0');
        // Only the result objects themselves: nothing sized by the claimed count.
        CHECK(allocator.largest_request() < 4096);
        require_nothing_held(allocator);
    }
}

TEST_CASE("a large input: validation reports in steps, and a cancel there stops before the Delaunay stage") {
    // 600,000 points: every pass of validation and sorting takes several steps.
    const std::vector<double> xyz = dbrg_test::random_sphere(600000, 51);
    const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    test::CountingAllocator counting;
    StageWatcher watched;
    watched.allocator = &counting;
    dbrg_params params;
    dbrg_params_init(&params);
    params.allocator = counting.get();
    params.progress = StageWatcher::report;
    params.progress_user = &watched;
    dbrg_mesh* mesh = nullptr;
    CHECK(dbrg_reconstruct(&points, &params, &mesh) == DBRG_ERR_CANCELLED);  // at the Delaunay stage's first report
    dbrg_mesh_destroy(mesh);
    REQUIRE(watched.reports.back().first == DBRG_STAGE_DELAUNAY);
    CHECK(watched.count_inside(Window{DBRG_STAGE_VALIDATE, 0.0, 1.0}) >= 20);
    // The insertion order is the one the renumbering in validation left: sorting has no pass of its own.
    CHECK(watched.count_inside(Window{DBRG_STAGE_SORT, 0.0, 1.0}) == 0);
    // The Delaunay stage reports as it starts, before it reserves its tetrahedron store (6 slots of 32
    // bytes per point; the conditioned points take 28).
    CHECK(watched.live_bytes.back() < 100 * xyz.size() / 3);

    for (dbrg_stage stage : {DBRG_STAGE_VALIDATE}) {
        CAPTURE(stage);
        test::CountingAllocator allocator;
        StageWatcher cancelling;
        cancelling.cancel_in = Window{stage, 0.0, 1.0};
        params.allocator = allocator.get();
        params.progress_user = &cancelling;
        mesh = nullptr;
        CHECK(dbrg_reconstruct(&points, &params, &mesh) == DBRG_ERR_CANCELLED);
        REQUIRE(mesh != nullptr);
        dbrg_stats stats;
        stats.struct_size = sizeof stats;
        REQUIRE(dbrg_mesh_stats(mesh, &stats) == DBRG_OK);
        CHECK(stats.tetrahedra == 0);
        CHECK(dbrg_mesh_triangle_count(mesh) == 0);
        dbrg_mesh_destroy(mesh);
        // Cancelled inside the stage, and no report after that one.
        CHECK(cancelling.reports.back().first == stage);
        CHECK(cancelling.reports.back().second < 1.0);
        CHECK(cancelling.count_inside(cancelling.cancel_in) == 1);
        require_nothing_held(allocator);
    }
}

TEST_CASE("every stage reports from 0 to 1, and each pass of growing and hole filling inside its share") {
    // 40,000 points each. Points at random on a sphere, jittered by a third of the spacing: hundreds of
    // holes, islands, thousands of edges whose flips wait for the holes to close, and more than 65,536
    // faces to label for components. A torus, whose handle takes a round of the search for small handles.
    // A clean sphere: no holes.
    const std::vector<double> noisy = [] {
        std::vector<double> xyz = dbrg_test::random_sphere(40000, 17);
        SplitMix64 random(3);
        const double spacing = std::sqrt(4 * 3.14159265358979 / 40000);
        for (double& x : xyz) x += spacing / 3 * (2 * random.uniform() - 1);
        return xyz;
    }();
    const std::vector<double> torus = samples::sample(samples::Shape::torus, 40000);
    const std::vector<double> sphere = samples::sample(samples::Shape::sphere, 3000);

    dbrg_params params;
    dbrg_params_init(&params);
    // The noisy sphere must reach growing and hole filling noisy, not smoothed (the cleaning stage's own
    // reports are checked in test_reconstruction).
    params.cleaning = DBRG_CLEANING_OFF;
    params.progress = StageWatcher::report;
    std::map<const std::vector<double>*, StageWatcher> watched;
    for (const std::vector<double>* xyz : {&noisy, &torus, &sphere}) {
        StageWatcher& watcher = watched[xyz];
        watcher.stop_at_delaunay = false;
        params.progress_user = &watcher;
        REQUIRE(call(EntryPoint::reconstruct, *xyz, params).status == DBRG_OK);
        for (int stage = DBRG_STAGE_VALIDATE; stage <= DBRG_STAGE_OUTPUT; ++stage) {
            CAPTURE(stage);
            std::vector<double> fractions;
            for (const auto& r : watcher.reports) {
                if (r.first == stage) fractions.push_back(r.second);
            }
            REQUIRE(!fractions.empty());
            CHECK(fractions.front() == 0.0);
            CHECK(fractions.back() == 1.0);
        }
    }

    const dbrg_stage GROW = DBRG_STAGE_GROW, FILL = DBRG_STAGE_FILL_HOLES;
    const double REGROWING = REGROW_PROGRESS_GROWING * FILL_PROGRESS_EARS;
    // The first round of removing small handles: the first half of that pass.
    const auto handles_round = [](double from, double to) {
        const double begin = FILL_PROGRESS_HANDLES, length = (FILL_PROGRESS_POINTS - FILL_PROGRESS_HANDLES) / 2;
        return Window{DBRG_STAGE_FILL_HOLES, begin + from * length, begin + to * length};
    };
    const struct {
        const char* pass;
        const std::vector<double>& xyz;
        Window window;
    } passes[] = {
        {"growing", noisy, {GROW, 0.0, GROW_PROGRESS_ISLANDS}},
        {"removing islands", noisy, {GROW, GROW_PROGRESS_ISLANDS, GROW_PROGRESS_FLIPS}},
        {"flipping edges", noisy, {GROW, GROW_PROGRESS_FLIPS, 1.0}},
        {"regrowing: the holes' edges", noisy, {FILL, 0.0, REGROWING}},
        {"regrowing: growing", noisy, {FILL, REGROWING, FILL_PROGRESS_EARS}},
        {"ears", noisy, {FILL, FILL_PROGRESS_EARS, FILL_PROGRESS_ISLANDS}},
        {"removing the islands of filling", noisy, {FILL, FILL_PROGRESS_ISLANDS, FILL_PROGRESS_HANDLES}},
        {"handles: labelling components", noisy, handles_round(0.0, HANDLES_PROGRESS_TREE)},
        {"handles: spanning tree", torus, handles_round(HANDLES_PROGRESS_TREE, HANDLES_PROGRESS_COTREE)},
        {"handles: cotree", torus, handles_round(HANDLES_PROGRESS_COTREE, HANDLES_PROGRESS_CYCLES)},
        {"handles: short cycles", torus, handles_round(HANDLES_PROGRESS_CYCLES, HANDLES_PROGRESS_CUTS)},
        {"point insertion", noisy, {FILL, FILL_PROGRESS_POINTS, FILL_PROGRESS_FLIPS}},
        {"deferred flips", noisy, {FILL, FILL_PROGRESS_FLIPS, 1.0}},
    };
    for (const auto& pass : passes) {
        CAPTURE(std::string(pass.pass));
        REQUIRE(watched[&pass.xyz].count_inside(pass.window) >= 1);

        test::CountingAllocator allocator;
        StageWatcher cancelling;
        cancelling.stop_at_delaunay = false;
        cancelling.cancel_in = pass.window;
        params.progress_user = &cancelling;
        params.allocator = allocator.get();
        CHECK(call(EntryPoint::reconstruct, pass.xyz, params).status == DBRG_ERR_CANCELLED);
        // Cancelled inside the pass, and no report after that one.
        CHECK(cancelling.count_inside(pass.window) == 1);
        CHECK(cancelling.cancel_in.holds(cancelling.reports.back().first, cancelling.reports.back().second));
        require_nothing_held(allocator);
    }
}

TEST_CASE("page advice before large fills keeps what the memory holds, from malloc and a caller's allocator") {
    test::CountingAllocator allocator;
    Memory from_malloc(nullptr), from_caller(allocator.get());
    CHECK(from_malloc.uses_system_allocator());
    CHECK_FALSE(from_caller.uses_system_allocator());
    for (Memory* memory : {&from_malloc, &from_caller}) {
        Array<uint32_t> values(*memory);
        // Written in three steps: a small fill, a fill of many pages after it, and advice over all of it.
        const size_t small = 1000, large = size_t(3) << 20;
        REQUIRE(values.resize(small, 7));
        REQUIRE(values.resize(small + large, 9));
        memory->populate(values.data(), values.size() * sizeof(uint32_t));
        size_t wrong = 0;
        for (size_t i = 0; i < values.size(); ++i) wrong += values[i] != (i < small ? 7u : 9u);
        CHECK(wrong == 0);
    }
    CHECK(allocator.live_blocks() == 0);
}
