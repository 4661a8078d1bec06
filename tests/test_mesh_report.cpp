// Tests of the mesh report: known answers on small meshes, face recall, points used, JSON, speed, and
// every mesh of ../shared/data checked against a naive std::map computation.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <dirent.h>
#include <initializer_list>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/pi.h"
#include "io/mesh_io.h"
#include "measure/mesh_report.h"
#include "predicates/exact_determinants.h"
#include "support/shared_data.h"

using namespace dbrg::io;
using namespace dbrg::measure;
using dbrg::PI;

namespace {


MeshReport report_of(const MeshData& mesh) {
    MeshReport report;
    const IoStatus status = make_mesh_report(mesh, report);
    INFO(status.message);
    REQUIRE(status.ok);
    return report;
}

MeshData make_mesh(std::vector<double> positions, std::vector<uint32_t> triangles) {
    MeshData mesh;
    mesh.positions = std::move(positions);
    mesh.triangles = std::move(triangles);
    mesh.has_faces = true;
    return mesh;
}

void add_quad(MeshData& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    mesh.triangles.insert(mesh.triangles.end(), {a, b, c, a, c, d});
}

MeshData tetrahedron() { return make_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3}); }

// Vertex x + 2y + 4z at (x, y, z); every face counter-clockwise seen from outside.
MeshData cube() {
    MeshData mesh = make_mesh({}, {});
    for (int v = 0; v < 8; ++v) mesh.positions.insert(mesh.positions.end(), {double(v & 1), double((v >> 1) & 1), double(v >> 2)});
    add_quad(mesh, 0, 2, 3, 1);
    add_quad(mesh, 4, 5, 7, 6);
    add_quad(mesh, 0, 1, 5, 4);
    add_quad(mesh, 2, 6, 7, 3);
    add_quad(mesh, 0, 4, 6, 2);
    add_quad(mesh, 1, 3, 7, 5);
    return mesh;
}

// An n x m grid of quads on a torus, two triangles each.
MeshData torus(uint32_t n, uint32_t m) {
    MeshData mesh = make_mesh({}, {});
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < m; ++j) {
            const double u = 2 * PI * i / n, v = 2 * PI * j / m;
            mesh.positions.insert(mesh.positions.end(), {(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
        }
    }
    auto at = [&](uint32_t i, uint32_t j) { return (i % n) * m + (j % m); };
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < m; ++j) add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
    return mesh;
}

// A band of n quads whose ends are glued with a half twist.
MeshData moebius_strip(uint32_t n) {
    MeshData mesh = make_mesh({}, {});
    for (uint32_t i = 0; i < n; ++i) {
        const double u = 2 * PI * i / n;
        for (double v : {-0.5, 0.5}) {
            mesh.positions.insert(mesh.positions.end(),
                                  {(1 + v * std::cos(u / 2)) * std::cos(u), (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2)});
        }
    }
    for (uint32_t i = 0; i + 1 < n; ++i) add_quad(mesh, 2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
    add_quad(mesh, 2 * (n - 1), 1, 0, 2 * (n - 1) + 1);  // the twist: top meets bottom
    return mesh;
}

// An open square grid of n x n quads.
MeshData grid(uint32_t n) {
    MeshData mesh = make_mesh({}, {});
    for (uint32_t i = 0; i <= n; ++i) {
        for (uint32_t j = 0; j <= n; ++j) mesh.positions.insert(mesh.positions.end(), {double(i), double(j), 0.0});
    }
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < n; ++j) add_quad(mesh, i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1);
    }
    return mesh;
}

MeshData translated_copy_appended(const MeshData& mesh, double dx) {
    MeshData both = mesh;
    const uint32_t offset = static_cast<uint32_t>(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        both.positions.insert(both.positions.end(), {mesh.positions[3 * v] + dx, mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]});
    }
    for (uint32_t index : mesh.triangles) both.triangles.push_back(index + offset);
    return both;
}

} // namespace

TEST_CASE("tetrahedron: closed, oriented, genus 0") {
    const MeshReport r = report_of(tetrahedron());
    CHECK(r.faces == 4);
    CHECK(r.vertices == 4);
    CHECK(r.edges_manifold == 6);
    CHECK(r.edges_boundary == 0);
    CHECK(r.edges_nonmanifold == 0);
    CHECK(r.vertices_nonmanifold == 0);
    CHECK(r.boundary_loops == 0);
    CHECK(r.components == 1);
    CHECK(r.oriented);
    CHECK(r.euler_characteristic == 2);
    REQUIRE(r.genus);
    CHECK(*r.genus == 0);
    CHECK(r.degenerate_faces == 0);
    CHECK(r.duplicate_faces == 0);
}

TEST_CASE("cube of 12 triangles") {
    const MeshReport r = report_of(cube());
    CHECK(r.faces == 12);
    CHECK(r.vertices == 8);
    CHECK(r.edges_manifold == 18);
    CHECK(r.edges_boundary == 0);
    CHECK(r.euler_characteristic == 2);
    CHECK(r.oriented);
    REQUIRE(r.genus);
    CHECK(*r.genus == 0);
}

TEST_CASE("torus grid: genus 1") {
    const MeshReport r = report_of(torus(12, 8));
    CHECK(r.faces == 192);
    CHECK(r.vertices == 96);
    CHECK(r.edges_manifold == 288);
    CHECK(r.euler_characteristic == 0);
    CHECK(r.oriented);
    REQUIRE(r.genus);
    CHECK(*r.genus == 1);
}

TEST_CASE("two disjoint closed components: genus adds up") {
    const MeshReport r = report_of(translated_copy_appended(torus(6, 5), 20.0));
    CHECK(r.components == 2);
    CHECK(r.euler_characteristic == 0);
    REQUIRE(r.genus);
    CHECK(*r.genus == 2);
    const MeshReport tets = report_of(translated_copy_appended(tetrahedron(), 5.0));
    CHECK(tets.components == 2);
    CHECK(tets.euler_characteristic == 4);
    REQUIRE(tets.genus);
    CHECK(*tets.genus == 0);
}

