// XYZ / PTS point reader (one point per line, blanks or commas between columns) and writer.
#include <algorithm>
#include <limits>
#include <memory>
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

// The points of an XYZ text, one line at a time.
class XyzPoints final : public PointParser {
public:
    explicit XyzPoints(ByteSource& source) : lines_(source) {}

    IoStatus read(double* xyz, size_t capacity, size_t& count) override {
        count = 0;
        std::string_view line, word;
        while (count < capacity && lines_.next(line)) {
            TokenSplitter tokens(strip_xyz_comment(line), true);
            if (!tokens.next(word)) continue;
            // A .pts file may start with the number of points on a line of its own; it is not needed.
            TokenSplitter after_first = tokens;
            std::string_view second;
            int64_t declared = 0;
            if (first_data_line_ && !after_first.next(second) && parse_int64(word, declared) && declared >= 0) {
                first_data_line_ = false;
                continue;
            }
            first_data_line_ = false;
            // Columns past the third (intensity, colour, normal) are ignored.
            for (size_t k = 0; k < 3; ++k) {
                if (k > 0 && !tokens.next(word)) return line_error(lines_.line_number(), "a point needs three coordinates");
                if (!parse_double(word, xyz[3 * count + k])) {
                    return line_error(lines_.line_number(), "expected a coordinate, found " + quote_token(word));
                }
            }
            ++count;
        }
        if (lines_.failed()) return line_error(lines_.line_number(), lines_.error());
        return IoStatus::success();
    }
    std::string place() const override { return line_place(lines_.line_number()); }

private:
    LineReader lines_;
    bool first_data_line_ = true;
};

} // namespace

std::unique_ptr<PointParser> xyz_points(ByteSource& source) { return std::make_unique<XyzPoints>(source); }

// The shortest line a point of usual precision takes ("-0.123456 0.123456 0.123456"): room for that many
// points is taken at once where the size is known, rather than grown by copies ...
constexpr uint64_t TYPICAL_POINT_BYTES = 28;
// ... but for no more than this many (1.5 GiB): a file of long lines (normals, colours) holds far fewer
// points than that estimate, and room it never needs must not make a readable file fail for memory.
constexpr uint64_t MAX_RESERVED_POINTS = uint64_t(1) << 26;

IoStatus read_xyz(ByteSource& source, MeshData& out) {
    XyzPoints points(source);
    const uint64_t expected = source.bytes_left().value_or(0) / TYPICAL_POINT_BYTES;
    out.positions.reserve(3 * size_t(std::min(expected, MAX_RESERVED_POINTS)));
    for (;;) {
        double xyz[3];
        size_t count = 0;
        const IoStatus status = points.read(xyz, 1, count);
        if (!status || count == 0) return status;
        for (double value : xyz) note_non_finite(out, value, [&] { return points.place(); });
        out.positions.insert(out.positions.end(), xyz, xyz + 3);
        if (out.vertex_count() >= std::numeric_limits<uint32_t>::max()) {
            return IoStatus::failure("XYZ " + points.place() + ": more than 4294967294 points");
        }
    }
}

void write_xyz(const MeshData& mesh, std::string& out) {
    out.clear();
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        append_values(out, &mesh.positions[3 * v], 3);
        out.push_back('\n');
    }
}

} // namespace dbrg::io
