// Tests of point conditioning: exact power-of-two rescaling, lexicographic order, duplicate merging,
// degeneracy statuses with counts, allocation failure, and progress reported in steps that a cancel stops.
#include <doctest/doctest.h>

#include <float.h>
#include <stdint.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "delaunay_test_support.h"
#include "points/point_conditioning.h"
#include "points/point_input.h"
#include "predicates/predicates.h"

using namespace dbrg;
using namespace dbrg_test;

namespace {

// Every conditioned point maps back exactly onto the input point it stands for.
void check_exact_and_sorted(const std::vector<double>& xyz, const ConditionedPoints& out) {
    for (uint32_t v = 0; v < out.size(); ++v) {
        const uint32_t i = out.input_index[v];
        for (int k = 0; k < 3; ++k) {
            CHECK(ldexp(out.point(v)[k], -out.scale_exponent) + out.origin[k] == xyz[3 * i + k]);
        }
        if (v > 0) CHECK(compare_points(out.point(v - 1), out.point(v)) < 0);
    }
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (uint32_t v = 0; v < out.size(); ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], out.point(v)[k]);
            hi[k] = std::max(hi[k], out.point(v)[k]);
        }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    CHECK(extent >= 0.5);
    CHECK(extent < 1.0);
}

// Records every progress report; cancels at report number `cancel_at` (counting from 0).
struct ProgressLog {
    std::vector<std::pair<dbrg_stage, double>> reports;
    size_t cancel_at = SIZE_MAX;

    static int record(void* user, dbrg_stage stage, double fraction) {
        ProgressLog& log = *static_cast<ProgressLog*>(user);
        log.reports.emplace_back(stage, fraction);
        return log.reports.size() > log.cancel_at ? 1 : 0;
    }
};

} // namespace

TEST_CASE("conditioning sorts, rescales exactly and keeps every distinct point") {
    for (double scale : {1.0, 1e-300, 1e300, 1e-310, 1e307}) {
        CAPTURE(scale);
        std::vector<double> xyz = random_cube(1000, 1);
        for (double& c : xyz) c = c * scale - 0.25 * scale;
        Context context(test_params());
        ConditionedPoints out(context.memory);
        REQUIRE(condition_points(xyz.data(), 1000, context, out) == DBRG_OK);
        CHECK(out.size() == 1000);
        CHECK(out.duplicates_merged == 0);
        check_exact_and_sorted(xyz, out);
    }
}

TEST_CASE("coordinates near the limits of the double range") {
    std::vector<double> xyz = {DBL_MAX, DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX, DBL_MAX,
                               DBL_MAX, -DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, -DBL_MAX, 0, 0, 0};
    Context context(test_params());
    ConditionedPoints out(context.memory);
    REQUIRE(condition_points(xyz.data(), 5, context, out) == DBRG_OK);
    CHECK(out.size() == 5);
}

TEST_CASE("a translation is used when it is exact") {
    std::vector<double> xyz = random_cube(100, 2);
    for (double& c : xyz) c += 1024.0;
    Context context(test_params());
    ConditionedPoints out(context.memory);
    REQUIRE(condition_points(xyz.data(), 100, context, out) == DBRG_OK);
    CHECK(out.origin[0] == 1024.0);
    check_exact_and_sorted(xyz, out);
}

TEST_CASE("duplicates are merged onto the smallest input index") {
    std::vector<double> xyz = random_cube(200, 3);
    std::vector<double> with_copies = xyz;
    // Copies of points 5 and 17 at the end and of point 42 in front of it.
    for (int p : {5, 17, 5}) with_copies.insert(with_copies.end(), xyz.begin() + 3 * p, xyz.begin() + 3 * p + 3);
    with_copies.insert(with_copies.begin(), xyz.begin() + 3 * 42, xyz.begin() + 3 * 42 + 3);
    Context context(test_params());
    ConditionedPoints out(context.memory);
    REQUIRE(condition_points(with_copies.data(), with_copies.size() / 3, context, out) == DBRG_OK);
    CHECK(out.size() == 200);
    CHECK(out.duplicates_merged == 4);
    std::vector<uint32_t> kept(out.input_index.begin(), out.input_index.end());
    std::sort(kept.begin(), kept.end());
    CHECK(std::binary_search(kept.begin(), kept.end(), 0u));    // the copy of 42 in front
    CHECK_FALSE(std::binary_search(kept.begin(), kept.end(), 43u));  // 42 itself, now at 43
    CHECK(std::binary_search(kept.begin(), kept.end(), 6u));    // 5, shifted by one
    CHECK_FALSE(std::binary_search(kept.begin(), kept.end(), 201u));
}