TEST_CASE("Moebius strip: manifold with one boundary loop, not orientable") {
    const uint32_t n = 10;
    const MeshReport r = report_of(moebius_strip(n));
    CHECK(r.faces == 2 * n);
    CHECK(r.vertices == 2 * n);
    CHECK(r.edges_boundary == 2 * n);
    CHECK(r.edges_manifold == 2 * n);
    CHECK(r.edges_nonmanifold == 0);
    CHECK(r.vertices_nonmanifold == 0);
    CHECK(r.boundary_loops == 1);
    CHECK(r.components == 1);
    CHECK_FALSE(r.oriented);
    CHECK(r.euler_characteristic == 0);
    CHECK_FALSE(r.genus);
}

TEST_CASE("a flipped face breaks the orientation of a closed mesh") {
    MeshData mesh = tetrahedron();
    std::swap(mesh.triangles[0], mesh.triangles[1]);
    const MeshReport r = report_of(mesh);
    CHECK_FALSE(r.oriented);
    CHECK(r.edges_boundary == 0);
    CHECK_FALSE(r.genus);
}

TEST_CASE("bow-tie: two triangles sharing one vertex") {
    const MeshReport r = report_of(make_mesh({0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0}, {0, 1, 2, 0, 3, 4}));
    CHECK(r.faces == 2);
    CHECK(r.vertices == 5);
    CHECK(r.edges_boundary == 6);
    CHECK(r.vertices_nonmanifold == 1);
    CHECK(r.boundary_loops == 2);
    CHECK(r.components == 2);
    CHECK(r.oriented);
    CHECK(r.euler_characteristic == 1);
    CHECK_FALSE(r.genus);
}

TEST_CASE("a closed surface pinched at a vertex is non-manifold there") {
    // Two tetrahedra sharing vertex 0.
    MeshData mesh = tetrahedron();
    mesh.positions.insert(mesh.positions.end(), {-1, 0, 0, 0, -1, 0, 0, 0, -1});
    mesh.triangles.insert(mesh.triangles.end(), {0, 4, 5, 0, 6, 4, 4, 6, 5, 0, 5, 6});
    const MeshReport r = report_of(mesh);
    CHECK(r.edges_boundary == 0);
    CHECK(r.edges_nonmanifold == 0);
    CHECK(r.vertices_nonmanifold == 1);
    CHECK(r.components == 2);
    CHECK(r.euler_characteristic == 3);
    CHECK_FALSE(r.genus);
}

TEST_CASE("a cube with a hole: one boundary loop, a disk") {
    MeshData mesh = cube();
    mesh.triangles.erase(mesh.triangles.begin() + 6, mesh.triangles.begin() + 12);  // the top face
    const MeshReport r = report_of(mesh);
    CHECK(r.faces == 10);
    CHECK(r.edges_boundary == 4);
    CHECK(r.edges_manifold == 13);
    CHECK(r.boundary_loops == 1);
    CHECK(r.euler_characteristic == 1);
    CHECK(r.oriented);
    CHECK(r.vertices_nonmanifold == 0);
    CHECK_FALSE(r.genus);
}

TEST_CASE("an open grid and a torus with two holes") {
    const MeshReport g = report_of(grid(5));
    CHECK(g.boundary_loops == 1);
    CHECK(g.edges_boundary == 20);
    CHECK(g.euler_characteristic == 1);
    MeshData holed = torus(12, 8);
    holed.triangles.erase(holed.triangles.begin() + 3 * 40, holed.triangles.begin() + 3 * 42);
    holed.triangles.erase(holed.triangles.begin(), holed.triangles.begin() + 6);
    const MeshReport t = report_of(holed);
    CHECK(t.boundary_loops == 2);
    CHECK(t.edges_boundary == 8);
    CHECK(t.euler_characteristic == -2);
    CHECK(t.vertices_nonmanifold == 0);
}

TEST_CASE("an edge with three faces") {
    const MeshReport r = report_of(make_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1}, {0, 1, 2, 1, 0, 3, 0, 1, 4}));
    CHECK(r.edges_nonmanifold == 1);
    CHECK(r.edges_boundary == 6);
    CHECK(r.edges_manifold == 0);
    CHECK(r.vertices_nonmanifold == 2);
    CHECK(r.components == 1);
    CHECK_FALSE(r.genus);
}

TEST_CASE("duplicate and degenerate faces") {
    MeshData mesh = tetrahedron();
    mesh.positions.insert(mesh.positions.end(), {0.5, 0, 0});  // vertex 4, on edge 0-1
    mesh.triangles.insert(mesh.triangles.end(), {
        1, 0, 2,  // face 0 again, other order and orientation: duplicate
        0, 1, 4,  // three distinct collinear corners: zero area
        2, 2, 3,  // a repeated index: degenerate and no part of the topology
        3, 2, 2,  // the same again: also a duplicate
    });
    const MeshReport r = report_of(mesh);
    CHECK(r.faces == 8);
    CHECK(r.duplicate_faces == 2);
    CHECK(r.degenerate_faces == 3);
    CHECK(r.vertices == 5);
    CHECK(r.edges_nonmanifold == 3);  // the edges of face 0 now have three faces
}

namespace {

MeshData scaled(MeshData mesh, double factor) {
    for (double& coordinate : mesh.positions) coordinate *= factor;
    return mesh;
}

// Appends three vertices and a face on them.
void add_triangle(MeshData& mesh, std::initializer_list<double> corners) {
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    mesh.positions.insert(mesh.positions.end(), corners);
    mesh.triangles.insert(mesh.triangles.end(), {first, first + 1, first + 2});
}

MeshReport welded_report_of(const MeshData& mesh) {
    MeshReport report;
    const IoStatus status = make_mesh_report(mesh, report, VertexIdentity::position);
    INFO(status.message);
    REQUIRE(status.ok);
    return report;
}

// Every figure of the mesh's shape: all but how its vertices were told apart.
void check_same_shape(const MeshReport& a, const MeshReport& b) {
    CHECK(a.faces == b.faces);
    CHECK(a.vertices == b.vertices);
    CHECK(a.vertices_isolated == b.vertices_isolated);
    CHECK(a.edges_manifold == b.edges_manifold);
    CHECK(a.edges_boundary == b.edges_boundary);
    CHECK(a.edges_nonmanifold == b.edges_nonmanifold);
    CHECK(a.vertices_nonmanifold == b.vertices_nonmanifold);
    CHECK(a.boundary_loops == b.boundary_loops);
    CHECK(a.components == b.components);
    CHECK(a.oriented == b.oriented);
    CHECK(a.euler_characteristic == b.euler_characteristic);
    CHECK(a.genus == b.genus);
    CHECK(a.degenerate_faces == b.degenerate_faces);
    CHECK(a.duplicate_faces == b.duplicate_faces);
}

} // namespace

