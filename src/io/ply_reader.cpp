// PLY reader: ascii, binary little- and big-endian; vertex x/y/z, nx/ny/nz and every other scalar vertex
// property (colours, intensity, confidence, ...), face lists and triangle strips.
//
// The vertex element's other scalar properties become MeshData::properties with their names and types,
// the face element's become MeshData::face_properties (none when the file has tristrips too, whose
// triangles have no values); the rest (lists besides the corners, other elements, tristrips besides
// vertex_indices) is read past and ignored. Counts in the header are checked against the
// bytes that follow before anything is reserved, so a lying header fails at once instead of allocating;
// when the input's size is unknown (a pipe), nothing is reserved for them and the data runs out as it is
// read.
#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include "io/formats.h"
#include "io/text_scan.h"

namespace dbrg::io {
namespace {

struct PlyTypeName {
    const char* name;
    ValueType type;
};

const PlyTypeName PLY_TYPE_NAMES[] = {
    {"char", ValueType::int8},     {"int8", ValueType::int8},       {"uchar", ValueType::uint8},
    {"uint8", ValueType::uint8},   {"short", ValueType::int16},     {"int16", ValueType::int16},
    {"ushort", ValueType::uint16}, {"uint16", ValueType::uint16},   {"int", ValueType::int32},
    {"int32", ValueType::int32},   {"uint", ValueType::uint32},     {"uint32", ValueType::uint32},
    {"float", ValueType::float32}, {"float32", ValueType::float32}, {"double", ValueType::float64},
    {"float64", ValueType::float64},
};

bool find_type(std::string_view name, ValueType& type) {
    for (const PlyTypeName& entry : PLY_TYPE_NAMES) {
        if (name == entry.name) {
            type = entry.type;
            return true;
        }
    }
    return false;
}

bool is_integer(ValueType type) { return type != ValueType::float32 && type != ValueType::float64; }

// What the reader does with a property's values: skip them, fill a vertex value, take them as corner
// indices, or carry them as a vertex or face property.
enum class Role : uint8_t { skip, x, y, z, nx, ny, nz, corners, carry };

// The vertex values a Role from x to nz fills, in that order.
const size_t VERTEX_VALUES = 6;
const char* const VERTEX_VALUE_NAMES[VERTEX_VALUES] = {"x", "y", "z", "nx", "ny", "nz"};

struct Property {
    std::string name;
    ValueType type = ValueType::float32;  // of the value, or of each list item
    bool is_list = false;
    ValueType count_type = ValueType::uint8;
    Role role = Role::skip;
    size_t carried = 0;  // Role::carry: its index in MeshData::properties or face_properties
};

enum class ElementKind : uint8_t { other, vertex, face, tristrips };

struct Element {
    std::string name;
    ElementKind kind = ElementKind::other;
    uint64_t count = 0;
    std::vector<Property> properties;
};

enum class Encoding : uint8_t { ascii, binary_little, binary_big };

// Real headers take a few kilobytes; a bound keeps a hostile one from costing time and memory, and 1 MiB
// still holds some 40,000 property lines.
const size_t MAX_HEADER_BYTES = 1 << 20;

struct Header {
    Encoding encoding = Encoding::ascii;
    std::vector<Element> elements;
    size_t header_lines = 0;  // lines up to and including end_header
    uint64_t vertex_count = 0;  // more than 32 bits only for the points streamed (ply_points)
    size_t vertex_line = 0;     // the line of the vertex element
    bool has_vertex_element = false;
    bool has_normals = false;  // the vertex element has nx, ny and nz
};

IoStatus header_error(size_t line, const std::string& what) {
    return IoStatus::failure("PLY header " + line_place(line) + ": " + what);
}

ElementKind element_kind(std::string_view name) {
    if (name == "vertex") return ElementKind::vertex;
    if (name == "face") return ElementKind::face;
    if (name == "tristrips") return ElementKind::tristrips;
    return ElementKind::other;
}

// Decides what to do with a property from its element and name; rejects the forms the reader can't use.
// `names` holds the names of the element's earlier properties.
IoStatus assign_role(const Element& element, const std::unordered_set<std::string>& names, Property& property, size_t line) {
    const std::string& name = property.name;
    for (size_t k = 0; element.kind == ElementKind::vertex && k < VERTEX_VALUES; ++k) {
        if (name != VERTEX_VALUE_NAMES[k]) continue;
        if (property.is_list) return header_error(line, "vertex property '" + name + "' is a list");
        property.role = static_cast<Role>(static_cast<int>(Role::x) + k);
    }
    const bool corner_name = name == "vertex_indices" || (element.kind == ElementKind::face && name == "vertex_index");
    const bool carried_kind = element.kind == ElementKind::vertex || element.kind == ElementKind::face;
    if (carried_kind && !property.is_list && property.role == Role::skip) property.role = Role::carry;
    if ((element.kind == ElementKind::face || element.kind == ElementKind::tristrips) && corner_name) {
        if (!property.is_list) return header_error(line, "'" + name + "' of element '" + element.name + "' is not a list");
        if (!is_integer(property.type)) return header_error(line, "the vertex indices of '" + element.name + "' are not integers");
        property.role = Role::corners;
    }
    if (names.count(name) != 0) return header_error(line, "element '" + element.name + "' has two properties named " + quote_token(name));
    if (property.is_list && !is_integer(property.count_type)) {
        return header_error(line, "the list count type of property " + quote_token(name) + " is not an integer type");
    }
    return IoStatus::success();
}

IoStatus parse_property(TokenSplitter& tokens, Element& element, std::unordered_set<std::string>& names, size_t line) {
    Property property;
    std::string_view word;
    if (!tokens.next(word)) return header_error(line, "'property' without a type");
    if (word == "list") {
        std::string_view count_type;
        if (!tokens.next(count_type) || !tokens.next(word)) return header_error(line, "'property list' needs a count type and an item type");
        if (!find_type(count_type, property.count_type)) return header_error(line, "unknown type " + quote_token(count_type));
        property.is_list = true;
    }
    if (!find_type(word, property.type)) return header_error(line, "unknown type " + quote_token(word));
    std::string_view name;
    if (!tokens.next(name)) return header_error(line, "a property without a name");
    property.name = std::string(name);
    IoStatus status = assign_role(element, names, property, line);
    if (!status) return status;
    names.insert(property.name);
    element.properties.push_back(std::move(property));
    return IoStatus::success();
}

IoStatus parse_element(TokenSplitter& tokens, Header& header, size_t line) {
    std::string_view name, count_text;
    if (!tokens.next(name) || !tokens.next(count_text)) return header_error(line, "'element' needs a name and a count");
    int64_t count = 0;
    if (!parse_int64(count_text, count) || count < 0) {
        return header_error(line, "the count of element " + quote_token(name) + " is not a non-negative integer: " + quote_token(count_text));
    }
    Element element;
    element.name = std::string(name);
    element.kind = element_kind(name);
    element.count = static_cast<uint64_t>(count);
    if (element.kind == ElementKind::vertex) {
        if (header.has_vertex_element) return header_error(line, "a second 'vertex' element");
        header.has_vertex_element = true;
        header.vertex_count = element.count;
        header.vertex_line = line;
    }
    header.elements.push_back(std::move(element));
    return IoStatus::success();
}

IoStatus parse_header(ByteSource& source, Header& header) {
    const uint64_t start = source.offset();
    LineReader lines(source, MAX_HEADER_BYTES);
    std::string_view line, word;
    if (!lines.next(line) || strip_blanks(line) != "ply") {
        return IoStatus::failure("PLY header line 1: the file does not begin with the line 'ply'");
    }
    bool have_format = false;
    std::unordered_set<std::string> property_names;  // of the latest element: names must differ
    for (;;) {
        if (!lines.next(line)) return header_error(lines.line_number(), lines.stop_reason("the header ends without 'end_header'"));
        const size_t number = lines.line_number();
        if (source.offset() - start > MAX_HEADER_BYTES) {
            return header_error(number, "the header is longer than " + std::to_string(MAX_HEADER_BYTES) + " bytes, the most this reader accepts");
        }
        TokenSplitter tokens(line);
        if (!tokens.next(word)) continue;
        if (word == "comment" || word == "obj_info") continue;
        if (word == "end_header") break;
        if (!have_format && word != "format") return header_error(number, "expected 'format' before " + quote_token(word));
        IoStatus status;
        if (word == "format") {
            std::string_view encoding, version;
            if (have_format) return header_error(number, "a second 'format' line");
            if (!tokens.next(encoding) || !tokens.next(version)) return header_error(number, "'format' needs an encoding and a version");
            if (encoding == "ascii") header.encoding = Encoding::ascii;
            else if (encoding == "binary_little_endian") header.encoding = Encoding::binary_little;
            else if (encoding == "binary_big_endian") header.encoding = Encoding::binary_big;
            else return header_error(number, "unknown format " + quote_token(encoding));
            if (version != "1.0" && version != "1") return header_error(number, "unsupported PLY version " + quote_token(version));
            have_format = true;
        } else if (word == "element") {
            status = parse_element(tokens, header, number);
            property_names.clear();
        } else if (word == "property") {
            if (header.elements.empty()) return header_error(number, "'property' before any 'element'");
            status = parse_property(tokens, header.elements.back(), property_names, number);
        } else {
            return header_error(number, "unknown header keyword " + quote_token(word));
        }
        if (!status) return status;
    }
    if (!have_format) return header_error(lines.line_number(), "no 'format' line before end_header");
    header.header_lines = lines.line_number();
    for (const Element& element : header.elements) {
        auto has_role = [&](Role role) {
            for (const Property& property : element.properties) {
                if (property.role == role) return true;
            }
            return false;
        };
        if (element.kind == ElementKind::vertex && !(has_role(Role::x) && has_role(Role::y) && has_role(Role::z))) {
            return header_error(header.header_lines, "the vertex element lacks an x, y or z property");
        }
        if (element.kind == ElementKind::vertex) header.has_normals = has_role(Role::nx) && has_role(Role::ny) && has_role(Role::nz);
        if (element.kind != ElementKind::vertex && element.kind != ElementKind::other && !has_role(Role::corners)) {
            return header_error(header.header_lines, "element '" + element.name + "' has no vertex_indices list");
        }
    }
    if (!header.has_vertex_element) return header_error(header.header_lines, "the file has no 'vertex' element");
    return IoStatus::success();
}

// Reads values from the binary body, in either byte order. Each read checks the bytes are there.
class BinarySource {
public:
    BinarySource(ByteSource& source, bool big_endian) : source_(source), big_endian_(big_endian) {}

