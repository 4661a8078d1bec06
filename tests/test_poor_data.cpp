// Poor data (paper §6): non-uniform density, sharp edges, noise and outliers, thin parts. Whatever the
// data, the output is a valid oriented manifold; where the sampling allows, it is closed with the right genus.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/pi.h"
#include "core/splitmix64.h"
#include "dbrg/dbrg.h"
#include "delaunay_test_support.h"
#include "measure/mesh_report.h"
#include "samples/samples.h"
#include "support/mesh_checks.h"

using namespace dbrg;

namespace {

// The sample moved by up to `fraction` of the median edge of its reconstruction, in a random direction.
std::vector<double> jittered(const std::vector<double>& xyz, double amplitude, uint32_t seed) {
    SplitMix64 random(seed);
    std::vector<double> moved(xyz);
    for (double& x : moved) x += amplitude * (2 * random.uniform() - 1);
    return moved;
}

void require_closed(const std::vector<double>& xyz, int genus, const char* what) {
    CAPTURE(std::string(what));
    const test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    const measure::MeshReport report = test::report_of(xyz, result.triangles);
    test::require_valid_manifold(report);
    CHECK(report.edges_boundary == 0);
    CHECK(report.components == 1);
    REQUIRE(report.genus.has_value());
    CHECK(*report.genus == genus);
    CHECK(test::signed_volume(xyz, result.triangles) > 0);
}

// Two unit spheres with centres `distance` apart (less than 2, so they overlap): the surface of their union,
// uniformly sampled. Near the circle where the spheres meet, the two sheets are closer than the spacing.
inline std::vector<double> overlapping_spheres(size_t points, double distance, uint32_t seed) {
    SplitMix64 random(seed);
    std::vector<double> xyz;
    while (xyz.size() < 3 * points) {
        const double z = 2 * random.uniform() - 1, a = 2 * PI * random.uniform();
        const double r = std::sqrt(1 - z * z);
        const bool upper = random.uniform() > 0.5;
        const double p[3] = {r * std::cos(a), r * std::sin(a), upper ? distance + z : z};
        const double other = upper ? p[2] : p[2] - distance;  // height above the other sphere's centre
        if (p[0] * p[0] + p[1] * p[1] + other * other < 1) continue;  // inside the other sphere
        xyz.insert(xyz.end(), {p[0], p[1], p[2]});
    }
    return xyz;
}

} // namespace

TEST_CASE("density falling tenfold across a sphere still gives a closed sphere") {
    for (size_t points : {3000, 12000}) require_closed(samples::sample(samples::Shape::graded_sphere, points), 0, "graded");
}

TEST_CASE("sharp edges and corners: cube, capped cylinder, fandisk-like solids close up") {
    for (size_t points : {3000, 10000}) {
        require_closed(samples::sample(samples::Shape::cube, points), 0, "cube");
        require_closed(samples::sample(samples::Shape::capped_cylinder, points), 0, "capped cylinder");
    }
}

TEST_CASE("sharp edges are reproduced where they are sampled: no triangle of the cube cuts across an edge") {
    // Random samples rarely fall on an edge, so a triangle has to bridge it; on a lattice they do.
    std::vector<double> xyz;
    const int n = 16;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            for (int k = 0; k <= n; ++k) {
                if (i == 0 || j == 0 || k == 0 || i == n || j == n || k == n) {
                    xyz.insert(xyz.end(), {2.0 * i / n - 1, 2.0 * j / n - 1, 2.0 * k / n - 1});
                }
            }
        }
    }
    const test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    // Every triangle lies on one face of the cube: its corners share a coordinate at +-1.
    size_t across = 0;
    for (size_t t = 0; t < result.triangles.size(); t += 3) {
        bool on_one_face = false;
        for (int axis = 0; axis < 3 && !on_one_face; ++axis) {
            for (double side : {-1.0, 1.0}) {
                bool all = true;
                for (int i = 0; i < 3; ++i) all = all && xyz[3 * result.triangles[t + i] + axis] == side;
                on_one_face = on_one_face || all;
            }
        }
        across += on_one_face ? 0 : 1;
    }
    MESSAGE("cube: " << across << " of " << result.triangles.size() / 3 << " triangles cut across an edge");
    CHECK(across == 0);
    CHECK(test::report_of(xyz, result.triangles).edges_boundary == 0);
}

