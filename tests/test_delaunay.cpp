// Tests of the Delaunay tetrahedralization: validity on random and degenerate sets, determinism,
// scale invariance, queries for region growing, failure paths, and agreement with TetGen.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "core/pi.h"
#include "delaunay/edge_ring.h"
#include "points/point_conditioning.h"
#include "points/spatial_sort.h"
#include "delaunay/tetgen_backend.h"
#include "delaunay/tetrahedralization.h"
#include "delaunay_test_support.h"
#include "samples/samples.h"
#include "support/quality_suite.h"

using namespace dbrg;
using namespace dbrg_test;

namespace {

using Quad = std::array<uint32_t, 4>;

// The finite tetrahedra as sorted vertex quadruples, sorted: comparable across builds.
std::vector<Quad> canonical_tets(const Tetrahedralization& tets) {
    std::vector<Quad> out;
    for (uint32_t t = 0; t < tets.tet_slots(); ++t) {
        if (tets.tet_is_free(t) || !tets.tet_is_finite(t)) continue;
        Quad q = {tets.tet_vertex(t, 0), tets.tet_vertex(t, 1), tets.tet_vertex(t, 2), tets.tet_vertex(t, 3)};
        std::sort(q.begin(), q.end());
        out.push_back(q);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Conditions and tetrahedralizes `xyz`, checks validate(), and returns the canonical tetrahedra.
struct Built {
    Context context;
    ConditionedPoints points;
    Tetrahedralization tets;
    dbrg_status status;

    // `hilbert_numbered`: renumber the points along the Hilbert curve first, as the pipeline does.
    explicit Built(const std::vector<double>& xyz, const dbrg_params& params = test_params(), bool hilbert_numbered = false)
        : context(params), points(context.memory), tets(context.memory) {
        status = condition_points(xyz.data(), xyz.size() / 3, context, points);
        if (status == DBRG_OK && hilbert_numbered) status = renumber_spatially(points, context);
        if (status == DBRG_OK) status = tets.build(points.coordinates.data(), points.size(), context);
    }
};

void check_valid(const std::vector<double>& xyz, uint32_t expected_vertices = 0) {
    Built b(xyz);
    REQUIRE_MESSAGE(b.status == DBRG_OK, b.context.message());
    char message[256];
    const bool valid = b.tets.validate(message, sizeof message);
    CHECK_MESSAGE(valid, message);
    CHECK(b.tets.vertex_count() == b.points.size());
    if (expected_vertices) CHECK(b.points.size() == expected_vertices);
    CHECK(b.tets.finite_tet_count() > 0);
}

} // namespace

TEST_CASE("hilbert_index visits face-adjacent cells in order") {
    const int bits = 3;
    const uint32_t side = 1u << bits;
    std::vector<std::array<uint32_t, 3>> cell(side * side * side);
    std::vector<bool> seen(cell.size(), false);
    for (uint32_t x = 0; x < side; ++x)
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t z = 0; z < side; ++z) {
                const uint64_t h = hilbert_index(x, y, z, bits);
                REQUIRE(h < cell.size());
                REQUIRE_FALSE(seen[h]);
                seen[h] = true;
                cell[h] = {x, y, z};
            }
    for (size_t i = 1; i < cell.size(); ++i) {
        uint32_t distance = 0;
        for (int k = 0; k < 3; ++k) distance += cell[i][k] > cell[i - 1][k] ? cell[i][k] - cell[i - 1][k] : cell[i - 1][k] - cell[i][k];
        CHECK(distance == 1);
    }
}

TEST_CASE("brio_hilbert_order is a permutation that depends on the points only") {
    const std::vector<double> xyz = random_cube(5000, 1);
    Context context(test_params());
    Array<uint32_t> a(context.memory), b(context.memory);
    const ProgressSpan sort(context, DBRG_STAGE_SORT);
    REQUIRE(brio_hilbert_order(xyz.data(), 5000, sort, a) == DBRG_OK);
    REQUIRE(brio_hilbert_order(xyz.data(), 5000, sort, b) == DBRG_OK);
    std::vector<uint32_t> sorted(a.begin(), a.end());
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < 5000; ++i) CHECK(sorted[i] == i);
    CHECK(std::equal(a.begin(), a.end(), b.begin()));
}