    bool read_number(ValueType type, double& value) {
        if (!take(type)) return false;
        value = decode_number(type);
        return true;
    }
    bool read_integer(ValueType type, int64_t& value) {
        if (!take(type)) return false;
        value = static_cast<int64_t>(decode_number(type));
        return true;
    }
    bool skip(ValueType type) { return take(type); }
    // place() stays at the list's count, or moves to the first item when they run out.
    bool skip_list_items(ValueType type, uint64_t count) {
        const uint64_t start = source_.offset();
        const uint64_t wanted = count * value_size(type);  // a list count has at most 32 bits: no overflow
        if (source_.skip(wanted)) {
            taken_ += wanted;
            return true;
        }
        taken_ = source_.offset() - start;
        return fail_truncated(wanted, taken_);
    }
    // Whether `count` items of at least `min_bytes` each can still follow (always, when the input's size
    // is unknown: the items then run out as they are read).
    bool can_hold(uint64_t count, size_t, size_t min_bytes) const {
        const std::optional<uint64_t> left = source_.bytes_left();
        return min_bytes == 0 || !left || count <= *left / min_bytes;
    }
    uint64_t list_limit(ValueType item_type) const {
        const std::optional<uint64_t> left = source_.bytes_left();
        return left ? *left / value_size(item_type) : std::numeric_limits<uint64_t>::max();
    }
    bool size_known() const { return source_.size_known(); }
    // The offset of the value read last (or of the one that ran out).
    std::string place() const { return byte_place(source_.offset() - taken_); }
    const std::string& error() const { return error_; }

private:
    bool take(ValueType type) {
        const size_t size = value_size(type);
        if (!source_.ensure(size)) {
            taken_ = 0;
            return fail_truncated(size, source_.window().size());
        }
        value_ = reinterpret_cast<const unsigned char*>(source_.window().data());
        source_.consume(size);
        taken_ = size;
        return true;
    }
    bool fail_truncated(uint64_t wanted, uint64_t left) {
        error_ = "the file ends in the middle of the data (" + std::to_string(wanted) + " more bytes expected, " + std::to_string(left) + " left)";
        return false;
    }
    uint64_t load_bits(size_t size) const {
        uint64_t bits = 0;
        for (size_t i = 0; i < size; ++i) bits |= uint64_t(value_[big_endian_ ? size - 1 - i : i]) << (8 * i);
        return bits;
    }
    double decode_number(ValueType type) const {
        const uint64_t bits = load_bits(value_size(type));
        switch (type) {
        case ValueType::int8: return static_cast<int8_t>(static_cast<uint8_t>(bits));
        case ValueType::uint8: return static_cast<uint8_t>(bits);
        case ValueType::int16: return static_cast<int16_t>(static_cast<uint16_t>(bits));
        case ValueType::uint16: return static_cast<uint16_t>(bits);
        case ValueType::int32: return static_cast<int32_t>(static_cast<uint32_t>(bits));
        case ValueType::uint32: return static_cast<uint32_t>(bits);
        case ValueType::float32: {
            const uint32_t narrow = static_cast<uint32_t>(bits);
            float value;
            std::memcpy(&value, &narrow, sizeof value);
            return value;
        }
        case ValueType::float64: {
            double value;
            std::memcpy(&value, &bits, sizeof value);
            return value;
        }
        }
        return 0.0;
    }

