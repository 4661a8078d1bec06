// Out-of-core reconstruction: a cloud file larger than memory reconstructed as slabs one after another,
// with only one slab's points, or one seam's, in memory at a time: the points sorted into per-slab bucket
// files, each slab's owned faces to disk, each wall stitched from the points and faces near it, the
// pieces oriented together by a parity union-find, and the mesh streamed out as binary PLY
// (docs/tiles.md, "Out of core"). Point ids are 64-bit throughout.
#pragma once

#include <cstdint>
#include <string>

#include "dbrg/dbrg.h"
#include "io/mesh_io.h"

namespace dbrg::out_of_core {

// Bytes one tile holds at its peak per point it reconstructs (its core and halo), with the loop's own
// arrays; measured as tile_peak_bytes over the tile's points on generated surfaces (docs/tiles.md).
constexpr double TILE_BYTES_PER_POINT = 450;

struct Options {
    // The memory the run may use; the number of slabs follows from it (TILE_BYTES_PER_POINT).
    uint64_t max_memory_bytes = 0;
    // The number of slabs asked instead, when not 0 (tests; fewer run where slabs would be too thin).
    uint32_t tiles = 0;
    dbrg_params params;  // progress and snapshots are not used
};

struct Report {
    uint64_t points = 0;
    uint64_t triangles = 0;
    uint64_t boundary_edges = 0;
    uint64_t components = 0;
    uint32_t tiles = 0;            // slabs run
    size_t tile_peak_bytes = 0;    // the most one tile or one stitch held through the library's allocator
    uint64_t orientation_conflicts = 0;  // seam edges whose pieces could not be turned to agree
    double spacing = 0;
    dbrg_stats sums{};             // the tiles' and stitches' counts and times, summed
};

// Reconstructs the points of `input` (.ply or .xyz/.pts) into `output` (binary .ply: every input point a
// vertex, in input order; no normals or other properties). Temporary files go to a folder beside the
// output, removed on success and on failure; the output appears only when complete. Messages name the
// file, the tile or the wall.
io::IoStatus reconstruct_file(const std::string& input, const std::string& output, const Options& options,
                              Report& report);

// The number of slabs for `count` points within `max_memory_bytes`.
uint32_t tiles_for_budget(uint64_t count, uint64_t max_memory_bytes);

} // namespace dbrg::out_of_core