TEST_CASE("points one ulp apart stay distinct, even away from the origin") {
    std::vector<double> xyz = {-1.5, 0, 0, 1, 0, 0, nextafter(1.0, 2.0), 0, 0, 0, 1, 0, 0, 0, 1, 1e-20, 1e-20, 0};
    Context context(test_params());
    ConditionedPoints out(context.memory);
    REQUIRE(condition_points(xyz.data(), 6, context, out) == DBRG_OK);
    CHECK(out.size() == 6);
    check_exact_and_sorted(xyz, out);
}

TEST_CASE("the order does not depend on the input order") {
    std::vector<double> xyz = random_cube(500, 4);
    std::vector<double> reversed;
    for (size_t i = 500; i-- > 0;) reversed.insert(reversed.end(), xyz.begin() + 3 * i, xyz.begin() + 3 * i + 3);
    Context context(test_params());
    ConditionedPoints a(context.memory), b(context.memory);
    REQUIRE(condition_points(xyz.data(), 500, context, a) == DBRG_OK);
    REQUIRE(condition_points(reversed.data(), 500, context, b) == DBRG_OK);
    REQUIRE(a.size() == b.size());
    for (uint32_t v = 0; v < a.size(); ++v) {
        CHECK(compare_points(a.point(v), b.point(v)) == 0);
        CHECK(a.input_index[v] == 499 - b.input_index[v]);
    }
}

TEST_CASE("degenerate inputs are named with their counts") {
    Context context(test_params());
    ConditionedPoints out(context.memory);
    SUBCASE("empty") {
        CHECK(condition_points(nullptr, 0, context, out) == DBRG_ERR_TOO_FEW_POINTS);
    }
    SUBCASE("all equal") {
        const double same[] = {1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3};
        CHECK(condition_points(same, 5, context, out) == DBRG_ERR_TOO_FEW_POINTS);
        CHECK(strstr(context.message(), "5") != nullptr);
    }
    SUBCASE("three distinct among many") {
        std::vector<double> xyz;
        for (int i = 0; i < 30; ++i) xyz.insert(xyz.end(), {double(i % 3), 0.0, 1.0});
        CHECK(condition_points(xyz.data(), 30, context, out) == DBRG_ERR_TOO_FEW_POINTS);
        CHECK(strstr(context.message(), "only 3 distinct") != nullptr);
    }
    SUBCASE("collinear") {
        std::vector<double> xyz;
        for (int i = 0; i < 50; ++i) xyz.insert(xyz.end(), {0.125 * i, 1.0 - 3.0 * i, 2.0 + 0.5 * i});  // exact
        CHECK(condition_points(xyz.data(), 50, context, out) == DBRG_ERR_DEGENERATE_INPUT);
        CHECK(strstr(context.message(), "50 distinct points") != nullptr);
        CHECK(strstr(context.message(), "collinear") != nullptr);
    }
    SUBCASE("coplanar: conditioned, and flat") {
        std::vector<double> xyz;
        Random r(5);
        for (int i = 0; i < 40; ++i) {
            const double u = r.uniform(), v = r.uniform();
            xyz.insert(xyz.end(), {u, v, 0.5});
        }
        CHECK(condition_points(xyz.data(), 40, context, out) == DBRG_OK);
        CHECK(out.flat);
        CHECK(refuse_flat(out, 40, context) == DBRG_ERR_DEGENERATE_INPUT);
        CHECK(strstr(context.message(), "40 distinct points (of 40 given) are coplanar") != nullptr);
    }
    SUBCASE("on one line but for rounding: coplanar, and said to be on a line") {
        // i * 0.1, i * 0.2, i * 0.3 are rounded off their line: exactly coplanar, not exactly collinear.
        std::vector<double> xyz;
        for (int i = 0; i < 500; ++i) xyz.insert(xyz.end(), {i * 0.1, i * 0.2, i * 0.3});
        CHECK(condition_points(xyz.data(), 500, context, out) == DBRG_ERR_DEGENERATE_INPUT);
        CHECK(strstr(context.message(), "500 distinct points") != nullptr);
        CHECK(strstr(context.message(), "coplanar: they lie on one line but for rounding") != nullptr);
    }
    SUBCASE("one point, said once") {
        const double one[] = {1, 2, 3};
        CHECK(condition_points(one, 1, context, out) == DBRG_ERR_TOO_FEW_POINTS);
        CHECK(strstr(context.message(), "1 point given;") != nullptr);
    }
    SUBCASE("coplanar except one point is fine") {
        std::vector<double> xyz;
        for (int i = 0; i < 40; ++i) xyz.insert(xyz.end(), {double(i % 7), double(i / 7), 0.0});
        xyz.insert(xyz.end(), {3.0, 3.0, 1e-9});
        CHECK(condition_points(xyz.data(), 41, context, out) == DBRG_OK);
        CHECK(!out.flat);
    }
}