TEST_CASE("zero area does not depend on the mesh's scale") {
    const MeshData surface = torus(12, 8);
    // Exactly collinear at every scale, rounding included: q, 2q, 4q, and three points differing in x only.
    MeshData with_flat_faces = surface;
    const double* q = &surface.positions[3 * 5];
    add_triangle(with_flat_faces, {q[0], q[1], q[2], 2 * q[0], 2 * q[1], 2 * q[2], 4 * q[0], 4 * q[1], 4 * q[2]});
    add_triangle(with_flat_faces, {0.3, -1.5, 2.7, 1.1, -1.5, 2.7, -0.7, -1.5, 2.7});
    const MeshReport unscaled = report_of(surface);
    const MeshReport unscaled_flat = report_of(with_flat_faces);
    CHECK(unscaled.degenerate_faces == 0);
    CHECK(unscaled_flat.degenerate_faces == 2);
    for (double factor : {1e-301, 1e300, 0x1p-1000, 0x1p1000}) {
        CAPTURE(factor);
        check_same_shape(report_of(scaled(surface, factor)), unscaled);
        check_same_shape(report_of(scaled(with_flat_faces, factor)), unscaled_flat);
    }
}

TEST_CASE("zero area is decided exactly, whatever the sizes of the coordinates") {
    const double tiny = std::numeric_limits<double>::denorm_min(), huge = std::numeric_limits<double>::max();
    const struct {
        const char* what;
        std::initializer_list<double> corners;
        bool flat;
    } cases[] = {
        {"edge vectors (1, 1, 0) and (2, 2, 0) rounded, exactly not parallel", {1e-20, 0, 0, 1, 1, 0, 2, 2, 0}, false},
        {"a height of 2^-1074 over a side of 2^-1074", {0, 0, 0, tiny, 0, 0, 0x1p1000, tiny, 0}, false},
        {"collinear from 2^-1074 to 2^1000", {0, 0, 0, tiny, tiny, tiny, 0x1p1000, 0x1p1000, 0x1p1000}, true},
        {"collinear across the whole range of doubles", {huge, huge, -huge, -huge, -huge, huge, 0, 0, 0}, true},
        {"off that line by 2^-1074", {huge, huge, -huge, -huge, -huge, huge, 0, tiny, 0}, false},
        {"three distinct vertices at one point", {1e-310, 2, 3, 1e-310, 2, 3, 1e-310, 2, 3}, true},
        {"all at the origin", {0, 0, 0, -0.0, 0, 0, 0, 0, -0.0}, true},
        {"a right triangle of subnormal sides", {0, 0, 0, 4 * tiny, 0, 0, 0, 0, 4 * tiny}, false},
    };
    for (const auto& c : cases) {
        INFO(c.what);
        MeshData mesh = make_mesh({}, {});
        add_triangle(mesh, c.corners);
        CHECK(report_of(mesh).degenerate_faces == (c.flat ? 1 : 0));
    }
}

TEST_CASE("zero area of triangles with long coordinates, off a line by one unit or on it") {
    // Integers of 40 to 50 bits, a + d and a + 2 d exact: the exact sums carry from word to word.
    const double a[3] = {742938245128763.0, -501229788451607.0, 3148925711.0};
    const double d[3] = {98765432109.0, 1234567890123.0, -77777777.0};
    for (double factor : {1.0, 0x1p-1000, 0x1p900}) {
        CAPTURE(factor);
        MeshData mesh = make_mesh({}, {});
        for (double off_line : {0.0, 1.0}) {
            add_triangle(mesh, {a[0] * factor, a[1] * factor, a[2] * factor, (a[0] + d[0]) * factor, (a[1] + d[1]) * factor,
                                (a[2] + d[2]) * factor, (a[0] + 2 * d[0]) * factor, (a[1] + 2 * d[1] + off_line) * factor,
                                (a[2] + 2 * d[2]) * factor});
        }
        CHECK(report_of(mesh).degenerate_faces == 1);
    }
}

TEST_CASE("zero area on a small grid, where plain arithmetic is exact, at scales of 2^-1060 to 2^1020") {
    // Corners on a 3 x 3 x 3 grid of integers are often collinear, and their cross products are exact in
    // doubles: the count at scale 1 is known, and scaling by a power of two changes no collinearity.
    std::mt19937 random(7);
    MeshData mesh = make_mesh({}, {});
    for (int i = 0; i < 9000; ++i) mesh.positions.push_back(double(int(random() % 3) - 1));
    uint64_t flat = 0;
    for (uint32_t t = 0; t < 1000; ++t) {
        const double* p = &mesh.positions[9 * size_t(t)];
        double u[3], v[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = p[3 + k] - p[k];
            v[k] = p[6 + k] - p[k];
        }
        flat += u[1] * v[2] == u[2] * v[1] && u[2] * v[0] == u[0] * v[2] && u[0] * v[1] == u[1] * v[0];
        mesh.triangles.insert(mesh.triangles.end(), {3 * t, 3 * t + 1, 3 * t + 2});
    }
    REQUIRE(flat > 100);
    for (double factor : {1.0, 0x1p-1060, 0x1p-600, 0x1p600, 0x1p1020}) {
        CAPTURE(factor);
        CHECK(report_of(scaled(mesh, factor)).degenerate_faces == flat);
    }
}

