// Unit tests of region growing below the C API: the surface stays valid after every insertion, the seed
// follows §3.1.1, components are grown from separate seeds, the edge flips come to rest, and the stage
// honours its limits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/context.h"
#include "core/params.h"
#include "grow/candidate_queue.h"
#include "points/point_conditioning.h"
#include "delaunay/tetrahedralization.h"
#include "grow/region_growing.h"
#include "grow/triangle_geometry.h"
#include "pipeline.h"
#include "samples/samples.h"
#include "surface/surface.h"

using namespace dbrg;

namespace {

// Conditioned points, their tetrahedralization and an empty surface, ready to grow.
struct Setup {
    explicit Setup(const std::vector<double>& xyz, const dbrg_params* given = nullptr)
        : context(params_of(given)), points(context.memory), delaunay(context.memory), surface(context.memory) {
        REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
        REQUIRE(delaunay.build(points.coordinates.data(), points.size(), context) == DBRG_OK);
    }
    static dbrg_params params_of(const dbrg_params* given) {
        dbrg_params p;
        fill_default_params(p);
        return given ? *given : p;
    }
    Context context;
    ConditionedPoints points;
    Tetrahedralization delaunay;
    Surface surface;
};

dbrg_status surface_is_valid(void* checks, const Surface& surface, double) {
    ++*static_cast<uint32_t*>(checks);
    char message[200];
    const bool valid = surface.validate(message, sizeof message);
    if (!valid) MESSAGE(message);
    return valid ? DBRG_OK : DBRG_ERR_INTERNAL;
}

uint32_t boundary_halfedges(const Surface& surface) {
    uint32_t count = 0;
    for (uint32_t h = 0; h < 3 * surface.face_count(); ++h) count += surface.is_boundary(h) ? 1 : 0;
    return count;
}

std::vector<double> shifted(std::vector<double> xyz, double dx) {
    for (size_t i = 0; i < xyz.size(); i += 3) xyz[i] += dx;
    return xyz;
}

} // namespace

TEST_CASE("the queue: a clearly smoother candidate first; among near ties, more faces of S, then the smaller one") {
    const auto candidate = [](double smoothness, uint8_t neighbours, double radius, uint32_t apex) {
        Candidate c{};
        c.radius = radius;
        c.apex = apex;
        c.halfedge = 7;
        c.set_smoothness(smoothness, neighbours);
        return c;
    };
    // Apart by more than the tie: smoothness decides, whatever the rest says.
    const double smooth = 1 - 0.25 * SMOOTHNESS_TIE, rougher = 1 - 2.5 * SMOOTHNESS_TIE;
    CHECK(more_credible(candidate(smooth, 1, 2.0, 1), candidate(rougher, 3, 1.0, 0)));
    CHECK_FALSE(more_credible(candidate(rougher, 3, 1.0, 0), candidate(smooth, 1, 2.0, 1)));
    // Within one step of the tie: the candidate closing a notch first, even when it is a little less smooth ...
    const double a = 1 - 0.1 * SMOOTHNESS_TIE, b = 1 - 0.9 * SMOOTHNESS_TIE;
    CHECK(more_credible(candidate(b, 2, 2.0, 1), candidate(a, 1, 1.0, 0)));
    // ... and among as many neighbours the smaller circumradius, then the smoother, then the apex id.
    CHECK(more_credible(candidate(b, 1, 1.0, 1), candidate(a, 1, 2.0, 0)));
    CHECK(more_credible(candidate(a, 1, 1.0, 1), candidate(b, 1, 1.0, 0)));
    CHECK(more_credible(candidate(a, 1, 1.0, 0), candidate(a, 1, 1.0, 1)));
    // Below -1 (no cosine is) and NaN rank last.
    CHECK(more_credible(candidate(-1, 0, 9.0, 0), candidate(-2, 3, 1.0, 0)));
    CHECK(more_credible(candidate(-1, 0, 9.0, 0), candidate(NAN, 3, 1.0, 0)));

    // A strict weak order on random candidates (with many ties of each key), so the heap pops in sorted order.
    std::mt19937 random(5);
    std::uniform_int_distribution<int> pick(0, 3);
    std::vector<Candidate> all;
    for (uint32_t i = 0; i < 400; ++i) {
        all.push_back(candidate(1 - pick(random) * 0.4 * SMOOTHNESS_TIE, uint8_t(pick(random)), 1 + pick(random), uint32_t(pick(random))));
        all.back().halfedge = i;
    }
    for (const Candidate& x : all) {
        CHECK_FALSE(more_credible(x, x));
        for (const Candidate& y : all) {
            if (more_credible(x, y)) CHECK_FALSE(more_credible(y, x));
        }
    }
    Context context(Setup::params_of(nullptr));
    CandidateQueue queue(context.memory);
    for (const Candidate& c : all) REQUIRE(queue.push(c));
    std::vector<Candidate> sorted = all;
    std::sort(sorted.begin(), sorted.end(), more_credible);
    for (const Candidate& expected : sorted) CHECK(queue.pop().halfedge == expected.halfedge);
}

