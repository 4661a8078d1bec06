// splitmix64 (Steele, Lea and Flood, 2014): a tiny, well-mixed generator whose sequence is the same on
// every platform, for the library's fixed shuffles and for generated test and benchmark data.
#pragma once

#include <stdint.h>

namespace dbrg {

class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}

    uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

    // Uniform in [0, 1): a multiple of 2^-53.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }

private:
    uint64_t state_;
};

} // namespace dbrg