TEST_CASE("a face with a NaN or infinite corner is degenerate only by a repeated index") {
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    MeshData mesh = make_mesh({}, {});
    add_triangle(mesh, {nan, 0, 0, 1, 0, 0, 2, 0, 0});
    add_triangle(mesh, {inf, 0, 0, 1, 0, 0, 2, 0, 0});
    add_triangle(mesh, {inf, inf, inf, inf, inf, inf, inf, inf, inf});
    CHECK(report_of(mesh).degenerate_faces == 0);
    mesh.triangles.insert(mesh.triangles.end(), {0, 0, 1});
    CHECK(report_of(mesh).degenerate_faces == 1);
}

TEST_CASE("a two-faced pillow is closed and of genus 0") {
    const MeshReport r = report_of(make_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 1}));
    CHECK(r.duplicate_faces == 1);
    CHECK(r.edges_manifold == 3);
    CHECK(r.oriented);
    REQUIRE(r.genus);
    CHECK(*r.genus == 0);
}

TEST_CASE("empty meshes and isolated vertices") {
    const MeshReport empty = report_of(MeshData());
    CHECK(empty.faces == 0);
    CHECK(empty.vertices == 0);
    CHECK(empty.components == 0);
    CHECK(empty.oriented);
    CHECK_FALSE(empty.genus);
    const MeshReport empty_welded = welded_report_of(MeshData());
    CHECK(empty_welded.vertices_welded);
    CHECK(empty_welded.faces == 0);
    CHECK(empty_welded.duplicate_positions == 0);
    MeshData mesh = tetrahedron();
    mesh.positions.insert(mesh.positions.end(), {9, 9, 9, 8, 8, 8});
    const MeshReport r = report_of(mesh);
    CHECK(r.vertices == 4);
    CHECK(r.vertices_isolated == 2);
    CHECK(r.euler_characteristic == 2);
}

TEST_CASE("vertices are told apart by index, not position") {
    // The cube's faces over unshared corners: 36 vertices, every edge a boundary.
    const MeshData shared = cube();
    MeshData split = make_mesh({}, {});
    for (uint32_t index : shared.triangles) {
        split.triangles.push_back(static_cast<uint32_t>(split.vertex_count()));
        split.positions.insert(split.positions.end(), shared.positions.begin() + 3 * index, shared.positions.begin() + 3 * index + 3);
    }
    const MeshReport r = report_of(split);
    CHECK(r.vertices == 36);
    CHECK(r.components == 12);
    CHECK(r.edges_boundary == 36);
    CHECK(r.boundary_loops == 12);
}

TEST_CASE("malformed arrays are reported, not read past") {
    MeshReport report;
    MeshData mesh = tetrahedron();
    mesh.triangles.push_back(4);
    mesh.triangles.push_back(0);
    mesh.triangles.push_back(1);
    IoStatus status = make_mesh_report(mesh, report);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("triangle 4 refers to vertex 4") != std::string::npos);
    mesh.triangles.pop_back();
    CHECK_FALSE(make_mesh_report(mesh, report).ok);
    CHECK_FALSE(add_face_recall(tetrahedron(), mesh, report).ok);
    CHECK_FALSE(add_points_used(mesh, tetrahedron(), report).ok);
}

TEST_CASE("face recall matches corner positions exactly, in any order and numbering") {
    const MeshData reference = torus(10, 6);
    MeshReport report = report_of(reference);
    REQUIRE(add_face_recall(reference, reference, report).ok);
    REQUIRE(report.face_recall);
    CHECK(*report.face_recall == 1.0);
    CHECK(*report.reference_faces == 120);

    // Renumbered vertices, reversed faces, and only half of the triangles.
    MeshData other = reference;
    const uint32_t n = static_cast<uint32_t>(reference.vertex_count());
    for (uint32_t v = 0; v < n; ++v) {
        for (int k = 0; k < 3; ++k) other.positions[3 * (n - 1 - v) + k] = reference.positions[3 * v + k];
    }
    other.triangles.clear();
    for (size_t t = 0; t < reference.triangle_count(); t += 2) {
        for (int k = 2; k >= 0; --k) other.triangles.push_back(n - 1 - reference.triangles[3 * t + k]);
    }
    REQUIRE(add_face_recall(other, reference, report).ok);
    CHECK(*report.face_recall == doctest::Approx(0.5));

    // Moving one vertex by the smallest step loses its six triangles.
    other = reference;
    other.positions[0] = std::nextafter(other.positions[0], 10.0);
    REQUIRE(add_face_recall(other, reference, report).ok);
    CHECK(*report.face_recall == doctest::Approx(114.0 / 120.0));

    REQUIRE(add_face_recall(reference, MeshData(), report).ok);
    CHECK(*report.reference_faces == 0);
    CHECK_FALSE(report.face_recall);
}

TEST_CASE("points used counts input points sitting at vertices of faces") {
    const MeshData mesh = tetrahedron();
    MeshData points;
    points.positions = {0, 0, 0, 1, 0, 0, -0.0, 1, 0, 5, 5, 5, 0, 0, 0};  // -0 equals 0; a duplicate counts twice
    MeshReport report = report_of(mesh);
    REQUIRE(add_points_used(mesh, points, report).ok);
    CHECK(*report.points_input == 5);
    CHECK(*report.points_used == 4);
}

TEST_CASE("welding: a cube with a texture seam is closed by position") {
    // The top face's corners (vertices 4-7) written again as vertices 8-11, which the top's two triangles use.
    const MeshData closed = cube();
    MeshData seam = closed;
    seam.positions.insert(seam.positions.end(), closed.positions.begin() + 3 * 4, closed.positions.end());
    for (size_t corner = 6; corner < 12; ++corner) seam.triangles[corner] += 4;
    const MeshReport by_index = report_of(seam);
    CHECK_FALSE(by_index.vertices_welded);
    CHECK(by_index.duplicate_positions == 4);
    CHECK(by_index.edges_boundary > 0);
    CHECK(by_index.boundary_loops == 2);  // the rim of the top and that of the open box
    CHECK(by_index.components == 2);
    CHECK_FALSE(by_index.genus);

    const MeshReport by_position = welded_report_of(seam);
    CHECK(by_position.vertices_welded);
    CHECK(by_position.duplicate_positions == 4);
    CHECK(by_position.edges_boundary == 0);
    REQUIRE(by_position.genus);
    CHECK(*by_position.genus == 0);
    check_same_shape(by_position, report_of(closed));
}

