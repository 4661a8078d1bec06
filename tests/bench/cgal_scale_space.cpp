// A peer for the scan benchmark: CGAL's scale-space surface reconstruction, which smooths the points before
// meshing them (jet fitting: 4 iterations of 12 neighbours, as issue #12 names it), then meshes the smoothed
// points by advancing front; the triangles are written on the original points, so the mesh interpolates the
// input as dbrg's does. Sequential: CGAL runs the smoother in parallel only when linked with TBB, which this
// build does not do. Built only where Debian's libcgal-dev and libeigen3-dev are installed.
//
//     cgal-scale-space INPUT OUTPUT     prints {"seconds": ..., "triangles": ...}
#include <CGAL/Scale_space_reconstruction_3/Advancing_front_mesher.h>
#include <CGAL/Scale_space_reconstruction_3/Jet_smoother.h>
#include <CGAL/Scale_space_surface_reconstruction_3.h>

#include "cgal_reconstruction_main.h"

namespace {

constexpr std::size_t SMOOTHING_ITERATIONS = 4;
constexpr unsigned int SMOOTHING_NEIGHBOURS = 12;

}  // namespace

int main(int argc, char** argv) {
    using dbrg_bench::Kernel;
    return dbrg_bench::run_reconstruction(argc, argv, "cgal-scale-space", [](const auto& points) {
        CGAL::Scale_space_surface_reconstruction_3<Kernel> reconstruction(points.begin(), points.end());
        reconstruction.increase_scale(SMOOTHING_ITERATIONS,
                                      CGAL::Scale_space_reconstruction_3::Jet_smoother<Kernel>(SMOOTHING_NEIGHBOURS));
        // The facets index the points in their input order at every scale.
        reconstruction.reconstruct_surface(CGAL::Scale_space_reconstruction_3::Advancing_front_mesher<Kernel>());
        return std::vector<dbrg_bench::Facet>(reconstruction.facets_begin(), reconstruction.facets_end());
    });
}