    ByteSource& source_;
    bool big_endian_;
    const unsigned char* value_ = nullptr;  // the bytes of the value read last, valid until the next read
    uint64_t taken_ = 0;                    // bytes consumed since that value began
    std::string error_;
};

// Reads values from the ascii body: a stream of tokens, line breaks being mere separators.
class AsciiSource {
public:
    AsciiSource(ByteSource& source, size_t header_lines) : tokens_(source), header_lines_(header_lines) {}

    bool read_number(ValueType, double& value) {
        std::string_view token;
        if (!next(token)) return false;
        if (!parse_double(token, value)) return fail("expected a number, found " + quote_token(token));
        return true;
    }
    bool read_integer(ValueType, int64_t& value) {
        std::string_view token;
        if (!next(token)) return false;
        if (!parse_int64(token, value)) return fail("expected an integer, found " + quote_token(token));
        return true;
    }
    bool skip(ValueType) {
        std::string_view token;
        return next(token);
    }
    bool skip_list_items(ValueType type, uint64_t count) {
        for (uint64_t i = 0; i < count; ++i) {
            if (!skip(type)) return false;
        }
        return true;
    }
    // A token takes at least one byte and all but the last one a separator too. Any count fits an input
    // of unknown size: the tokens then run out as they are read.
    bool can_hold(uint64_t count, size_t min_tokens, size_t) const {
        const std::optional<uint64_t> left = tokens_.bytes_left();
        return min_tokens == 0 || !left || count <= (*left / 2 + 1) / min_tokens;
    }
    uint64_t list_limit(ValueType) const {
        const std::optional<uint64_t> left = tokens_.bytes_left();
        return left ? *left / 2 + 1 : std::numeric_limits<uint64_t>::max();
    }
    bool size_known() const { return tokens_.bytes_left().has_value(); }
    // The line of the value read last (or of the end of the text).
    std::string place() const { return line_place(header_lines_ + tokens_.line_number()); }
    const std::string& error() const { return error_; }

private:
    bool next(std::string_view& token) {
        if (tokens_.next(token)) return true;
        return fail(tokens_.error().empty() ? "the file ends in the middle of the data" : tokens_.error());
    }
    bool fail(std::string message) {
        error_ = std::move(message);
        return false;
    }

