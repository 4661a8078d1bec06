// Point input: checks the caller's strided float/double array and copies it into x, y, z doubles.
#pragma once

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

// The share of DBRG_STAGE_VALIDATE's progress that reading the caller's points takes; conditioning them
// has the rest.
constexpr double VALIDATE_READ_SHARE = 0.05;

// The counts every stage needs, each a status with its message set: at most DBRG_MAX_POINTS
// (DBRG_ERR_TOO_MANY_POINTS), at least 4 (DBRG_ERR_TOO_FEW_POINTS: fewer cannot span a tetrahedron), both.
dbrg_status check_not_too_many_points(size_t count, Context& context);
dbrg_status check_enough_points(size_t count, Context& context);
dbrg_status check_point_count(size_t count, Context& context);

// Checks the caller's `points` (type, stride, the count, count * stride overflow, NULL data, NaN / infinity
// with the offending index) and copies the coordinates into `xyz` as doubles (exact for float input).
// Reports DBRG_STAGE_VALIDATE progress up to VALIDATE_READ_SHARE; DBRG_ERR_CANCELLED when the caller cancels.
dbrg_status copy_caller_points(const dbrg_points* points, Context& context, Array<double>& xyz);

} // namespace dbrg