TEST_CASE("the Hilbert order and its check are the same on one thread and on several") {
    // Two slices of 20,000 points on two threads.
    const std::vector<double> xyz = random_cube(2 * 20000, 11);
    dbrg_params params = test_params();
    params.threads = 1;
    Context context(params);
    params.threads = 2;
    Context two_threads(params);
    const ProgressSpan on_one(context, DBRG_STAGE_SORT), on_two(two_threads, DBRG_STAGE_SORT);
    ConditionedPoints points(context.memory);
    REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
    const uint32_t n = points.size();
    Array<uint32_t> one(context.memory), several(context.memory);
    REQUIRE(hilbert_order(points.coordinates.data(), n, on_one, one) == DBRG_OK);
    REQUIRE(hilbert_order(points.coordinates.data(), n, on_two, several) == DBRG_OK);
    CHECK(std::equal(one.begin(), one.end(), several.begin()));
    REQUIRE(renumber_spatially(points, context) == DBRG_OK);
    bool ordered = false;
    REQUIRE(in_hilbert_order(points.coordinates.data(), n, on_two, ordered) == DBRG_OK);
    CHECK(ordered);
    // A descent exactly where the second slice begins, and one inside it, are both seen.
    for (uint32_t at : {n / 2, n / 2 + 1000}) {
        CAPTURE(at);
        std::vector<double> swapped(points.coordinates.begin(), points.coordinates.end());
        std::swap_ranges(swapped.begin() + 3 * size_t(at - 1), swapped.begin() + 3 * size_t(at), swapped.begin() + 3 * size_t(at));
        for (const ProgressSpan& threads : {on_two, on_one}) {
            REQUIRE(in_hilbert_order(swapped.data(), n, threads, ordered) == DBRG_OK);
            CHECK_FALSE(ordered);
        }
    }
}

TEST_CASE("the insertion order is streamed on Hilbert-numbered points and equals the sorted one") {
    for (const std::vector<double>& xyz : {random_cube(20000, 7), random_sphere(5000, 8), lattice(12, 0.0, 9)}) {
        Context context(test_params());
        ConditionedPoints points(context.memory);
        REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
        for (int numbered = 0; numbered < 2; ++numbered) {
            if (numbered) REQUIRE(renumber_spatially(points, context) == DBRG_OK);
            const uint32_t n = points.size();
            // Lexicographic numbering is not along the curve; renumber_spatially's is.
            const ProgressSpan sort(context, DBRG_STAGE_SORT);
            bool ordered = false;
            REQUIRE(in_hilbert_order(points.coordinates.data(), n, sort, ordered) == DBRG_OK);
            CHECK(ordered == (numbered == 1));
            Array<uint32_t> sorted(context.memory);
            REQUIRE(brio_hilbert_order(points.coordinates.data(), n, sort, sorted) == DBRG_OK);
            // Checked, and taken from the points as renumber_spatially marked them: the same order.
            CHECK((points.order == PointOrder::hilbert) == (numbered == 1));
            for (PointOrder told : {PointOrder::any, points.order}) {
                BrioOrder order(context.memory);
                REQUIRE(order.prepare(points.coordinates.data(), n, told, context) == DBRG_OK);
                CHECK(order.streamed() == (numbered == 1));
                uint32_t v = 0, i = 0;
                bool same = true;
                while (order.next(v)) same &= i < n && sorted[i++] == v;
                CHECK(same);
                CHECK(i == n);
            }
        }
        // The tetrahedralization of the renumbered points is valid and has the same tetrahedra.
        Tetrahedralization tets(context.memory);
        REQUIRE(tets.build(points.coordinates.data(), points.size(), context) == DBRG_OK);
        char message[256];
        CHECK_MESSAGE(tets.validate(message, sizeof message), message);
        Built lexicographic(xyz);
        REQUIRE(lexicographic.status == DBRG_OK);
        CHECK(tets.finite_tet_count() == lexicographic.tets.finite_tet_count());
        std::set<std::array<double, 12>> ours, theirs;
        auto corners = [](const Tetrahedralization& t, uint32_t s) {
            std::array<std::array<double, 3>, 4> c;
            for (uint32_t lv = 0; lv < 4; ++lv)
                for (int k = 0; k < 3; ++k) c[lv][k] = t.point(t.tet_vertex(s, lv))[k];
            std::sort(c.begin(), c.end());
            std::array<double, 12> flat;
            for (int j = 0; j < 12; ++j) flat[j] = c[j / 3][j % 3];
            return flat;
        };
        for (uint32_t s = 0; s < tets.tet_slots(); ++s)
            if (!tets.tet_is_free(s) && tets.tet_is_finite(s)) ours.insert(corners(tets, s));
        const Tetrahedralization& other = lexicographic.tets;
        for (uint32_t s = 0; s < other.tet_slots(); ++s)
            if (!other.tet_is_free(s) && other.tet_is_finite(s)) theirs.insert(corners(other, s));
        CHECK(ours == theirs);
    }
}

