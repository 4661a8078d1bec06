// Pipeline: runs the stages of one call in order — read points, condition, tetrahedralize, grow, fill
// holes — and hands the results over in the caller's point indexing.
#pragma once

#include "core/array.h"
#include "core/context.h"
#include "surface_output.h"

namespace dbrg {

class RegionGrower;
class Surface;
class Tetrahedralization;

struct TetrahedraResult {
    explicit TetrahedraResult(Memory& memory) : tets(memory), adjacency(memory) {}
    Array<uint32_t> tets;       // 4 per finite tetrahedron, caller's indices
    Array<uint32_t> adjacency;  // 4 per finite tetrahedron, DBRG_NO_NEIGHBOR on the hull
    uint32_t unique_points = 0;
};

// Reconstructs the surface; the result's arrays are allocated from their own Memory, the working data
// from the context's. Fills context.stats.
dbrg_status reconstruct_surface(const dbrg_points* points, Context& context, SurfaceResult& result);

// Grows the surface from a given partial one (RegionGrower::grow_from) on the Delaunay tetrahedralization
// of the points, then fills holes as fill_holes does but for the handle cut (a strip is open), with the
// loops through a fixed vertex left alone (HoleFiller::keep_fixed), and flips the deferred edges. `seeds` holds 3 caller indices per face; `fixed` (NULL: none) a flag per caller point
// that no new face may use. The result holds the whole surface, the seeds that fitted included. Points all
// in one plane are refused (DBRG_ERR_DEGENERATE_INPUT). Fills context.stats.
dbrg_status grow_from_surface(const dbrg_points* points, const uint32_t* seeds, size_t seed_count,
                              const uint8_t* fixed, Context& context, SurfaceResult& result);

// Tetrahedralizes the points with context.params.backend.
dbrg_status tetrahedralize_points(const dbrg_points* points, Context& context, TetrahedraResult& result);

// The hole-filling stage of reconstruct_surface, on S as `grower` left it: Delaunay triangles over the holes
// (RegionGrower::regrow_holes), then ears (HoleFiller), small handles removed, and last the flips growing
// deferred (RegionGrower::flip_deferred), each reporting in its share of DBRG_STAGE_FILL_HOLES's progress
// (FILL_PROGRESS_* in holes/hole_filling.h). Fills the hole and handle fields of context.stats.
dbrg_status fill_holes(const Tetrahedralization& delaunay, Surface& surface, RegionGrower& grower, Context& context);

} // namespace dbrg
