// Tests of the point-cleaning stage's neighbour search and local fit: the k nearest neighbours against brute
// force (random points, a lattice full of equal distances) and against the search from the root (one query
// at a time and a leaf's queries together), the same answer on one thread and two, allocation failure and
// cancelling; the local quadric fit on exact surfaces, lines and single spots, in any frame.
#include <doctest/doctest.h>

#include <stdint.h>

#include <algorithm>
#include <vector>

#include "delaunay_test_support.h"
#include "points/local_fit.h"
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
// smallest distances to the other points. Where the k-th distance is not also the (k + 1)-th, they are exactly
// the k nearest, equal distances in the order of their indices; otherwise which of the equal ones is the
// search's choice.
void check_against_brute_force(const std::vector<double>& xyz, uint32_t k, const Array<uint32_t>& neighbours) {
    const size_t n = xyz.size() / 3;
    REQUIRE(neighbours.size() == k * n);
    std::vector<std::pair<double, uint32_t>> all;
    for (size_t i = 0; i < n; ++i) {
        all.clear();
        for (size_t j = 0; j < n; ++j) {
            if (j != i) all.emplace_back(squared_distance(xyz, i, j), uint32_t(j));
        }
        std::sort(all.begin(), all.end());
        std::vector<uint32_t> found(neighbours.begin() + k * i, neighbours.begin() + k * (i + 1));
        const bool tied = k < all.size() && all[k - 1].first == all[k].first;
        for (uint32_t j = 0; j < k; ++j) {
            CHECK(found[j] != i);
            CHECK(squared_distance(xyz, i, found[j]) == all[j].first);
            if (!tied) CHECK(found[j] == all[j].second);
        }
        std::sort(found.begin(), found.end());
        CHECK(std::adjacent_find(found.begin(), found.end()) == found.end());
    }
}

