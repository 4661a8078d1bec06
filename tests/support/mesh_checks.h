// Test support: run a reconstruction through the C API and check the properties every output must have.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dbrg/dbrg.h"
#include "measure/mesh_report.h"

namespace dbrg::test {

struct Reconstruction {
    dbrg_status status = DBRG_OK;
    std::vector<uint32_t> triangles;
    std::vector<uint8_t> face_flags;  // dbrg_mesh_face_flags, one per triangle
    uint32_t boundary_loops = 0;
    std::vector<uint32_t> outliers;  // dbrg_mesh_outliers
    dbrg_stats stats{};
};

// Reconstructs x, y, z doubles (or any dbrg_points) with `params` (NULL: defaults).
Reconstruction reconstruct(const std::vector<double>& xyz, const dbrg_params* params = nullptr);
Reconstruction reconstruct(const dbrg_points& points, const dbrg_params* params = nullptr);
// The same with dbrg_reconstruct_tiled in `tiles` slabs and the default parameters.
Reconstruction reconstruct_tiled(const std::vector<double>& xyz, uint32_t tiles);

// dbrg_mesh_assemble over the triangles (indices into xyz) and the tiles' outliers with `params` (NULL: defaults).
Reconstruction assemble(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles,
                        const dbrg_params* params = nullptr, const std::vector<uint32_t>& outliers = {});

// `dbrg stats` figures of the triangles over the points.
measure::MeshReport report_of(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles);

// The library's promise: no non-manifold edge or vertex, consistently oriented, no degenerate or duplicate face.
void require_valid_manifold(const measure::MeshReport& report);

// Six times the signed volume enclosed (positive when closed and facing outward).
double signed_volume(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles);

double longest_edge(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles);
double median_edge(const std::vector<double>& xyz, const std::vector<uint32_t>& triangles);

// Each triangle as its corner coordinates, rotated to start at its smallest corner (orientation kept),
// the list sorted: comparable across point orders.
std::vector<std::array<double, 9>> triangles_by_position(const std::vector<double>& xyz,
                                                         const std::vector<uint32_t>& triangles);

} // namespace dbrg::test
