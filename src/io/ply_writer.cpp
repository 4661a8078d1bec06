// PLY writer: binary little-endian or ascii, float32 coordinates when that loses nothing (always for input
// read as float32), else float64; float32 normals when the mesh has them.
#include <cmath>
#include <cstring>

#include "io/formats.h"

namespace dbrg::io {
namespace {

// Whether every coordinate survives a trip through float32 unchanged.
bool float32_is_exact(const std::vector<double>& positions) {
    for (double value : positions) {
        if (!std::isnan(value) && static_cast<double>(static_cast<float>(value)) != value) return false;
    }
    return true;
}

template <class Unsigned>
void append_little_endian(std::string& out, Unsigned bits) {
    for (size_t i = 0; i < sizeof bits; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

void append_binary_float(std::string& out, float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    append_little_endian(out, bits);
}

void append_binary_coordinate(std::string& out, double value, bool as_float) {
    if (as_float) {
        append_binary_float(out, static_cast<float>(value));
    } else {
        uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        append_little_endian(out, bits);
    }
}

// "x y z [nx ny nz]" of vertex v, ending the line.
void append_vertex_line(std::string& out, const MeshData& mesh, size_t v) {
    append_values(out, &mesh.positions[3 * v], 3);
    if (!mesh.normals.empty()) {
        out.push_back(' ');
        append_values(out, &mesh.normals[3 * v], 3);
    }
    out.push_back('\n');
}

} // namespace

void write_ply(const MeshData& mesh, bool binary, std::string& out) {
    const bool as_float = float32_is_exact(mesh.positions);
    const bool write_faces = mesh.has_faces || !mesh.triangles.empty();
    const char* type = as_float ? "float" : "double";
    out = "ply\nformat ";
    out += binary ? "binary_little_endian" : "ascii";
    out += " 1.0\ncomment written by dbrg\nelement vertex ";
    append_unsigned(out, mesh.vertex_count());
    for (const char* axis : {"x", "y", "z"}) out += std::string("\nproperty ") + type + " " + axis;
    const bool write_normals = !mesh.normals.empty();
    if (write_normals) out += "\nproperty float nx\nproperty float ny\nproperty float nz";
    if (write_faces) {
        out += "\nelement face ";
        append_unsigned(out, mesh.triangle_count());
        out += "\nproperty list uchar uint vertex_indices";
    }
    out += "\nend_header\n";

    if (binary) {
        out.reserve(out.size() + mesh.positions.size() * (as_float ? 4 : 8) + mesh.normals.size() * 4 +
                    mesh.triangle_count() * 13);
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            for (size_t k = 0; k < 3; ++k) append_binary_coordinate(out, mesh.positions[3 * v + k], as_float);
            if (write_normals) {
                for (size_t k = 0; k < 3; ++k) append_binary_float(out, mesh.normals[3 * v + k]);
            }
        }
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            out.push_back(3);
            for (size_t k = 0; k < 3; ++k) append_little_endian(out, mesh.triangles[3 * t + k]);
        }
        return;
    }
    for (size_t v = 0; v < mesh.vertex_count(); ++v) append_vertex_line(out, mesh, v);
    append_triangle_lines(out, mesh);
}

} // namespace dbrg::io
