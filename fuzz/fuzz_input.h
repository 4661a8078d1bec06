// The fuzzers' byte reader: draws integers, choices and doubles from the input, front to back. Once the
// bytes run out every draw returns zeros, so any input, even an empty one, is a valid test case.
#pragma once

#include <stddef.h>
#include <stdint.h>
#include <string.h>

namespace dbrg::fuzz {

class FuzzInput {
public:
    FuzzInput(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    size_t remaining() const { return size_; }

    uint8_t byte() {
        if (size_ == 0) return 0;
        --size_;
        return *data_++;
    }

    uint32_t u32() {
        uint32_t value = 0;
        for (int i = 0; i < 4; ++i) value = value << 8 | byte();
        return value;
    }

    // A value in [0, n); n > 0. Uses one byte when n fits in one, four otherwise.
    uint32_t below(uint32_t n) { return n <= 256 ? byte() % n : u32() % n; }

    bool flag() { return byte() & 1; }

    // Eight bytes taken as the bits of a double: every value, NaN payloads and subnormals included.
    double raw_double() {
        uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) bits = bits << 8 | byte();
        double value;
        memcpy(&value, &bits, sizeof value);
        return value;
    }

    // One of the given values.
    template <class T, size_t N>
    const T& pick(const T (&options)[N]) {
        return options[below(static_cast<uint32_t>(N))];
    }

private:
    const uint8_t* data_;
    size_t size_;
};

} // namespace dbrg::fuzz