TEST_CASE("thin parts: the two faces of a thin plate are not fused together") {
    // 20,000 points once left a few faces cut off by a pinch as a second, overlapping component.
    require_closed(samples::sample(samples::Shape::thin_plate, 20000), 0, "thin plate, 20k");
    const std::vector<double> xyz = samples::sample(samples::Shape::thin_plate, 6000);
    require_closed(xyz, 0, "thin plate");
    const test::Reconstruction result = test::reconstruct(xyz);
    // A triangle with corners on both large faces, away from the rim, would join the sheets.
    size_t fused = 0;
    for (size_t t = 0; t < result.triangles.size(); t += 3) {
        bool top = false, bottom = false;
        for (int i = 0; i < 3; ++i) {
            const double* p = &xyz[3 * result.triangles[t + i]];
            const bool inner = std::fabs(p[0]) < 0.95 && std::fabs(p[1]) < 0.95;
            top = top || (inner && p[2] > 0.03);
            bottom = bottom || (inner && p[2] < -0.03);
        }
        fused += top && bottom ? 1 : 0;
    }
    CHECK(fused == 0);
}

TEST_CASE("two sheets closer than the spacing: always a valid manifold, often closed with genus 0") {
    // Along the crease where the spheres meet, growing bridges the two sheets with a few triangles; the small
    // handles this makes are cut and filled, but on these irregular (not Poisson-disk) samples the crease
    // also leaves holes no valid fill reaches: measured, 1 of these 12 samples comes out closed with genus 0,
    // the others with 3 to 63 boundary edges or one handle left.
    size_t closed_genus_0 = 0;
    for (size_t points : {3000, 6000}) {
        for (uint32_t seed = 1; seed <= 6; ++seed) {
            CAPTURE(points);
            CAPTURE(seed);
            const std::vector<double> xyz = overlapping_spheres(points, 1.97, seed);
            const test::Reconstruction result = test::reconstruct(xyz);
            REQUIRE(result.status == DBRG_OK);
            const measure::MeshReport report = test::report_of(xyz, result.triangles);
            test::require_valid_manifold(report);
            closed_genus_0 += report.edges_boundary == 0 && report.genus == 0 ? 1 : 0;
        }
    }
    MESSAGE("overlapping spheres: " << closed_genus_0 << " of 12 closed with genus 0");
    CHECK(closed_genus_0 >= 1);  // a regression sentinel at the measured rate, not a promise
}

TEST_CASE("uniformly random points on a sphere: the points left under the surface are put back in") {
    // Random points cluster: closer pairs than the spacing make flat Delaunay tetrahedra, growing takes one
    // face of each and the point on the other side stays under it. Measured before point insertion: about 1.7 %
    // of the points left out; with it, 0.1-0.2 %.
    for (uint32_t seed = 1; seed <= 3; ++seed) {
        CAPTURE(seed);
        const size_t points = 10000;
        const std::vector<double> xyz = dbrg_test::random_sphere(points, seed);
        const test::Reconstruction result = test::reconstruct(xyz);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(xyz, result.triangles);
        test::require_valid_manifold(report);
        CHECK(test::signed_volume(xyz, result.triangles) > 0);
        CHECK(result.stats.points_inserted > points / 200);
        CHECK((result.stats.unique_points - result.stats.vertices_used) < points / 200);
        MESSAGE("random sphere " << seed << ": " << result.stats.points_inserted << " inserted, "
                                 << (result.stats.unique_points - result.stats.vertices_used) << " left out, " << report.edges_boundary
                                 << " boundary edges");
    }
}

TEST_CASE("a coarsely sampled torus keeps its handle: its short cycles are long in edge lengths") {
    // 100 to 250 points leave the tube 4 to 6 edges around, as short in edges as a bridge's cycles.
    for (size_t points : {100, 150, 250}) {
        CAPTURE(points);
        require_closed(samples::sample(samples::Shape::torus, points), 1, "coarse torus");
    }
}

