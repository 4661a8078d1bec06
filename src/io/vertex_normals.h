// Per-vertex normals of an oriented triangle mesh, written with it for viewers that shade smoothly.
#pragma once

#include <cstdint>
#include <vector>

namespace dbrg::io {

// Unit normals, three floats per vertex of `positions` (x, y, z per vertex): the sum of the unit normals
// of the triangles around each vertex, each weighted by the triangle's angle at that vertex, normalized.
// Angle weights make the normal independent of how a region is cut into triangles (a fan of thin
// triangles does not outvote one wide one). A triangle's normal is the side from which its corners turn
// counter-clockwise: outward on dbrg's closed surfaces. Degenerate triangles count for nothing; a vertex
// no triangle uses, or whose triangles' normals cancel, gets (0, 0, 0). Indices must be in range.
std::vector<float> vertex_normals(const std::vector<double>& positions, const std::vector<uint32_t>& triangles);

} // namespace dbrg::io
