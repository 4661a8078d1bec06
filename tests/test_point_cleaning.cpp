// Tests of the point-cleaning stage and its neighbour search: the k nearest neighbours against brute force
// (random points, a lattice full of equal distances), the same answer on one thread and two, allocation
// failure and cancelling.
#include <doctest/doctest.h>

#include <stdint.h>

#include <algorithm>
#include <vector>

#include "delaunay_test_support.h"
#include "points/neighbour_search.h"

using namespace dbrg;
using namespace dbrg_test;

namespace {

double squared_distance(const std::vector<double>& xyz, size_t a, size_t b) {
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += (xyz[3 * a + k] - xyz[3 * b + k]) * (xyz[3 * a + k] - xyz[3 * b + k]);
    return sum;
}

// Every point's neighbours are k distinct other points, nearest first, and their distances are the k
// smallest distances to the other points (which points among equal distances is the search's choice).
void check_against_brute_force(const std::vector<double>& xyz, uint32_t k, const Array<uint32_t>& neighbours) {
    const size_t n = xyz.size() / 3;
    REQUIRE(neighbours.size() == k * n);
    std::vector<double> all;
    for (size_t i = 0; i < n; ++i) {
        all.clear();
        for (size_t j = 0; j < n; ++j) {
            if (j != i) all.push_back(squared_distance(xyz, i, j));
        }
        std::sort(all.begin(), all.end());
        std::vector<uint32_t> found(neighbours.begin() + k * i, neighbours.begin() + k * (i + 1));
        for (uint32_t j = 0; j < k; ++j) {
            CHECK(found[j] != i);
            CHECK(squared_distance(xyz, i, found[j]) == all[j]);
        }
        std::sort(found.begin(), found.end());
        CHECK(std::adjacent_find(found.begin(), found.end()) == found.end());
    }
}

} // namespace

TEST_CASE("k nearest neighbours agree with brute force, equal distances too") {
    for (const std::vector<double>& xyz : {random_cube(700, 3), random_sphere(500, 4), lattice(8, 0.0, 0),
                                           cube_surface_lattice(9)}) {
        for (uint32_t wanted : {1u, 6u, 16u}) {
            CAPTURE(xyz.size() / 3);
            CAPTURE(wanted);
            Context context(test_params());
            Array<uint32_t> neighbours(context.memory);
            uint32_t k = 0;
            REQUIRE(find_nearest_neighbours(xyz.data(), uint32_t(xyz.size() / 3), wanted,
                                            ProgressSpan(context, DBRG_STAGE_CLEAN), k, neighbours) == DBRG_OK);
            CHECK(k == wanted);
            check_against_brute_force(xyz, k, neighbours);
        }
    }
}

TEST_CASE("k nearest neighbours of fewer points than asked for, and of none") {
    const std::vector<double> xyz = random_cube(5, 9);
    Context context(test_params());
    Array<uint32_t> neighbours(context.memory);
    uint32_t k = 0;
    REQUIRE(find_nearest_neighbours(xyz.data(), 5, 16, ProgressSpan(context, DBRG_STAGE_CLEAN), k, neighbours) == DBRG_OK);
    CHECK(k == 4);
    check_against_brute_force(xyz, k, neighbours);
    REQUIRE(find_nearest_neighbours(xyz.data(), 0, 16, ProgressSpan(context, DBRG_STAGE_CLEAN), k, neighbours) == DBRG_OK);
    CHECK(k == 0);
    CHECK(neighbours.empty());
}

TEST_CASE("k nearest neighbours are the same on one thread and two") {
    const std::vector<double> xyz = lattice(36, 0.5, 8);  // 46,656 points: two parts
    std::vector<std::vector<uint32_t>> results;
    for (uint32_t threads : {1u, 2u}) {
        dbrg_params params = test_params();
        params.threads = threads;
        Context context(params);
        Array<uint32_t> neighbours(context.memory);
        uint32_t k = 0;
        REQUIRE(find_nearest_neighbours(xyz.data(), uint32_t(xyz.size() / 3), 12, ProgressSpan(context, DBRG_STAGE_CLEAN),
                                        k, neighbours) == DBRG_OK);
        results.emplace_back(neighbours.begin(), neighbours.end());
    }
    CHECK(results[0] == results[1]);
}

TEST_CASE("neighbour search under a failing allocator, and cancelled") {
    const std::vector<double> xyz = random_cube(300, 6);
    for (uint64_t fail_at = 1; fail_at <= 4; ++fail_at) {
        CountingAllocator counting;
        counting.fail_at = fail_at;
        {
            Context context(test_params(&counting.allocator));
            Array<uint32_t> neighbours(context.memory);
            uint32_t k = 0;
            const dbrg_status status = find_nearest_neighbours(xyz.data(), 300, 8, ProgressSpan(context, DBRG_STAGE_CLEAN),
                                                               k, neighbours);
            CHECK((status == DBRG_ERR_OUT_OF_MEMORY || (status == DBRG_OK && counting.allocations < fail_at)));
        }
        CHECK(counting.live_blocks == 0);
    }
    const dbrg_progress_fn cancel = [](void*, dbrg_stage, double) { return 1; };
    Context context(test_params(nullptr, cancel));
    Array<uint32_t> neighbours(context.memory);
    uint32_t k = 0;
    CHECK(find_nearest_neighbours(xyz.data(), 300, 8, ProgressSpan(context, DBRG_STAGE_CLEAN), k, neighbours) ==
          DBRG_ERR_CANCELLED);
}
