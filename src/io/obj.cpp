// Wavefront OBJ reader (v and f lines; polygons fanned into triangles) and writer.
#include <limits>
#include <string>
#include <vector>

#include "io/formats.h"
#include "io/text_scan.h"

namespace dbrg::io {
namespace {

IoStatus line_error(size_t line, const std::string& what) {
    return IoStatus::failure("OBJ " + line_place(line) + ": " + what);
}

} // namespace

IoStatus read_obj(ByteSource& source, MeshData& out) {
    LineReader lines(source);
    std::string_view line, word;
    std::vector<uint32_t> corners;
    // OBJ lets a face name a vertex defined further down; those are checked once all vertices are known.
    int64_t largest_forward_index = -1;
    size_t largest_forward_line = 0;
    while (lines.next(line)) {
        TokenSplitter tokens(strip_comment(line));
        if (!tokens.next(word)) continue;
        if (word == "v") {
            double xyz[3];
            for (double& value : xyz) {
                if (!tokens.next(word)) return line_error(lines.line_number(), "a 'v' line needs three coordinates");
                if (!parse_double(word, value)) return line_error(lines.line_number(), "expected a coordinate, found " + quote_token(word));
                note_non_finite(out, value, [&] { return line_place(lines.line_number()); });
            }
            if (out.vertex_count() >= std::numeric_limits<uint32_t>::max() - 1) {
                return line_error(lines.line_number(), "more than 4294967294 vertices");
            }
            out.positions.insert(out.positions.end(), xyz, xyz + 3);
        } else if (word == "f") {
            out.has_faces = true;
            corners.clear();
            const int64_t defined = static_cast<int64_t>(out.vertex_count());
            while (tokens.next(word)) {
                // Only the position index matters: the part before the first '/' of v, v/vt, v//vn, v/vt/vn.
                const std::string_view position_text = word.substr(0, word.find('/'));
                int64_t index = 0;
                if (!parse_int64(position_text, index) || index == 0) {
                    return line_error(lines.line_number(), "expected a vertex index (1-based, or negative), found " + quote_token(word));
                }
                if (index < 0) {
                    // Relative to the vertices defined so far: -1 is the last one.
                    if (index < -defined) {
                        return line_error(lines.line_number(), "relative vertex index " + std::to_string(index) + " reaches before the first vertex (" +
                                                                   std::to_string(defined) + " defined so far)");
                    }
                    index += defined;
                } else {
                    index -= 1;
                    if (index >= std::numeric_limits<uint32_t>::max() - 1) {
                        return line_error(lines.line_number(), "vertex index " + std::string(position_text) + " is too large");
                    }
                    if (index >= defined && index > largest_forward_index) {
                        largest_forward_index = index;
                        largest_forward_line = lines.line_number();
                    }
                }
                corners.push_back(static_cast<uint32_t>(index));
            }
            if (corners.size() < 3) {
                return line_error(lines.line_number(), "a face with " + std::to_string(corners.size()) + " corners; a face needs at least 3");
            }
            append_fan(out.triangles, corners.data(), corners.size());
        }
    }
    if (lines.failed()) return line_error(lines.line_number(), lines.error());
    if (largest_forward_index >= static_cast<int64_t>(out.vertex_count())) {
        return line_error(largest_forward_line, "vertex index " + std::to_string(largest_forward_index + 1) +
                                                    " is out of range (the file has " + std::to_string(out.vertex_count()) + " vertices)");
    }
    return IoStatus::success();
}

void write_obj(const MeshData& mesh, std::string& out) {
    out = "# written by dbrg\n";
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        out += "v ";
        append_values(out, &mesh.positions[3 * v], 3);
        out.push_back('\n');
    }
    // Normal k belongs to vertex k, so a corner names the same number twice: "f a//a b//b c//c".
    const bool with_normals = !mesh.normals.empty();
    for (size_t v = 0; with_normals && v < mesh.vertex_count(); ++v) {
        out += "vn ";
        append_values(out, &mesh.normals[3 * v], 3);
        out.push_back('\n');
    }
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        out += "f";
        for (size_t k = 0; k < 3; ++k) {
            out.push_back(' ');
            const uint64_t index = uint64_t(mesh.triangles[3 * t + k]) + 1;
            append_unsigned(out, index);
            if (with_normals) {
                out += "//";
                append_unsigned(out, index);
            }
        }
        out.push_back('\n');
    }
}

} // namespace dbrg::io
