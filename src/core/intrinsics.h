// Intrinsics: the few compiler builtins the core uses, behind portable names with plain C++ fallbacks.
#pragma once

#include <stdint.h>

namespace dbrg {

// A hint to the processor that `address` will be read soon; does nothing where the compiler has no hint.
inline void prefetch(const void* address) {
#if defined(__GNUC__)
    __builtin_prefetch(address);
#else
    (void)address;
#endif
}

// The number of zero bits above the highest set bit of x, which must not be 0.
inline int count_leading_zeros(uint64_t x) {
#if defined(__GNUC__)
    return __builtin_clzll(x);
#else
    int zeros = 0;
    for (uint64_t bit = uint64_t(1) << 63; (x & bit) == 0; bit >>= 1) ++zeros;
    return zeros;
#endif
}

} // namespace dbrg
