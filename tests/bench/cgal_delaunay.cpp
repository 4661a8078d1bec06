// CGAL comparison: times CGAL's Delaunay_triangulation_3 on the same points, for the benchmark only.
// Built only when the CGAL headers are installed (Debian libcgal-dev), with exceptions, in its own library.
#include "cgal_delaunay.h"

#include <time.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

namespace dbrg_bench {

namespace {
double now() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);  // as the benchmark's other engines
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
} // namespace

bool cgal_delaunay(const double* xyz, size_t count, CgalRun& run) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Triangulation = CGAL::Delaunay_triangulation_3<Kernel>;
    try {
        std::vector<Kernel::Point_3> points;
        points.reserve(count);
        for (size_t i = 0; i < count; ++i) points.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        const double start = now();
        Triangulation triangulation(points.begin(), points.end());  // range insertion: spatial sort included
        run.seconds = now() - start;
        run.finite_tets = triangulation.number_of_finite_cells();
        return true;
    } catch (...) {
        return false;
    }
}

} // namespace dbrg_bench
