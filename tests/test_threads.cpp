// Concurrency: four threads reconstructing and tetrahedralizing different inputs at once, each with its own
// allocator and progress callback, get exactly the results the same calls give one at a time; and one
// result is read from four threads at once; threads the system refuses leave their work to the caller.
// Built and run under ThreadSanitizer in CI (.ci/test).
#include <doctest/doctest.h>

#include <pthread.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "dbrg/dbrg.h"
#include "delaunay_test_support.h"
#include "samples/samples.h"
#include "support/counting_allocator.h"

using namespace dbrg;

namespace {

const size_t THREADS = 4;

std::vector<std::vector<double>> inputs() {
    return {samples::sample(samples::Shape::sphere, 800),       samples::sample(samples::Shape::torus, 1000),
            samples::sample(samples::Shape::hemisphere, 700),   samples::sample(samples::Shape::double_torus, 1200),
            samples::sample(samples::Shape::cube, 800),         samples::sample(samples::Shape::saddle, 700),
            dbrg_test::cube_surface_lattice(8),                 dbrg_test::lattice(6, 0.25, 9)};
}

// What one call produced; compared whole between runs.
struct Outcome {
    dbrg_status status = DBRG_ERR_INTERNAL;
    std::vector<uint32_t> triangles;
    std::vector<uint32_t> loops;  // each loop's length, then its vertices
    std::vector<uint32_t> tets;
    std::vector<uint32_t> adjacency;
    uint64_t live_blocks_after = 0;
    uint64_t progress_reports = 0;
    // Allocator and progress calls from another thread than the caller's: the library's threads must make none.
    uint64_t allocations_off_thread = 0;
    uint64_t reports_off_thread = 0;
    std::thread::id caller = std::this_thread::get_id();

    bool operator==(const Outcome& o) const {
        return status == o.status && triangles == o.triangles && loops == o.loops && tets == o.tets && adjacency == o.adjacency;
    }
};

int count_report(void* user, dbrg_stage, double) {
    Outcome& out = *static_cast<Outcome*>(user);
    ++out.progress_reports;
    out.reports_off_thread += std::this_thread::get_id() != out.caller;
    return 0;
}

// Reconstructs and tetrahedralizes `xyz` with a private allocator and progress counter; `threads` is the
// parameter of that name, whose value must not change the result.
Outcome run(const std::vector<double>& xyz, uint32_t threads) {
    Outcome out;
    test::CountingAllocator allocator;
    dbrg_params params;
    dbrg_params_init(&params);
    params.allocator = allocator.get();
    params.progress = count_report;
    params.progress_user = &out;
    params.threads = threads;
    const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};

    dbrg_mesh* mesh = nullptr;
    out.status = dbrg_reconstruct(&points, &params, &mesh);
    const uint32_t* triangles = dbrg_mesh_triangles(mesh);
    out.triangles.assign(triangles, triangles + 3 * size_t(dbrg_mesh_triangle_count(mesh)));
    for (uint32_t loop = 0; loop < dbrg_mesh_boundary_loop_count(mesh); ++loop) {
        uint32_t length = 0;
        const uint32_t* vertices = dbrg_mesh_boundary_loop(mesh, loop, &length);
        out.loops.push_back(length);
        out.loops.insert(out.loops.end(), vertices, vertices + length);
    }
    dbrg_mesh_destroy(mesh);

    dbrg_tetrahedralization* tets = nullptr;
    if (dbrg_tetrahedralize(&points, &params, &tets) == DBRG_OK) {
        const size_t n = 4 * size_t(dbrg_tetrahedralization_tet_count(tets));
        out.tets.assign(dbrg_tetrahedralization_tets(tets), dbrg_tetrahedralization_tets(tets) + n);
        out.adjacency.assign(dbrg_tetrahedralization_adjacency(tets), dbrg_tetrahedralization_adjacency(tets) + n);
    }
    dbrg_tetrahedralization_destroy(tets);
    out.live_blocks_after = allocator.live_blocks();
    out.allocations_off_thread = allocator.foreign_thread_calls();
    return out;
}

} // namespace

TEST_CASE("four threads at once get the results each call gets alone") {
    const std::vector<std::vector<double>> sets = inputs();
    std::vector<Outcome> alone;
    for (const std::vector<double>& xyz : sets) {
        alone.push_back(run(xyz, 1));
        REQUIRE(alone.back().status == DBRG_OK);
    }

    // Thread t takes inputs t, t + 4, ... and, in a second round, those of thread t + 1, so that every input
    // runs twice while other inputs run beside it. Each thread sets a different `threads` parameter.
    std::vector<std::vector<Outcome>> together(THREADS);
    std::vector<std::thread> workers;
    for (size_t t = 0; t < THREADS; ++t) {
        workers.emplace_back([&, t] {
            const uint32_t threads_parameter[THREADS] = {1, 0, 2, 4};
            for (size_t round = 0; round < 2; ++round) {
                for (size_t i = (t + round) % THREADS; i < sets.size(); i += THREADS) {
                    together[t].push_back(run(sets[i], threads_parameter[t]));
                }
            }
        });
    }
    for (std::thread& worker : workers) worker.join();

    for (size_t t = 0; t < THREADS; ++t) {
        size_t k = 0;
        for (size_t round = 0; round < 2; ++round) {
            for (size_t i = (t + round) % THREADS; i < sets.size(); i += THREADS, ++k) {
                CAPTURE(t);
                CAPTURE(i);
                REQUIRE(k < together[t].size());
                CHECK(together[t][k] == alone[i]);
                CHECK(together[t][k].live_blocks_after == 0);
                CHECK(together[t][k].progress_reports > 0);
            }
        }
    }
}

