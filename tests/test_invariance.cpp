// Invariance of dbrg_reconstruct on sample shapes and hostile sets (lattices, cospherical points,
// duplicates): the same points in another order give the same triangles by corner coordinates; moved by
// a power of two or scaled by one they give the same connectivity; float32 and float64 copies of
// float32-exact coordinates, in any stride and alignment, give the same mesh.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "dbrg/dbrg.h"
#include "delaunay_test_support.h"
#include "samples/samples.h"
#include "support/mesh_checks.h"
#include "support/point_layout.h"

using namespace dbrg;

namespace {

struct PointSetCase {
    std::string name;
    std::vector<double> xyz;
};

// Multiples of 2^-20 below 2^4 in magnitude: float32-exact, and exact after adding up to 2^20 or
// scaling by 2^-900 .. 2^900.
std::vector<double> snapped(std::vector<double> xyz) {
    for (double& x : xyz) x = std::ldexp(std::round(std::ldexp(x, 20)), -20);
    return xyz;
}

// Every integer point at distance sqrt(r2) from the origin: one large cospherical set.
std::vector<double> integer_sphere(int r2) {
    std::vector<double> xyz;
    const int r = static_cast<int>(std::sqrt(double(r2)));
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r2) xyz.insert(xyz.end(), {double(x), double(y), double(z)});
    return xyz;
}

std::vector<double> concatenated(std::vector<double> a, const std::vector<double>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

const std::vector<PointSetCase>& point_sets() {
    static const std::vector<PointSetCase> sets = [] {
        std::vector<PointSetCase> out;
        const struct {
            samples::Shape shape;
            size_t count;
        } shapes[] = {{samples::Shape::sphere, 1200},        {samples::Shape::torus, 1500},
                      {samples::Shape::double_torus, 2000},  {samples::Shape::bumpy_sphere, 1500},
                      {samples::Shape::hemisphere, 1000},    {samples::Shape::open_cylinder, 1000},
                      {samples::Shape::saddle, 1000},        {samples::Shape::cube, 1200},
                      {samples::Shape::capped_cylinder, 1200}, {samples::Shape::graded_sphere, 1200},
                      {samples::Shape::thin_plate, 1200}};
        for (const auto& s : shapes) out.push_back({samples::facts(s.shape).name, snapped(samples::sample(s.shape, s.count))});
        out.push_back({"lattice 7x7x7", dbrg_test::lattice(7, 0.0, 0)});
        out.push_back({"jittered lattice 7x7x7", snapped(dbrg_test::lattice(7, 0.3, 3))});
        out.push_back({"lattice cube surface 10", dbrg_test::cube_surface_lattice(10)});
        // Clumped points: point insertion puts some of them in after hole filling.
        out.push_back({"random sphere", snapped(dbrg_test::random_sphere(1500, 5))});
        out.push_back({"integer sphere r^2 = 50", integer_sphere(50)});
        out.push_back({"concentric integer spheres r^2 = 27, 75", concatenated(integer_sphere(27), integer_sphere(75))});
        // A sphere with its first 100 points repeated at the end and 50 more in the middle.
        std::vector<double> duplicated = snapped(samples::sample(samples::Shape::sphere, 500));
        const std::vector<double> head(duplicated.begin(), duplicated.begin() + 300);
        duplicated.insert(duplicated.end(), head.begin(), head.end());
        duplicated.insert(duplicated.begin() + 600, head.begin(), head.begin() + 150);
        out.push_back({"sphere with duplicates", duplicated});
        return out;
    }();
    return sets;
}

std::vector<double> shuffled(const std::vector<double>& xyz, uint32_t seed) {
    std::vector<size_t> order(xyz.size() / 3);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    std::vector<double> out(xyz.size());
    for (size_t i = 0; i < order.size(); ++i) std::copy_n(&xyz[3 * order[i]], 3, &out[3 * i]);
    return out;
}

std::vector<double> reversed(const std::vector<double>& xyz) {
    const size_t n = xyz.size() / 3;
    std::vector<double> out(xyz.size());
    for (size_t i = 0; i < n; ++i) std::copy_n(&xyz[3 * (n - 1 - i)], 3, &out[3 * i]);
    return out;
}

// The reconstruction of each set in its own order and layout, computed once for all test cases.
const test::Reconstruction& reference(size_t set) {
    static const std::vector<test::Reconstruction> results = [] {
        std::vector<test::Reconstruction> out;
        for (const PointSetCase& c : point_sets()) out.push_back(test::reconstruct(c.xyz));
        return out;
    }();
    return results[set];
}

} // namespace

