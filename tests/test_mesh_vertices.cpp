// Tests of the vertex output for viewers (io/vertex_normals.h, io/unused_vertices.h): normals that are unit
// length and on the side the triangles' orientation says, through PLY and OBJ and back through the
// project's own readers; dropping unused vertices keeps every triangle, renumbered by the returned map.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/mesh_io.h"
#include "io/unused_vertices.h"
#include "io/vertex_normals.h"

using namespace dbrg::io;

namespace {

double dot3(const double* a, const float* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm3(const float* n) { return std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]); }

// A closed unit sphere centred at the origin: an octahedron whose triangles are split into four `levels`
// times, every vertex pushed onto the sphere; triangles counter-clockwise seen from outside.
MeshData geodesic_sphere(int levels) {
    MeshData mesh;
    mesh.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    mesh.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            double p[3], length = 0;
            for (int k = 0; k < 3; ++k) {
                p[k] = (mesh.positions[3 * a + k] + mesh.positions[3 * b + k]) / 2;
                length += p[k] * p[k];
            }
            for (double& value : p) mesh.positions.push_back(value / std::sqrt(length));
            const uint32_t index = static_cast<uint32_t>(mesh.vertex_count() - 1);
            midpoints[key] = index;
            return index;
        };
        std::vector<uint32_t> finer;
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            const uint32_t a = mesh.triangles[3 * t], b = mesh.triangles[3 * t + 1], c = mesh.triangles[3 * t + 2];
            const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
        }
        mesh.triangles = finer;
    }
    mesh.has_faces = true;
    return mesh;
}

// The values of every line of `text` that begins with `keyword` and a blank.
std::vector<float> values_after(const std::string& text, const std::string& keyword) {
    std::vector<float> values;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.compare(0, keyword.size() + 1, keyword + " ") != 0) continue;
        std::istringstream fields(line.substr(keyword.size() + 1));
        std::string field;
        while (fields >> field) values.push_back(std::strtof(field.c_str(), nullptr));
    }
    return values;
}

} // namespace

TEST_CASE("vertex normals of a closed sphere are unit length and point outward") {
    const MeshData sphere = geodesic_sphere(3);
    const std::vector<float> normals = vertex_normals(sphere.positions, sphere.triangles);
    REQUIRE(normals.size() == sphere.positions.size());
    for (size_t v = 0; v < sphere.vertex_count(); ++v) {
        CAPTURE(v);
        CHECK(norm3(&normals[3 * v]) == doctest::Approx(1.0).epsilon(1e-6));
        // On a unit sphere the outward direction is the position itself; the mesh's facets tilt the
        // normals by a few degrees at most.
        CHECK(dot3(&sphere.positions[3 * v], &normals[3 * v]) > 0.99);
    }
}

TEST_CASE("turning every triangle over turns every normal over") {
    const MeshData sphere = geodesic_sphere(2);
    std::vector<uint32_t> reversed = sphere.triangles;
    for (size_t t = 0; t < reversed.size(); t += 3) std::swap(reversed[t + 1], reversed[t + 2]);
    const std::vector<float> outward = vertex_normals(sphere.positions, sphere.triangles);
    const std::vector<float> inward = vertex_normals(sphere.positions, reversed);
    for (size_t i = 0; i < outward.size(); ++i) CHECK(inward[i] == doctest::Approx(-outward[i]).epsilon(1e-6));
}

TEST_CASE("normals are weighted by angle: splitting a triangle through a corner changes no corner's normal") {
    // Splitting triangle (a, b, c) at the midpoint m of b-c into (a, b, m) and (a, m, c) halves the area
    // that b and c see in that plane but keeps their angles; an area weighting would move their normals.
    const MeshData sphere = geodesic_sphere(1);
    const std::vector<float> before = vertex_normals(sphere.positions, sphere.triangles);
    for (size_t t = 0; t < sphere.triangle_count(); ++t) {
        CAPTURE(t);
        MeshData split = sphere;
        const uint32_t a = split.triangles[3 * t], b = split.triangles[3 * t + 1], c = split.triangles[3 * t + 2];
        for (int k = 0; k < 3; ++k) split.positions.push_back((split.positions[3 * b + k] + split.positions[3 * c + k]) / 2);
        const uint32_t m = static_cast<uint32_t>(split.vertex_count() - 1);
        split.triangles[3 * t + 2] = m;
        split.triangles.insert(split.triangles.end(), {a, m, c});
        const std::vector<float> after = vertex_normals(split.positions, split.triangles);
        for (size_t i = 0; i < before.size(); ++i) CHECK(after[i] == doctest::Approx(before[i]).epsilon(1e-6));
    }
}

