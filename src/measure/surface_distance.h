// How far one triangle mesh's surface strays from another's: the distance from points spread over the
// first mesh's triangles to the nearest point of the second mesh's triangles.
//
// Each triangle is sampled at its corners, its edges' midpoints and its centroid (7 points), so a
// triangle that bridges across a gap or covers an opening shows up, and so does an uncovered part of the
// other surface when measured the other way. Distances are Euclidean, in the meshes' own units.
#pragma once

#include <cstdint>
#include <optional>

#include "io/mesh_io.h"

namespace dbrg::measure {

// Meshes come as the readers give them.
using io::IoStatus;
using io::MeshData;

struct SurfaceDistance {
    double max = 0;
    double mean = 0;         // over the sample points
    uint64_t samples = 0;
};

// The distance from `from`'s surface to `to`'s. Triangles with a repeated corner or a non-finite
// coordinate take no part. nullopt when either mesh has no other triangle, when a distance is too large
// for a double, or when the search takes too long: more than 2,048 box or triangle visits per sample point
// (after a first million), where surfaces close together take 25-45, surfaces hundreds of sides apart up
// to about 1,200, and only triangles piled onto each other by the thousand come near it.
// The arrays must be well formed (indices below the vertex count).
std::optional<SurfaceDistance> surface_distance(const MeshData& from, const MeshData& to);

} // namespace dbrg::measure
