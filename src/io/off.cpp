// Object File Format (OFF, with the C/N/ST variants' extra columns ignored) reader and writer.
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "io/formats.h"
#include "io/text_scan.h"

namespace dbrg::io {
namespace {

IoStatus line_error(size_t line, const std::string& what) {
    return IoStatus::failure("OFF " + line_place(line) + ": " + what);
}

// The failure of a text that stopped where more was due: at its end, or at a line the reader refused.
IoStatus ended(const LineReader& lines, const std::string& at_end) {
    return line_error(lines.line_number(), lines.stop_reason(at_end));
}

// OFF, COFF, NOFF, CNOFF, STOFF, STCNOFF...: per-vertex colours, normals and texture
// coordinates only add columns after x y z, which the reader ignores. 4OFF and nOFF change the dimension.
bool is_three_dimensional_off_keyword(std::string_view word) {
    if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
    std::string_view prefix = word.substr(0, word.size() - 3);
    if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
    if (!prefix.empty() && prefix.front() == 'C') prefix.remove_prefix(1);
    if (!prefix.empty() && prefix.front() == 'N') prefix.remove_prefix(1);
    return prefix.empty();
}

// Hands out the non-blank lines with comments removed.
bool next_content_line(LineReader& lines, TokenSplitter& tokens) {
    std::string_view line;
    while (lines.next(line)) {
        line = strip_blanks(strip_comment(line));
        if (!line.empty()) {
            tokens = TokenSplitter(line);
            return true;
        }
    }
    return false;
}

bool read_count(TokenSplitter& tokens, int64_t& count) {
    std::string_view word;
    return tokens.next(word) && parse_int64(word, count) && count >= 0;
}

} // namespace

IoStatus read_off(ByteSource& source, MeshData& out) {
    LineReader lines(source);
    TokenSplitter tokens{std::string_view()};
    std::string_view word;
    if (!next_content_line(lines, tokens) || !tokens.next(word)) return ended(lines, "the file is empty");
    if (!is_three_dimensional_off_keyword(word)) {
        return line_error(lines.line_number(), "expected the keyword 'OFF', found " + quote_token(word));
    }
    // The counts may share the keyword's line.
    TokenSplitter rest = tokens;
    if (rest.next(word)) {
        if (word == "BINARY") return line_error(lines.line_number(), "binary OFF is not supported");
    } else if (!next_content_line(lines, tokens)) {
        return ended(lines, "the file ends before the vertex and face counts");
    }
    int64_t vertex_count = 0, face_count = 0;
    if (!read_count(tokens, vertex_count) || !read_count(tokens, face_count)) {
        return line_error(lines.line_number(), "expected the vertex and face counts as non-negative integers");
    }
    if (vertex_count >= std::numeric_limits<uint32_t>::max()) {
        return line_error(lines.line_number(), "the header declares " + std::to_string(vertex_count) + " vertices; at most 4294967294 are supported");
    }
    out.has_faces = true;
    // A vertex line takes at least six bytes ("0 0 0\n"): cap the reservation by what the text can hold,
    // and leave it to the vertices read when that is unknown.
    const uint64_t room = source.bytes_left().value_or(0) / 6;
    out.positions.reserve(3 * static_cast<size_t>(std::min<uint64_t>(static_cast<uint64_t>(vertex_count), room)));
    for (int64_t v = 0; v < vertex_count; ++v) {
        if (!next_content_line(lines, tokens)) {
            return ended(lines, "the file ends after " + std::to_string(v) + " of " + std::to_string(vertex_count) + " vertices");
        }
        for (size_t k = 0; k < 3; ++k) {
            double value = 0.0;
            if (!tokens.next(word)) return line_error(lines.line_number(), "a vertex line needs three coordinates");
            if (!parse_double(word, value)) return line_error(lines.line_number(), "expected a coordinate, found " + quote_token(word));
            note_non_finite(out, value, [&] { return line_place(lines.line_number()); });
            out.positions.push_back(value);
        }
    }
    std::vector<uint32_t> corners;
    for (int64_t f = 0; f < face_count; ++f) {
        if (!next_content_line(lines, tokens)) {
            return ended(lines, "the file ends after " + std::to_string(f) + " of " + std::to_string(face_count) + " faces");
        }
        int64_t corner_count = 0;
        if (!read_count(tokens, corner_count)) return line_error(lines.line_number(), "expected the number of corners of a face");
        if (corner_count < 3) {
            return line_error(lines.line_number(), "a face with " + std::to_string(corner_count) + " corners; a face needs at least 3");
        }
        corners.clear();
        // Colour columns may follow the indices; only the declared number of corners is read.
        for (int64_t k = 0; k < corner_count; ++k) {
            int64_t index = 0;
            if (!tokens.next(word)) {
                return line_error(lines.line_number(), "the face declares " + std::to_string(corner_count) + " corners but lists " + std::to_string(k));
            }
            if (!parse_int64(word, index)) return line_error(lines.line_number(), "expected a vertex index, found " + quote_token(word));
            if (index < 0 || index >= vertex_count) {
                return line_error(lines.line_number(), "vertex index " + std::to_string(index) + " is out of range (the file has " +
                                                           std::to_string(vertex_count) + " vertices)");
            }
            corners.push_back(static_cast<uint32_t>(index));
        }
        append_fan(out.triangles, corners.data(), corners.size());
    }
    return IoStatus::success();
}

void write_off(const MeshData& mesh, std::string& out) {
    out = "OFF\n";
    append_unsigned(out, mesh.vertex_count());
    out.push_back(' ');
    append_unsigned(out, mesh.triangle_count());
    out += " 0\n";
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        append_values(out, &mesh.positions[3 * v], 3);
        out.push_back('\n');
    }
    append_triangle_lines(out, mesh);
}

} // namespace dbrg::io
