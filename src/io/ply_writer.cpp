// PLY writer: binary little-endian or ascii, float32 coordinates when that loses nothing, else float64.
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

void append_binary_coordinate(std::string& out, double value, bool as_float) {
    if (as_float) {
        const float narrow = static_cast<float>(value);
        uint32_t bits;
        std::memcpy(&bits, &narrow, sizeof bits);
        append_little_endian(out, bits);
    } else {
        uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        append_little_endian(out, bits);
    }
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
    if (write_faces) {
        out += "\nelement face ";
        append_unsigned(out, mesh.triangle_count());
        out += "\nproperty list uchar uint vertex_indices";
    }
    out += "\nend_header\n";

    if (binary) {
        out.reserve(out.size() + mesh.positions.size() * (as_float ? 4 : 8) + mesh.triangle_count() * 13);
        for (double value : mesh.positions) append_binary_coordinate(out, value, as_float);
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            out.push_back(3);
            for (size_t k = 0; k < 3; ++k) append_little_endian(out, mesh.triangles[3 * t + k]);
        }
        return;
    }
    append_vertex_and_triangle_lines(out, mesh);
}

} // namespace dbrg::io
