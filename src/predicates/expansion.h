// Expansion arithmetic: exact sums and products of doubles, each result held as a sum of non-overlapping
// doubles ("expansion") stored in order of increasing magnitude.
//
// Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates" (1997), sections 2.3-2.6 (Two-Sum, Dekker's Two-Product, Fast-Expansion-Sum,
// Scale-Expansion with zero elimination).
//
// Exactness needs round-to-nearest-even binary64 arithmetic without fused multiply-add contraction
// (this code is compiled with -ffp-contract=off), no overflow, and no underflow: every exact partial
// product must be representable. Every expansion has at least one component; zero is {0}.
#pragma once

#include <assert.h>

namespace dbrg {
namespace expansion {

// hi + lo == a + b exactly, with hi the rounded sum.
inline void two_sum(double a, double b, double& hi, double& lo) {
    hi = a + b;
    const double b_part = hi - a;
    const double a_part = hi - b_part;
    lo = (a - a_part) + (b - b_part);
}

// hi + lo == a - b exactly. Negation is exact, so this is two_sum in disguise.
inline void two_diff(double a, double b, double& hi, double& lo) { two_sum(a, -b, hi, lo); }

// a == hi + lo with hi and lo holding at most 26 significant bits each, so that products of halves
// are exact (Veltkamp's splitting with the constant 2^27 + 1).
inline void split(double a, double& hi, double& lo) {
    const double scaled = 134217729.0 * a;
    const double shifted = scaled - a;
    hi = scaled - shifted;
    lo = a - hi;
}

// hi + lo == a * b exactly, given b already split into b_hi + b_lo (Dekker's product).
inline void two_product_split(double a, double b, double b_hi, double b_lo, double& hi, double& lo) {
    hi = a * b;
    double a_hi, a_lo;
    split(a, a_hi, a_lo);
    const double error1 = hi - a_hi * b_hi;
    const double error2 = error1 - a_lo * b_hi;
    const double error3 = error2 - a_hi * b_lo;
    lo = a_lo * b_lo - error3;
}

inline void two_product(double a, double b, double& hi, double& lo) {
    double b_hi, b_lo;
    split(b, b_hi, b_lo);
    two_product_split(a, b, b_hi, b_lo, hi, lo);
}

// h = e + f. h holds ne + nf doubles and aliases neither input. Returns the length of h.
// Merging the components by magnitude before one Two-Sum sweep keeps the output non-overlapping.
inline int sum(const double* e, int ne, const double* f, int nf, double* h) {
    int i = 0, j = 0, n = 0;
    auto next_smallest = [&]() {
        if (j == nf || (i < ne && (e[i] < 0 ? -e[i] : e[i]) <= (f[j] < 0 ? -f[j] : f[j]))) return e[i++];
        return f[j++];
    };
    double carry = next_smallest();
    while (i < ne || j < nf) {
        double lo;
        two_sum(carry, next_smallest(), carry, lo);
        if (lo != 0) h[n++] = lo;
    }
    if (carry != 0 || n == 0) h[n++] = carry;
    return n;
}

// h = e * b. h holds 2 * ne doubles and does not alias e. Returns the length of h.
inline int scale(const double* e, int ne, double b, double* h) {
    double b_hi, b_lo;
    split(b, b_hi, b_lo);
    double carry, lo;
    two_product_split(e[0], b, b_hi, b_lo, carry, lo);
    int n = 0;
    if (lo != 0) h[n++] = lo;
    for (int i = 1; i < ne; ++i) {
        double product_hi, product_lo, partial;
        two_product_split(e[i], b, b_hi, b_lo, product_hi, product_lo);
        two_sum(carry, product_lo, partial, lo);
        if (lo != 0) h[n++] = lo;
        two_sum(product_hi, partial, carry, lo);
        if (lo != 0) h[n++] = lo;
    }
    if (carry != 0 || n == 0) h[n++] = carry;
    return n;
}

// h = -e, exactly; h may be e. Returns the length of h.
inline int negate(const double* e, int ne, double* h) {
    for (int i = 0; i < ne; ++i) h[i] = -e[i];
    return ne;
}

// The sign of an expansion is the sign of its largest component (zero elimination keeps it non-zero
// unless the whole expansion is zero).
inline int sign(const double* e, int ne) { return (e[ne - 1] > 0) - (e[ne - 1] < 0); }

// h (4 doubles) = a * b - c * d. Returns the length of h.
inline int product_difference(double a, double b, double c, double d, double* h) {
    double ab[2], cd[2];
    two_product(a, b, ab[1], ab[0]);
    two_product(c, d, cd[1], cd[0]);
    negate(cd, 2, cd);
    return sum(ab, 2, cd, 2, h);
}

// h (6 doubles) = x^2 + y^2 + z^2. Returns the length of h.
inline int squared_norm(double x, double y, double z, double* h) {
    double xx[2], yy[2], zz[2], xy[4];
    two_product(x, x, xx[1], xx[0]);
    two_product(y, y, yy[1], yy[0]);
    two_product(z, z, zz[1], zz[0]);
    const int nxy = sum(xx, 2, yy, 2, xy);
    return sum(xy, nxy, zz, 2, h);
}

// A running exact sum in two fixed buffers of Capacity doubles; Capacity must bound the total length
// of everything added (the sum of the lengths, not the usually much shorter actual result).
template <int Capacity>
class Accumulator {
public:
    Accumulator() = default;
    Accumulator(const Accumulator&) = delete;
    Accumulator& operator=(const Accumulator&) = delete;

    void add(const double* e, int ne) {
        assert(length_ + ne <= Capacity);
        double* other = total_ == buffers_[0] ? buffers_[1] : buffers_[0];
        if (length_ == 0) {
            for (int i = 0; i < ne; ++i) other[i] = e[i];
            length_ = ne;
        } else {
            length_ = sum(total_, length_, e, ne, other);
        }
        total_ = other;
    }

    // Adds e * f; Scratch bounds 2 * ne.
    template <int Scratch>
    void add_product(const double* e, int ne, const double* f, int nf) {
        assert(2 * ne <= Scratch);
        double scaled[Scratch];
        for (int k = 0; k < nf; ++k) add(scaled, scale(e, ne, f[k], scaled));
    }

    int sign() const { return length_ == 0 ? 0 : expansion::sign(total_, length_); }

private:
    double buffers_[2][Capacity];
    double* total_ = buffers_[0];
    int length_ = 0;
};

} // namespace expansion
} // namespace dbrg
