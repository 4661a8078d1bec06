// CGAL comparison: times CGAL's Delaunay_triangulation_3 on the same points, for the benchmark only.
#pragma once

#include <stddef.h>
#include <stdint.h>

namespace dbrg_bench {

struct CgalRun {
    double seconds = 0;           // inserting the points (CGAL sorts them spatially itself)
    uint64_t finite_tets = 0;
};

// Builds the Delaunay triangulation of `count` points (x, y, z triples) with CGAL's exact-predicates
// kernel, single-threaded. Returns false when CGAL throws.
bool cgal_delaunay(const double* xyz, size_t count, CgalRun& run);

} // namespace dbrg_bench
