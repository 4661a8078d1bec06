// The per-format readers and writers behind mesh_io.h, and the small helpers they share.
//
// Readers pull their bytes from a ByteSource as they parse, fill an empty MeshData and return a status
// whose message says where the problem is (line or byte offset). They give the same results and messages
// whether the source holds the whole input or delivers it in pieces, except that counts in a header can
// only be checked against the input's size when that is known. Writers are handed a mesh whose indices
// are in range.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "io/byte_source.h"
#include "io/mesh_io.h"

namespace dbrg::io {

// Reads `source` as `format`, as read_mesh_buffer does (exceptions become statuses; on failure `out` is
// left empty).
IoStatus read_mesh_source(ByteSource& source, MeshFormat format, MeshData& out);

IoStatus read_ply(ByteSource& source, MeshData& out);
IoStatus read_obj(ByteSource& source, MeshData& out);
IoStatus read_off(ByteSource& source, MeshData& out);
IoStatus read_xyz(ByteSource& source, MeshData& out);
IoStatus read_stl(ByteSource& source, MeshData& out);
IoStatus read_las(ByteSource& source, MeshData& out);

// The points of a file a batch at a time, for clouds larger than memory (point_reader.h).
class PointParser {
public:
    virtual ~PointParser() = default;
    // Stores up to `capacity` points (x, y, z each) in `xyz` and their number in `count`, 0 once the
    // points are over; a failure's message says where it is, as the readers' do.
    virtual IoStatus read(double* xyz, size_t capacity, size_t& count) = 0;
    // The place of the last point read, in the words of the messages.
    virtual std::string place() const = 0;
    // The number of points, when the file declares it (a PLY header).
    virtual std::optional<uint64_t> declared_count() const { return std::nullopt; }
};

// The PLY vertex element's x, y, z (any encoding; everything else is read past); parses the header first.
IoStatus ply_points(ByteSource& source, std::unique_ptr<PointParser>& out);
// The points of XYZ/PTS lines.
std::unique_ptr<PointParser> xyz_points(ByteSource& source);

void write_ply(const MeshData& mesh, bool binary, std::string& out);
void write_obj(const MeshData& mesh, std::string& out);
void write_off(const MeshData& mesh, std::string& out);
void write_xyz(const MeshData& mesh, std::string& out);
void write_stl(const MeshData& mesh, std::string& out);

// The places readers name in their messages and in MeshData::non_finite_at.
inline std::string line_place(uint64_t line) { return "line " + std::to_string(line); }
inline std::string byte_place(uint64_t offset) { return "byte offset " + std::to_string(offset); }

// Records in out.non_finite_at where the input's first non-finite vertex coordinate is. `place()` names
// the place of `value` and is called for that one value only, so a finite value costs a single test.
template <class Place>
void note_non_finite(MeshData& out, double value, const Place& place) {
    if (!std::isfinite(value) && out.non_finite_at.empty()) out.non_finite_at = place();
}


// Appends `count` values separated by blanks, each as the shortest decimal text that reads back as exactly
// it (a float's own shortest text for a float; locale-independent).
template <class Number>
void append_values(std::string& out, const Number* values, size_t count) {
    for (size_t k = 0; k < count; ++k) {
        if (k > 0) out.push_back(' ');
        char text[32];
        const auto result = std::to_chars(text, text + sizeof text, values[k]);
        out.append(text, result.ptr);
    }
}

// A number as append_values writes it, for messages.
inline std::string value_text(double value) {
    std::string text;
    append_values(text, &value, 1);
    return text;
}

// The PLY name of a value type, as the writer declares it.
inline const char* ply_type_name(ValueType type) {
    switch (type) {
    case ValueType::int8: return "char";
    case ValueType::uint8: return "uchar";
    case ValueType::int16: return "short";
    case ValueType::uint16: return "ushort";
    case ValueType::int32: return "int";
    case ValueType::uint32: return "uint";
    case ValueType::float32: return "float";
    case ValueType::float64: return "double";
    }
    return "double";
}

inline void append_unsigned(std::string& out, uint64_t value) {
    char text[24];
    const auto result = std::to_chars(text, text + sizeof text, value);
    out.append(text, result.ptr);
}


// The faces of OFF and ascii PLY: a line "3 a b c" per triangle.
inline void append_triangle_lines(std::string& out, const MeshData& mesh) {
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        out += "3";
        for (size_t k = 0; k < 3; ++k) {
            out.push_back(' ');
            append_unsigned(out, mesh.triangles[3 * t + k]);
        }
        out.push_back('\n');
    }
}

// Appends the triangles of a polygon fanned around its first corner.
inline void append_fan(std::vector<uint32_t>& triangles, const uint32_t* corners, size_t count) {
    for (size_t i = 2; i < count; ++i) {
        triangles.push_back(corners[0]);
        triangles.push_back(corners[i - 1]);
        triangles.push_back(corners[i]);
    }
}

} // namespace dbrg::io