TEST_CASE("conditioning under a failing allocator") {
    const std::vector<double> xyz = random_cube(300, 6);
    for (uint64_t k = 1; k <= 8; ++k) {
        CountingAllocator counting;
        counting.fail_at = k;
        const dbrg_params params = test_params(&counting.allocator);
        {
            Context context(params);
            {
                ConditionedPoints out(context.memory);
                const dbrg_status status = condition_points(xyz.data(), 300, context, out);
                CHECK((status == DBRG_ERR_OUT_OF_MEMORY || (status == DBRG_OK && counting.allocations < k)));
            }
            CHECK(context.memory.bytes_in_use() == 0);
        }
        CHECK(counting.live_blocks == 0);
    }
}

TEST_CASE("points closer than the predicates' grid merge onto the smallest coordinates, in any order") {
    // Two distinct points 3e-289 apart in a cloud of unit extent round to one grid point; the one with the
    // smaller coordinates stands for both, wherever it is in the input.
    const std::vector<double> base = {0, 0, 1, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    const double near_a[3] = {0, -1.7e-18, 3e-289}, near_b[3] = {0, -1.7e-18, 0};
    for (bool a_first : {true, false}) {
        CAPTURE(a_first);
        std::vector<double> xyz = base;
        const double* first = a_first ? near_a : near_b;
        const double* second = a_first ? near_b : near_a;
        xyz.insert(xyz.begin(), first, first + 3);
        xyz.insert(xyz.end(), second, second + 3);
        Context context(test_params());
        ConditionedPoints out(context.memory);
        REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, out) == DBRG_OK);
        CHECK(out.size() == 5);
        CHECK(out.duplicates_merged == 1);
        const uint32_t expected = a_first ? 5 : 0;  // where near_b, the smaller one, is
        CHECK(std::count(out.input_index.begin(), out.input_index.end(), expected) == 1);
    }
}

TEST_CASE("conditioning a large input reports its progress in steps, and a cancel between two steps stops it") {
    // Each pass over the points takes three steps.
    const size_t n = 3 * STEP_ITEMS;
    const std::vector<double> xyz = random_cube(n, 41);
    ProgressLog log;
    {
        Context context(test_params(nullptr, ProgressLog::record, &log));
        ConditionedPoints out(context.memory);
        REQUIRE(condition_points(xyz.data(), n, context, out) == DBRG_OK);
        REQUIRE(out.size() == n);
        bool sorted = true;
        for (uint32_t v = 1; v < out.size(); ++v) sorted = sorted && compare_points(out.point(v - 1), out.point(v)) < 0;
        CHECK(sorted);
    }
    // Within conditioning's share of DBRG_STAGE_VALIDATE, in order, from the first pass to the last.
    REQUIRE(log.reports.size() >= 20);
    bool in_share = true, in_order = true;
    for (size_t i = 0; i < log.reports.size(); ++i) {
        const double fraction = log.reports[i].second;
        in_share = in_share && log.reports[i].first == DBRG_STAGE_VALIDATE && fraction >= VALIDATE_READ_SHARE &&
                   fraction <= VALIDATE_CONDITION_END;
        in_order = in_order && (i == 0 || fraction > log.reports[i - 1].second);
    }
    CHECK(in_share);
    CHECK(in_order);
    CHECK(log.reports.front().second == VALIDATE_READ_SHARE);
    CHECK(log.reports.back().second == VALIDATE_CONDITION_END);
    // Cancelled at the first report, one in the middle (while sorting) and the last one.
    const size_t reports = log.reports.size();
    for (size_t cancel_at : {size_t(0), reports / 2, reports - 1}) {
        CAPTURE(cancel_at);
        ProgressLog cancelling;
        cancelling.cancel_at = cancel_at;
        Context context(test_params(nullptr, ProgressLog::record, &cancelling));
        ConditionedPoints out(context.memory);
        CHECK(condition_points(xyz.data(), n, context, out) == DBRG_ERR_CANCELLED);
        CHECK(cancelling.reports.size() == cancel_at + 1);
        CHECK(out.size() == 0);
        CHECK(context.memory.bytes_in_use() == 0);
    }
}
