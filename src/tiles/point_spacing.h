// Point spacing: the typical distance between neighbouring points, the unit in which tiles measure their
// halo and the seam strips the stitch regrows.
#pragma once

#include <stddef.h>

#include "core/context.h"

namespace dbrg {

// The 90th percentile of the distance from a point to its nearest other point (the strips must be wider
// than nearly all triangles, and on unevenly sampled data the median is far below the larger ones), over
// a sample of about 4096 points chosen by a hash of their coordinates (so the figure does not depend on
// the points' order), found with a uniform grid. 0 for fewer than 2 distinct points. Returns DBRG_OK or
// DBRG_ERR_OUT_OF_MEMORY.
dbrg_status estimate_spacing(const double* xyz, size_t count, Context& context, double& spacing);

} // namespace dbrg