TEST_CASE("random points in a cube") {
    check_valid(random_cube(3000, 2), 3000);
    Built b(random_cube(20000, 3));
    REQUIRE(b.status == DBRG_OK);
    const double per_point = double(b.tets.finite_tet_count()) / 20000;
    CHECK(per_point > 6.0);
    CHECK(per_point < 7.0);
}

TEST_CASE("random points on a sphere") { check_valid(random_sphere(3000, 4), 3000); }

TEST_CASE("exact 40x40x40 lattice") { check_valid(lattice(40, 0.0, 5), 64000); }

TEST_CASE("jittered lattice") { check_valid(lattice(20, 0.3, 6), 8000); }

TEST_CASE("cube surface lattice (massively cospherical)") { check_valid(cube_surface_lattice(25)); }

TEST_CASE("small degenerate sets") {
    SUBCASE("a cube's corners") { check_valid(cube_surface_lattice(2), 8); }
    SUBCASE("3x3x3 lattice") { check_valid(lattice(3, 0.0, 1), 27); }
    SUBCASE("a regular octahedron") {
        check_valid({1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1}, 6);
    }
    SUBCASE("cocircular points on a plane plus one above") {
        std::vector<double> xyz;
        for (int i = 0; i < 12; ++i) {
            xyz.push_back(cos(i * PI / 6));
            xyz.push_back(sin(i * PI / 6));
            xyz.push_back(0);
        }
        xyz.insert(xyz.end(), {0, 0, 1});
        check_valid(xyz, 13);
    }
}

TEST_CASE("points on a few planes") {
    Random r(7);
    std::vector<double> xyz;
    for (int plane = 0; plane < 3; ++plane) {
        for (int i = 0; i < 600; ++i) {
            const double u = r.uniform(), v = r.uniform();
            if (plane == 0) xyz.insert(xyz.end(), {u, v, 0.0});
            if (plane == 1) xyz.insert(xyz.end(), {u, 0.5, v});
            if (plane == 2) xyz.insert(xyz.end(), {0.25 * u + 0.75 * v, u, 1.0 - v});  // not axis-aligned
        }
    }
    // Grid points on planes too: coplanar and cocircular at once.
    for (int i = 0; i < 15; ++i)
        for (int j = 0; j < 15; ++j) xyz.insert(xyz.end(), {i / 14.0, j / 14.0, 1.0});
    check_valid(xyz);
}

