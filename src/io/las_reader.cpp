// LAS reader: the point records of ASPRS LAS 1.0 to 1.4, point data record formats 0 to 10, uncompressed.
//
// Based on: ASPRS, "LAS Specification 1.4 - R15" (2019): the public header block and the point data
// record formats. A position is a record's integer X, Y, Z times the header's scale factor plus its offset;
// intensity and, in the formats with colour (2, 3, 5, 7, 8, 10), red, green and blue become uint16 vertex
// properties. The rest of a record (returns, classification, GPS time, waveforms), the variable length
// records and whatever follows the points are read past. The header's sizes, offset and point count are
// checked against the record format and the input's size before anything is reserved.
#include <cstring>
#include <limits>
#include <string>

#include "io/formats.h"

namespace dbrg::io {
namespace {

// Where the public header block's fields are, in bytes from the start of the file.
const size_t VERSION_MAJOR_AT = 24;
const size_t VERSION_MINOR_AT = 25;
const size_t HEADER_SIZE_AT = 94;
const size_t POINT_DATA_OFFSET_AT = 96;
const size_t RECORD_FORMAT_AT = 104;
const size_t RECORD_LENGTH_AT = 105;
const size_t LEGACY_POINT_COUNT_AT = 107;
const size_t SCALE_AT = 131;   // x, y, z as doubles
const size_t OFFSET_AT = 155;  // x, y, z as doubles
const size_t POINT_COUNT_AT = 247;  // LAS 1.4: the 64-bit count

// The public header block's size: 1.0 to 1.2, then 1.3 (adds the waveform data's start), then 1.4 (adds
// the extended records and the 64-bit counts).
size_t header_size_of_version(unsigned minor) { return minor <= 2 ? 227 : minor == 3 ? 235 : 375; }

// LASzip marks a compressed file by setting this bit of the record format.
const uint8_t COMPRESSED_BIT = 0x80;

// Where a record's values are, in bytes from its start.
const size_t INTENSITY_AT = 12;
const size_t NO_COLOUR = 0;

struct RecordLayout {
    size_t length;     // the format's record length; a file's records may be longer (extra bytes)
    size_t colour_at;  // red, green, blue as uint16, or NO_COLOUR
};

// By format: 0 and 1 (GPS time), 2 and 3 (colour), 4 and 5 (waveform packets), then the 1.4 formats 6 to
// 10 with their wider return and scan angle fields (7 colour, 8 colour and near infrared, 9 and 10 waveform).
const RecordLayout RECORD_LAYOUTS[] = {
    {20, NO_COLOUR}, {28, NO_COLOUR}, {26, 20}, {34, 28}, {57, NO_COLOUR}, {63, 28},
    {30, NO_COLOUR}, {36, 30},        {38, 30}, {59, NO_COLOUR}, {67, 30},
};
const unsigned LAST_RECORD_FORMAT = 10;

uint64_t load_unsigned(const char* at, size_t size) {
    uint64_t bits = 0;
    for (size_t i = 0; i < size; ++i) bits |= uint64_t(static_cast<unsigned char>(at[i])) << (8 * i);
    return bits;
}

int32_t load_int32(const char* at) { return static_cast<int32_t>(static_cast<uint32_t>(load_unsigned(at, 4))); }

double load_double(const char* at) {
    const uint64_t bits = load_unsigned(at, 8);
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

IoStatus header_error(const std::string& what) { return IoStatus::failure("LAS header: " + what); }

struct Header {
    unsigned minor = 0;
    uint64_t header_size = 0;
    uint64_t point_data_offset = 0;
    unsigned record_format = 0;
    uint64_t record_length = 0;
    uint64_t point_count = 0;
    double scale[3] = {1, 1, 1};
    double offset[3] = {0, 0, 0};
};

// Reads and checks the public header block at the start of `source`, leaving the source there.
IoStatus parse_header(ByteSource& source, Header& header) {
    const size_t smallest = header_size_of_version(0);
    if (!source.ensure(4) || std::memcmp(source.window().data(), "LASF", 4) != 0) {
        return header_error("the file does not begin with 'LASF'");
    }
    if (!source.ensure(smallest)) {
        return header_error("the file ends after " + std::to_string(source.window().size()) + " bytes, inside the " +
                            std::to_string(smallest) + "-byte public header block");
    }
    const char* bytes = source.window().data();
    const unsigned major = static_cast<unsigned char>(bytes[VERSION_MAJOR_AT]);
    header.minor = static_cast<unsigned char>(bytes[VERSION_MINOR_AT]);
    if (major != 1 || header.minor > 4) {
        return header_error("version " + std::to_string(major) + "." + std::to_string(header.minor) +
                            " is not supported (1.0 to 1.4 are)");
    }
    const unsigned format_byte = static_cast<unsigned char>(bytes[RECORD_FORMAT_AT]);
    if (format_byte & COMPRESSED_BIT) {
        return header_error("the points are compressed (LAZ); decompress the file first, e.g. with "
                            "'laszip -i FILE.laz -o FILE.las'");
    }
    if (format_byte > LAST_RECORD_FORMAT) {
        return header_error("unknown point data record format " + std::to_string(format_byte) + " (0 to 10 are read)");
    }
    header.record_format = format_byte;
    header.header_size = load_unsigned(bytes + HEADER_SIZE_AT, 2);
    header.point_data_offset = load_unsigned(bytes + POINT_DATA_OFFSET_AT, 4);
    header.record_length = load_unsigned(bytes + RECORD_LENGTH_AT, 2);
    const uint64_t legacy_count = load_unsigned(bytes + LEGACY_POINT_COUNT_AT, 4);
    for (size_t k = 0; k < 3; ++k) {
        header.scale[k] = load_double(bytes + SCALE_AT + 8 * k);
        header.offset[k] = load_double(bytes + OFFSET_AT + 8 * k);
    }

    const size_t version_size = header_size_of_version(header.minor);
    const std::string version = "LAS 1." + std::to_string(header.minor);
    if (header.header_size < version_size) {
        return header_error("header size " + std::to_string(header.header_size) + " is smaller than the " +
                            std::to_string(version_size) + " bytes of a " + version + " header");
    }
    if (!source.ensure(version_size)) {
        return header_error("the file ends after " + std::to_string(source.window().size()) + " bytes, inside the " +
                            std::to_string(version_size) + "-byte " + version + " header");
    }
    header.point_count = legacy_count;
    if (header.minor >= 4) {
        header.point_count = load_unsigned(source.window().data() + POINT_COUNT_AT, 8);
        // A 1.4 file may leave the legacy count 0 (formats 6 to 10, or more points than it can hold).
        if (legacy_count != 0 && legacy_count != header.point_count) {
            return header_error("the legacy point count " + std::to_string(legacy_count) + " differs from the point count " +
                                std::to_string(header.point_count));
        }
    }
    if (header.point_data_offset < header.header_size) {
        return header_error("the offset to point data " + std::to_string(header.point_data_offset) +
                            " lies inside the header (" + std::to_string(header.header_size) + " bytes)");
    }
    const RecordLayout layout = RECORD_LAYOUTS[header.record_format];
    if (header.record_length < layout.length) {
        return header_error("point data record length " + std::to_string(header.record_length) + " is smaller than the " +
                            std::to_string(layout.length) + " bytes of format " + std::to_string(header.record_format));
    }
    // Indices are 32-bit; UINT32_MAX stays free as a sentinel for users of the mesh.
    if (header.point_count >= std::numeric_limits<uint32_t>::max()) {
        return header_error("the file declares " + std::to_string(header.point_count) +
                            " points; at most 4294967294 are supported");
    }
    const char* const axes[3] = {"x", "y", "z"};
    for (size_t k = 0; k < 3; ++k) {
        if (!std::isfinite(header.scale[k]) || header.scale[k] == 0) {
            return header_error(std::string("the ") + axes[k] + " scale factor is not a finite non-zero number");
        }
        if (!std::isfinite(header.offset[k])) return header_error(std::string("the ") + axes[k] + " offset is not finite");
    }
    const std::optional<uint64_t> size = source.bytes_left();
    if (size && header.point_data_offset > *size) {
        return header_error("the offset to point data " + std::to_string(header.point_data_offset) +
                            " is past the end of the file (" + std::to_string(*size) + " bytes)");
    }
    // Both factors are below 2^32 and 2^16: the product cannot overflow.
    if (size && header.point_count * header.record_length > *size - header.point_data_offset) {
        return header_error("the file declares " + std::to_string(header.point_count) + " points of " +
                            std::to_string(header.record_length) + " bytes, more than the " +
                            std::to_string(*size - header.point_data_offset) + " bytes after the offset to point data hold");
    }
    return IoStatus::success();
}

} // namespace

IoStatus read_las(ByteSource& source, MeshData& out) {
    Header header;
    IoStatus status = parse_header(source, header);
    if (!status) return status;
    if (!source.skip(header.point_data_offset)) {
        return header_error("the file ends before the offset to point data " + std::to_string(header.point_data_offset));
    }
    const RecordLayout layout = RECORD_LAYOUTS[header.record_format];
    const bool has_colour = layout.colour_at != NO_COLOUR;
    out.properties.push_back({"intensity", ValueType::uint16, {}});
    if (has_colour) {
        for (const char* channel : {"red", "green", "blue"}) out.properties.push_back({channel, ValueType::uint16, {}});
    }
    // parse_header has bounded the count by the input's size; when that is unknown, the arrays grow with
    // what is read.
    if (source.size_known()) {
        out.positions.reserve(3 * header.point_count);
        for (VertexProperty& property : out.properties) property.bytes.reserve(2 * header.point_count);
    }
    for (uint64_t point = 0; point < header.point_count; ++point) {
        const uint64_t at = source.offset();
        if (!source.ensure(header.record_length)) {
            return IoStatus::failure("LAS " + byte_place(at) + ": the file ends in the middle of point record " +
                                     std::to_string(point) + " (" + std::to_string(header.record_length) +
                                     " bytes expected, " + std::to_string(source.window().size()) + " left)");
        }
        const char* record = source.window().data();
        for (size_t k = 0; k < 3; ++k) {
            const double value = load_int32(record + 4 * k) * header.scale[k] + header.offset[k];
            note_non_finite(out, value, [&] { return byte_place(at + 4 * k); });
            out.positions.push_back(value);
        }
        out.properties[0].append(static_cast<double>(load_unsigned(record + INTENSITY_AT, 2)));
        for (size_t channel = 0; has_colour && channel < 3; ++channel) {
            out.properties[1 + channel].append(static_cast<double>(load_unsigned(record + layout.colour_at + 2 * channel, 2)));
        }
        source.consume(header.record_length);
    }
    return IoStatus::success();
}

} // namespace dbrg::io