TEST_CASE("the surface is a valid oriented manifold after every insertion, edge flips included") {
    uint32_t flips = 0;
    // Flips are rare (a few in these thousands of faces, and which samples have them moves with the queue's
    // order): several shapes and sizes, so that some come up.
    const std::pair<samples::Shape, uint32_t> inputs[] = {
        {samples::Shape::sphere, 800}, {samples::Shape::torus, 600}, {samples::Shape::saddle, 600},
        {samples::Shape::double_torus, 600}, {samples::Shape::graded_sphere, 800}};
    for (const auto& [shape, count] : inputs) {
        Setup setup(samples::sample(shape, count));
        RegionGrower grower(setup.delaunay, setup.surface, setup.context);
        uint32_t checks = 0;
        grower.observe_steps(surface_is_valid, &checks);
        REQUIRE(grower.grow() == DBRG_OK);
        CHECK(checks == setup.surface.face_count());  // every face, those the flips added too
        CHECK(checks > 1000);
        flips += grower.edge_flips().flip_count();
    }
    CHECK(flips > 0);
}

TEST_CASE("diametral balls and tetrahedron circumradii, which rank the two ways through a tetrahedron") {
    // A quadrilateral a, c, b, d in the plane z = 0, with diagonal a-b the Delaunay one: d is outside the
    // circle through a, b, c, but b is inside the one through a, c, d.
    const double a[3] = {-1, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1.1, 0}, d[3] = {0, -1.1, 0};
    CHECK_FALSE(in_diametral_ball(a, b, c, d));
    CHECK(in_diametral_ball(a, c, d, b));
    // The diametral ball is the smallest through the triangle: a point off its plane but within it counts.
    const double above[3] = {0, 0.3, 0.5};
    CHECK(in_diametral_ball(a, b, c, above));
    // A regular tetrahedron of edge sqrt(8) has circumradius sqrt(3); coplanar corners have none.
    const double p[3] = {1, 1, 1}, q[3] = {1, -1, -1}, r[3] = {-1, 1, -1}, s[3] = {-1, -1, 1};
    CHECK(tet_circumradius(p, q, r, s) == doctest::Approx(std::sqrt(3.0)));
    CHECK(tet_circumradius(a, b, c, d) == HUGE_VAL);
}

TEST_CASE("growing starts from the highest point's smallest Delaunay triangle, facing up") {
    Setup setup(samples::sample(samples::Shape::sphere, 400));
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    REQUIRE(grower.grow() == DBRG_OK);
    uint32_t top = 0;
    for (uint32_t v = 1; v < setup.points.size(); ++v) {
        if (setup.points.point(v)[2] > setup.points.point(top)[2]) top = v;
    }
    const uint32_t a = setup.surface.corner(0, 0), b = setup.surface.corner(0, 1), c = setup.surface.corner(0, 2);
    CHECK((a == top || b == top || c == top));
    const double* pa = setup.points.point(a);
    const double* pb = setup.points.point(b);
    const double* pc = setup.points.point(c);
    const double normal_z = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
    CHECK(normal_z > 0);
}

