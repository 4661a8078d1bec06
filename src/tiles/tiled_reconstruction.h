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
    // Whether point p lies in the core: every point of the cloud lies in exactly one.
    bool contains(const double* p) const;
};

// The halo and the seam strips, in point spacings (docs/tiles.md argues for the figures).
constexpr double HALO_SPACINGS = 8.0;
constexpr double STRIP_SPACINGS = 3.0;   // half-width of the band cut and regrown around a wall
constexpr double MARGIN_SPACINGS = 3.0;  // the band beyond it whose faces seed the regrowing
// The thinnest slab: one with no interior between the strips of its walls holds nothing of its own.
constexpr double MIN_SLAB_SPACINGS = 2 * (STRIP_SPACINGS + MARGIN_SPACINGS);

// How a cloud is cut: slabs along `axis` between `walls` (ascending), measured in the point spacing.
struct TilingPlan {
    explicit TilingPlan(Memory& memory) : walls(memory) {}
    int axis = 0;
    double spacing = 0;
    Array<double> walls;
};

// Plans `tile_count` slabs over the `count` points `xyz`: the spacing (estimate_spacing), the longest axis
// of their box, and walls at point-count quantiles, fewer where a slab would be thinner than
// MIN_SLAB_SPACINGS or points share a coordinate. No walls when the cloud is to run as one piece.
dbrg_status plan_tiling(const double* xyz, size_t count, uint32_t tile_count, Context& context, TilingPlan& plan);

// Reconstructs the surface of `points` (a tile's core and halo) and keeps the triangles the core owns
// (TileCore::owns). Writes them to `owned`, 3 indices into `points` each, and to `outliers` the indices of
// the points in the core that cleaning left out as outliers, ascending. Fills context.stats as
// reconstruct_surface does.
dbrg_status reconstruct_tile(const dbrg_points* points, const TileCore& core, Context& context,
                             Array<uint32_t>& owned, Array<uint32_t>& outliers);

// Stitches the seam around `wall` (docs/tiles.md, steps 2 and 3) from the `count` points `xyz` near it,
// numbered in ascending global id, and `faces` (3 indices each, oriented as their tiles grew them): cuts the
// faces with a corner in the strip, orients the cut faces and the seeds around them together, and regrows
// the strip from the seeds. Writes to `dropped` the faces cut or used as seeds (ascending indices into
// `faces`) and to `added` the faces that replace them (the regrown strip, seeds included). The result
// depends on the sets of points and faces near the wall only: not on the order of `faces`, nor on points
// and faces further away. Fills context.stats as grow_from_surface does.
dbrg_status stitch_seam(const double* xyz, size_t count, const uint32_t* faces, size_t face_count, int axis,
                        double wall, double spacing, Context& context, Array<uint32_t>& dropped,
                        Array<uint32_t>& added);

// Puts the stitched faces (3 indices into the points `xyz` each) into one surface: oriented together,
// taken in the orientation walk's order, a face that would break the manifold left out and counted in
// seam_faces_dropped, pinched vertices keeping their largest fan; hands it over as the single call does,
// with those of `outliers` (the tiles' outliers, ascending) that no face uses as its outliers, and
// context.stats.unique_points less their number. Needs the whole mesh.
// Takes `xyz` and `mesh` over.
dbrg_status assemble_tiles(Array<double>& xyz, Array<uint32_t>& mesh, const Array<uint32_t>& outliers,
                           Context& context, SurfaceResult& result);

// Adds a piece's figures (a tile's, a seam stitch's) to the whole run's: counts and seconds add up (a halo
// point cleaned in two tiles counts in both; a count stops at its type's largest value); the noise estimate
// and the smoothing rounds are the largest a piece had. The whole mesh's figures (points, faces, loops,
// outliers, tiles) are the total's own.
void add_piece_stats(const dbrg_stats& piece, dbrg_stats& total);

// Reconstructs `points` as `tile_count` slabs (plan_tiling), one after another, then stitches the even
// walls (the first, third, ...) and then the odd ones, each stitch on the faces as they were before its
// half began, as a cluster would run them at once, and assembles the result (docs/tiles.md). One tile is
// reconstruct_surface itself. The result is in the caller's indexing; context.stats is filled for the
// whole mesh (the tiles' own figures summed where they are counts and times), tiles, seam_faces_dropped
// and tile_peak_bytes included.
dbrg_status reconstruct_tiled(const dbrg_points* points, uint32_t tile_count, Context& context, SurfaceResult& result);

} // namespace dbrg