TEST_CASE("welding a triangle soup gives back the mesh it was cut from") {
    for (const MeshData& mesh : {tetrahedron(), cube(), torus(7, 5), moebius_strip(9), grid(3)}) {
        // Every corner of every face a vertex of its own, as STL stores a mesh.
        MeshData soup = make_mesh({}, {});
        for (uint32_t index : mesh.triangles) {
            soup.triangles.push_back(static_cast<uint32_t>(soup.vertex_count()));
            soup.positions.insert(soup.positions.end(), &mesh.positions[3 * size_t(index)], &mesh.positions[3 * size_t(index)] + 3);
        }
        const MeshReport pieces = report_of(soup);
        CHECK(pieces.components == mesh.triangle_count());
        CHECK(pieces.edges_boundary == mesh.triangles.size());
        CHECK(pieces.duplicate_positions == soup.vertex_count() - mesh.vertex_count());
        const MeshReport welded = welded_report_of(soup);
        CHECK(welded.duplicate_positions == pieces.duplicate_positions);
        check_same_shape(welded, report_of(mesh));
        // Nothing to weld: the same figures either way.
        check_same_shape(welded_report_of(mesh), report_of(mesh));
        CHECK(welded_report_of(mesh).duplicate_positions == 0);
    }
}

TEST_CASE("welding: equal coordinates only, and faces whose corners merge are degenerate") {
    const double nan = std::nan("");
    MeshData mesh = tetrahedron();
    mesh.positions.insert(mesh.positions.end(), {
        -0.0, 0, -0.0,  // 4: vertex 0 again (-0 equals 0)
        nan, 0, 0,      // 5, 6: NaN equals nothing, not even itself
        nan, 0, 0,
        1, 0, 0,        // 7: vertex 1 again, used by no face
        1, 0, 1e-300,   // 8: close to vertex 1, but not at it
    });
    mesh.triangles.insert(mesh.triangles.end(), {0, 4, 1});  // by index a face of zero area on edge 0-1
    const MeshReport by_index = report_of(mesh);
    CHECK(by_index.duplicate_positions == 2);
    CHECK(by_index.degenerate_faces == 1);
    CHECK(by_index.edges_nonmanifold == 1);  // edge 0-1 has three faces
    CHECK(by_index.vertices_isolated == 4);
    const MeshReport by_position = welded_report_of(mesh);
    CHECK(by_position.duplicate_positions == 2);
    CHECK(by_position.degenerate_faces == 1);  // now (0, 0, 1): a repeated index, no part of the topology
    CHECK(by_position.edges_nonmanifold == 0);
    CHECK(by_position.vertices == 4);
    CHECK(by_position.vertices_isolated == 3);  // 5, 6 and 8
    REQUIRE(by_position.genus);
    CHECK(*by_position.genus == 0);

    // Two faces on the same positions become one face listed twice.
    const MeshData twins = make_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0}, {0, 1, 2, 3, 1, 2});
    CHECK(report_of(twins).duplicate_faces == 0);
    CHECK(welded_report_of(twins).duplicate_faces == 1);
}

TEST_CASE("JSON says whether vertices were welded") {
    const MeshData mesh = make_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0}, {0, 1, 2, 3, 1, 2});
    const std::string by_index = to_json(report_of(mesh));
    CHECK(by_index.find("\"vertices_welded\": false,") != std::string::npos);
    CHECK(by_index.find("\"duplicate_positions\": 1,") != std::string::npos);
    CHECK(by_index.find("vertices_merged") == std::string::npos);
    const std::string by_position = to_json(welded_report_of(mesh));
    CHECK(by_position.find("\"vertices_welded\": true,") != std::string::npos);
    CHECK(by_position.find("\"vertices_merged\": 1,") != std::string::npos);
    CHECK(by_position.find("duplicate_positions") == std::string::npos);
}

TEST_CASE("JSON has every key, genus null when unknown") {
    MeshReport report = report_of(grid(2));
    std::string json = to_json(report);
    for (const char* key : {"faces", "vertices", "vertices_welded", "duplicate_positions", "edges_manifold", "edges_boundary", "edges_nonmanifold", "vertices_nonmanifold",
                            "boundary_loops", "components", "oriented", "euler_characteristic", "genus", "degenerate_faces",
                            "duplicate_faces"}) {
        CAPTURE(key);
        CHECK(json.find("\"" + std::string(key) + "\": ") != std::string::npos);
    }
    CHECK(json.find("\"genus\": null") != std::string::npos);
    CHECK(json.find("\"faces\": 8,") != std::string::npos);
    CHECK(json.find("face_recall") == std::string::npos);
    CHECK(json.front() == '{');
    CHECK(json.substr(json.size() - 2) == "}\n");

    REQUIRE(add_face_recall(grid(2), grid(2), report).ok);
    REQUIRE(add_points_used(grid(2), grid(2), report).ok);
    json = to_json(report_of(tetrahedron()));
    CHECK(json.find("\"genus\": 0,") != std::string::npos);
    CHECK(json.find("\"oriented\": true,") != std::string::npos);
    json = to_json(report);
    CHECK(json.find("\"face_recall\": 1,") != std::string::npos);
    CHECK(json.find("\"points_input\": 9,") != std::string::npos);
    CHECK(json.find("\"points_used\": 9\n") != std::string::npos);
}

namespace {

// A "triangle" whose three corners (three vertices) sit at one point: all its samples are that point,
// so the distance from it is the distance from the point.
MeshData point_probe(double x, double y, double z) { return make_mesh({x, y, z, x, y, z, x, y, z}, {0, 1, 2}); }

SurfaceDistance distance(const MeshData& from, const MeshData& to) {
    const std::optional<SurfaceDistance> d = surface_distance(from, to);
    REQUIRE(d.has_value());
    return *d;
}

MeshData unit_square(double z, double scale = 1) {
    return make_mesh({0, 0, z * scale, scale, 0, z * scale, scale, scale, z * scale, 0, scale, z * scale}, {0, 1, 2, 0, 2, 3});
}

} // namespace

