// Point input: checks the caller's strided float/double array and copies it into x, y, z doubles.
#pragma once

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

// Checks `points` (NULL data, stride, count * stride overflow, DBRG_MAX_POINTS, NaN / infinity with the
// offending index) and copies the coordinates into `xyz` as doubles (exact for float input).
dbrg_status read_points(const dbrg_points* points, Context& context, Array<double>& xyz);

} // namespace dbrg
