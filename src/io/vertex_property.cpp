// Per-vertex values of any PLY type, stored at their own size (see VertexProperty in mesh_io.h).
#include <cstring>

#include "io/mesh_io.h"

namespace dbrg::io {
namespace {

template <class Number>
double load(const unsigned char* at) {
    Number value;
    std::memcpy(&value, at, sizeof value);
    return static_cast<double>(value);
}

template <class Number>
void store(std::vector<unsigned char>& bytes, double value) {
    const Number narrow = static_cast<Number>(value);
    const auto* raw = reinterpret_cast<const unsigned char*>(&narrow);
    bytes.insert(bytes.end(), raw, raw + sizeof narrow);
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

void VertexProperty::append(double value) {
    switch (type) {
    case ValueType::int8: return store<int8_t>(bytes, value);
    case ValueType::uint8: return store<uint8_t>(bytes, value);
    case ValueType::int16: return store<int16_t>(bytes, value);
    case ValueType::uint16: return store<uint16_t>(bytes, value);
    case ValueType::int32: return store<int32_t>(bytes, value);
    case ValueType::uint32: return store<uint32_t>(bytes, value);
    case ValueType::float32: return store<float>(bytes, value);
    case ValueType::float64: return store<double>(bytes, value);
    }
}

} // namespace dbrg::io
