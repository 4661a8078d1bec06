// Delaunay backend choice: the tetrahedralization from the engine the parameters name, the built-in one
// or TetGen.
#pragma once

#include <stdint.h>

#include "core/context.h"
#include "delaunay/tetrahedralization.h"

namespace dbrg {

// Builds `out` with `backend`: Tetrahedralization::build for DBRG_BACKEND_BUILTIN (told how the points
// are numbered), build_with_tetgen for DBRG_BACKEND_TETGEN; returns their status.
dbrg_status build_tetrahedralization(dbrg_backend backend, const double* points, uint32_t count, PointOrder order,
                                     Context& context, Tetrahedralization& out);

// DBRG_OK when this build has `backend`; otherwise the status and message build_tetrahedralization would
// give. For callers that need no tetrahedra (a flat point set) but must answer a missing backend alike.
dbrg_status check_backend(dbrg_backend backend, Context& context);

} // namespace dbrg