// A random orthonormal frame: (u, v, n).
void random_frame(Random& random, Vec3& u, Vec3& v, Vec3& n) {
    n = normalized(Vec3{random.normal(), random.normal(), random.normal()});
    u = normalized(cross(n, fabs(n.x) < 0.5 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    v = cross(n, u);
}

// Offsets of points on the graph of h + a x^2 + b x y + c y^2 over the plane of u and v (n up), at x, y in
// pairs symmetric about the origin, so that n is exactly a principal axis of their covariance; the origin
// itself first.
std::vector<Vec3> quadric_patch(Random& random, Vec3 u, Vec3 v, Vec3 n, double h, double a, double b, double c) {
    std::vector<Vec3> offsets{Vec3{0, 0, 0}};
    for (int pair = 0; pair < 8; ++pair) {
        const double x = 2 * random.uniform() - 1, y = 2 * random.uniform() - 1;
        const double z = h + a * x * x + b * x * y + c * y * y;
        offsets.push_back(x * u + y * v + z * n);
        offsets.push_back(-x * u + -y * v + z * n);
    }
    return offsets;
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

TEST_CASE("k nearest neighbours: the search from the query's leaf gives what one from the root gives") {
    // Lattices have many points at the k-th distance, where the answer is the root search's choice; the
    // queries come in a scrambled order with one hint passed along, which must not change any answer.
    for (const std::vector<double>& xyz : {random_sphere(3000, 5), lattice(12, 0.0, 0), cube_surface_lattice(14),
                                           lattice(10, 0.5, 6)}) {
        const uint32_t n = uint32_t(xyz.size() / 3);
        Context context(test_params());
        NeighbourIndex index(context.memory);
        REQUIRE(index.build(xyz.data(), n, ProgressSpan(context, DBRG_STAGE_CLEAN)) == DBRG_OK);
        std::vector<uint32_t> queries(n);
        for (uint32_t i = 0; i < n; ++i) queries[i] = i;
        Random random(7);
        for (uint32_t i = n; i > 1; --i) std::swap(queries[i - 1], queries[uint32_t(random.uniform() * i)]);
        for (uint32_t k : {1u, 6u, 16u, 32u}) {
            CAPTURE(n);
            CAPTURE(k);
            NearestHint hint;
            for (uint32_t query : queries) {
                uint32_t fast[MAX_NEIGHBOURS], root[MAX_NEIGHBOURS];
                REQUIRE(index.nearest(query, k, fast, &hint) == k);
                REQUIRE(index.nearest_from_root(query, k, root) == k);
                CHECK(std::equal(fast, fast + k, root));
                // A hint that promises too much (nothing nearer than the query itself): searched again.
                NearestHint wrong{query, k, 0.0};
                REQUIRE(index.nearest(query, k, fast, &wrong) == k);
                CHECK(std::equal(fast, fast + k, root));
            }
        }
    }
}

// Dense clumps among sparse points: a leaf's batch, sized by the leaf before it, holds too many points near a
// clump and too few (so that queries are searched alone) past one.
std::vector<double> clumps_among_sparse_points(uint64_t seed) {
    Random random(seed + 1);
    std::vector<double> xyz = random_cube(1500, seed);
    for (int clump = 0; clump < 6; ++clump) {
        const double centre[3] = {random.uniform(), random.uniform(), random.uniform()};
        for (int i = 0; i < 400; ++i) {
            for (int a = 0; a < 3; ++a) xyz.push_back(centre[a] + 1e-3 * random.normal());
        }
    }
    return xyz;
}

TEST_CASE("k nearest neighbours of every point, a leaf at a time, are the root search's") {
    // Ten points make a tree of one leaf.
    for (const std::vector<double>& xyz : {random_sphere(3000, 8), lattice(12, 0.0, 0), cube_surface_lattice(14),
                                           clumps_among_sparse_points(9), random_cube(10, 11)}) {
        const uint32_t n = uint32_t(xyz.size() / 3);
        for (uint32_t wanted : {1u, 16u, 32u}) {
            CAPTURE(n);
            CAPTURE(wanted);
            Context context(test_params());
            NeighbourIndex index(context.memory);
            REQUIRE(index.build(xyz.data(), n, ProgressSpan(context, DBRG_STAGE_CLEAN)) == DBRG_OK);
            Array<uint32_t> neighbours(context.memory);
            uint32_t k = 0;
            REQUIRE(find_nearest_neighbours(index, wanted, ProgressSpan(context, DBRG_STAGE_CLEAN), k, neighbours) ==
                    DBRG_OK);
            REQUIRE(k == std::min(wanted, n - 1));
            uint32_t mismatches = 0;
            for (uint32_t query = 0; query < n; ++query) {
                uint32_t root[MAX_NEIGHBOURS];
                REQUIRE(index.nearest_from_root(query, k, root) == k);
                mismatches += !std::equal(root, root + k, neighbours.data() + size_t(k) * query);
            }
            CHECK(mismatches == 0);
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

TEST_CASE("a local quadric fit through points on a quadric: the point's own height, the surface's normal") {
    Random random(11);
    for (int trial = 0; trial < 200; ++trial) {
        CAPTURE(trial);
        Vec3 u, v, n;
        random_frame(random, u, v, n);
        const double a = 0.2 * random.normal(), b = 0.2 * random.normal(), c = 0.2 * random.normal();
        const std::vector<Vec3> offsets = quadric_patch(random, u, v, n, 0.0, a, b, c);
        const LocalFit fit = fit_local_quadric(offsets.data(), uint32_t(offsets.size()));
        CHECK(fabs(length(fit.normal) - 1) < 1e-12);
        CHECK(fabs(fabs(dot(fit.normal, n)) - 1) < 1e-12);
        CHECK(fabs(fit.height) < 1e-12);
        CHECK(fit.rms < 1e-7);  // the square root of rounding: the residual comes from the normal equations
    }
}

TEST_CASE("a local quadric fit is the same fit in any frame and at any scale") {
    Random random(12);
    for (int trial = 0; trial < 200; ++trial) {
        CAPTURE(trial);
        std::vector<Vec3> offsets{Vec3{0, 0, 0}};
        for (int i = 0; i < 16; ++i) offsets.push_back(Vec3{random.normal(), random.normal(), 0.3 * random.normal()});
        Vec3 u, v, n;
        random_frame(random, u, v, n);
        const double scale = ldexp(1.0, int(random.uniform() * 40) - 20);
        std::vector<Vec3> moved;
        for (const Vec3& p : offsets) moved.push_back(scale * (p.x * u + p.y * v + p.z * n));
        const LocalFit fit = fit_local_quadric(offsets.data(), uint32_t(offsets.size()));
        const LocalFit moved_fit = fit_local_quadric(moved.data(), uint32_t(moved.size()));
        const Vec3 normal = fit.normal.x * u + fit.normal.y * v + fit.normal.z * n;
        CHECK(fabs(fabs(dot(normal, moved_fit.normal)) - 1) < 1e-10);
        const Vec3 step = fit.height * normal, moved_step = (1 / scale) * moved_fit.height * moved_fit.normal;
        CHECK(length(step - moved_step) < 1e-10);
        CHECK(fabs(moved_fit.rms / scale - fit.rms) < 1e-10);
    }
}

TEST_CASE("a local quadric fit of points on a line, or on one spot, stays on them") {
    Random random(13);
    for (uint32_t count : {2u, 3u, 5u, 17u, 33u}) {
        for (int trial = 0; trial < 50; ++trial) {
            CAPTURE(count);
            CAPTURE(trial);
            const Vec3 direction = normalized(Vec3{random.normal(), random.normal(), random.normal()});
            std::vector<Vec3> offsets{Vec3{0, 0, 0}};
            while (offsets.size() < count) offsets.push_back(random.normal() * direction);
            const LocalFit fit = fit_local_quadric(offsets.data(), count);
            CHECK(fabs(length(fit.normal) - 1) < 1e-12);
            CHECK(fabs(dot(fit.normal, direction)) < 1e-8);
            CHECK(fabs(fit.height) < 1e-12);
            CHECK(fit.rms < 1e-7);
        }
    }
    for (uint32_t count : {1u, 5u}) {
        const std::vector<Vec3> spot(count, Vec3{0, 0, 0});
        const LocalFit fit = fit_local_quadric(spot.data(), count);
        CHECK(length(fit.normal) == 1);
        CHECK(fit.height == 0);
        CHECK(fit.rms == 0);
    }
}