TEST_CASE("noise: jitter of a fraction of the spacing still gives a valid manifold, closed for mild noise") {
    const std::vector<double> clean = samples::sample(samples::Shape::sphere, 4000);
    const double spacing = std::sqrt(4 * PI / 4000);
    require_closed(jittered(clean, 0.1 * spacing, 1), 0, "10% jitter");
    for (double fraction : {0.3, 0.6}) {
        CAPTURE(fraction);
        const std::vector<double> noisy = jittered(clean, fraction * spacing, 2);
        const test::Reconstruction result = test::reconstruct(noisy);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(noisy, result.triangles);
        test::require_valid_manifold(report);
        MESSAGE("jitter " << fraction << " of the spacing: " << report.edges_boundary << " boundary edges, "
                          << report.components << " components, " << report.faces << " faces");
        CHECK(report.faces > 2 * 4000 * 9 / 10);
    }
}

TEST_CASE("outliers: a few stray points far from the surface are left out and listed, never joined as a spike") {
    const size_t surface_points = 4000;
    std::vector<double> xyz = samples::sample(samples::Shape::torus, surface_points);
    const size_t n = xyz.size() / 3;
    SplitMix64 random(5);
    const auto box = [&random] { return 4 * random.uniform() - 2; };
    for (int i = 0; i < 20; ++i) {
        const double x = box(), y = box(), z = box();
        xyz.insert(xyz.end(), {x, y, z});
    }
    dbrg_params params;
    dbrg_params_init(&params);
    for (dbrg_cleaning cleaning : {DBRG_CLEANING_AUTO, DBRG_CLEANING_OFF}) {
        CAPTURE(int(cleaning));
        params.cleaning = cleaning;
        const test::Reconstruction result = test::reconstruct(xyz, &params);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(xyz, result.triangles);
        test::require_valid_manifold(report);
        MESSAGE("torus with 20 outliers, cleaning " << int(cleaning) << ": " << report.edges_boundary
                                                    << " boundary edges, longest edge / median "
                                                    << test::longest_edge(xyz, result.triangles) /
                                                           test::median_edge(xyz, result.triangles));
        CHECK(report.components == 1);
        // No spike to a stray point, left out or not: growing refuses triangles that large, and so does the
        // first seed since it passes the open-surface test (the longest edge was 4.4 and 2.8 times the
        // median, with cleaning and without, when a stray point above the torus seeded it).
        CHECK(test::longest_edge(xyz, result.triangles) < 2.5 * test::median_edge(xyz, result.triangles));
        if (cleaning == DBRG_CLEANING_OFF) continue;
        // Every stray point far from the torus (its tube has radius 0.35 about a circle of radius 1; the
        // spacing is about 0.06) is listed as an outlier, and no triangle touches a listed point.
        std::vector<uint32_t> far;
        for (size_t i = n; i < xyz.size() / 3; ++i) {
            const double ring = std::hypot(xyz[3 * i], xyz[3 * i + 1]) - 1.0;
            if (std::fabs(std::hypot(ring, xyz[3 * i + 2]) - 0.35) > 0.5) far.push_back(uint32_t(i));
        }
        CHECK(far.size() >= 10);
        dbrg_mesh* mesh = nullptr;
        const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
        REQUIRE(dbrg_reconstruct(&points, &params, &mesh) == DBRG_OK);
        uint32_t count = 0;
        const uint32_t* outliers = dbrg_mesh_outliers(mesh, &count);
        const std::vector<uint32_t> listed(outliers, outliers + count);
        for (uint32_t i : far) CHECK(std::find(listed.begin(), listed.end(), i) != listed.end());
        for (uint32_t i : listed) CHECK(i >= n);  // no torus point is called an outlier
        CHECK(std::is_sorted(listed.begin(), listed.end()));
        for (uint32_t corner : result.triangles) CHECK(std::find(listed.begin(), listed.end(), corner) == listed.end());
        CHECK(result.stats.outliers == count);
        dbrg_mesh_destroy(mesh);
    }
}