TEST_CASE("surface distance: from points to the nearest corner, edge or inside of a triangle") {
    const MeshData target = make_mesh({0, 0, 0, 4, 0, 0, 0, 4, 0}, {0, 1, 2});
    const struct {
        double x, y, z, expected;
    } probes[] = {
        {1, 1, 0, 0},                 // inside
        {1, 1, -3, 3},                // below the inside
        {-3, -4, 0, 5},               // beyond corner (0, 0)
        {7, 0, 4, 5},                 // beyond corner (4, 0)
        {2, -2, 0, 2},                // beyond edge y = 0
        {-1, 2, 1, std::sqrt(2.0)},   // beyond edge x = 0, above the plane
        {3, 3, 0, std::sqrt(2.0)},    // beyond the long edge x + y = 4
        {0, 6, 0, 2},                 // beyond corner (0, 4)
    };
    for (const auto& p : probes) {
        CAPTURE(p.x);
        CAPTURE(p.y);
        CAPTURE(p.z);
        const SurfaceDistance d = distance(point_probe(p.x, p.y, p.z), target);
        CHECK(d.max == doctest::Approx(p.expected).epsilon(1e-12));
        CHECK(d.mean == doctest::Approx(p.expected).epsilon(1e-12));
        CHECK(d.samples == 7);
    }
    // A target without area (collinear corners): the nearest point is on its longest side.
    const MeshData needle = make_mesh({0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2});
    CHECK(distance(point_probe(1.5, 2, 0), needle).max == doctest::Approx(2.0));
    CHECK(distance(point_probe(3, 0, 0), needle).max == doctest::Approx(1.0));
}

TEST_CASE("surface distance: between whole meshes, both ways, at any scale") {
    CHECK(distance(grid(5), grid(5)).max == 0);
    for (double scale : {1.0, 1e300, 1e-300}) {
        CAPTURE(scale);
        const SurfaceDistance lifted = distance(unit_square(0.25, scale), unit_square(0, scale));
        CHECK(lifted.max == doctest::Approx(0.25 * scale).epsilon(1e-12));
        CHECK(lifted.mean == doctest::Approx(0.25 * scale).epsilon(1e-12));
        CHECK(lifted.samples == 14);
    }
    // A small triangle inside a large one: none of it is away from the large one, while the large one's
    // corner (4, 0) is sqrt(5) from the small one's corner (2, 1).
    const MeshData large = make_mesh({0, 0, 0, 4, 0, 0, 0, 4, 0}, {0, 1, 2});
    const MeshData small = make_mesh({1, 1, 0, 2, 1, 0, 1, 2, 0}, {0, 1, 2});
    CHECK(distance(small, large).max < 1e-12);
    CHECK(distance(large, small).max == doctest::Approx(std::sqrt(5.0)));
}

TEST_CASE("surface distance: unusable triangles are left out; nothing usable or piled-up triangles give none") {
    const double nan = std::nan("");
    // A triangle with a NaN corner and one with a repeated corner take no part.
    MeshData from = make_mesh({0, 0, 1, 1, 0, 1, 0, 1, 1, nan, 0, 0, 5, 5, 5}, {0, 1, 2, 3, 1, 2, 4, 4, 1});
    const SurfaceDistance d = distance(from, unit_square(0));
    CHECK(d.max == doctest::Approx(1.0));
    CHECK(d.samples == 7);
    CHECK_FALSE(surface_distance(make_mesh({nan, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}), unit_square(0)).has_value());
    CHECK_FALSE(surface_distance(unit_square(0), make_mesh({0, 0, 0, 1, 0, 0}, {0, 0, 1})).has_value());
    const double huge = 1.5e308;
    CHECK_FALSE(surface_distance(point_probe(-huge, -huge, -huge), point_probe(huge, huge, huge)).has_value());

    // Thousands of thin triangles crossing one square in every direction: their boxes all cover the
    // middle, so a point above it would be compared with every one of them. The search gives up.
    std::vector<double> xyz;
    std::vector<uint32_t> triangles;
    const uint32_t slivers = 8000;
    for (uint32_t i = 0; i < slivers; ++i) {
        const double angle = PI * i / slivers, c = std::cos(angle), s = std::sin(angle);
        const uint32_t base = static_cast<uint32_t>(xyz.size() / 3);
        xyz.insert(xyz.end(), {-c, -s, 0, c, s, 0, c - 1e-9 * s, s + 1e-9 * c, 0});
        triangles.insert(triangles.end(), {base, base + 1, base + 2});
    }
    MeshData probes;
    for (uint32_t i = 0; i < 100; ++i) {
        const MeshData p = point_probe(0.005 * i - 0.25, 0.3, 1);
        const uint32_t base = static_cast<uint32_t>(probes.positions.size() / 3);
        probes.positions.insert(probes.positions.end(), p.positions.begin(), p.positions.end());
        probes.triangles.insert(probes.triangles.end(), {base, base + 1, base + 2});
    }
    CHECK_FALSE(surface_distance(probes, make_mesh(xyz, triangles)).has_value());
    // Surfaces far apart are no reason to give up, though each search then looks at hundreds of boxes: a
    // coarse torus inside the tube of a finely tessellated one 1.5 times its size, about 15 of the fine
    // one's sides away.
    MeshData large_torus = torus(400, 200);
    for (double& x : large_torus.positions) x *= 1.5;
    const SurfaceDistance apart = distance(torus(50, 25), large_torus);
    CHECK(apart.max == doctest::Approx(1.0).epsilon(0.02));
    // The same slivers measured from themselves stop at once: every sample lies on its own triangle.
    CHECK(distance(make_mesh(xyz, triangles), make_mesh(xyz, triangles)).max < 1e-9);
}