    TokenStream tokens_;
    size_t header_lines_;
    std::string error_;
};

// Turns the corner lists of face and tristrips elements into triangles.
class CornerDecoder {
public:
    CornerDecoder(uint32_t vertex_count, std::vector<uint32_t>& triangles)
        : vertex_count_(vertex_count), triangles_(triangles) {}

    void begin(ElementKind kind) {
        kind_ = kind;
        corners_.clear();
    }
    // Takes the next index of the current list; false (with a message) when it is out of range.
    bool add(int64_t index, std::string& error) {
        if (kind_ == ElementKind::tristrips && index == -1) {
            corners_.clear();  // a strip restarts
            return true;
        }
        if (index < 0 || index >= vertex_count_) {
            error = "vertex index " + std::to_string(index) + " is out of range (the file has " +
                    std::to_string(vertex_count_) + " vertices)";
            return false;
        }
        corners_.push_back(static_cast<uint32_t>(index));
        if (kind_ == ElementKind::tristrips && corners_.size() >= 3) emit_strip_triangle();
        return true;
    }
    bool end(std::string& error) {
        if (kind_ == ElementKind::tristrips) return true;
        if (corners_.size() < 3) {
            error = "a face with " + std::to_string(corners_.size()) + " corners; a face needs at least 3";
            return false;
        }
        append_fan(triangles_, corners_.data(), corners_.size());
        return true;
    }

private:
    // Strip triangles alternate orientation; the ones with a repeated corner only join strip pieces.
    void emit_strip_triangle() {
        const size_t n = corners_.size();
        uint32_t a = corners_[n - 3], b = corners_[n - 2];
        const uint32_t c = corners_[n - 1];
        if ((n - 3) % 2 == 1) std::swap(a, b);
        if (a == b || b == c || a == c) return;
        triangles_.insert(triangles_.end(), {a, b, c});
    }

