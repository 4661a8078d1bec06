// Point cleaning: outliers left out, near-duplicates merged and noisy points moved onto a local surface
// estimate before the tetrahedralization, each only where the data call for it.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "points/point_conditioning.h"

namespace dbrg {

// Cleans conditioned, Hilbert-numbered points as context.params.cleaning says (AUTO or ON; not called for
// OFF). When a rule acts, the points kept (each merged group's first point along the curve, at its smoothed
// position when smoothed) are conditioned and renumbered again, each still standing for its caller index;
// otherwise `points` is left exactly as it was. `outliers` receives the caller indices of the outliers,
// ascending. Fills the cleaning fields of context.stats. Reports DBRG_STAGE_CLEAN; returns DBRG_OK,
// DBRG_ERR_OUT_OF_MEMORY, DBRG_ERR_CANCELLED, or a conditioning status when too few points are left.
dbrg_status clean_points(ConditionedPoints& points, Context& context, Array<uint32_t>& outliers);

} // namespace dbrg