namespace {

// From 32,768 points on (twice the fewest a thread gets), sorting, scanning, filling the store and
// inserting split into parts.
// Uniformly random points: besides the splitting, point insertion puts some in after hole filling, and the
// tetrahedra's slots, which differ with the threads that built them, must not change which.
std::vector<double> input_to_split() { return dbrg_test::random_sphere(40000, 9); }

// `xyz` on two threads and on all of them gives what it gives on one, leaks nothing, and calls the
// allocator and the progress callback from the caller's thread only.
void check_as_on_one_thread(const std::vector<double>& xyz) {
    const Outcome one = run(xyz, 1);
    REQUIRE(one.status == DBRG_OK);
    for (uint32_t threads : {2u, 0u}) {
        CAPTURE(threads);
        const Outcome several = run(xyz, threads);
        CHECK(several == one);
        CHECK(several.live_blocks_after == 0);
        CHECK(several.progress_reports > 0);
        CHECK(several.allocations_off_thread == 0);
        CHECK(several.reports_off_thread == 0);
    }
}

} // namespace

TEST_CASE("an input large enough to be split gives the same results on one thread and on several") {
    check_as_on_one_thread(input_to_split());
}

#if defined(__GLIBC__)
namespace {

// While it lives, new threads get a default stack larger than any address space, so pthread_create
// refuses them (a GNU extension: threads started without attributes take the process's defaults).
class ThreadsRefused {
public:
    ThreadsRefused() {
        saved_ = pthread_getattr_default_np(&defaults_) == 0;
        pthread_attr_t huge;
        if (!saved_ || pthread_attr_init(&huge) != 0) return;
        set_ = pthread_attr_setstacksize(&huge, size_t(1) << 48) == 0 && pthread_setattr_default_np(&huge) == 0;
        pthread_attr_destroy(&huge);
    }
    ~ThreadsRefused() {
        if (!saved_) return;
        if (set_) pthread_setattr_default_np(&defaults_);
        pthread_attr_destroy(&defaults_);
    }
    bool in_force() const { return set_; }

private:
    pthread_attr_t defaults_;
    bool saved_ = false, set_ = false;
};

void* do_nothing(void*) { return nullptr; }

} // namespace

TEST_CASE("threads the system refuses to start leave their parts to the calling thread: same results") {
    ThreadsRefused refused;
    REQUIRE(refused.in_force());
    pthread_t probe;
    const int started = pthread_create(&probe, nullptr, do_nothing, nullptr);
    if (started == 0) pthread_join(probe, nullptr);
    REQUIRE_MESSAGE(started != 0, "the huge default stack did not make pthread_create refuse");
    check_as_on_one_thread(input_to_split());
}
#endif

TEST_CASE("one result read from four threads at once") {
    const std::vector<double> xyz = samples::sample(samples::Shape::open_cylinder, 1500);
    const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    dbrg_mesh* mesh = nullptr;
    REQUIRE(dbrg_reconstruct(&points, nullptr, &mesh) == DBRG_OK);

    // Every reader sums everything the accessors give; all sums must agree.
    std::vector<uint64_t> sums(THREADS, 0);
    std::atomic<int> ready{0};
    std::vector<std::thread> readers;
    for (size_t t = 0; t < THREADS; ++t) {
        readers.emplace_back([&, t] {
            ++ready;
            while (ready.load() < int(THREADS)) std::this_thread::yield();
            uint64_t sum = dbrg_mesh_status(mesh) + dbrg_mesh_point_count(mesh);
            const uint32_t* triangles = dbrg_mesh_triangles(mesh);
            for (size_t i = 0; i < 3 * size_t(dbrg_mesh_triangle_count(mesh)); ++i) sum += triangles[i] * (i + 1);
            for (uint32_t loop = 0; loop < dbrg_mesh_boundary_loop_count(mesh); ++loop) {
                uint32_t length = 0;
                const uint32_t* vertices = dbrg_mesh_boundary_loop(mesh, loop, &length);
                for (uint32_t i = 0; i < length; ++i) sum += vertices[i];
            }
            dbrg_stats stats;
            stats.struct_size = sizeof stats;
            dbrg_mesh_stats(mesh, &stats);
            sums[t] = sum + stats.triangles + std::string(dbrg_mesh_message(mesh)).size();
        });
    }
    for (std::thread& reader : readers) reader.join();
    for (size_t t = 1; t < THREADS; ++t) CHECK(sums[t] == sums[0]);
    dbrg_mesh_destroy(mesh);
}