    int64_t vertex_count_;
    std::vector<uint32_t>& triangles_;
    ElementKind kind_ = ElementKind::other;
    std::vector<uint32_t> corners_;
};

// The least a single item of `element` occupies: bytes in a binary body, tokens in an ascii one.
void minimum_item_size(const Element& element, size_t& bytes, size_t& tokens) {
    bytes = 0;
    tokens = element.properties.size();
    for (const Property& property : element.properties) bytes += value_size(property.is_list ? property.count_type : property.type);
}

template <class Source>
IoStatus read_body(const Header& header, Source& source, MeshData& out) {
    auto fail = [&](const std::string& what) { return IoStatus::failure("PLY " + source.place() + ": " + what); };
    CornerDecoder corners(static_cast<uint32_t>(header.vertex_count), out.triangles);
    std::string error;
    std::vector<double> face_values(out.face_properties.size(), 0.0);  // the current face's, by Property::carried
    for (const Element& element : header.elements) {
        const auto carried = [&](const Property& property) -> VertexProperty& {
            return element.kind == ElementKind::vertex ? out.properties[property.carried] : out.face_properties[property.carried];
        };
        const auto not_a = [&](const Property& property, uint64_t item, double value) {
            return fail(element.name + " " + std::to_string(item) + ": property " + quote_token(property.name) + " holds " +
                        value_text(value) + ", not a " + ply_type_name(property.type));
        };
        if (element.properties.empty() || element.count == 0) continue;
        size_t min_bytes = 0, min_tokens = 0;
        minimum_item_size(element, min_bytes, min_tokens);
        if (!source.can_hold(element.count, min_tokens, min_bytes)) {
            return fail("element '" + element.name + "' declares " + std::to_string(element.count) +
                        " items, more than the rest of the file can hold");
        }
        const bool is_vertex = element.kind == ElementKind::vertex;
        // One triangle per face is the common case. can_hold has bounded the count by the input's size;
        // when that is unknown, the arrays grow with what is read.
        const size_t reserved = source.size_known() ? static_cast<size_t>(element.count) : 0;
        if (is_vertex) out.positions.reserve(3 * reserved);
        if (is_vertex && header.has_normals) out.normals.reserve(3 * reserved);
        for (const Property& property : element.properties) {
            if (property.role == Role::carry) carried(property).bytes.reserve(reserved * value_size(property.type));
        }
        if (element.kind == ElementKind::face) out.triangles.reserve(out.triangles.size() + 3 * reserved);
        for (uint64_t item = 0; item < element.count; ++item) {
            double values[VERTEX_VALUES] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // by Role, x to nz
            corners.begin(element.kind);
            for (const Property& property : element.properties) {
                if (!property.is_list) {
                    if (property.role == Role::skip) {
                        if (!source.skip(property.type)) return fail(source.error());
                        continue;
                    }
                    if (property.role == Role::carry) {
                        double value = 0.0;
                        if (!source.read_number(property.type, value)) return fail(source.error());
                        if (is_vertex && !carried(property).append(value)) return not_a(property, item, value);
                        if (!is_vertex) face_values[property.carried] = value;
                        continue;
                    }
                    const size_t slot = static_cast<size_t>(property.role) - static_cast<size_t>(Role::x);
                    if (!source.read_number(property.type, values[slot])) return fail(source.error());
                    if (slot < 3) note_non_finite(out, values[slot], [&] { return source.place(); });
                    continue;
                }
                int64_t count = 0;
                if (!source.read_integer(property.count_type, count)) return fail(source.error());
                if (count < 0) return fail("negative list length " + std::to_string(count));
                if (static_cast<uint64_t>(count) > source.list_limit(property.type)) {
                    return fail("list length " + std::to_string(count) + " is more than the rest of the file can hold");
                }
                if (property.role != Role::corners) {
                    if (!source.skip_list_items(property.type, static_cast<uint64_t>(count))) return fail(source.error());
                    continue;
                }
                for (int64_t i = 0; i < count; ++i) {
                    int64_t index = 0;
                    if (!source.read_integer(property.type, index)) return fail(source.error());
                    if (!corners.add(index, error)) return fail(element.name + " " + std::to_string(item) + ": " + error);
                }
            }
            if (is_vertex) out.positions.insert(out.positions.end(), values, values + 3);
            if (is_vertex && header.has_normals) {
                for (size_t k = 3; k < VERTEX_VALUES; ++k) out.normals.push_back(static_cast<float>(values[k]));
            }
            if (element.kind == ElementKind::face || element.kind == ElementKind::tristrips) {
                const size_t before = out.triangle_count();
                if (!corners.end(error)) return fail(element.name + " " + std::to_string(item) + ": " + error);
                // Each triangle of the face's fan takes the face's values.
                for (const Property& property : element.properties) {
                    if (property.role != Role::carry) continue;
                    for (size_t t = before; t < out.triangle_count(); ++t) {
                        if (!carried(property).append(face_values[property.carried])) {
                            return not_a(property, item, face_values[property.carried]);
                        }
                    }
                }
            }
        }
    }
    return IoStatus::success();
}

// The vertex positions of a PLY body, an item at a time: x, y, z read, everything else read past, and
// the elements before the vertex element read past whole.
template <class Source>
class PlyPoints final : public PointParser {
public:
    template <class... Arguments>
    PlyPoints(Header header, Arguments&&... arguments)
        : header_(std::move(header)), source_(std::forward<Arguments>(arguments)...) {}