TEST_CASE("every invariance case reconstructs into a valid manifold") {
    for (size_t i = 0; i < point_sets().size(); ++i) {
        CAPTURE(point_sets()[i].name);
        const test::Reconstruction& result = reference(i);
        REQUIRE(result.status == DBRG_OK);
        test::require_valid_manifold(test::report_of(point_sets()[i].xyz, result.triangles));
        // The random sphere is here for point insertion: the order tests below cover it only if it runs.
        if (point_sets()[i].name == "random sphere") CHECK(result.stats.points_inserted > 0);
    }
}

TEST_CASE("the same points in another order give the same triangles") {
    for (size_t i = 0; i < point_sets().size(); ++i) {
        const PointSetCase& set = point_sets()[i];
        const test::Reconstruction& first = reference(i);
        REQUIRE(first.status == DBRG_OK);
        const auto expected = test::triangles_by_position(set.xyz, first.triangles);
        const std::vector<double> orders[] = {reversed(set.xyz), shuffled(set.xyz, 1), shuffled(set.xyz, 2)};
        for (size_t k = 0; k < 3; ++k) {
            CAPTURE(set.name);
            CAPTURE(k);
            const test::Reconstruction other = test::reconstruct(orders[k]);
            REQUIRE(other.status == DBRG_OK);
            CHECK(test::triangles_by_position(orders[k], other.triangles) == expected);
            CHECK(other.boundary_loops == first.boundary_loops);
        }
    }
}

TEST_CASE("moving the points by powers of two keeps the connectivity") {
    // Each offset is a multiple of every set's extent rounded up to a power of two, and exact on the grid.
    const double offsets[][3] = {{1024, 1024, 1024}, {-0x1p20, 0x1p12, 0}, {0x1p20, -1024, 0x1p16}};
    for (size_t i = 0; i < point_sets().size(); ++i) {
        const PointSetCase& set = point_sets()[i];
        REQUIRE(reference(i).status == DBRG_OK);
        for (const auto& offset : offsets) {
            CAPTURE(set.name);
            CAPTURE(offset[0]);
            std::vector<double> moved(set.xyz);
            for (size_t j = 0; j < moved.size(); ++j) moved[j] += offset[j % 3];
            const test::Reconstruction result = test::reconstruct(moved);
            REQUIRE(result.status == DBRG_OK);
            CHECK(result.triangles == reference(i).triangles);
        }
    }
}

TEST_CASE("scaling the points by powers of two keeps the connectivity") {
    for (size_t i = 0; i < point_sets().size(); ++i) {
        const PointSetCase& set = point_sets()[i];
        REQUIRE(reference(i).status == DBRG_OK);
        for (int exponent : {-900, -20, -1, 1, 20, 900}) {
            CAPTURE(set.name);
            CAPTURE(exponent);
            std::vector<double> scaled(set.xyz);
            for (double& x : scaled) x = std::ldexp(x, exponent);
            const test::Reconstruction result = test::reconstruct(scaled);
            REQUIRE(result.status == DBRG_OK);
            CHECK(result.triangles == reference(i).triangles);
        }
    }
}

TEST_CASE("float32 and float64 copies in any stride and alignment give the same mesh") {
    const test::PointLayout layouts[] = {
        {DBRG_FLOAT32, 0, 0}, {DBRG_FLOAT32, 4, 0}, {DBRG_FLOAT32, 1, 3},  // packed, padded, odd stride misaligned
        {DBRG_FLOAT64, 8, 0}, {DBRG_FLOAT64, 5, 1},                        // padded, odd stride misaligned
    };
    for (size_t i = 0; i < point_sets().size(); ++i) {
        const PointSetCase& set = point_sets()[i];
        REQUIRE(reference(i).status == DBRG_OK);
        for (const test::PointLayout& layout : layouts) {
            CAPTURE(set.name);
            CAPTURE(layout.type);
            CAPTURE(layout.padding);
            const test::StoredPoints stored(set.xyz, layout);
            const test::Reconstruction result = test::reconstruct(stored.points());
            REQUIRE(result.status == DBRG_OK);
            CHECK(result.triangles == reference(i).triangles);
            CHECK(result.boundary_loops == reference(i).boundary_loops);
        }
    }
}