TEST_CASE("two points one ulp apart") {
    std::vector<double> xyz = random_cube(500, 8);
    const double x = xyz[0], y = xyz[1], z = xyz[2];
    xyz.insert(xyz.end(), {nextafter(x, 2.0), y, z});
    xyz.insert(xyz.end(), {x, nextafter(y, -1.0), z});
    xyz.insert(xyz.end(), {0.5, 0.5, 0.5});
    xyz.insert(xyz.end(), {0.5, 0.5, nextafter(0.5, 1.0)});
    check_valid(xyz, 504);
}

TEST_CASE("points spanning a thousand binary orders of magnitude") {
    // Tiny coordinates beside unit ones once made the exact predicates underflow (a walk that never ended,
    // a broken cavity); conditioning rounds them onto the predicates' 2^-200 grid.
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        Random r(seed);
        std::vector<double> xyz = random_cube(200, seed);
        for (int i = 0; i < 50; ++i) {
            const double scale = ldexp(1.0, -static_cast<int>(r.next() % 1000));
            xyz.insert(xyz.end(), {scale * (r.uniform() - 0.5), scale * (r.uniform() - 0.5), scale * (r.uniform() - 0.5)});
        }
        check_valid(xyz);
    }
}

TEST_CASE("scaled copies give the same tetrahedra") {
    const std::vector<double> base = random_cube(2000, 9);
    Built unit(base);
    REQUIRE(unit.status == DBRG_OK);
    const std::vector<Quad> expected = canonical_tets(unit.tets);
    for (double scale : {1e-300, 1e300, 3.0, -1.0}) {
        std::vector<double> scaled = base;
        for (double& c : scaled) c *= scale;
        Built copy(scaled);
        REQUIRE(copy.status == DBRG_OK);
        char message[256];
        CHECK_MESSAGE(copy.tets.validate(message, sizeof message), message);
        if (scale > 0) {
            CHECK(canonical_tets(copy.tets) == expected);
        } else {
            CHECK(canonical_tets(copy.tets).size() == expected.size());  // mirrored: ids are reordered
        }
    }
}

TEST_CASE("shuffled copies give identical tetrahedra") {
    for (const std::vector<double>& base : {random_cube(3000, 10), lattice(12, 0.0, 0), cube_surface_lattice(12)}) {
        Built first(base);
        REQUIRE(first.status == DBRG_OK);
        const size_t n = base.size() / 3;
        std::vector<size_t> permutation(n);
        for (size_t i = 0; i < n; ++i) permutation[i] = i;
        Random r(11);
        for (size_t i = n - 1; i > 0; --i) std::swap(permutation[i], permutation[r.next() % (i + 1)]);
        std::vector<double> shuffled(base.size());
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) shuffled[3 * i + k] = base[3 * permutation[i] + k];
        Built second(shuffled);
        REQUIRE(second.status == DBRG_OK);
        CHECK(canonical_tets(first.tets) == canonical_tets(second.tets));
        // The store itself is identical: insertion order comes from the coordinates only.
        REQUIRE(first.tets.tet_slots() == second.tets.tet_slots());
        bool same = true;
        for (uint32_t t = 0; t < first.tets.tet_slots(); ++t)
            for (uint32_t k = 0; k < 4; ++k) {
                same &= first.tets.tet_vertex(t, k) == second.tets.tet_vertex(t, k);
                same &= first.tets.tet_adjacent(t, k) == second.tets.tet_adjacent(t, k);
            }
        CHECK(same);
    }
}

