// Point input: checks the caller's strided float/double array and copies it into x, y, z doubles.
#pragma once

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

// The share of DBRG_STAGE_VALIDATE's progress that reading the caller's points takes; conditioning them
// has the rest.
constexpr double VALIDATE_READ_SHARE = 0.05;

// Checks `points` (NULL data, stride, count * stride overflow, DBRG_MAX_POINTS, NaN / infinity with the
// offending index) and copies the coordinates into `xyz` as doubles (exact for float input). Reports
// DBRG_STAGE_VALIDATE progress up to VALIDATE_READ_SHARE; DBRG_ERR_CANCELLED when the caller cancels.
dbrg_status read_points(const dbrg_points* points, Context& context, Array<double>& xyz);

} // namespace dbrg
