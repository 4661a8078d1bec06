// Flat inputs: points exactly in one plane are reconstructed in their plane (planar/), through the C API and
// the planar triangulation below it. Judged against the region each set samples.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <vector>

#include "dbrg/dbrg.h"
#include "planar/planar_delaunay.h"
#include "support/flat_regions.h"
#include "support/mesh_checks.h"

namespace {

using namespace dbrg::test;
using Triangle = std::array<uint32_t, 3>;

// Rotated to start at its smallest index, orientation kept.
Triangle canonical(Triangle t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
}

std::vector<Triangle> triangles_of(const std::vector<uint32_t>& flat) {
    std::vector<Triangle> out;
    for (size_t i = 0; i < flat.size(); i += 3) out.push_back(canonical({flat[i], flat[i + 1], flat[i + 2]}));
    return out;
}

// Exact in-circle sign in the (u, v) coordinates, which are multiples of 1/256 below 64 in magnitude: as
// integers the determinant's terms stay far below 2^127. Positive when d is inside the circle of the
// counter-clockwise a, b, c. Independent of the library's predicates.
int incircle_uv(const double* a, const double* b, const double* c, const double* d) {
    __extension__ typedef __int128 Wide;  // __extension__: -Wpedantic knows no 128-bit type
    const auto scaled = [](double x) { return Wide(std::llround(x * 256)); };
    const Wide adx = scaled(a[0]) - scaled(d[0]), ady = scaled(a[1]) - scaled(d[1]);
    const Wide bdx = scaled(b[0]) - scaled(d[0]), bdy = scaled(b[1]) - scaled(d[1]);
    const Wide cdx = scaled(c[0]) - scaled(d[0]), cdy = scaled(c[1]) - scaled(d[1]);
    const Wide det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) - (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
                     (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
    return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// Half the signed area... twice: the cross product of the sides in (u, v).
double orient_area_uv(const double* a, const double* b, const double* c) {
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

int orient_uv(const double* a, const double* b, const double* c) {
    const double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);  // exact on these coordinates
    return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

double longest_side_uv(const double* a, const double* b, const double* c) {
    const auto side = [](const double* p, const double* q) { return std::hypot(p[0] - q[0], p[1] - q[1]); };
    return std::max({side(a, b), side(b, c), side(c, a)});
}

// Grid steps: the narrowest opening of the regions (a notch of the E; the hole is 12 wide). A triangle that
// bridges an opening has a side across it.
const double NARROWEST_OPENING = 6;

// Corners where the outline turns inward: the hole's four, the E's four where its arms leave the bar.
int inward_corners(FlatShape shape) { return shape == FlatShape::disk ? 0 : 4; }

// The 2-D Delaunay triangles of the set (the planar triangulation, itself checked against every point below)
// whose centroid lies in the region: the reference the reconstruction's face recall is measured against.
std::vector<Triangle> reference_triangles(const FlatSet& set) {
    dbrg_params params;
    dbrg_params_init(&params);
    dbrg::Context context(params);
    dbrg::PlanarTriangulation triangulation(context.memory);
    REQUIRE(triangulation.build(set.xyz.data(), uint32_t(set.xyz.size() / 3), context,
                                dbrg::ProgressSpan(context, DBRG_STAGE_DELAUNAY)) == DBRG_OK);
    std::vector<Triangle> out;
    for (uint32_t t = 0; t < triangulation.slot_count(); ++t) {
        if (!triangulation.triangle_is_finite(t)) continue;
        Triangle corners;
        double u = 0, v = 0;
        for (uint32_t lv = 0; lv < 3; ++lv) {
            corners[lv] = triangulation.triangle_vertex(t, lv);
            u += set.uv[2 * corners[lv]] / 3;
            v += set.uv[2 * corners[lv] + 1] / 3;
        }
        if (inside_region(set.shape, u, v)) out.push_back(canonical(corners));
    }
    return out;
}

double face_recall(const std::vector<Triangle>& result, const std::vector<Triangle>& reference) {
    const std::set<Triangle> found(result.begin(), result.end());
    size_t recalled = 0;
    for (const Triangle& t : reference) recalled += found.count(t);
    return double(recalled) / double(reference.size());
}

} // namespace

TEST_CASE("flat sets are reconstructed in their plane: one oriented manifold region per shape, holes and notches kept") {
    for (const FlatSet& set : all_flat_sets()) {
        CAPTURE(set.name);
        // The orientation check below needs u_axis x v_axis to be the normal the library turns faces to.
        const auto largest = std::max_element(set.normal.begin(), set.normal.end(),
                                              [](double x, double y) { return std::fabs(x) < std::fabs(y); });
        REQUIRE(*largest > 0);
        const Reconstruction r = reconstruct(set.xyz);
        REQUIRE(r.status == DBRG_OK);
        const dbrg::measure::MeshReport report = report_of(set.xyz, r.triangles);
        require_valid_manifold(report);
        CHECK(report.components == 1);
        CHECK(report.boundary_loops == uint64_t(region_loops(set.shape)));
        CHECK(r.boundary_loops == uint32_t(region_loops(set.shape)));
        CHECK(report.euler_characteristic == region_euler(set.shape));
        CHECK(r.stats.triangles == r.triangles.size() / 3);
        CHECK(r.stats.boundary_edges == report.edges_boundary);
        CHECK(r.stats.tetrahedra == 0);

        const std::vector<Triangle> triangles = triangles_of(r.triangles);
        const uint32_t n = uint32_t(set.uv.size() / 2);
        std::vector<uint8_t> used(n, 0);
        size_t clockwise = 0, bridging = 0, not_empty = 0;
        double area_inside = 0, area_outside = 0;
        for (const Triangle& t : triangles) {
            const double *a = &set.uv[2 * t[0]], *b = &set.uv[2 * t[1]], *c = &set.uv[2 * t[2]];
            for (uint32_t v : t) used[v] = 1;
            // The normal u_axis x v_axis has its largest component positive in both planes: counter-clockwise in
            // (u, v) is the one orientation the result may have.
            clockwise += orient_uv(a, b, c) <= 0;
            // No triangle over the hole, a notch or past the outline. Where the outline turns inward the samples
            // cannot tell where its corner is: triangles cutting it off, smaller than any opening, may lie outside.
            if (!inside_region(set.shape, (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3)) {
                bridging += longest_side_uv(a, b, c) >= NARROWEST_OPENING;
                area_outside += std::fabs(orient_area_uv(a, b, c));
            } else {
                area_inside += std::fabs(orient_area_uv(a, b, c));
            }
            // Delaunay triangles: no point strictly inside a circumcircle.
            for (uint32_t p = 0; p < n; ++p) not_empty += incircle_uv(a, b, c, &set.uv[2 * p]) > 0;
        }
        CHECK(clockwise == 0);
        CHECK(bridging == 0);
        // Corners cut cover little: the border rule reaches about three cell radii (2.1 steps) past a corner,
        // a cut of legs 3 at most, 4.5 square steps, at each corner where the outline turns inward.
        CHECK(area_outside <= 4.5 * inward_corners(set.shape));
        CHECK(not_empty == 0);
        const uint32_t unused = n - uint32_t(std::count(used.begin(), used.end(), 1));
        CHECK(unused == 0);
        const double recall = face_recall(triangles, reference_triangles(set));
        CHECK(recall >= 0.97);
        MESSAGE(set.name << ": " << triangles.size() << " triangles, face recall " << recall << ", area outside " << area_outside / area_inside);
    }
}

TEST_CASE("the planar triangulation is Delaunay, and the same whatever the insertion order") {
    for (const FlatSet& set : all_flat_sets()) {
        CAPTURE(set.name);
        const uint32_t n = uint32_t(set.xyz.size() / 3);
        // The points in reverse order: a triangle of the one is the triangle of the other over the same positions.
        std::vector<double> reversed;
        for (uint32_t i = n; i-- > 0;) reversed.insert(reversed.end(), &set.xyz[3 * i], &set.xyz[3 * i + 3]);
        std::vector<std::set<Triangle>> triangulations;
        const std::vector<double>* orders[] = {&set.xyz, &reversed};
        for (const std::vector<double>* xyz : orders) {
            dbrg_params params;
            dbrg_params_init(&params);
            dbrg::Context context(params);
            dbrg::PlanarTriangulation triangulation(context.memory);
            REQUIRE(triangulation.build(xyz->data(), n, context, dbrg::ProgressSpan(context, DBRG_STAGE_DELAUNAY)) == DBRG_OK);
            char message[200] = "";
            CHECK_MESSAGE(triangulation.validate(message, sizeof message), message);
            std::set<Triangle> triangles;
            for (uint32_t t = 0; t < triangulation.slot_count(); ++t) {
                if (!triangulation.triangle_is_finite(t)) continue;
                Triangle corners;
                for (uint32_t lv = 0; lv < 3; ++lv) {
                    const uint32_t v = triangulation.triangle_vertex(t, lv);
                    corners[lv] = xyz == &set.xyz ? v : n - 1 - v;
                }
                triangles.insert(canonical(corners));
            }
            // Euler's formula over the convex hull: 2n - 2 - h triangles for h hull vertices, so at most 2n - 5.
            CHECK(triangles.size() == triangulation.finite_triangle_count());
            CHECK(triangles.size() <= 2 * size_t(n) - 5);
            size_t not_empty = 0;
            for (const Triangle& t : triangles) {
                for (uint32_t p = 0; p < n; ++p) {
                    not_empty += incircle_uv(&set.uv[2 * t[0]], &set.uv[2 * t[1]], &set.uv[2 * t[2]], &set.uv[2 * p]) > 0;
                }
            }
            CHECK(not_empty == 0);
            triangulations.push_back(triangles);
        }
        CHECK(triangulations[0] == triangulations[1]);
    }
}

TEST_CASE("flat sets: too few distinct points and collinear points stay errors, and there are no tetrahedra") {
    const FlatSet set = flat_set(FlatShape::disk, FlatSampling::grid, FlatPlane::tilted);
    const dbrg_points points{set.xyz.data(), set.xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    char message[200] = "";
    CHECK(dbrg_points_validate(&points, nullptr, message, sizeof message) == DBRG_OK);

    dbrg_tetrahedralization* tets = nullptr;
    CHECK(dbrg_tetrahedralize(&points, nullptr, &tets) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(std::strstr(dbrg_tetrahedralization_message(tets), "coplanar") != nullptr);
    CHECK(dbrg_tetrahedralization_tet_count(tets) == 0);
    dbrg_tetrahedralization_destroy(tets);

    // Three distinct points, repeated: a flat set, but fewer than the four distinct points every call needs.
    std::vector<double> three;
    for (int copy = 0; copy < 4; ++copy) three.insert(three.end(), set.xyz.begin(), set.xyz.begin() + 9);
    CHECK(reconstruct(three).status == DBRG_ERR_TOO_FEW_POINTS);

    std::vector<double> line;
    for (int i = 0; i < 40; ++i) line.insert(line.end(), {0.25 * i, 3.0 - 0.5 * i, 1.0 + i});
    CHECK(reconstruct(line).status == DBRG_ERR_DEGENERATE_INPUT);
    // Meant to lie on one line, rounded off it: exactly coplanar, but no region.
    std::vector<double> rounded;
    for (int i = 0; i < 500; ++i) rounded.insert(rounded.end(), {i * 0.1, i * 0.2, i * 0.3});
    CHECK(reconstruct(rounded).status == DBRG_ERR_DEGENERATE_INPUT);
}

TEST_CASE("flat sets: the statistics") {
    const FlatSet set = flat_set(FlatShape::square_with_hole, FlatSampling::jittered, FlatPlane::tilted);
    const Reconstruction r = reconstruct(set.xyz);
    REQUIRE(r.status == DBRG_OK);
    CHECK(r.stats.unique_points == set.xyz.size() / 3);
    CHECK(r.stats.tetrahedra == 0);
    CHECK(r.stats.triangles == r.triangles.size() / 3);
    CHECK(r.stats.boundary_loops == 2);
    CHECK(r.stats.components == 1);
    CHECK(r.stats.candidates_evaluated >= r.stats.triangles - 1);
    CHECK(r.stats.rejected_boundary > 0);  // the edges of the hole and the outline refuse what lies across them
    CHECK(r.stats.predicate_calls > 0);
    CHECK(r.stats.holes_found == 0);
}