TEST_CASE("the reference distance is in the report and its JSON, null where it cannot be measured") {
    MeshReport report = report_of(unit_square(0.5));
    REQUIRE(add_reference_distance(unit_square(0.5), unit_square(0), report).ok);
    REQUIRE(report.reference_distance.has_value());
    const ReferenceDistance& d = *report.reference_distance;
    REQUIRE(d.side_mean.has_value());
    CHECK(*d.side_mean == doctest::Approx((4 + 2 * std::sqrt(2.0)) / 6));
    REQUIRE(d.to_reference.has_value());
    REQUIRE(d.from_reference.has_value());
    CHECK(d.to_reference->max == doctest::Approx(0.5));
    CHECK(d.from_reference->mean == doctest::Approx(0.5));
    std::string json = to_json(report);
    CHECK(json.find("\"distance_to_reference_max\": 0.5,") != std::string::npos);
    CHECK(json.find("\"distance_from_reference_mean\": 0.5") != std::string::npos);

    MeshData empty = make_mesh({0, 0, 0}, {});
    REQUIRE(add_reference_distance(unit_square(0), empty, report).ok);
    REQUIRE(report.reference_distance.has_value());
    CHECK_FALSE(report.reference_distance->side_mean.has_value());
    CHECK_FALSE(report.reference_distance->to_reference.has_value());
    CHECK_FALSE(report.reference_distance->from_reference.has_value());
    json = to_json(report);
    CHECK(json.find("\"reference_side_mean\": null,") != std::string::npos);
    CHECK(json.find("\"distance_to_reference_max\": null,") != std::string::npos);
    MeshData broken = make_mesh({0, 0, 0}, {0, 1, 2});
    CHECK_FALSE(add_reference_distance(unit_square(0), broken, report).ok);
}

TEST_CASE("a two-million-face mesh is reported in about a second") {
    const MeshData mesh = torus(1000, 1000);
    const auto start = std::chrono::steady_clock::now();
    const MeshReport r = report_of(mesh);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    MESSAGE("report on " << r.faces << " faces in " << seconds << " s");
    CHECK(r.faces == 2000000);
    REQUIRE(r.genus);
    CHECK(*r.genus == 1);
}

// ------------------------------------------------------------------------------------------------
// The shared reference meshes, against a deliberately naive computation with ordered maps.

namespace {

struct NaiveFigures {
    uint64_t vertices = 0, edges_manifold = 0, edges_boundary = 0, edges_nonmanifold = 0, vertices_nonmanifold = 0;
    uint64_t boundary_loops = 0, components = 0, degenerate = 0, duplicates = 0;
    bool oriented = true;
    int64_t euler = 0;
};

// Connected components of a graph given as adjacency lists over arbitrary keys, by depth-first search;
// `label` receives the component number of each node.
template <class Node>
uint64_t count_components(const std::map<Node, std::vector<Node>>& adjacency, std::map<Node, uint64_t>& label) {
    uint64_t count = 0;
    for (const auto& entry : adjacency) {
        if (label.count(entry.first)) continue;
        std::vector<Node> stack = {entry.first};
        label[entry.first] = count;
        while (!stack.empty()) {
            const Node node = stack.back();
            stack.pop_back();
            for (const Node& next : adjacency.at(node)) {
                if (label.emplace(next, count).second) stack.push_back(next);
            }
        }
        ++count;
    }
    return count;
}

NaiveFigures naive_figures(const MeshData& mesh) {
    NaiveFigures n;
    using Edge = std::pair<uint32_t, uint32_t>;
    std::map<Edge, std::vector<std::pair<size_t, bool>>> edge_faces;  // faces and whether they run low to high
    std::set<std::vector<uint32_t>> seen;
    std::set<uint32_t> used;
    uint64_t proper = 0;
    auto edge_of = [](uint32_t a, uint32_t b) { return Edge(std::min(a, b), std::max(a, b)); };
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t* c = &mesh.triangles[3 * t];
        std::vector<uint32_t> sorted(c, c + 3);
        std::sort(sorted.begin(), sorted.end());
        if (!seen.insert(sorted).second) ++n.duplicates;
        const bool repeated = sorted[0] == sorted[1] || sorted[1] == sorted[2];
        // Collinear corners by the predicates' expansion arithmetic, exact at these meshes' ordinary scales.
        const double* p[3] = {&mesh.positions[3 * c[0]], &mesh.positions[3 * c[1]], &mesh.positions[3 * c[2]]};
        bool flat = true;
        for (int u = 0; u < 3; ++u) flat = flat && dbrg::exact::orient2d(p[0], p[1], p[2], u, (u + 1) % 3) == 0;
        if (repeated || flat) ++n.degenerate;
        if (repeated) continue;
        ++proper;
        for (int k = 0; k < 3; ++k) {
            used.insert(c[k]);
            edge_faces[edge_of(c[k], c[(k + 1) % 3])].push_back({t, c[k] < c[(k + 1) % 3]});
        }
    }
    n.vertices = used.size();
    std::map<size_t, std::vector<size_t>> face_graph;
    std::set<uint32_t> bad_vertices;
    for (const auto& [edge, faces] : edge_faces) {
        if (faces.size() == 1) ++n.edges_boundary;
        if (faces.size() == 2) ++n.edges_manifold;
        if (faces.size() == 2 && faces[0].second == faces[1].second) n.oriented = false;
        if (faces.size() > 2) {
            ++n.edges_nonmanifold;
            bad_vertices.insert(edge.first);
            bad_vertices.insert(edge.second);
        }
        for (const auto& face : faces) {
            face_graph[face.first];
            for (const auto& other : faces) face_graph[face.first].push_back(other.first);
        }
    }
    std::map<size_t, uint64_t> face_label;
    n.components = count_components(face_graph, face_label);

