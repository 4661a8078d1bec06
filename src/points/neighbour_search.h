// Neighbour search: the k nearest neighbours of every point, through a k-d tree over the points.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"

namespace dbrg {

// The most neighbours a search may ask for.
constexpr uint32_t MAX_NEIGHBOURS = 32;

// The k nearest neighbours of each of `count` distinct points (x, y, z triples), the point itself left out:
// neighbours[k * i + j] is the (j + 1)-th nearest neighbour of point i, nearest first; k is min(wanted,
// count - 1), wanted at most MAX_NEIGHBOURS. A search prunes every part of the tree not strictly nearer than
// the k-th neighbour found so far, so a point among many equal distances (a grid, a sphere's centre) costs
// about what any other does; among equal distances it keeps the points it meets first, ties in one leaf
// going to the smaller index. The tree and the searches depend on the coordinates and their numbering
// only, and each point's search is independent of the others', so the result is the same for any number
// of threads and, for points numbered by their coordinates (conditioned points), any input order. Uses up to context.params.threads threads;
// reports to `progress`; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
dbrg_status find_nearest_neighbours(const double* xyz, uint32_t count, uint32_t wanted, const ProgressSpan& progress,
                                    uint32_t& k, Array<uint32_t>& neighbours);

} // namespace dbrg
