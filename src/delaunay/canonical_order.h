// Canonical order: the finite tetrahedra of a tetrahedralization numbered and written so that the output
// depends on the coordinates only, never on the slots construction left them in.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "delaunay/tetrahedralization.h"

namespace dbrg {

// Writes the finite tetrahedra of `delaunay` in the order of their canonical corners (canonical_corners),
// each with its corners in that order: 4 corners per tetrahedron into `tets` as input_index[vertex], and
// into `adjacency` the number of the tetrahedron across from each corner, DBRG_NO_NEIGHBOR on the hull.
// Reports its passes within `progress`; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
dbrg_status write_canonical_tetrahedra(const Tetrahedralization& delaunay, const uint32_t* input_index,
                                       const ProgressSpan& progress, Array<uint32_t>& tets, Array<uint32_t>& adjacency);

} // namespace dbrg
