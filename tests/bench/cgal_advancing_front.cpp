// The reference for the end-to-end benchmark: CGAL's advancing-front surface reconstruction (the closest
// published algorithm) on a point file, timed the same way as `dbrg reconstruct`, writing its mesh so that
// `dbrg stats` can judge both. Built only where Debian's libcgal-dev is installed.
//
//     cgal-advancing-front INPUT OUTPUT     prints {"seconds": ..., "triangles": ...}
#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <iterator>
#include <vector>

#include "io/mesh_io.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: cgal-advancing-front INPUT OUTPUT\n");
        return 2;
    }
    dbrg::io::MeshData mesh;
    const dbrg::io::IoStatus read = dbrg::io::read_mesh(argv[1], mesh);
    if (!read) {
        std::fprintf(stderr, "cgal-advancing-front: %s\n", read.message.c_str());
        return 1;
    }
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    std::vector<Kernel::Point_3> points;
    points.reserve(mesh.vertex_count());
    for (size_t i = 0; i < mesh.vertex_count(); ++i) {
        points.emplace_back(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
    }
    std::vector<std::array<std::size_t, 3>> facets;
    const auto start = std::chrono::steady_clock::now();
    CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    mesh.triangles.clear();
    for (const auto& facet : facets) {
        for (std::size_t corner : facet) mesh.triangles.push_back(static_cast<uint32_t>(corner));
    }
    mesh.has_faces = true;
    const dbrg::io::IoStatus written = dbrg::io::write_mesh(argv[2], mesh);
    if (!written) {
        std::fprintf(stderr, "cgal-advancing-front: %s\n", written.message.c_str());
        return 1;
    }
    std::printf("{\"seconds\": %.6f, \"triangles\": %zu}\n", seconds, facets.size());
    return 0;
}