TEST_CASE("a closed sphere closes without hole filling") {
    Setup setup(samples::sample(samples::Shape::sphere, 3000));
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    REQUIRE(grower.grow() == DBRG_OK);
    CHECK(boundary_halfedges(setup.surface) == 0);
    CHECK(setup.surface.live_face_count() == 2 * setup.points.size() - 4);
    CHECK(setup.context.stats.components == 1);
}

TEST_CASE("separate objects are grown from separate seeds, up to max_components") {
    std::vector<double> xyz = samples::sample(samples::Shape::sphere, 800);
    const std::vector<double> second = shifted(samples::sample(samples::Shape::sphere, 800, 7), 5.0);
    xyz.insert(xyz.end(), second.begin(), second.end());
    {
        Setup setup(xyz);
        RegionGrower grower(setup.delaunay, setup.surface, setup.context);
        REQUIRE(grower.grow() == DBRG_OK);
        CHECK(setup.context.stats.components == 2);
        CHECK(boundary_halfedges(setup.surface) == 0);
        Array<uint32_t> labels(setup.context.memory);
        CHECK(setup.surface.label_components(labels) == 2);
    }
    dbrg_params params;
    fill_default_params(params);
    params.max_components = 1;
    Setup setup(xyz, &params);
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    REQUIRE(grower.grow() == DBRG_OK);
    CHECK(setup.context.stats.components == 1);
    uint32_t used = 0;
    for (uint32_t v = 0; v < setup.points.size(); ++v) used += setup.surface.is_used(v) ? 1 : 0;
    CHECK(used < setup.points.size() / 2 + 20);
}

TEST_CASE("stray points do not become components of their own") {
    std::vector<double> xyz = samples::sample(samples::Shape::sphere, 1000);
    // A few outliers far from the sphere and from each other.
    for (double x : {3.0, -4.0, 5.5}) xyz.insert(xyz.end(), {x, 0.3 * x, -0.2 * x});
    Setup setup(xyz);
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    REQUIRE(grower.grow() == DBRG_OK);
    CHECK(setup.context.stats.components == 1);
}

TEST_CASE("the open-surface test refuses candidates and records why the edges stayed open") {
    const std::vector<double> xyz = samples::sample(samples::Shape::hemisphere, 1500);
    Setup setup(xyz);
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    REQUIRE(grower.grow() == DBRG_OK);
    CHECK(setup.context.stats.rejected_boundary > 0);
    uint32_t open = 0, boundary = 0;
    for (uint32_t h = 0; h < 3 * setup.surface.face_count(); ++h) {
        if (!setup.surface.is_boundary(h)) continue;
        ++boundary;
        open += grower.boundary_causes().of(h) == BOUNDARY_OPEN ? 1 : 0;
    }
    CHECK(boundary > 50);
    CHECK(open > boundary / 2);
}

namespace {

// What the edge flips would still do with the live edges of S: flips left, edges deferred, and edges whose
// two half-edges get different decisions (the pass visits an edge from one side only).
struct FlipsLeft {
    uint32_t flips = 0, deferred = 0, one_sided = 0;
};
FlipsLeft flips_left(const RegionGrower& grower, const Surface& surface) {
    FlipsLeft left;
    for (uint32_t h = 0; h < 3 * surface.face_count(); ++h) {
        if (surface.face_removed(Surface::face_of(h))) continue;
        uint32_t tet = NO_TET;
        const EdgeFlipper::Decision decision = grower.edge_flips().decide(h, tet);
        left.flips += decision == EdgeFlipper::Decision::flip ? 1 : 0;
        left.deferred += decision == EdgeFlipper::Decision::defer ? 1 : 0;
        const uint32_t twin = surface.twin(h);
        if (twin != NO_HALFEDGE && grower.edge_flips().decide(twin, tet) != decision) ++left.one_sided;
    }
    return left;
}

} // namespace

