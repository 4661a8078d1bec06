// The out-of-core loop's manifold check at a seam: which faces near a wall to leave out so that the faces
// there form a manifold, as the tiles' assembly leaves them out in one process (docs/tiles.md, "Out of
// core"). Works on 64-bit ids, on the faces around one wall.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace dbrg::out_of_core {

// A face's three ids, ascending: the order faces are taken in below.
std::array<uint64_t, 3> sorted_corners(const uint64_t* face);

// The faces among `count` triangles of three ids at `faces` to leave out so that no face repeats another,
// no edge with an end in `checked` is used by more than two faces, and the faces around each vertex of
// `checked` form one fan. Every face with a corner in `checked` must be among `faces`: a vertex elsewhere is
// not looked at. Faces are taken in the order of their sorted corners: one that repeats a face taken or
// would be the third on an edge is left out. A vertex whose faces form several fans keeps the largest (of
// equal ones, the one holding the first face in that order) and the others are left out, until no vertex
// has two (a corner not in `checked` is not looked at, even where a face left out splits its fan). Returns the
// indices of the faces left out, ascending.
std::vector<size_t> faces_breaking_manifold(const uint64_t* faces, size_t count,
                                            const std::unordered_set<uint64_t>& checked);

} // namespace dbrg::out_of_core
