// Pipeline: runs the stages of one call in order — read points, condition, tetrahedralize, grow, fill
// holes — and hands the results over in the caller's point indexing.
#pragma once

#include "core/array.h"
#include "core/context.h"

namespace dbrg {

struct SurfaceResult {
    explicit SurfaceResult(Memory& memory) : triangles(memory), loop_offsets(memory), loop_vertices(memory) {}
    Array<uint32_t> triangles;      // 3 per triangle, caller's indices
    Array<uint32_t> loop_offsets;   // loop i is loop_vertices[loop_offsets[i] .. loop_offsets[i + 1])
    Array<uint32_t> loop_vertices;  // caller's indices
};

struct TetrahedraResult {
    explicit TetrahedraResult(Memory& memory) : tets(memory), adjacency(memory) {}
    Array<uint32_t> tets;       // 4 per finite tetrahedron, caller's indices
    Array<uint32_t> adjacency;  // 4 per finite tetrahedron, DBRG_NO_NEIGHBOR on the hull
    uint32_t unique_points = 0;
};

// Reconstructs the surface; the result's arrays are allocated from their own Memory, the working data
// from the context's. Fills context.stats.
dbrg_status reconstruct_surface(const dbrg_points* points, Context& context, SurfaceResult& result);

// Tetrahedralizes the points with context.params.backend.
dbrg_status tetrahedralize_points(const dbrg_points* points, Context& context, TetrahedraResult& result);

} // namespace dbrg