TEST_CASE("a vertex without triangles, or with only degenerate ones, has a zero normal") {
    MeshData mesh = geodesic_sphere(0);
    for (double value : {5.0, 5.0, 5.0, 6.0, 6.0, 6.0}) mesh.positions.push_back(value);
    mesh.triangles.insert(mesh.triangles.end(), {7, 7, 0});  // zero area: counts for nothing
    const std::vector<float> normals = vertex_normals(mesh.positions, mesh.triangles);
    for (size_t v : {6, 7}) {
        CAPTURE(v);
        CHECK(normals[3 * v] == 0.0f);
        CHECK(normals[3 * v + 1] == 0.0f);
        CHECK(normals[3 * v + 2] == 0.0f);
    }
    CHECK(norm3(&normals[0]) == doctest::Approx(1.0));
    CHECK(vertex_normals({}, {}).empty());
}

TEST_CASE("normals round-trip exactly through binary and ascii PLY read by the project's reader") {
    MeshData mesh = geodesic_sphere(2);
    mesh.normals = vertex_normals(mesh.positions, mesh.triangles);
    for (MeshFormat format : {MeshFormat::ply_binary, MeshFormat::ply_ascii}) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        CHECK(bytes.find("property float nx\nproperty float ny\nproperty float nz\n") != std::string::npos);
        MeshData back;
        const IoStatus status = read_mesh_buffer(bytes.data(), bytes.size(), format, back);
        INFO(status.message);
        REQUIRE(status.ok);
        CHECK(back.positions == mesh.positions);
        CHECK(back.triangles == mesh.triangles);
        CHECK(back.normals == mesh.normals);
    }
}

TEST_CASE("OBJ writes a vn per vertex, and faces that name it beside the position") {
    MeshData mesh = geodesic_sphere(1);
    mesh.normals = vertex_normals(mesh.positions, mesh.triangles);
    std::string text;
    REQUIRE(write_mesh_buffer(mesh, MeshFormat::obj, text).ok);
    CHECK(values_after(text, "vn") == mesh.normals);  // each float's shortest text reads back as itself
    CHECK(text.find("\nf 1//1 ") != std::string::npos);
    MeshData back;
    REQUIRE(read_mesh_buffer(text.data(), text.size(), MeshFormat::obj, back).ok);
    CHECK(back.positions == mesh.positions);
    CHECK(back.triangles == mesh.triangles);

    mesh.normals.clear();
    REQUIRE(write_mesh_buffer(mesh, MeshFormat::obj, text).ok);
    CHECK(text.find("vn ") == std::string::npos);
    CHECK(text.find("//") == std::string::npos);
}

TEST_CASE("the PLY reader takes normals only when a vertex has all three") {
    const std::string partial = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                "property float z\nproperty float nx\nproperty float ny\nend_header\n1 2 3 0 1\n";
    MeshData back;
    REQUIRE(read_mesh_buffer(partial.data(), partial.size(), MeshFormat::ply_ascii, back).ok);
    CHECK(back.normals.empty());
    CHECK(back.positions == std::vector<double>{1, 2, 3});
    // Normals are not coordinates: a NaN among them is no non-finite vertex.
    const std::string full = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float nz\nproperty float x\n"
                             "property float ny\nproperty float y\nproperty float nx\nproperty float z\nend_header\n"
                             "nan 1 0.5 2 0.25 3\n";
    REQUIRE(read_mesh_buffer(full.data(), full.size(), MeshFormat::ply_ascii, back).ok);
    CHECK(back.positions == std::vector<double>{1, 2, 3});
    REQUIRE(back.normals.size() == 3);
    CHECK(back.normals[0] == 0.25f);
    CHECK(back.normals[1] == 0.5f);
    CHECK(std::isnan(back.normals[2]));
    CHECK(back.non_finite_at.empty());
}

