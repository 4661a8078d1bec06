// Surface output: S handed over as the caller sees it, in the caller's point indexing: its triangles with
// every closed component turned outward, and its boundary loops.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "points/point_conditioning.h"
#include "surface/surface.h"

namespace dbrg {

struct SurfaceResult {
    explicit SurfaceResult(Memory& memory)
        : triangles(memory), face_flags(memory), loop_offsets(memory), loop_vertices(memory), outliers(memory), smoothed_points(memory) {}
    Array<uint32_t> triangles;      // 3 per triangle, caller's indices
    Array<uint8_t> face_flags;      // 1 per triangle: dbrg_face_flag bits
    Array<uint32_t> loop_offsets;   // loop i is loop_vertices[loop_offsets[i] .. loop_offsets[i + 1])
    Array<uint32_t> loop_vertices;  // caller's indices
    Array<uint32_t> outliers;       // caller's indices, ascending
    Array<double> smoothed_points;  // 3 per caller point when params.output_smoothed asked and points were smoothed
};

// Writes the live faces of S and their flags into `result`, those of closed components whose signed volume is negative
// turned over, and its boundary loops. Fills the output fields of context.stats (triangles, components,
// vertices_used, boundary_edges, boundary_loops).
dbrg_status emit_surface(const Surface& surface, const ConditionedPoints& conditioned, Context& context,
                         SurfaceResult& result);

} // namespace dbrg