    IoStatus read(double* xyz, size_t capacity, size_t& count) override {
        count = 0;
        while (element_ < header_.elements.size()) {
            const Element& element = header_.elements[element_];
            if (item_ == 0 && !element.properties.empty()) {
                size_t min_bytes = 0, min_tokens = 0;
                minimum_item_size(element, min_bytes, min_tokens);
                if (!source_.can_hold(element.count, min_tokens, min_bytes)) {
                    return fail("element '" + element.name + "' declares " + std::to_string(element.count) +
                                " items, more than the rest of the file can hold");
                }
            }
            if (element.properties.empty()) item_ = element.count;
            const bool is_vertex = element.kind == ElementKind::vertex;
            for (; item_ < element.count; ++item_) {
                if (is_vertex && count == capacity) return IoStatus::success();
                double values[3] = {0.0, 0.0, 0.0};
                for (const Property& property : element.properties) {
                    const std::string error = read_value(property, values);
                    if (!error.empty()) return fail(error);
                }
                if (!is_vertex) continue;
                for (size_t k = 0; k < 3; ++k) xyz[3 * count + k] = values[k];
                ++count;
            }
            if (is_vertex) {
                element_ = header_.elements.size();  // the points are over: what follows is not read
                break;
            }
            ++element_;
            item_ = 0;
        }
        return IoStatus::success();
    }
    std::string place() const override { return source_.place(); }
    std::optional<uint64_t> declared_count() const override { return header_.vertex_count; }

private:
    // Reads one value (or list) of an item, keeping x, y and z in `values`; returns what went wrong, or "".
    std::string read_value(const Property& property, double values[3]) {
        bool read = false;
        if (property.is_list) {
            int64_t length = 0;
            if (!source_.read_integer(property.count_type, length)) return source_.error();
            if (length < 0) return "negative list length " + std::to_string(length);
            if (static_cast<uint64_t>(length) > source_.list_limit(property.type)) {
                return "list length " + std::to_string(length) + " is more than the rest of the file can hold";
            }
            read = source_.skip_list_items(property.type, static_cast<uint64_t>(length));
        } else if (property.role == Role::x || property.role == Role::y || property.role == Role::z) {
            const size_t slot = static_cast<size_t>(property.role) - static_cast<size_t>(Role::x);
            read = source_.read_number(property.type, values[slot]);
        } else {
            read = source_.skip(property.type);
        }
        return read ? std::string() : source_.error();
    }
    IoStatus fail(const std::string& what) { return IoStatus::failure("PLY " + source_.place() + ": " + what); }

