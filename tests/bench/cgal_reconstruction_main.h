// The shared frame of the CGAL reconstruction programs of the benchmarks: read a point file with the project's
// I/O library, time only the reconstruction, write its triangles on the points read (so that `dbrg stats`
// judges every program's mesh the same way), print {"seconds": ..., "triangles": ...}.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "io/mesh_io.h"

namespace dbrg_bench {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Facet = std::array<std::size_t, 3>;

// `reconstruct(const std::vector<Kernel::Point_3>&)` returns the facets as indices into the points given.
template <typename Reconstruct>
int run_reconstruction(int argc, char** argv, const char* program, Reconstruct reconstruct) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s INPUT OUTPUT\n", program);
        return 2;
    }
    dbrg::io::MeshData mesh;
    const dbrg::io::IoStatus read = dbrg::io::read_mesh(argv[1], mesh);
    if (!read) {
        std::fprintf(stderr, "%s: %s\n", program, read.message.c_str());
        return 1;
    }
    std::vector<Kernel::Point_3> points;
    points.reserve(mesh.vertex_count());
    for (size_t i = 0; i < mesh.vertex_count(); ++i) {
        points.emplace_back(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Facet> facets = reconstruct(points);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    mesh.triangles.clear();
    mesh.face_properties.clear();  // the input's, when it was a mesh: they describe other faces
    for (const Facet& facet : facets) {
        for (std::size_t corner : facet) mesh.triangles.push_back(static_cast<uint32_t>(corner));
    }
    mesh.has_faces = true;
    const dbrg::io::IoStatus written = dbrg::io::write_mesh(argv[2], mesh);
    if (!written) {
        std::fprintf(stderr, "%s: %s\n", program, written.message.c_str());
        return 1;
    }
    std::printf("{\"seconds\": %.6f, \"triangles\": %zu}\n", seconds, facets.size());
    return 0;
}

}  // namespace dbrg_bench
