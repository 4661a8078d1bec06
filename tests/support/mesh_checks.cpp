// Test support: run a reconstruction through the C API and check the properties every output must have.
#include "support/mesh_checks.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace dbrg::test {
namespace {

double edge_length(const std::vector<double>& xyz, uint32_t a, uint32_t b) {
    const double dx = xyz[3 * a] - xyz[3 * b], dy = xyz[3 * a + 1] - xyz[3 * b + 1], dz = xyz[3 * a + 2] - xyz[3 * b + 2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

std::vector<double> edge_lengths(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles) {
    std::vector<double> lengths;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        for (int i = 0; i < 3; ++i) lengths.push_back(edge_length(xyz, triangles[t + i], triangles[t + (i + 1) % 3]));
    }
    return lengths;
}

} // namespace

namespace {

// What a call that made `mesh` with `status` gives; frees the mesh.
Reconstruction result_of(dbrg_status status, dbrg_mesh* mesh) {
    Reconstruction result;
    result.status = status;
    REQUIRE(mesh != nullptr);
    const uint32_t* triangles = dbrg_mesh_triangles(mesh);
    result.triangles.assign(triangles, triangles + 3 * size_t(dbrg_mesh_triangle_count(mesh)));
    const uint8_t* flags = dbrg_mesh_face_flags(mesh);
    if (flags) result.face_flags.assign(flags, flags + dbrg_mesh_triangle_count(mesh));
    result.boundary_loops = dbrg_mesh_boundary_loop_count(mesh);
    uint32_t outlier_count = 0;
    const uint32_t* outliers = dbrg_mesh_outliers(mesh, &outlier_count);
    if (outliers) result.outliers.assign(outliers, outliers + outlier_count);
    result.stats.struct_size = sizeof result.stats;
    dbrg_mesh_stats(mesh, &result.stats);
    if (result.status != DBRG_OK) MESSAGE(dbrg_status_string(result.status) << ": " << dbrg_mesh_message(mesh));
    dbrg_mesh_destroy(mesh);
    return result;
}

dbrg_points points_of(const std::vector<double>& xyz) {
    return dbrg_points{xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
}

} // namespace

Reconstruction reconstruct(const dbrg_points& points, const dbrg_params* params) {
    dbrg_mesh* mesh = nullptr;
    const dbrg_status status = dbrg_reconstruct(&points, params, &mesh);
    return result_of(status, mesh);
}

Reconstruction reconstruct(const std::vector<double>& xyz, const dbrg_params* params) {
    return reconstruct(points_of(xyz), params);
}

Reconstruction reconstruct_tiled(const std::vector<double>& xyz, uint32_t tiles) {
    const dbrg_points points = points_of(xyz);
    dbrg_mesh* mesh = nullptr;
    const dbrg_status status = dbrg_reconstruct_tiled(&points, tiles, nullptr, &mesh);
    return result_of(status, mesh);
}

Reconstruction assemble(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles,
                        const dbrg_params* params, const std::vector<uint32_t>& outliers) {
    const dbrg_points points = points_of(xyz);
    dbrg_mesh* mesh = nullptr;
    const dbrg_status status = dbrg_mesh_assemble(&points, triangles.data(), triangles.size() / 3, outliers.data(),
                                                  outliers.size(), params, &mesh);
    return result_of(status, mesh);
}

measure::MeshReport report_of(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles) {
    io::MeshData mesh;
    mesh.positions = xyz;
    mesh.triangles = triangles;
    mesh.has_faces = true;
    measure::MeshReport report;
    REQUIRE(measure::make_mesh_report(mesh, report).ok);
    return report;
}

void require_valid_manifold(const measure::MeshReport& report) {
    CHECK(report.faces > 0);
    CHECK(report.edges_nonmanifold == 0);
    CHECK(report.vertices_nonmanifold == 0);
    CHECK(report.oriented);
    CHECK(report.degenerate_faces == 0);
    CHECK(report.duplicate_faces == 0);
}

double signed_volume(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles) {
    double volume = 0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const double* a = &xyz[3 * triangles[t]];
        const double* b = &xyz[3 * triangles[t + 1]];
        const double* c = &xyz[3 * triangles[t + 2]];
        volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return volume;
}

double longest_edge(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles) {
    const std::vector<double> lengths = edge_lengths(xyz, triangles);
    return lengths.empty() ? 0 : *std::max_element(lengths.begin(), lengths.end());
}

double median_edge(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles) {
    std::vector<double> lengths = edge_lengths(xyz, triangles);
    if (lengths.empty()) return 0;
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    return lengths[lengths.size() / 2];
}

std::vector<std::array<double, 9>> triangles_by_position(const std::vector<double>& xyz,
                                                         const std::vector<uint32_t>& triangles) {
    std::vector<std::array<double, 9>> out;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        std::array<std::array<double, 3>, 3> corners;
        for (int i = 0; i < 3; ++i) corners[i] = {xyz[3 * triangles[t + i]], xyz[3 * triangles[t + i] + 1], xyz[3 * triangles[t + i] + 2]};
        std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
        std::array<double, 9> flat;
        for (int i = 0; i < 9; ++i) flat[i] = corners[i / 3][i % 3];
        out.push_back(flat);
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace dbrg::test
