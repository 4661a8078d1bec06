// Fixed-width signed integers for the exact stage of the predicates: N 64-bit limbs in two's complement,
// least significant first. Every operation is exact modulo 2^(64 N) and takes the same steps whatever the
// values, with no allocation and no normalisation; the caller picks N so that the true value of every
// operand it multiplies or takes the sign of lies in [-2^(64 N - 1), 2^(64 N - 1)). Sums may wrap on the
// way, since arithmetic modulo 2^(64 N) agrees with the integers once the final value is in range.
// Everything is forced inline: a determinant is a few dozen of these operations on one or two limbs, and
// as calls, with their operands passed through memory, they took most of its time.
#pragma once

#include <stdint.h>
#include <string.h>

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace dbrg {
namespace wide {

template <int N>
struct Int {
    uint64_t limb[N];
};

// The limb operations, portably; the ones below use the target's carry flag and full multiplication
// where they can.
namespace portable {

// a + b + carry, carry (0 or 1) replaced by the carry out.
[[gnu::always_inline]] inline uint64_t add(uint64_t a, uint64_t b, uint64_t& carry) {
    const uint64_t partial = a + b, sum = partial + carry;
    carry = (partial < a) | (sum < partial);
    return sum;
}

// a - b - borrow, borrow (0 or 1) replaced by the borrow out.
[[gnu::always_inline]] inline uint64_t subtract(uint64_t a, uint64_t b, uint64_t& borrow) {
    const uint64_t partial = a - b, difference = partial - borrow;
    borrow = (a < b) | (partial < borrow);
    return difference;
}

// The low limb of a * b + c + d, hi replaced by the high one ((2^64 - 1)^2 + 2 (2^64 - 1) < 2^128: it
// fits). d may be hi itself.
[[gnu::always_inline]] inline uint64_t multiply_add(uint64_t a, uint64_t b, uint64_t c, uint64_t d, uint64_t& hi) {
    const uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t middle = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);  // below 3 * 2^32
    uint64_t lo = (middle << 32) | (p00 & 0xffffffffu);
    uint64_t high = p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32);
    lo += c;
    high += lo < c;
    lo += d;
    high += lo < d;
    hi = high;
    return lo;
}

} // namespace portable

#if defined(__x86_64__)
// Compilers turn chains of these into add-with-carry instructions; from portable code they do not.
[[gnu::always_inline]] inline uint64_t add(uint64_t a, uint64_t b, uint64_t& carry) {
    unsigned long long sum;
    carry = _addcarry_u64(static_cast<unsigned char>(carry), a, b, &sum);
    return sum;
}

[[gnu::always_inline]] inline uint64_t subtract(uint64_t a, uint64_t b, uint64_t& borrow) {
    unsigned long long difference;
    borrow = _subborrow_u64(static_cast<unsigned char>(borrow), a, b, &difference);
    return difference;
}
#else
using portable::add;
using portable::subtract;
#endif

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 DoubleLimb;  // __extension__: -Wpedantic knows no 128-bit type
__extension__ typedef __int128 SignedDoubleLimb;

[[gnu::always_inline]] inline uint64_t multiply_add(uint64_t a, uint64_t b, uint64_t c, uint64_t d, uint64_t& hi) {
    const DoubleLimb sum = static_cast<DoubleLimb>(a) * b + c + d;
    hi = static_cast<uint64_t>(sum >> 64);
    return static_cast<uint64_t>(sum);
}
#else
using portable::multiply_add;
#endif

// All ones when a is negative, else zero.
template <int N>
[[gnu::always_inline]] inline uint64_t sign_mask(const Int<N>& a) {
    return static_cast<uint64_t>(-static_cast<int64_t>(a.limb[N - 1] >> 63));
}

template <int N>
[[gnu::always_inline]] inline Int<N> operator+(const Int<N>& a, const Int<N>& b) {
    Int<N> r;
    uint64_t carry = 0;
    for (int i = 0; i < N; ++i) r.limb[i] = add(a.limb[i], b.limb[i], carry);
    return r;
}

template <int N>
[[gnu::always_inline]] inline Int<N> operator-(const Int<N>& a, const Int<N>& b) {
    Int<N> r;
    uint64_t borrow = 0;
    for (int i = 0; i < N; ++i) r.limb[i] = subtract(a.limb[i], b.limb[i], borrow);
    return r;
}

// The signed product, in N + M limbs: the unsigned product of the two bit patterns, less b 2^(64 N) when
// a is negative and a 2^(64 M) when b is (a pattern of a negative value is a + 2^(64 N)).
template <int N, int M>
[[gnu::always_inline]] inline Int<N + M> operator*(const Int<N>& a, const Int<M>& b) {
    Int<N + M> r;
    for (int i = 0; i < N; ++i) {
        uint64_t carry = 0;
        for (int j = 0; j < M; ++j) r.limb[i + j] = multiply_add(a.limb[i], b.limb[j], i == 0 ? 0 : r.limb[i + j], carry, carry);
        r.limb[i + M] = carry;
    }
    const uint64_t a_negative = sign_mask(a), b_negative = sign_mask(b);
    uint64_t borrow = 0;
    for (int j = 0; j < M; ++j) r.limb[N + j] = subtract(r.limb[N + j], b.limb[j] & a_negative, borrow);
    borrow = 0;
    for (int i = 0; i < N; ++i) r.limb[M + i] = subtract(r.limb[M + i], a.limb[i] & b_negative, borrow);
    return r;
}