TEST_CASE("stray points above a surface do not seed it: the first seed passes the open-surface test") {
    // Growing starts at the highest point (§3.1.1). A stray point there, left in (cleaning off, or one the
    // outlier rules keep), seeded the surface with a huge triangle, and the mean circumradius r_a it started
    // from let growing reach across empty space: a spike to the stray point.
    const std::vector<double> sphere = samples::sample(samples::Shape::sphere, 4000);
    std::vector<double> xyz = sphere;
    const size_t n = sphere.size() / 3;
    xyz.insert(xyz.end(), {0.3, 0.2, 4.0, 2.5, 0.1, 3.0, -2.0, 1.5, 2.5});
    dbrg_params params;
    dbrg_params_init(&params);
    params.cleaning = DBRG_CLEANING_OFF;
    const test::Reconstruction alone = test::reconstruct(sphere, &params);
    const test::Reconstruction with_strays = test::reconstruct(xyz, &params);
    REQUIRE(alone.status == DBRG_OK);
    REQUIRE(with_strays.status == DBRG_OK);
    CHECK(std::count_if(with_strays.triangles.begin(), with_strays.triangles.end(), [&](uint32_t v) { return v >= n; }) == 0);
    const measure::MeshReport report = test::report_of(xyz, with_strays.triangles);
    test::require_valid_manifold(report);
    CHECK(report.edges_boundary == 0);
    CHECK(test::longest_edge(xyz, with_strays.triangles) < 6 * test::median_edge(xyz, with_strays.triangles));
    // The same seed as without them, so the same surface.
    std::vector<std::array<uint32_t, 3>> faces[2];
    for (int k = 0; k < 2; ++k) {
        const std::vector<uint32_t>& t = k == 0 ? alone.triangles : with_strays.triangles;
        for (size_t f = 0; f < t.size(); f += 3) {
            std::array<uint32_t, 3> face{t[f], t[f + 1], t[f + 2]};
            std::sort(face.begin(), face.end());
            faces[k].push_back(face);
        }
        std::sort(faces[k].begin(), faces[k].end());
    }
    CHECK(faces[0] == faces[1]);
}

TEST_CASE("near-duplicates: a sphere sampled twice, each copy 1e-9 off, comes out closed like the sphere") {
    const std::vector<double> sphere = samples::sample(samples::Shape::sphere, 2000);
    std::vector<double> xyz = sphere;
    SplitMix64 random(3);
    for (size_t i = 0; i < sphere.size(); ++i) xyz.push_back(sphere[i] + 1e-9 * (2 * random.uniform() - 1));
    const size_t n = sphere.size() / 3;
    const test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    const measure::MeshReport report = test::report_of(xyz, result.triangles);
    test::require_valid_manifold(report);
    CHECK(report.edges_boundary == 0);
    REQUIRE(report.genus.has_value());
    CHECK(*report.genus == 0);
    CHECK(result.stats.near_duplicates_merged == n);
    CHECK(result.stats.unique_points == n);
    // Each pair is one vertex, by one of its two input indices, and nearly every pair is in the surface.
    std::vector<int> used(n, 0);
    for (uint32_t corner : result.triangles) used[corner % n] |= corner < n ? 1 : 2;
    for (size_t i = 0; i < n; ++i) CHECK(used[i] != 3);
    CHECK(result.stats.vertices_used > n * 99 / 100);
}

TEST_CASE("noise: tiles report their cleaning, the noisiest tile's estimate and the points they smoothed") {
    const std::vector<double> clean = samples::sample(samples::Shape::torus, 12000);
    const std::vector<double> noisy = jittered(clean, 0.02, 11);
    const test::Reconstruction single = test::reconstruct(noisy);
    REQUIRE(single.status == DBRG_OK);
    REQUIRE(single.stats.points_smoothed > 0);
    for (uint32_t tiles : {2u, 3u}) {
        CAPTURE(tiles);
        const test::Reconstruction tiled = test::reconstruct_tiled(noisy, tiles);
        REQUIRE(tiled.status == DBRG_OK);
        REQUIRE(tiled.stats.tiles > 1);
        // Each tile judges its own points as noisy as the whole; the halos count in two tiles.
        CHECK(tiled.stats.noise_level > 0.8 * single.stats.noise_level);
        CHECK(tiled.stats.noise_level < 1.25 * single.stats.noise_level);
        CHECK(tiled.stats.smoothing_iterations == single.stats.smoothing_iterations);
        CHECK(tiled.stats.points_smoothed >= single.stats.points_smoothed);
        CHECK(tiled.stats.points_smoothed < 2 * single.stats.points_smoothed);
        CHECK(tiled.stats.seconds_clean > 0);
    }
    // A clean sample: estimated, not smoothed.
    const test::Reconstruction tiled = test::reconstruct_tiled(clean, 3);
    REQUIRE(tiled.status == DBRG_OK);
    CHECK(tiled.stats.noise_level > 0);
    CHECK(tiled.stats.points_smoothed == 0);
    CHECK(tiled.stats.smoothing_iterations == 0);
}