TEST_CASE("threads inserting the last round at once make the tetrahedra of one thread") {
    // From 32,768 points on the last BRIO round is split among threads. A surface sample in Hilbert
    // numbering (as the pipeline gives it: the order is streamed), the same with its points shuffled (the
    // order is an array), points on one sphere (all on the hull, all cospherical), an exact lattice and a
    // cube's surface lattice (massively degenerate), and a torus, whose long tetrahedra inside the tube
    // make threads meet and whose growing number of tetrahedra per point fills the store the threads were
    // given (they stop, it grows, they go on).
    std::vector<double> shuffled = samples::sample(samples::Shape::bumpy_sphere, 40000);
    Random r(5);
    const size_t n = shuffled.size() / 3;
    for (size_t i = n - 1; i > 0; --i) {
        const size_t j = r.next() % (i + 1);
        for (int k = 0; k < 3; ++k) std::swap(shuffled[3 * i + k], shuffled[3 * j + k]);
    }
    const std::vector<double> inputs[] = {samples::sample(samples::Shape::bumpy_sphere, 40000), shuffled,
                                          random_sphere(34000, 3), lattice(33, 0.0, 0), cube_surface_lattice(76),
                                          samples::sample(samples::Shape::torus, 60000)};
    for (size_t input = 0; input < std::size(inputs); ++input) {
        CAPTURE(input);
        dbrg_params params = test_params();
        params.threads = 1;
        Built one(inputs[input], params, input != 1);
        REQUIRE(one.status == DBRG_OK);
        const std::vector<Quad> expected = canonical_tets(one.tets);
        for (uint32_t threads = 2; threads <= (input + 1 == std::size(inputs) ? 3u : 2u); ++threads) {
            CAPTURE(threads);
            params.threads = threads;
            Built several(inputs[input], params, input != 1);
            REQUIRE(several.status == DBRG_OK);
            char message[256];
            const bool valid = several.tets.validate(message, sizeof message);
            CHECK_MESSAGE(valid, message);
            CHECK(several.tets.finite_tet_count() == one.tets.finite_tet_count());
            CHECK(canonical_tets(several.tets) == expected);
            CHECK(several.tets.counters.calls > 0);
        }
    }
}

TEST_CASE("threads sharing the last round of a cylinder make about the predicate calls of one thread" * doctest::test_suite(test::QUALITY_SUITE)) {
    // Points on an open cylinder: the long tetrahedra across its inside make the threads meet, and many
    // points are set aside for the calling thread. Each of those walks from the one inserted before it, so
    // a walk that starts from an arbitrary tetrahedron around that point crosses the cylinder: counts, not
    // time, so the check holds on a loaded machine (with no point set aside the counts are equal).
    Random r(31);
    const size_t n = 60000;
    std::vector<double> cylinder(3 * n);
    for (size_t i = 0; i < n; ++i) {
        const double angle = 6.283185307179586 * r.uniform();
        cylinder[3 * i] = cos(angle);
        cylinder[3 * i + 1] = sin(angle);
        cylinder[3 * i + 2] = 6 * r.uniform();
    }
    dbrg_params params = test_params();
    params.threads = 1;
    Built one(cylinder, params, true);
    REQUIRE(one.status == DBRG_OK);
    params.threads = 2;
    Built two(cylinder, params, true);
    REQUIRE(two.status == DBRG_OK);
    CHECK(canonical_tets(two.tets) == canonical_tets(one.tets));
    MESSAGE("predicate calls, one thread: " << one.tets.counters.calls << ", two: " << two.tets.counters.calls);
    CHECK(double(two.tets.counters.calls) < 1.25 * double(one.tets.counters.calls));
}

