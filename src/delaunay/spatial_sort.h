// Spatial sort: the insertion order of the tetrahedralization — BRIO rounds, Hilbert order inside each.
//
// Based on: N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO" (SoCG 2003) for the rounds;
// J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004) for the curve index.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

// Bits per axis of the grid the Hilbert order is computed on (the sort key keeps 7 bits for the round).
constexpr int HILBERT_BITS = 19;

// Position of grid cell (x, y, z), each coordinate below 2^bits, along a 3D Hilbert curve filling the
// 2^bits cube: consecutive positions are face-adjacent cells. bits is in 1..21.
uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits);

// Fills `order` with a permutation of 0 .. count - 1: rounds of geometrically growing size drawn by a
// pseudo-random generator seeded with each point's index (so the order depends on the point array and
// nothing else), each round sorted along a Hilbert curve over the points' bounding box. Reports
// DBRG_STAGE_SORT progress; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
dbrg_status brio_hilbert_order(const double* points, uint32_t count, Context& context, Array<uint32_t>& order);

// Fills `order` with the permutation of 0 .. count - 1 along a Hilbert curve over the points' bounding box,
// ties by index. Returns false on allocation failure.
bool hilbert_order(const double* points, uint32_t count, Array<uint32_t>& order);

} // namespace dbrg
