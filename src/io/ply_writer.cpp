// PLY writer: binary little-endian or ascii, float32 coordinates when that loses nothing (always for input
// read as float32), else float64; float32 normals when the mesh has them; then the vertex properties,
// each with its own name and type; the face properties after each face's vertex_indices.
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

bool host_is_little_endian() {
    const uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

// The value of item `item` (a vertex or a triangle) as little-endian bytes (properties hold them in the
// machine's order).
void append_binary_value(std::string& out, const VertexProperty& property, size_t item, bool little_endian_host) {
    const size_t size = value_size(property.type);
    const unsigned char* value = property.bytes.data() + item * size;
    for (size_t i = 0; i < size; ++i) out.push_back(static_cast<char>(value[little_endian_host ? i : size - 1 - i]));
}

// A property's value as text: integers as integers, floats as their shortest exact text.
void append_text_value(std::string& out, const VertexProperty& property, size_t item) {
    const double value = property.value(item);
    if (property.type == ValueType::float32) {
        const float narrow = static_cast<float>(value);
        append_values(out, &narrow, 1);
    } else if (property.type == ValueType::float64) {
        append_values(out, &value, 1);
    } else {
        const int64_t whole = static_cast<int64_t>(value);
        append_values(out, &whole, 1);
    }
}

// "x y z [nx ny nz] [properties]" of vertex v, ending the line.
void append_vertex_line(std::string& out, const MeshData& mesh, size_t v) {
    append_values(out, &mesh.positions[3 * v], 3);
    if (!mesh.normals.empty()) {
        out.push_back(' ');
        append_values(out, &mesh.normals[3 * v], 3);
    }
    for (const VertexProperty& property : mesh.properties) {
        out.push_back(' ');
        append_text_value(out, property, v);
    }
    out.push_back('\n');
}

// "3 a b c [properties]" of triangle t, ending the line.
void append_face_line(std::string& out, const MeshData& mesh, size_t t) {
    out += "3";
    for (size_t k = 0; k < 3; ++k) {
        out.push_back(' ');
        append_unsigned(out, mesh.triangles[3 * t + k]);
    }
    for (const VertexProperty& property : mesh.face_properties) {
        out.push_back(' ');
        append_text_value(out, property, t);
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
    size_t property_bytes = 0;
    for (const VertexProperty& property : mesh.properties) {
        out += std::string("\nproperty ") + ply_type_name(property.type) + " " + property.name;
        property_bytes += value_size(property.type);
    }
    if (write_faces) {
        out += "\nelement face ";
        append_unsigned(out, mesh.triangle_count());
        out += "\nproperty list uchar uint vertex_indices";
        for (const VertexProperty& property : mesh.face_properties) {
            out += std::string("\nproperty ") + ply_type_name(property.type) + " " + property.name;
        }
    }
    out += "\nend_header\n";

    if (binary) {
        out.reserve(out.size() + mesh.positions.size() * (as_float ? 4 : 8) + mesh.normals.size() * 4 +
                    mesh.vertex_count() * property_bytes + mesh.triangle_count() * (13 + mesh.face_properties.size() * 8));
        const bool little_endian_host = host_is_little_endian();
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            for (size_t k = 0; k < 3; ++k) append_binary_coordinate(out, mesh.positions[3 * v + k], as_float);
            if (write_normals) {
                for (size_t k = 0; k < 3; ++k) append_binary_float(out, mesh.normals[3 * v + k]);
            }
            for (const VertexProperty& property : mesh.properties) append_binary_value(out, property, v, little_endian_host);
        }
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            out.push_back(3);
            for (size_t k = 0; k < 3; ++k) append_little_endian(out, mesh.triangles[3 * t + k]);
            for (const VertexProperty& property : mesh.face_properties) append_binary_value(out, property, t, little_endian_host);
        }
        return;
    }
    for (size_t v = 0; v < mesh.vertex_count(); ++v) append_vertex_line(out, mesh, v);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) append_face_line(out, mesh, t);
}

} // namespace dbrg::io
