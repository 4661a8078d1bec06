// TetGen backend: the Delaunay tetrahedralization computed by TetGen (AGPL, optional) and converted
// into the same Tetrahedralization store as the built-in engine, for cross-checks and benchmarks.
#pragma once

#include <stdint.h>

#include "core/context.h"
#include "delaunay/tetrahedralization.h"

namespace dbrg {

// True when this build has the TetGen backend (configured with -Dtetgen=enabled).
bool tetgen_available();

// DBRG_OK when this build has the TetGen backend; otherwise DBRG_ERR_UNSUPPORTED with a message saying how
// to get it.
dbrg_status check_tetgen(Context& context);

// As Tetrahedralization::build, with TetGen computing the tetrahedra; the result has the same layout
// (positively oriented finite tetrahedra, infinite tetrahedra behind the hull faces with the infinite
// vertex in slot 3, no free slots). On points in general position it holds the same tetrahedra as
// the built-in engine; on cospherical points TetGen's own tie-breaking may choose others. TetGen
// allocates its working memory with new/malloc, outside the context's allocator; only the result
// lives in context.memory. Returns DBRG_ERR_UNSUPPORTED in builds without TetGen and
// DBRG_ERR_INTERNAL when TetGen fails, besides the statuses of build.
dbrg_status build_with_tetgen(const double* points, uint32_t count, Context& context, Tetrahedralization& out);

} // namespace dbrg