TEST_CASE("too few and collinear inputs fail with a status; coplanar ones have no tetrahedra") {
    Context context(test_params());
    ConditionedPoints points(context.memory);
    Tetrahedralization tets(context.memory);
    const double three[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK(condition_points(three, 3, context, points) == DBRG_ERR_TOO_FEW_POINTS);
    CHECK(tets.build(three, 3, context) == DBRG_ERR_TOO_FEW_POINTS);
    CHECK(condition_points(three, 0, context, points) == DBRG_ERR_TOO_FEW_POINTS);

    std::vector<double> line;
    for (int i = 0; i < 10; ++i) line.insert(line.end(), {0.25 * i, 2.0 * i + 1, -3.0 * i});  // exact
    CHECK(condition_points(line.data(), 10, context, points) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(strstr(context.message(), "collinear") != nullptr);
    CHECK(tets.build(line.data(), 10, context) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(tets.tet_slots() == 0);

    std::vector<double> plane;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) plane.insert(plane.end(), {double(i), double(j), double(i + 2 * j)});
    CHECK(condition_points(plane.data(), 100, context, points) == DBRG_OK);
    CHECK(points.flat);
    CHECK(refuse_flat(points, 100, context) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(strstr(context.message(), "coplanar") != nullptr);
    CHECK(strstr(context.message(), "100") != nullptr);
    points.coordinates.release();
    points.input_index.release();
    CHECK(tets.build(plane.data(), 100, context) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(context.memory.bytes_in_use() == 0);
}

TEST_CASE("edge circulation: closed cycles of faces of the reported tets") {
    Built b(random_cube(1500, 12));
    REQUIRE(b.status == DBRG_OK);
    const Tetrahedralization& tets = b.tets;
    // Every finite triangle, as a sorted triple; every edge of a finite tet with one tet holding it.
    std::map<std::array<uint32_t, 3>, int> visits;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> edges;
    for (uint32_t t = 0; t < tets.tet_slots(); ++t) {
        if (tets.tet_is_free(t)) continue;
        for (uint32_t lf = 0; lf < 4; ++lf) {
            std::array<uint32_t, 3> f;
            int k = 0;
            for (uint32_t lv = 0; lv < 4; ++lv) if (lv != lf) f[k++] = tets.tet_vertex(t, lv);
            std::sort(f.begin(), f.end());
            if (f[2] != INFINITE_VERTEX) visits[f] = 0;
        }
        if (!tets.tet_is_finite(t)) continue;
        for (uint32_t i = 0; i < 4; ++i)
            for (uint32_t j = i + 1; j < 4; ++j) {
                const uint32_t u = tets.tet_vertex(t, i), v = tets.tet_vertex(t, j);
                edges.emplace(std::make_pair(std::min(u, v), std::max(u, v)), t);
            }
    }
    Array<uint32_t> around(b.context.memory);
    bool all_faces = true, all_closed = true, rings_whole = true;
    for (const auto& edge : edges) {
        const uint32_t u = edge.first.first, v = edge.first.second;
        std::vector<uint32_t> apexes, holders;
        walk_edge_ring(tets, edge.second, u, v, [&](uint32_t apex, uint32_t tet) {
            all_faces &= tets.tet_local_index(tet, u) < 4 && tets.tet_local_index(tet, v) < 4 &&
                         tets.tet_local_index(tet, apex) < 4;
            apexes.push_back(apex);
            holders.push_back(tet);
        });
        // Closed: as many triangles as tetrahedra around the edge, and no apex twice.
        REQUIRE(tets.tets_around_vertex(u, around));
        size_t around_edge = 0;
        std::vector<uint32_t> ring;
        for (uint32_t s : around) {
            if (tets.tet_local_index(s, v) < 4) ring.push_back(s);
        }
        around_edge = ring.size();
        // Each tetrahedron of the ring once.
        std::sort(ring.begin(), ring.end());
        std::sort(holders.begin(), holders.end());
        rings_whole &= holders == ring;
        all_closed &= apexes.size() == around_edge && apexes.size() >= 3;
        std::vector<uint32_t> distinct = apexes;
        std::sort(distinct.begin(), distinct.end());
        all_closed &= std::unique(distinct.begin(), distinct.end()) == distinct.end();
        for (uint32_t a : apexes) {
            if (a == INFINITE_VERTEX) continue;
            std::array<uint32_t, 3> f = {u, v, a};
            std::sort(f.begin(), f.end());
            const auto it = visits.find(f);
            REQUIRE(it != visits.end());
            it->second += 1;
        }
    }
    CHECK(all_faces);
    CHECK(all_closed);
    CHECK(rings_whole);
    // Every Delaunay triangle appears around each of its three edges, once each.
    bool three_each = true;
    for (const auto& f : visits) three_each &= f.second == 3;
    CHECK(three_each);
}

TEST_CASE("tets_around_vertex finds exactly the tetrahedra holding the vertex") {
    Built b(lattice(8, 0.0, 0));
    REQUIRE(b.status == DBRG_OK);
    Array<uint32_t> around(b.context.memory);
    for (uint32_t v = 0; v < b.tets.vertex_count(); v += 7) {
        REQUIRE(b.tets.tets_around_vertex(v, around));
        std::vector<uint32_t> got(around.begin(), around.end()), expected;
        for (uint32_t t = 0; t < b.tets.tet_slots(); ++t) {
            if (!b.tets.tet_is_free(t) && b.tets.tet_local_index(t, v) < 4) expected.push_back(t);
        }
        std::sort(got.begin(), got.end());
        CHECK(got == expected);
    }
}

TEST_CASE("a failing allocator gives OUT_OF_MEMORY and leaks nothing") {
    const std::vector<double> xyz = random_cube(3000, 13);
    uint64_t total = 0;
    {
        CountingAllocator counting;
        const dbrg_params params = test_params(&counting.allocator);
        {
            Built b(xyz, params);
            REQUIRE(b.status == DBRG_OK);
        }
        total = counting.allocations;
        CHECK(counting.live_blocks == 0);
        CHECK(counting.live_bytes == 0);
    }
    REQUIRE(total > 5);
    std::vector<uint64_t> sample;
    for (uint64_t k = 1; k <= total; k += (k < 40 ? 1 : 1 + total / 60)) sample.push_back(k);
    sample.push_back(total);
    for (uint64_t k : sample) {
        CAPTURE(k);
        CountingAllocator counting;
        counting.fail_at = k;
        const dbrg_params params = test_params(&counting.allocator);
        {
            Context context(params);
            {
                ConditionedPoints points(context.memory);
                Tetrahedralization tets(context.memory);
                dbrg_status status = condition_points(xyz.data(), xyz.size() / 3, context, points);
                if (status == DBRG_OK) status = tets.build(points.coordinates.data(), points.size(), context);
                CHECK(status == DBRG_ERR_OUT_OF_MEMORY);
                CHECK(context.memory.failed());
            }
            CHECK(context.memory.bytes_in_use() == 0);
        }
        CHECK(counting.live_blocks == 0);
    }
}

TEST_CASE("the progress callback sees DBRG_STAGE_DELAUNAY and can cancel") {
    struct Log {
        int delaunay_calls = 0;
        int cancel_after = -1;
        double last = -1;
        bool monotonic = true;
    };
    const std::vector<double> xyz = random_cube(50000, 14);
    auto callback = [](void* user, dbrg_stage stage, double fraction) -> int {
        Log& log = *static_cast<Log*>(user);
        if (stage != DBRG_STAGE_DELAUNAY) return 0;
        log.monotonic &= fraction >= log.last;
        log.last = fraction;
        ++log.delaunay_calls;
        return log.cancel_after >= 0 && log.delaunay_calls > log.cancel_after;
    };
    {
        Log log;
        Built b(xyz, test_params(nullptr, callback, &log));
        CHECK(b.status == DBRG_OK);
        CHECK(log.delaunay_calls > 5);
        CHECK(log.monotonic);
        CHECK(log.last == 1.0);
    }
    {
        Log log;
        log.cancel_after = 3;
        Built b(xyz, test_params(nullptr, callback, &log));
        CHECK(b.status == DBRG_ERR_CANCELLED);
        CHECK(b.tets.tet_slots() == 0);
        CHECK(log.delaunay_calls == 4);
    }
}

namespace {

// The Delaunay stage's reports, and at each one how many tetrahedron slots the store under construction
// has written.
struct StoreWatch {
    const Tetrahedralization* tets = nullptr;
    std::vector<double> fractions;
    std::vector<uint32_t> written;
    static int report(void* user, dbrg_stage stage, double fraction) {
        StoreWatch& self = *static_cast<StoreWatch*>(user);
        if (stage != DBRG_STAGE_DELAUNAY) return 0;
        self.fractions.push_back(fraction);
        self.written.push_back(self.tets->tet_slots());
        return 0;
    }
};

// Tetrahedralizes `xyz` with `threads` threads, watching the store.
StoreWatch watch_store(const std::vector<double>& xyz, uint32_t threads) {
    StoreWatch watch;
    dbrg_params params = test_params(nullptr, StoreWatch::report, &watch);
    params.threads = threads;
    Context context(params);
    ConditionedPoints points(context.memory);
    Tetrahedralization tets(context.memory);
    watch.tets = &tets;
    REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
    REQUIRE(tets.build(points.coordinates.data(), points.size(), context) == DBRG_OK);
    return watch;
}

} // namespace

TEST_CASE("the tetrahedron store is written in steps between progress reports, not all at once") {
    // 150,000 points: 900,000 slots reserved at the start, written 131,072 at a time as insertion needs
    // them or ahead of need (while fewer than 32 per point inserted are written).
    const StoreWatch watch = watch_store(random_cube(150000, 21), 1);
    REQUIRE(watch.written.size() > 100);
    uint32_t largest_step = 0;
    for (size_t i = 1; i < watch.written.size(); ++i) {
        if (watch.written[i] > watch.written[i - 1]) largest_step = std::max(largest_step, watch.written[i] - watch.written[i - 1]);
    }
    CHECK(largest_step > 0);
    CHECK(largest_step <= 1u << 18);
}

TEST_CASE("threads sharing the last round: the calling thread reports all their points as they come in") {
    // 200,000 points on two threads: the last round's three quarters are split in two. Counting only the
    // calling thread's points, or not reporting while it waits for the other thread, leaves a jump of up
    // to 37 % of the stage; the calling thread reports every 256 of its points, which with the other
    // thread's move the fraction by about 0.3 % (more while the calling thread waits for a processor).
    const StoreWatch watch = watch_store(random_cube(200000, 22), 2);
    REQUIRE(watch.fractions.size() > 50);
    double largest_jump = 0;
    for (size_t i = 1; i < watch.fractions.size(); ++i) {
        largest_jump = std::max(largest_jump, watch.fractions[i] - watch.fractions[i - 1]);
    }
    CHECK(watch.fractions.back() == 1.0);
    CHECK(largest_jump < 0.25);
}

TEST_CASE("the TetGen backend's availability matches the build") {
    Context context(test_params());
    Tetrahedralization tets(context.memory);
    const std::vector<double> xyz = random_cube(100, 15);
#if DBRG_HAVE_TETGEN
    CHECK(tetgen_available());
#else
    CHECK_FALSE(tetgen_available());
    CHECK(build_with_tetgen(xyz.data(), 100, context, tets) == DBRG_ERR_UNSUPPORTED);
#endif
}

#if DBRG_HAVE_TETGEN
TEST_CASE("TetGen and the built-in engine agree on points in general position") {
    for (const std::vector<double>& xyz : {random_cube(5000, 16), random_sphere(3000, 17), lattice(15, 0.2, 18)}) {
        Built ours(xyz);
        REQUIRE(ours.status == DBRG_OK);
        Tetrahedralization theirs(ours.context.memory);
        REQUIRE(build_with_tetgen(ours.points.coordinates.data(), ours.points.size(), ours.context, theirs) == DBRG_OK);
        char message[256];
        CHECK_MESSAGE(theirs.validate(message, sizeof message), message);
        CHECK(canonical_tets(theirs) == canonical_tets(ours.tets));
    }
}

TEST_CASE("TetGen's result is a valid tetrahedralization on a degenerate lattice") {
    Built ours(lattice(10, 0.0, 0));
    REQUIRE(ours.status == DBRG_OK);
    Tetrahedralization theirs(ours.context.memory);
    REQUIRE(build_with_tetgen(ours.points.coordinates.data(), ours.points.size(), ours.context, theirs) == DBRG_OK);
    CHECK(theirs.finite_tet_count() > 0);
    CHECK(theirs.vertex_count() == 1000);
}
#endif
