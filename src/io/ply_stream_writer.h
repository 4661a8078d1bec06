// A binary little-endian PLY of points and triangles written as they come, for meshes larger than memory:
// the counts are declared up front (a streaming producer knows them from its earlier passes) and checked
// at the end, and the file appears at its path only once complete (FileWriter's guarantees).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/file_output.h"

namespace dbrg::io {

class PlyStreamWriter {
public:
    struct Layout {
        uint64_t vertex_count = 0;
        uint64_t triangle_count = 0;
        // Coordinates as double; else float (the caller knows whether float loses nothing).
        bool double_coordinates = true;
        // Corner indices as uint64 instead of uint: forced past 2^32 vertices, where 32 bits cannot number
        // them (PLY 1.0's own types stop at 32 bits; readers that know 64-bit types, as plyfile does, take it).
        bool wide_indices = false;
    };

    // Creates the file and writes the header.
    IoStatus open(const std::string& path, const Layout& layout);
    // Appends `count` vertices (x, y, z each), then, once all vertices are in, `count` triangles (3 vertex
    // indices each, below vertex_count). More than declared, a triangle before the last vertex or an index
    // out of range fails.
    IoStatus add_vertices(const double* xyz, size_t count);
    IoStatus add_triangles(const uint64_t* corners, size_t count);
    // Checks that the declared counts were written and puts the file in place.
    IoStatus finish();

private:
    IoStatus refuse(const std::string& what);

    FileWriter file_;
    Layout layout_;
    uint64_t vertices_written_ = 0;
    uint64_t triangles_written_ = 0;
    std::string path_;
    std::string chunk_;  // one call's values, encoded
    IoStatus status_;
};

} // namespace dbrg::io