TEST_CASE("the edge flips come to rest: none is left to make, and only edges at the boundary wait") {
    uint32_t flips = 0;
    for (samples::Shape shape : {samples::Shape::sphere, samples::Shape::torus, samples::Shape::saddle,
                                 samples::Shape::bumpy_sphere}) {
        Setup setup(samples::sample(shape, 4000));
        RegionGrower grower(setup.delaunay, setup.surface, setup.context);
        REQUIRE(grower.grow() == DBRG_OK);
        const FlipsLeft left = flips_left(grower, setup.surface);
        CHECK(left.flips == 0);
        CHECK(left.one_sided == 0);
        if (boundary_halfedges(setup.surface) == 0) CHECK(left.deferred == 0);
        flips += grower.edge_flips().flip_count();
    }
    CHECK(flips > 0);
}

TEST_CASE("hole filling makes the flips growing deferred, and those around the faces it added") {
    // Growing leaves holes along the cylinder's sharp rims, where it defers flips, and on the sparse side
    // of the graded sphere, where the filled holes' new faces change what is around their edges; filling
    // closes both. (Samples where flips wait for hole filling: most are made while growing.)
    struct Input {
        samples::Shape shape;
        size_t points;
        uint64_t seed;
    };
    for (const Input& input : {Input{samples::Shape::capped_cylinder, 3000, 3}, Input{samples::Shape::graded_sphere, 2000, 1}}) {
        Setup setup(samples::sample(input.shape, input.points, input.seed));
        RegionGrower grower(setup.delaunay, setup.surface, setup.context);
        REQUIRE(grower.grow() == DBRG_OK);
        REQUIRE(boundary_halfedges(setup.surface) > 0);
        const uint32_t flips_while_growing = grower.edge_flips().flip_count();
        REQUIRE(fill_holes(setup.delaunay, setup.surface, grower, setup.context) == DBRG_OK);
        CHECK(boundary_halfedges(setup.surface) == 0);
        const FlipsLeft left = flips_left(grower, setup.surface);
        CHECK(left.flips == 0);
        CHECK(left.deferred == 0);
        CHECK(left.one_sided == 0);
        CHECK(grower.edge_flips().flip_count() > flips_while_growing);
    }
}

TEST_CASE("after hole filling no flip is left on closed shapes, and both sides of every edge agree") {
    for (samples::Shape shape : {samples::Shape::sphere, samples::Shape::torus, samples::Shape::double_torus,
                                 samples::Shape::bumpy_sphere, samples::Shape::cube, samples::Shape::capped_cylinder,
                                 samples::Shape::graded_sphere, samples::Shape::thin_plate}) {
        for (uint64_t seed : {1, 2}) {
            Setup setup(samples::sample(shape, 3000, seed));
            RegionGrower grower(setup.delaunay, setup.surface, setup.context);
            REQUIRE(grower.grow() == DBRG_OK);
            REQUIRE(fill_holes(setup.delaunay, setup.surface, grower, setup.context) == DBRG_OK);
            const FlipsLeft left = flips_left(grower, setup.surface);
            CHECK(left.flips == 0);
            CHECK(left.one_sided == 0);
            if (boundary_halfedges(setup.surface) == 0) CHECK(left.deferred == 0);
        }
    }
}

TEST_CASE("a cancelling progress callback stops growing") {
    dbrg_params params;
    fill_default_params(params);
    int calls = 0;
    params.progress = [](void* user, dbrg_stage stage, double) -> int {
        return stage == DBRG_STAGE_GROW && ++*static_cast<int*>(user) > 1;
    };
    params.progress_user = &calls;
    Setup setup(samples::sample(samples::Shape::sphere, 5000), &params);
    RegionGrower grower(setup.delaunay, setup.surface, setup.context);
    CHECK(grower.grow() == DBRG_ERR_CANCELLED);
}
