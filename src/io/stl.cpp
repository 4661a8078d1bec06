// STL reader (binary and ascii; corners with identical coordinates become one vertex) and binary writer.
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>

#include "io/formats.h"
#include "io/text_scan.h"

namespace dbrg::io {
namespace {

const size_t STL_HEADER_BYTES = 80;
const size_t STL_PREAMBLE_BYTES = 84;  // header + uint32 triangle count
const size_t STL_TRIANGLE_BYTES = 50;  // normal, three corners (float32 each), uint16 attribute

struct CornerKey {
    uint64_t bits[3];
    bool operator==(const CornerKey& other) const {
        return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
    }
};

struct CornerKeyHash {
    size_t operator()(const CornerKey& key) const {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (uint64_t b : key.bits) h = (h ^ b) * 0xbf58476d1ce4e5b9ull;
        return static_cast<size_t>(h ^ (h >> 31));
    }
};

// STL repeats each corner in every triangle that uses it; equal coordinates are joined into one vertex.
class VertexMerger {
public:
    explicit VertexMerger(MeshData& out) : out_(out) {}

    void reserve(size_t corners) { index_.reserve(corners); }
    bool add(const double xyz[3]) {
        CornerKey key;
        for (size_t k = 0; k < 3; ++k) {
            const double value = xyz[k] == 0.0 ? 0.0 : xyz[k];  // -0 and +0 are the same place
            std::memcpy(&key.bits[k], &value, sizeof value);
        }
        const auto inserted = index_.emplace(key, static_cast<uint32_t>(out_.vertex_count()));
        if (inserted.second) {
            if (out_.vertex_count() >= std::numeric_limits<uint32_t>::max() - 1) return false;
            out_.positions.insert(out_.positions.end(), xyz, xyz + 3);
        }
        out_.triangles.push_back(inserted.first->second);
        return true;
    }

private:
    MeshData& out_;
    std::unordered_map<CornerKey, uint32_t, CornerKeyHash> index_;
};

float load_float32_le(const unsigned char* bytes) {
    const uint32_t bits = uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24;
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

uint64_t declared_triangles(std::string_view preamble) {
    const unsigned char* data = reinterpret_cast<const unsigned char*>(preamble.data());
    return uint64_t(data[80]) | uint64_t(data[81]) << 8 | uint64_t(data[82]) << 16 | uint64_t(data[83]) << 24;
}

IoStatus read_binary_stl(ByteSource& source, MeshData& out) {
    if (!source.ensure(STL_PREAMBLE_BYTES)) {
        return IoStatus::failure("STL byte offset 0: " + std::to_string(source.window().size()) + " bytes is too short for a binary STL (84 at least)");
    }
    const uint64_t count = declared_triangles(source.window());
    source.consume(STL_PREAMBLE_BYTES);
    // Only a known size can expose a lying count at once; otherwise the triangles run out as they are read.
    const std::optional<uint64_t> left = source.bytes_left();
    if (left && count > *left / STL_TRIANGLE_BYTES) {
        return IoStatus::failure("STL byte offset 80: the header declares " + std::to_string(count) + " triangles, but the file holds only " +
                                 std::to_string(*left / STL_TRIANGLE_BYTES));
    }
    out.has_faces = true;
    VertexMerger merger(out);
    if (left) {
        out.triangles.reserve(3 * count);
        merger.reserve(3 * count);
    }
    for (uint64_t t = 0; t < count; ++t) {
        if (!source.ensure(STL_TRIANGLE_BYTES)) {
            return IoStatus::failure("STL " + byte_place(source.offset()) + ": the file ends after " + std::to_string(t) + " of " +
                                     std::to_string(count) + " triangles");
        }
        // The corners follow the facet normal, which is not judged.
        const unsigned char* corner = reinterpret_cast<const unsigned char*>(source.window().data()) + 12;
        uint64_t corner_offset = source.offset() + 12;
        for (size_t k = 0; k < 3; ++k, corner += 12, corner_offset += 12) {
            const double xyz[3] = {load_float32_le(corner), load_float32_le(corner + 4), load_float32_le(corner + 8)};
            for (size_t axis = 0; axis < 3; ++axis) {
                note_non_finite(out, xyz[axis], [&] { return byte_place(corner_offset + 4 * axis); });
            }
            if (!merger.add(xyz)) return IoStatus::failure("STL: more than 4294967294 distinct vertices");
        }
        source.consume(STL_TRIANGLE_BYTES);
    }
    return IoStatus::success();
}

IoStatus read_ascii_stl(ByteSource& source, MeshData& out) {
    auto fail = [](size_t line, const std::string& what) { return IoStatus::failure("STL " + line_place(line) + ": " + what); };
    LineReader lines(source);
    std::string_view line, word;
    VertexMerger merger(out);
    size_t corners_in_facet = 0;
    bool in_facet = false;
    out.has_faces = true;
    while (lines.next(line)) {
        TokenSplitter tokens(line);
        if (!tokens.next(word)) continue;
        if (word == "facet") {
            if (in_facet) return fail(lines.line_number(), "'facet' inside a facet");
            in_facet = true;
            corners_in_facet = 0;
        } else if (word == "vertex") {
            if (!in_facet) return fail(lines.line_number(), "'vertex' outside a facet");
            if (++corners_in_facet > 3) return fail(lines.line_number(), "a facet with more than three vertices");
            double xyz[3];
            for (double& value : xyz) {
                if (!tokens.next(word) || !parse_double(word, value)) return fail(lines.line_number(), "a 'vertex' line needs three coordinates");
                note_non_finite(out, value, [&] { return line_place(lines.line_number()); });
            }
            if (!merger.add(xyz)) return fail(lines.line_number(), "more than 4294967294 distinct vertices");
        } else if (word == "endfacet") {
            if (!in_facet || corners_in_facet != 3) return fail(lines.line_number(), "a facet without exactly three vertices");
            in_facet = false;
        }
    }
    if (lines.failed()) return fail(lines.line_number(), lines.error());
    if (in_facet) return fail(lines.line_number(), "the file ends inside a facet");
    return IoStatus::success();
}

// Ascii STL starts with "solid", but so do many binary files' free-form headers. With the input's size
// known, a binary file's exact size wins. Without it (a pipe), so does a triangle count holding a byte
// that text never holds: a binary file's count has one below 16,777,216 triangles (its top byte is 0).
bool looks_binary(std::string_view start, std::optional<uint64_t> size) {
    if (start.size() < STL_PREAMBLE_BYTES) return strip_blanks(start).substr(0, 5) != "solid";
    if (strip_blanks(start.substr(0, STL_HEADER_BYTES)).substr(0, 5) != "solid") return true;
    if (size) return STL_PREAMBLE_BYTES + declared_triangles(start) * STL_TRIANGLE_BYTES == *size;
    for (size_t i = STL_HEADER_BYTES; i < STL_PREAMBLE_BYTES; ++i) {
        const unsigned char c = static_cast<unsigned char>(start[i]);
        if (c < 0x20 && !(c >= '\t' && c <= '\r')) return true;
    }
    return false;
}

void append_float32_le(std::string& out, double value) {
    const float narrow = static_cast<float>(value);
    uint32_t bits;
    std::memcpy(&bits, &narrow, sizeof bits);
    for (size_t i = 0; i < 4; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

} // namespace

IoStatus read_stl(ByteSource& source, MeshData& out) {
    source.ensure(STL_PREAMBLE_BYTES);  // or all of a shorter input
    return looks_binary(source.window(), source.bytes_left()) ? read_binary_stl(source, out) : read_ascii_stl(source, out);
}

void write_stl(const MeshData& mesh, std::string& out) {
    // The header must not begin with "solid", or readers may take the file for ascii STL.
    out.assign(STL_HEADER_BYTES, ' ');
    const std::string title = "binary STL written by dbrg";
    out.replace(0, title.size(), title);
    const uint32_t count = static_cast<uint32_t>(mesh.triangle_count());
    for (size_t i = 0; i < 4; ++i) out.push_back(static_cast<char>((count >> (8 * i)) & 0xff));
    out.reserve(STL_PREAMBLE_BYTES + STL_TRIANGLE_BYTES * mesh.triangle_count());
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const double* p[3];
        for (size_t k = 0; k < 3; ++k) p[k] = &mesh.positions[3 * size_t(mesh.triangles[3 * t + k])];
        const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double normal[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        for (double& n : normal) n = length > 0.0 ? n / length : 0.0;
        for (double n : normal) append_float32_le(out, n);
        for (size_t k = 0; k < 3; ++k) {
            for (size_t axis = 0; axis < 3; ++axis) append_float32_le(out, p[k][axis]);
        }
        out.append(2, '\0');  // attribute byte count
    }
}

} // namespace dbrg::io
