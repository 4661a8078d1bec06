// Out-of-core reconstruction: a cloud file larger than memory reconstructed as slabs one after another,
// with only one slab's points, or one seam's, in memory at a time: the points sorted into per-slab bucket
// files, each slab's owned faces to disk, each wall stitched from the points and faces near it and then
// checked for a manifold, the pieces oriented together by a parity union-find, and the mesh streamed out as
// binary PLY (docs/tiles.md, "Out of core"). Point ids are 64-bit throughout.
#pragma once

#include <cstdint>
#include <string>

#include "dbrg/dbrg.h"
#include "io/mesh_io.h"

namespace dbrg::out_of_core {

// Resident bytes a tile needs at its peak per point it reconstructs (its core and halo), the loop's own
// arrays included, and the program's own before any tile; measured on generated surfaces (docs/tiles.md).
constexpr double TILE_BYTES_PER_POINT = 800;
constexpr double BASE_BYTES = 16 << 20;

struct Options {
    // The memory the run may use; the number of slabs follows from it (TILE_BYTES_PER_POINT).
    uint64_t max_memory_bytes = 0;
    // The number of slabs asked instead, when not 0 (tests; fewer run where slabs would be too thin).
    uint32_t tiles = 0;
    // The pieces' parameters; its progress callback hears the run's steps (files read as validation, slabs
    // as growing, walls as hole filling, orientation and output as output) and may cancel between them or
    // within a slab or a stitch (the passes over the file finish first); snapshots are not taken.
    dbrg_params params;
};

struct Report {
    uint64_t points = 0;
    uint64_t triangles = 0;
    uint64_t boundary_edges = 0;
    uint64_t components = 0;  // counted before faces are left out where pieces cannot be turned to agree
    uint32_t tiles = 0;            // slabs run
    size_t tile_peak_bytes = 0;    // the most one tile or one stitch held through the library's allocator
    uint64_t orientation_conflicts = 0;  // edges whose two faces could not be turned to agree (a face left out)
    uint64_t seam_faces_dropped = 0;     // faces left out so that the mesh is an oriented manifold
    double spacing = 0;
};

// Reconstructs the points of `input` (.ply or .xyz/.pts) into `output` (binary .ply: every input point a
// vertex, in input order; no normals or other properties). Temporary files go to a folder beside the
// output, removed on success and on failure; the output appears only when complete. Messages name the
// file, the tile or the wall.
io::IoStatus reconstruct_file(const std::string& input, const std::string& output, const Options& options,
                              Report& report);

// The number of slabs for `count` points within `max_memory_bytes`, each slab holding its share of the
// points and a halo of `halo_share` of them (twice the halo over the box's length along the slabs' axis,
// as for points spread evenly along it); 0 when no number of slabs fits.
uint32_t tiles_for_budget(uint64_t count, uint64_t max_memory_bytes, double halo_share);

} // namespace dbrg::out_of_core