TEST_CASE("writers refuse normals that do not match the vertices") {
    MeshData mesh = geodesic_sphere(0);
    mesh.normals = {0, 0, 1};
    std::string bytes;
    const IoStatus status = write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("normal array") != std::string::npos);
}

TEST_CASE("dropping unused vertices keeps every triangle, renumbered by the returned map") {
    // The sphere's vertices interleaved with points no triangle uses, as a reconstruction leaves out noise.
    const MeshData sphere = geodesic_sphere(2);
    MeshData mesh;
    std::vector<uint32_t> placed;
    for (size_t v = 0; v < sphere.vertex_count(); ++v) {
        if (v % 3 == 0) mesh.positions.insert(mesh.positions.end(), {10.0 + v, 0.0, 0.0});
        placed.push_back(static_cast<uint32_t>(mesh.vertex_count()));
        mesh.positions.insert(mesh.positions.end(), &sphere.positions[3 * v], &sphere.positions[3 * v] + 3);
    }
    mesh.positions.insert(mesh.positions.end(), {-9.0, -9.0, -9.0});
    for (uint32_t vertex : sphere.triangles) mesh.triangles.push_back(placed[vertex]);
    mesh.has_faces = true;
    mesh.normals = vertex_normals(mesh.positions, mesh.triangles);
    // Properties of one, two and eight bytes, each vertex's value its own.
    mesh.properties = {{"red", ValueType::uint8, {}}, {"intensity", ValueType::int16, {}}, {"confidence", ValueType::float64, {}}};
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        CHECK(mesh.properties[0].append(double(v % 256)));
        CHECK(mesh.properties[1].append(-double(v)));
        CHECK(mesh.properties[2].append(v / 7.0));
    }
    const MeshData before = mesh;

    const std::vector<uint32_t> old_to_new = drop_unused_vertices(mesh);
    REQUIRE(old_to_new.size() == before.vertex_count());
    CHECK(mesh.vertex_count() == sphere.vertex_count());
    CHECK(mesh.normals.size() == mesh.positions.size());
    for (size_t i = 0; i < before.triangles.size(); ++i) CHECK(mesh.triangles[i] == old_to_new[before.triangles[i]]);
    std::vector<bool> used(before.vertex_count(), false);
    for (uint32_t vertex : before.triangles) used[vertex] = true;
    uint32_t next = 0;
    for (size_t v = 0; v < before.vertex_count(); ++v) {
        CAPTURE(v);
        if (!used[v]) {
            CHECK(old_to_new[v] == DROPPED_VERTEX);
            continue;
        }
        REQUIRE(old_to_new[v] == next++);  // kept vertices stay in their order
        for (size_t k = 0; k < 3; ++k) {
            CHECK(mesh.positions[3 * old_to_new[v] + k] == before.positions[3 * v + k]);
            CHECK(mesh.normals[3 * old_to_new[v] + k] == before.normals[3 * v + k]);
        }
        for (size_t p = 0; p < mesh.properties.size(); ++p) CHECK(mesh.properties[p].value(old_to_new[v]) == before.properties[p].value(v));
    }
    for (const VertexProperty& property : mesh.properties) CHECK(property.size() == mesh.vertex_count());
    // The compacted mesh has the same normals as computed from scratch: nothing depended on the dropped points.
    CHECK(vertex_normals(mesh.positions, mesh.triangles) == mesh.normals);
}

TEST_CASE("dropping unused vertices of a mesh without triangles keeps none") {
    MeshData mesh;
    mesh.positions = {1, 2, 3, 4, 5, 6};
    mesh.properties = {{"intensity", ValueType::uint16, {}}};
    CHECK(mesh.properties[0].append(1));
    CHECK(mesh.properties[0].append(2));
    const std::vector<uint32_t> old_to_new = drop_unused_vertices(mesh);
    CHECK(old_to_new == std::vector<uint32_t>{DROPPED_VERTEX, DROPPED_VERTEX});
    CHECK(mesh.positions.empty());
    CHECK(mesh.properties[0].bytes.empty());
    MeshData empty;
    CHECK(drop_unused_vertices(empty).empty());
}