    // Fans: per vertex, its faces joined through manifold edges at that vertex.
    std::map<uint32_t, std::vector<size_t>> faces_at;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t* c = &mesh.triangles[3 * t];
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
        for (int k = 0; k < 3; ++k) faces_at[c[k]].push_back(t);
    }
    using FanNode = std::pair<uint32_t, size_t>;  // (vertex, face)
    std::map<FanNode, std::vector<FanNode>> fan_graph;
    for (const auto& [vertex, faces] : faces_at) {
        for (size_t f : faces) fan_graph[{vertex, f}];
    }
    for (const auto& [edge, faces] : edge_faces) {
        if (faces.size() != 2) continue;
        for (uint32_t vertex : {edge.first, edge.second}) {
            fan_graph[{vertex, faces[0].first}].push_back({vertex, faces[1].first});
            fan_graph[{vertex, faces[1].first}].push_back({vertex, faces[0].first});
        }
    }
    std::map<FanNode, uint64_t> fan_label;
    count_components(fan_graph, fan_label);
    std::map<uint32_t, std::set<uint64_t>> fans_at;
    for (const auto& [node, label] : fan_label) fans_at[node.first].insert(label);
    for (const auto& [vertex, fans] : fans_at) {
        if (fans.size() > 1) bad_vertices.insert(vertex);
    }
    n.vertices_nonmanifold = bad_vertices.size();

    // Boundary loops: boundary edges chained through the fans at their ends.
    std::map<uint64_t, std::vector<uint64_t>> loop_graph;
    for (const auto& [edge, faces] : edge_faces) {
        if (faces.size() != 1) continue;
        const uint64_t a = fan_label.at({edge.first, faces[0].first}), b = fan_label.at({edge.second, faces[0].first});
        loop_graph[a].push_back(b);
        loop_graph[b].push_back(a);
    }
    std::map<uint64_t, uint64_t> loop_label;
    n.boundary_loops = count_components(loop_graph, loop_label);
    n.euler = int64_t(n.vertices) - int64_t(edge_faces.size()) + int64_t(proper);
    return n;
}

} // namespace

TEST_CASE("the naive computation agrees on the hand-made meshes") {
    for (const MeshData& mesh : {tetrahedron(), cube(), torus(7, 5), moebius_strip(9), grid(3)}) {
        const MeshReport r = report_of(mesh);
        const NaiveFigures n = naive_figures(mesh);
        CHECK(n.vertices == r.vertices);
        CHECK(n.edges_boundary == r.edges_boundary);
        CHECK(n.boundary_loops == r.boundary_loops);
        CHECK(n.oriented == r.oriented);
        CHECK(n.euler == r.euler_characteristic);
    }
}

namespace {

void check_against_naive(const MeshReport& r, const MeshData& mesh) {
    const NaiveFigures n = naive_figures(mesh);
    CHECK(r.faces == mesh.triangle_count());
    CHECK(r.vertices == n.vertices);
    CHECK(r.vertices + r.vertices_isolated == mesh.vertex_count());
    CHECK(r.edges_manifold == n.edges_manifold);
    CHECK(r.edges_boundary == n.edges_boundary);
    CHECK(r.edges_nonmanifold == n.edges_nonmanifold);
    CHECK(r.vertices_nonmanifold == n.vertices_nonmanifold);
    CHECK(r.boundary_loops == n.boundary_loops);
    CHECK(r.components == n.components);
    CHECK(r.oriented == n.oriented);
    CHECK(r.euler_characteristic == n.euler);
    CHECK(r.degenerate_faces == n.degenerate);
    CHECK(r.duplicate_faces == n.duplicates);
    const bool closed = n.edges_boundary == 0 && n.edges_nonmanifold == 0 && n.vertices_nonmanifold == 0 && n.oriented;
    CHECK(bool(r.genus) == closed);
    if (r.genus) CHECK(*r.genus == (2 * int64_t(n.components) - n.euler) / 2);
}

// The mesh with one vertex per distinct position, in order of first appearance (no NaN expected here).
MeshData naively_welded(const MeshData& mesh) {
    MeshData out = make_mesh({}, {});
    std::map<std::array<double, 3>, uint32_t> number;
    std::vector<uint32_t> renumbered;
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const std::array<double, 3> position = {mesh.positions[3 * v] + 0.0, mesh.positions[3 * v + 1] + 0.0,
                                                mesh.positions[3 * v + 2] + 0.0};  // + 0.0 makes -0 into 0
        const auto [at, added] = number.emplace(position, static_cast<uint32_t>(out.vertex_count()));
        if (added) out.positions.insert(out.positions.end(), position.begin(), position.end());
        renumbered.push_back(at->second);
    }
    for (uint32_t index : mesh.triangles) out.triangles.push_back(renumbered[index]);
    return out;
}

} // namespace

TEST_CASE("every mesh in ../shared/data matches the naive computation" *
          doctest::test_suite(dbrg::test::SHARED_DATA_SUITE)) {
    const std::string dir = dbrg::test::shared_data_dir_or_skip();
    if (dir.empty()) return;
    DIR* listing = opendir(dir.c_str());
    REQUIRE(listing != nullptr);
    std::vector<std::string> names;
    while (const dirent* entry = readdir(listing)) {
        if (format_from_path(entry->d_name)) names.push_back(entry->d_name);
    }
    closedir(listing);
    std::sort(names.begin(), names.end());
    CHECK_FALSE(names.empty());
    for (const std::string& name : names) {
        CAPTURE(name);
        MeshData mesh;
        const IoStatus status = read_mesh(dir + "/" + name, mesh);
        INFO(status.message);
        REQUIRE(status.ok);
        const MeshReport r = report_of(mesh);
        std::string figures = to_json(r);
        figures.erase(std::remove(figures.begin(), figures.end(), '\n'), figures.end());
        figures.erase(std::unique(figures.begin(), figures.end(), [](char a, char b) { return a == ' ' && b == ' '; }), figures.end());
        MESSAGE(name << ": " << figures);
        check_against_naive(r, mesh);
        // Welded: against the naive figures of the mesh welded through an ordered map.
        const MeshData welded_naively = naively_welded(mesh);
        const MeshReport welded = welded_report_of(mesh);
        CHECK(welded.duplicate_positions == mesh.vertex_count() - welded_naively.vertex_count());
        check_against_naive(welded, welded_naively);
        // Facts stated by the data's README.
        if (name == "rocker-arm.off") CHECK(r.genus == std::optional<int64_t>(1));
        if (name == "spot.obj") CHECK(r.genus == std::optional<int64_t>(0));
        if (name == "stanford-bunny.obj") CHECK(mesh.vertex_count() == 35947);
        if (name == "cow.ply") CHECK(mesh.vertex_count() == 2903);
    }
}
