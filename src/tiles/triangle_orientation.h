// Triangle orientation: turns a triangle soup's faces so that faces sharing an edge traverse it in opposite
// directions, for the pieces tiles return, which each tile could only orient within itself.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

// Rotates each of `triangles` (3 point indices each) to start at its smallest index, sorts them, and turns
// faces over so that two faces on an edge that only they share traverse it in opposite directions: a
// breadth-first walk from the first face of each edge-connected component, where a cycle that cannot
// agree keeps the first face reached's choice. Each component is then turned as region growing seeds it:
// the smallest-circumradius face at its highest point (largest z, then the smallest index) faces up (+z,
// or +x, then +y, for a vertical face). The faces come back in the walk's order — each after the first of
// its component shares an edge with an earlier one, so a surface built in that order has few pinched
// vertices on the way — which depends on the set of triangles only. `xyz` holds the points' coordinates.
// With `turn_up` false the components are not turned: each keeps the orientation its first face (in the
// sorted order) was given, so faces already oriented alike stay as they are. Returns DBRG_OK,
// DBRG_ERR_OUT_OF_MEMORY, or DBRG_ERR_TOO_MANY_POINTS for 2^32 / 3 faces or more (a mesh of about 700
// million points: the 32-bit API checks its face counts before).
dbrg_status orient_triangles(Array<uint32_t>& triangles, const double* xyz, bool turn_up, Context& context);

} // namespace dbrg
