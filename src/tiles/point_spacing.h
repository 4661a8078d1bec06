// Point spacing: the typical distance between neighbouring points, the unit in which tiles measure their
// halo and the seam strips the stitch regrows.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "core/context.h"

namespace dbrg {

// The 90th percentile of the distance from a point to its nearest other point (the strips must be wider
// than nearly all triangles, and on unevenly sampled data the median is far below the larger ones), over
// a sample of about 4096 points chosen by a hash of their coordinates (so the figure does not depend on
// the points' order), found with a uniform grid. 0 for fewer than 2 distinct points. Returns DBRG_OK or
// DBRG_ERR_OUT_OF_MEMORY.
// The hash of a point's coordinates that chooses the sample: the same point gets the same hash wherever it is
// read, so a streamed pass over a file picks the points a call on the whole cloud picks.
uint64_t coordinate_hash(const double* p);

// How many points in `count` the sample keeps one of: those whose coordinate_hash is a multiple of it.
uint64_t spacing_sample_stride(size_t count);

// The side of the grid cells the search runs in, for points in a box whose longest side is `extent`.
double spacing_grid_cell(double extent, size_t count);

dbrg_status estimate_spacing(const double* xyz, size_t count, Context& context, double& spacing);

} // namespace dbrg
