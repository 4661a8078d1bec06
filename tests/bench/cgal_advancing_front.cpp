// The reference for the end-to-end benchmark: CGAL's advancing-front surface reconstruction (the closest
// published algorithm) on a point file, timed the same way as `dbrg reconstruct`, writing its mesh so that
// `dbrg stats` can judge both. Built only where Debian's libcgal-dev is installed.
//
//     cgal-advancing-front INPUT OUTPUT     prints {"seconds": ..., "triangles": ...}
#include <CGAL/Advancing_front_surface_reconstruction.h>

#include <iterator>

#include "cgal_reconstruction_main.h"

int main(int argc, char** argv) {
    return dbrg_bench::run_reconstruction(argc, argv, "cgal-advancing-front", [](const auto& points) {
        std::vector<dbrg_bench::Facet> facets;
        CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets));
        return facets;
    });
}