#if defined(__SIZEOF_INT128__)
// The products of one-limb differences and of their two-limb minors, the bulk of the exact stage, with
// the target's signed multiplication where it has one.
[[gnu::always_inline]] inline Int<2> operator*(const Int<1>& a, const Int<1>& b) {
    const SignedDoubleLimb product = static_cast<SignedDoubleLimb>(static_cast<int64_t>(a.limb[0])) *
                                     static_cast<int64_t>(b.limb[0]);
    return Int<2>{{static_cast<uint64_t>(product), static_cast<uint64_t>(static_cast<DoubleLimb>(product) >> 64)}};
}

// a (b1 2^64 + b0) = a b0 + a b1 2^64, where a b0 is the unsigned product of the bit patterns less b0 2^64
// for negative a. Everything above the low limb is the signed (a b) >> 64, below 2^126 in magnitude.
[[gnu::always_inline]] inline Int<3> operator*(const Int<1>& a, const Int<2>& b) {
    const DoubleLimb low = static_cast<DoubleLimb>(a.limb[0]) * b.limb[0];
    const SignedDoubleLimb high = static_cast<SignedDoubleLimb>(static_cast<int64_t>(a.limb[0])) *
                                  static_cast<int64_t>(b.limb[1]);
    const SignedDoubleLimb upper = static_cast<SignedDoubleLimb>(low >> 64) + high -
                                   static_cast<SignedDoubleLimb>(b.limb[0] & sign_mask(a));
    return Int<3>{{static_cast<uint64_t>(low), static_cast<uint64_t>(upper),
                   static_cast<uint64_t>(static_cast<DoubleLimb>(upper) >> 64)}};
}
#endif

template <int N>
[[gnu::always_inline]] inline int sign(const Int<N>& a) {
    if (a.limb[N - 1] >> 63) return -1;
    uint64_t any = 0;
    for (int i = 0; i < N; ++i) any |= a.limb[i];
    return any != 0;
}

// A finite double as (-1)^negative * odd * 2^exponent, odd an odd integer below 2^53; zero has odd = 0
// and an exponent above every other, so that it never sets the finest grain of a set of numbers.
struct Binary {
    uint64_t odd;
    int exponent;
    bool negative;
};

constexpr int ZERO_EXPONENT = 1 << 20;

[[gnu::always_inline]] inline int trailing_zeros(uint64_t x) {  // x != 0
#if defined(__GNUC__)
    return __builtin_ctzll(x);
#else
    int n = 0;
    for (; !(x & 1); x >>= 1) ++n;
    return n;
#endif
}

[[gnu::always_inline]] inline Binary decompose(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const int biased = static_cast<int>(bits >> 52) & 0x7ff;
    uint64_t significand = bits & ((uint64_t(1) << 52) - 1);
    if (biased != 0) significand |= uint64_t(1) << 52;  // normal numbers have the hidden bit
    Binary b;
    b.negative = bits >> 63;
    if (significand == 0) {
        b.odd = 0;
        b.exponent = ZERO_EXPONENT;
        return b;
    }
    const int zeros = trailing_zeros(significand);
    b.odd = significand >> zeros;
    b.exponent = (biased != 0 ? biased : 1) - 1075 + zeros;
    return b;
}

// x / 2^unit modulo 2^(64 N), for x a multiple of 2^unit (x.exponent >= unit).
template <int N>
[[gnu::always_inline]] inline Int<N> scaled(const Binary& x, int unit) {
    const int shift = x.exponent - unit;
    const int whole = shift >> 6, bits = shift & 63;
    // odd < 2^53 spans at most two limbs; (odd >> 1) >> (63 - bits) is 0, not undefined, for bits == 0.
    const uint64_t low = x.odd << bits, high = (x.odd >> 1) >> (63 - bits);
    Int<N> r;
    for (int i = 0; i < N; ++i) r.limb[i] = (i == whole ? low : 0) | (i == whole + 1 ? high : 0);
    // -r == ~r + 1, and for positive x (mask 0) this adds nothing.
    const uint64_t mask = static_cast<uint64_t>(-static_cast<int64_t>(x.negative));
    uint64_t carry = mask & 1;
    for (int i = 0; i < N; ++i) {
        const uint64_t flipped = r.limb[i] ^ mask;
        r.limb[i] = flipped + carry;
        carry = r.limb[i] < carry;
    }
    return r;
}

} // namespace wide
} // namespace dbrg