    Header header_;
    Source source_;
    size_t element_ = 0;
    uint64_t item_ = 0;
};

} // namespace

IoStatus ply_points(ByteSource& source, std::unique_ptr<PointParser>& out) {
    Header header;
    const IoStatus status = parse_header(source, header);
    if (!status) return status;
    if (header.encoding == Encoding::ascii) {
        const size_t header_lines = header.header_lines;
        out = std::make_unique<PlyPoints<AsciiSource>>(std::move(header), source, header_lines);
    } else {
        const bool big_endian = header.encoding == Encoding::binary_big;
        out = std::make_unique<PlyPoints<BinarySource>>(std::move(header), source, big_endian);
    }
    return IoStatus::success();
}

IoStatus read_ply(ByteSource& source, MeshData& out) {
    Header header;
    IoStatus status = parse_header(source, header);
    if (!status) return status;
    // A mesh's indices are 32-bit; UINT32_MAX stays free as a sentinel for users of the mesh.
    if (header.vertex_count >= std::numeric_limits<uint32_t>::max()) {
        return header_error(header.vertex_line, "element vertex declares " + std::to_string(header.vertex_count) +
                                                    " vertices; at most 4294967294 are supported");
    }
    for (Element& element : header.elements) {
        for (Property& property : element.properties) {
            if (property.role != Role::carry) continue;
            std::vector<VertexProperty>& carried = element.kind == ElementKind::vertex ? out.properties : out.face_properties;
            property.carried = carried.size();
            carried.push_back({property.name, property.type, {}});
        }
    }
    for (const Element& element : header.elements) {
        out.has_faces = out.has_faces || element.kind == ElementKind::face || element.kind == ElementKind::tristrips;
    }
    if (header.encoding == Encoding::ascii) {
        AsciiSource body(source, header.header_lines);
        status = read_body(header, body, out);
    } else {
        BinarySource body(source, header.encoding == Encoding::binary_big);
        status = read_body(header, body, out);
    }
    // Triangles from strips have no face values: the values then say nothing about the triangles as a whole.
    const auto per_triangle = [&](const VertexProperty& property) { return property.size() == out.triangle_count(); };
    if (!std::all_of(out.face_properties.begin(), out.face_properties.end(), per_triangle)) out.face_properties.clear();
    return status;
}

} // namespace dbrg::io
