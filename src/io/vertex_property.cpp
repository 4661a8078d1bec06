// Per-vertex values of any PLY type, stored at their own size (see VertexProperty in mesh_io.h).
#include <cmath>
#include <cstring>
#include <limits>

#include "io/mesh_io.h"

namespace dbrg::io {
namespace {

template <class Number>
double load(const unsigned char* at) {
    Number value;
    std::memcpy(&value, at, sizeof value);
    return static_cast<double>(value);
}

// Appends `value` as a Number when it is one: a whole number in the integer type's range.
template <class Number>
bool store(std::vector<unsigned char>& bytes, double value) {
    const bool fits = value >= static_cast<double>(std::numeric_limits<Number>::min()) &&
                      value <= static_cast<double>(std::numeric_limits<Number>::max()) && value == std::trunc(value);
    if (!fits) return false;
    const Number narrow = static_cast<Number>(value);
    const auto* raw = reinterpret_cast<const unsigned char*>(&narrow);
    bytes.insert(bytes.end(), raw, raw + sizeof narrow);
    return true;
}

template <class Float>
bool store_float(std::vector<unsigned char>& bytes, double value) {
    // A double beyond the float's range has no nearest float: it becomes an infinity of its sign.
    const double largest = std::numeric_limits<Float>::max();
    const Float narrow = value > largest ? std::numeric_limits<Float>::infinity()
                         : value < -largest ? -std::numeric_limits<Float>::infinity()
                                            : static_cast<Float>(value);
    const auto* raw = reinterpret_cast<const unsigned char*>(&narrow);
    bytes.insert(bytes.end(), raw, raw + sizeof narrow);
    return true;
}

} // namespace

size_t value_size(ValueType type) {
    switch (type) {
    case ValueType::int8:
    case ValueType::uint8: return 1;
    case ValueType::int16:
    case ValueType::uint16: return 2;
    case ValueType::int32:
    case ValueType::uint32:
    case ValueType::float32: return 4;
    case ValueType::float64: return 8;
    }
    return 8;
}

double VertexProperty::value(size_t vertex) const {
    const unsigned char* at = bytes.data() + vertex * value_size(type);
    switch (type) {
    case ValueType::int8: return load<int8_t>(at);
    case ValueType::uint8: return load<uint8_t>(at);
    case ValueType::int16: return load<int16_t>(at);
    case ValueType::uint16: return load<uint16_t>(at);
    case ValueType::int32: return load<int32_t>(at);
    case ValueType::uint32: return load<uint32_t>(at);
    case ValueType::float32: return load<float>(at);
    case ValueType::float64: return load<double>(at);
    }
    return 0.0;
}

bool VertexProperty::append(double value) {
    switch (type) {
    case ValueType::int8: return store<int8_t>(bytes, value);
    case ValueType::uint8: return store<uint8_t>(bytes, value);
    case ValueType::int16: return store<int16_t>(bytes, value);
    case ValueType::uint16: return store<uint16_t>(bytes, value);
    case ValueType::int32: return store<int32_t>(bytes, value);
    case ValueType::uint32: return store<uint32_t>(bytes, value);
    case ValueType::float32: return store_float<float>(bytes, value);
    case ValueType::float64: return store_float<double>(bytes, value);
    }
    return false;
}

} // namespace dbrg::io
