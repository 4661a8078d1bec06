// XYZ / PTS point reader (one point per line, blanks or commas between columns) and writer.
#include <limits>
#include <string>

#include "io/formats.h"
#include "io/text_scan.h"

namespace dbrg::io {
namespace {

IoStatus line_error(size_t line, const std::string& what) {
    return IoStatus::failure("XYZ " + line_place(line) + ": " + what);
}

// Comments start with '#' or "//".
std::string_view strip_xyz_comment(std::string_view line) {
    line = strip_comment(line, '#');
    const size_t slashes = line.find("//");
    return slashes == std::string_view::npos ? line : line.substr(0, slashes);
}

} // namespace

IoStatus read_xyz(ByteSource& source, MeshData& out) {
    LineReader lines(source);
    std::string_view line, word;
    bool first_data_line = true;
    while (lines.next(line)) {
        TokenSplitter tokens(strip_xyz_comment(line), true);
        if (!tokens.next(word)) continue;
        // A .pts file may start with the number of points on a line of its own; it is not needed.
        TokenSplitter after_first = tokens;
        std::string_view second;
        int64_t count = 0;
        if (first_data_line && !after_first.next(second) && parse_int64(word, count) && count >= 0) {
            first_data_line = false;
            continue;
        }
        first_data_line = false;
        // Columns past the third (intensity, colour, normal) are ignored.
        for (size_t k = 0; k < 3; ++k) {
            double value = 0.0;
            if (k > 0 && !tokens.next(word)) return line_error(lines.line_number(), "a point needs three coordinates");
            if (!parse_double(word, value)) return line_error(lines.line_number(), "expected a coordinate, found " + quote_token(word));
            note_non_finite(out, value, [&] { return line_place(lines.line_number()); });
            out.positions.push_back(value);
        }
        if (out.vertex_count() >= std::numeric_limits<uint32_t>::max()) {
            return line_error(lines.line_number(), "more than 4294967294 points");
        }
    }
    if (lines.failed()) return line_error(lines.line_number(), lines.error());
    return IoStatus::success();
}

void write_xyz(const MeshData& mesh, std::string& out) {
    out.clear();
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        append_values(out, &mesh.positions[3 * v], 3);
        out.push_back('\n');
    }
}

} // namespace dbrg::io
