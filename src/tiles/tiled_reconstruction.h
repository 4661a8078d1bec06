// Tiled reconstruction: a surface reconstructed as tiles — a core box and a halo of points around it — whose
// owned triangles are stitched into one mesh by regrowing the seam strips around the core walls
// (docs/tiles.md).
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "surface_output.h"

namespace dbrg {

// A tile's core: the half-open box [low, high) on each axis (infinite bounds allowed).
struct TileCore {
    double low[3];
    double high[3];

    // Whether the centroid of the triangle with corners a, b, c lies in the core: (a + b + c) / 3 with the
    // corners summed in lexicographic order of their coordinates, so every tile computes the same number.
    bool owns(const double* a, const double* b, const double* c) const;
};

// The halo and the seam strips, in point spacings (docs/tiles.md argues for the figures).
constexpr double HALO_SPACINGS = 8.0;
constexpr double STRIP_SPACINGS = 3.0;   // half-width of the band cut and regrown around a wall
constexpr double MARGIN_SPACINGS = 3.0;  // the band beyond it whose faces seed the regrowing
// The thinnest slab: one with no interior between the strips of its walls holds nothing of its own.
constexpr double MIN_SLAB_SPACINGS = 2 * (STRIP_SPACINGS + MARGIN_SPACINGS);

// Reconstructs the surface of `points` (a tile's core and halo) and keeps the triangles the core owns
// (TileCore::owns). Writes them to `owned`, 3 indices into `points` each. Fills context.stats as
// reconstruct_surface does.
dbrg_status reconstruct_tile(const dbrg_points* points, const TileCore& core, Context& context,
                             Array<uint32_t>& owned);

// Reconstructs `points` as `tile_count` slabs along the longest axis of their box, cut at point-count
// quantiles, then stitches them (docs/tiles.md); fewer slabs where they would be thinner than
// MIN_SLAB_SPACINGS. One tile is reconstruct_surface itself. The result is in
// the caller's indexing; context.stats is filled for the whole mesh (the tiles' own figures summed where
// they are counts and times), tiles, seam_faces_dropped and tile_peak_bytes included.
dbrg_status reconstruct_tiled(const dbrg_points* points, uint32_t tile_count, Context& context, SurfaceResult& result);

} // namespace dbrg
