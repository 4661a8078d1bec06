// Dropping the vertices no triangle uses (the points a reconstruction left out), for files that hold the
// surface only.
#pragma once

#include <cstdint>
#include <vector>

#include "io/mesh_io.h"

namespace dbrg::io {

// The index map's mark for a vertex that was dropped.
constexpr uint32_t DROPPED_VERTEX = UINT32_MAX;

// Keeps the vertices some triangle of `mesh` uses, in their order, with their normals and other vertex
// values, and renumbers the triangles to match. Returns the map from each old vertex index to its new one,
// or DROPPED_VERTEX: old_to_new[mesh_before.triangles[i]] == mesh.triangles[i] for every i. Indices must be
// in range; a mesh without triangles keeps no vertex.
std::vector<uint32_t> drop_unused_vertices(MeshData& mesh);

} // namespace dbrg::io