TEST_CASE("noise: a noisy torus is smoothed for growing and comes out closed; the output stays on the input") {
    const std::vector<double> clean = samples::sample(samples::Shape::torus, 12000);
    const std::vector<double> noisy = jittered(clean, 0.02, 11);  // about a third of the spacing (0.034)
    dbrg_params params;
    dbrg_params_init(&params);
    for (dbrg_cleaning cleaning : {DBRG_CLEANING_OFF, DBRG_CLEANING_AUTO}) {
        params.cleaning = cleaning;
        const test::Reconstruction result = test::reconstruct(noisy, &params);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(noisy, result.triangles);
        test::require_valid_manifold(report);
        MESSAGE("noisy torus, cleaning " << int(cleaning) << ": " << report.edges_boundary << " boundary edges, chi "
                                         << report.euler_characteristic << ", noise estimate "
                                         << result.stats.noise_level);
        if (cleaning == DBRG_CLEANING_OFF) {
            CHECK(result.stats.points_smoothed == 0);
            continue;
        }
        CHECK(result.stats.points_smoothed > 0);
        CHECK(report.edges_boundary == 0);
        REQUIRE(report.genus.has_value());
        CHECK(*report.genus == 1);
    }
    // The smoothed positions, when asked for, lie nearer the torus than the noisy input.
    params.output_smoothed = 1;
    dbrg_mesh* mesh = nullptr;
    const dbrg_points points{noisy.data(), noisy.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    REQUIRE(dbrg_reconstruct(&points, &params, &mesh) == DBRG_OK);
    const double* smoothed = dbrg_mesh_smoothed_points(mesh);
    REQUIRE(smoothed != nullptr);
    const auto off_torus = [](const double* p) {
        return std::fabs(std::hypot(std::hypot(p[0], p[1]) - 1.0, p[2]) - 0.35);
    };
    double before = 0, after = 0;
    for (size_t i = 0; i < noisy.size() / 3; ++i) {
        before += off_torus(&noisy[3 * i]);
        after += off_torus(smoothed + 3 * i);
    }
    CHECK(after < 0.5 * before);
    dbrg_mesh_destroy(mesh);
    params.output_smoothed = 0;
    REQUIRE(dbrg_reconstruct(&points, &params, &mesh) == DBRG_OK);
    CHECK(dbrg_mesh_smoothed_points(mesh) == nullptr);
    dbrg_mesh_destroy(mesh);
}

TEST_CASE("a successful result that leaves most points out carries a warning, and only then") {
    const std::vector<double> xyz = samples::sample(samples::Shape::sphere, 2000);
    const dbrg_points points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    dbrg_params params;
    dbrg_params_init(&params);
    for (double factor : {1.1, 3.0}) {
        CAPTURE(factor);
        params.boundary_factor = factor;
        dbrg_mesh* mesh = nullptr;
        REQUIRE(dbrg_reconstruct(&points, &params, &mesh) == DBRG_OK);
        dbrg_stats stats;
        stats.struct_size = sizeof stats;
        REQUIRE(dbrg_mesh_stats(mesh, &stats) == DBRG_OK);
        const std::string message = dbrg_mesh_message(mesh);
        const bool most_left_out = stats.vertices_used < stats.unique_points / 2;
        CHECK(most_left_out == (factor < 2));
        CHECK(message.empty() == !most_left_out);
        if (most_left_out) {
            CHECK(message.rfind("warning: only " + std::to_string(stats.vertices_used) + " of ", 0) == 0);
            CHECK(message.find("boundary_factor") != std::string::npos);
        }
        dbrg_mesh_destroy(mesh);
    }
}
