// Exact determinant signs in fixed-width integer arithmetic. Each determinant is a polynomial in the
// coordinate differences p - q, which are all multiples of 2^unit for some power of two, so it is an
// integer times a power of two and has the sign of that integer. The integer is evaluated exactly, with
// no rounding to reason about and the same steps whatever the values, so exact zeros and near-ties cost
// the same, in the cheapest type that holds it: machine words for lattice-like points, one 64-bit limb per
// difference for the doubles of a generic point cloud, two or four for coordinates of very unequal size.
// Before all of these, grids and other coarse lattices get the same determinants in doubles, where that
// evaluation is provably exact (the lattice stage, below).
#include "predicates/exact_determinants.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "predicates/wide_integer.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dbrg {
namespace exact {
namespace {

using wide::Binary;
using wide::Int;

uint64_t bits_of(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

// The least e with x < 2^e, for normal x > 0 (an e with x < 2^e for subnormal x).
int exponent_above(double x) {
    const int biased = static_cast<int>(bits_of(x) >> 52) & 0x7ff;
    return (biased != 0 ? biased : 1) - 1022;
}

// 2^e as a double, for -1022 <= e <= 1023.
double power_of_two(int e) {
    const uint64_t bits = static_cast<uint64_t>(e + 1023) << 52;
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

// The differences p_i - p_last of one call's points, each exactly as hi + lo (Knuth's two-difference;
// lo is 0 whenever the rounded difference is exact, as it is for nearby points).
template <int Rows>
struct Differences {
    double hi[Rows][3];
    double lo[Rows][3];
    int top;     // every |p_i - p_last| is below 2^top (0 when all are 0)
    bool tails;  // some lo is not 0: some difference is not a double
};

// Knuth's two-difference, on doubles or, lane by lane with the same operations, on pairs of them.
template <class Lanes>
[[gnu::always_inline]] inline void two_difference(Lanes a, Lanes b, Lanes& hi, Lanes& lo) {
    hi = a - b;
    const Lanes b_virtual = a - hi, a_virtual = hi + b_virtual;
    lo = (a - a_virtual) + (b_virtual - b);
}

template <int Rows>
[[gnu::always_inline]] inline void set_top(double largest, Differences<Rows>& d) {
    // Rounding is monotone and 2^top is a double: a rounded difference below 2^top is one of an exact
    // difference below it.
    d.top = largest == 0 ? 0 : exponent_above(largest);
}

#if defined(__SSE2__)
// Two differences at a time: each row's x and y, then the z of two rows (the exact stage's preparation
// took as many instructions as its arithmetic on the doubles of a sphere).
template <int Points>
[[gnu::always_inline]] inline Differences<Points - 1> differences(const double* const* points) {
    constexpr int Rows = Points - 1;
    Differences<Rows> d;
    const double* last = points[Rows];
    const __m128d last_xy = _mm_loadu_pd(last), last_z = _mm_set1_pd(last[2]), sign_bit = _mm_set1_pd(-0.0);
    __m128d largest = _mm_setzero_pd(), tails = _mm_setzero_pd();
    const auto take = [&](__m128d a, __m128d b, __m128d& hi, __m128d& lo) {
        two_difference(a, b, hi, lo);
        tails = _mm_or_pd(tails, _mm_cmpneq_pd(lo, _mm_setzero_pd()));  // -0 is 0
        largest = _mm_max_pd(largest, _mm_andnot_pd(sign_bit, hi));
    };
    __m128d hi, lo;
    for (int i = 0; i < Rows; ++i) {
        take(_mm_loadu_pd(points[i]), last_xy, hi, lo);
        _mm_storeu_pd(d.hi[i], hi);
        _mm_storeu_pd(d.lo[i], lo);
    }
    for (int i = 0; i < Rows; i += 2) {
        const int j = i + 1 < Rows ? i + 1 : i;  // an odd last row pairs with itself
        take(_mm_set_pd(points[j][2], points[i][2]), last_z, hi, lo);
        _mm_storel_pd(&d.hi[i][2], hi);
        _mm_storel_pd(&d.lo[i][2], lo);
        _mm_storeh_pd(&d.hi[j][2], hi);
        _mm_storeh_pd(&d.lo[j][2], lo);
    }
    d.tails = _mm_movemask_pd(tails) != 0;
    set_top(_mm_cvtsd_f64(_mm_max_sd(largest, _mm_unpackhi_pd(largest, largest))), d);
    return d;
}
#else
template <int Points>
[[gnu::always_inline]] inline Differences<Points - 1> differences(const double* const* points) {
    Differences<Points - 1> d;
    double largest = 0;
    uint64_t tail_bits = 0;
    for (int i = 0; i < Points - 1; ++i) {
        for (int k = 0; k < 3; ++k) {
            two_difference(points[i][k], points[Points - 1][k], d.hi[i][k], d.lo[i][k]);
            tail_bits |= bits_of(d.lo[i][k]) << 1;  // not the sign: -0 is 0
            largest = fabs(d.hi[i][k]) > largest ? fabs(d.hi[i][k]) : largest;
        }
    }
    d.tails = tail_bits != 0;
    set_top(largest, d);
    return d;
}
#endif

// rows = the differences / 2^(top - 62) as one-limb integers, when each is a multiple of that power of two
// (then each is below 2^62, one limb). Returns false, rows unspecified, when one is not.
template <int Rows>
[[gnu::always_inline]] inline bool one_limb_rows(const Differences<Rows>& d, Int<1> (*rows)[3], uint64_t& ored_limbs) {
    const int scale_exponent = 62 - d.top;
    if (scale_exponent < -1022 || scale_exponent > 1023) return false;
    // Exact products: below 2^62, and, as the differences are multiples of 2^(top - 254), not below 2^-192.
    const double scale = power_of_two(scale_exponent);
    bool integral = true;
    for (int i = 0; i < Rows; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double hi = d.hi[i][k] * scale;  // below 2^62
            const int64_t hi_integer = static_cast<int64_t>(hi);
            integral &= static_cast<double>(hi_integer) == hi;
            int64_t lo_integer = 0;
            if (d.tails) {
                const double lo = d.lo[i][k] * scale;
                lo_integer = static_cast<int64_t>(lo);
                integral &= static_cast<double>(lo_integer) == lo;
            }
            rows[i][k].limb[0] = static_cast<uint64_t>(hi_integer + lo_integer);
            ored_limbs |= rows[i][k].limb[0];
        }
    }
    return integral;
}

// rows = one-limb rows / 2^51 as machine words, when every difference is a double (no tails) and every
// limb a multiple of 2^51: the differences are then integer multiples of 2^(top - 11), below 2^11.
template <int Rows>
[[gnu::always_inline]] inline bool machine_word_rows(const Differences<Rows>& d, const Int<1> (*one)[3],
                                                     uint64_t ored_limbs, int64_t (*rows)[3]) {
    constexpr int FREE_BITS = 62 - 11;
    if (d.tails || (ored_limbs & ((uint64_t(1) << FREE_BITS) - 1)) != 0) return false;
    for (int i = 0; i < Rows; ++i)
        for (int k = 0; k < 3; ++k) rows[i][k] = static_cast<int64_t>(one[i][k].limb[0]) >> FREE_BITS;  // exact
    return true;
}

// The finest binary grain among the differences: every one is a multiple of 2^unit.
template <int Rows>
int finest_unit(const Differences<Rows>& d) {
    int unit = wide::ZERO_EXPONENT;
    for (int i = 0; i < Rows; ++i) {
        for (int k = 0; k < 3; ++k) {
            const int hi = wide::decompose(d.hi[i][k]).exponent, lo = wide::decompose(d.lo[i][k]).exponent;
            unit = hi < unit ? hi : unit;
            unit = lo < unit ? lo : unit;
        }
    }
    return unit;
}

// rows = the differences / 2^unit in K limbs each.
template <int K, int Rows>
void rows_on_grid(const Differences<Rows>& d, int unit, Int<K> (*rows)[3]) {
    for (int i = 0; i < Rows; ++i)
        for (int k = 0; k < 3; ++k)
            rows[i][k] = wide::scaled<K>(wide::decompose(d.hi[i][k]), unit) +
                         wide::scaled<K>(wide::decompose(d.lo[i][k]), unit);
}

// Runs evaluate(rows) on the differences as integers of the cheapest type in which their products keep
// every value of the evaluation in range. The largest values are insphere's: for differences below 2^w
// they are below 4 * 2^(2 w + 2) * 3 * 2^(2 w + 1) * 2^w < 2^(5 w + 7), and each smaller determinant is as
// far within its own type. So one machine word holds every value for w <= 11 (lattices of up to 2048
// steps a side), and K limbs per difference, 5 K for the largest products, hold them for 64 K >= w + 2.
// A call's w is the span from its finest grain to its largest difference: one limb for the doubles of
// any one point cloud whose coordinates are of similar size, more for coordinates near 0 next to large ones.
template <int Rows, class Evaluate>
int evaluate_exactly(const Differences<Rows>& d, Evaluate evaluate) {
    Int<1> one[Rows][3];
    uint64_t ored_limbs = 0;
    if (one_limb_rows(d, one, ored_limbs)) {
        int64_t small[Rows][3];
        if (machine_word_rows(d, one, ored_limbs, small)) return evaluate(small);
        return evaluate(one);
    }
    const int unit = finest_unit(d), width = d.top - unit;
    if (width <= 62) {
        rows_on_grid(d, unit, one);
        return evaluate(one);
    }
    if (width <= 126) {
        Int<2> two[Rows][3];
        rows_on_grid(d, unit, two);
        return evaluate(two);
    }
    assert(width <= 254 && "the exact predicates need the coordinates of a call to span at most 254 bits");
    Int<4> four[Rows][3];
    rows_on_grid(d, unit, four);
    return evaluate(four);
}

// The determinants below are written once for any of those integer types: products of Int<K> widen to
// the limbs they need, products of machine words stay machine words.

template <int K>
int sign_of(const Int<K>& value) {
    return wide::sign(value);
}

int sign_of(int64_t value) { return (value > 0) - (value < 0); }

int sign_of(double value) { return (value > 0) - (value < 0); }

// p[u] q[v] - q[u] p[v].
template <class Integer>
[[gnu::always_inline]] inline auto minor2(const Integer* p, const Integer* q, int u, int v) {
    return p[u] * q[v] - q[u] * p[v];
}

template <class Integer>
[[gnu::always_inline]] inline auto squared_length(const Integer* p) {
    return p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
}

// det[p; q; r] expanded along z, given the xy-minors of its pairs.
template <class Integer, class Minor>
[[gnu::always_inline]] inline auto det3(const Integer* p, const Integer* q, const Integer* r, const Minor& qr,
                                        const Minor& pr, const Minor& pq) {
    return p[2] * qr - q[2] * pr + r[2] * pq;
}

template <class Integer>
int orient3d_sign(const Integer (*rows)[3]) {
    const auto bc = minor2(rows[1], rows[2], 0, 1), ac = minor2(rows[0], rows[2], 0, 1), ab = minor2(rows[0], rows[1], 0, 1);
    return sign_of(det3(rows[0], rows[1], rows[2], bc, ac, ab));
}

// Expanded along the lift column, each 3x3 minor along z over the six xy-minors they share. Those minors
// are orient3d of four of the points, e among them; the fifth orientation is their alternating sum
// (the 4x4 determinant of the rows (p - e, 1) expanded along its last column).
template <class Integer>
int insphere_sign(const Integer (*rows)[3], int* orientations) {
    const Integer *a = rows[0], *b = rows[1], *c = rows[2], *d = rows[3];
    const auto ab = minor2(a, b, 0, 1), ac = minor2(a, c, 0, 1), ad = minor2(a, d, 0, 1);
    const auto bc = minor2(b, c, 0, 1), bd = minor2(b, d, 0, 1), cd = minor2(c, d, 0, 1);
    const auto abc = det3(a, b, c, bc, ac, ab), abd = det3(a, b, d, bd, ad, ab);
    const auto acd = det3(a, c, d, cd, ad, ac), bcd = det3(b, c, d, cd, bd, bc);
    const int sign = sign_of((squared_length(d) * abc - squared_length(c) * abd) +
                             (squared_length(b) * acd - squared_length(a) * bcd));
    if (sign == 0 && orientations != nullptr) {
        orientations[0] = sign_of(bcd);
        orientations[1] = sign_of(acd);
        orientations[2] = sign_of(abd);
        orientations[3] = sign_of(abc);
        orientations[4] = sign_of(abc - abd + acd - bcd);
    }
    return sign;
}

// The same along the lift column, over the 2x2 minors, which are orient2d of three of the points.
template <class Integer>
int incircle_lifted_sign(const Integer (*rows)[3], int u, int v, int* orientations) {
    const Integer *a = rows[0], *b = rows[1], *c = rows[2];
    const auto ab = minor2(a, b, u, v), ac = minor2(a, c, u, v), bc = minor2(b, c, u, v);
    const int sign = sign_of(squared_length(a) * bc - squared_length(b) * ac + squared_length(c) * ab);
    if (sign == 0 && orientations != nullptr) {
        orientations[0] = sign_of(bc);
        orientations[1] = sign_of(ac);
        orientations[2] = sign_of(ab);
        orientations[3] = sign_of(ab - ac + bc);
    }
    return sign;
}

template <class Integer>
int orient2d_sign(const Integer (*rows)[3], int u, int v) {
    return sign_of(minor2(rows[0], rows[1], u, v));
}

// The lattice stage: the same determinants evaluated in doubles, when that evaluation is exact. Say every
// coordinate of the call is a multiple of 2^g, and every difference below 2^(g + Width): then each
// difference is an integer number of units 2^g below 2^Width, so the rounded difference is the exact one,
// and every value of a determinant's tree is an integer number of units^degree. Width is chosen per
// determinant so that no value reaches 2^53 units^degree, so every operation is exact: the sign, zero
// included, and the perturbation's cofactors are those of the integer stage. From the largest value of
// each tree for differences below D:
//   insphere (degree 5): 4 lifts (< 3 D^2) times 3x3 minors (< 6 D^3), summed: < 72 D^5 < 2^53 for D < 2^9;
//   incircle_lifted (4): 3 lifts times 2x2 minors (< 2 D^2), < 18 D^4: D < 2^12;
//   orient3d (3): < 6 D^3: D < 2^16;  orient2d (2): < 2 D^2: D < 2^25.
// g is the least power the width allows for the call's largest difference: the finest grid, so the
// weakest test of the coordinates. g <= 0 keeps the scaling of that test exact, and degree * g >= -1074
// keeps each unit^degree representable (subnormal at worst, exactly). The conditioned points of a grid
// pass; a point cloud with full significands fails the test.
// Whether every coordinate of the points times scale (a power of two, at least 1, so the products are
// exact) is an integer: whether it survives the round trip through a 32-bit integer (one out of that
// range does not, nor does a NaN, and is left to the integer stage).
template <int Points>
[[gnu::always_inline]] inline bool integral_multiples(const double* const* points, double scale) {
#if defined(__SSE2__)
    // Two coordinates at a time: each point's (x, y), then the z of two points.
    const __m128d factor = _mm_set1_pd(scale);
    __m128d off = _mm_setzero_pd();
    const auto test = [&](__m128d pair) {
        const __m128d v = _mm_mul_pd(pair, factor);
        off = _mm_or_pd(off, _mm_cmpneq_pd(_mm_cvtepi32_pd(_mm_cvttpd_epi32(v)), v));
    };
    for (int i = 0; i < Points; ++i) test(_mm_loadu_pd(points[i]));
    for (int i = 0; i + 1 < Points; i += 2) test(_mm_set_pd(points[i + 1][2], points[i][2]));
    if (Points % 2 != 0) test(_mm_set1_pd(points[Points - 1][2]));
    return _mm_movemask_pd(off) == 0;
#else
    bool integral = true;
    for (int i = 0; i < Points; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double v = points[i][k] * scale;
            integral &= fabs(v) < 0x1p31 && static_cast<double>(static_cast<int32_t>(v)) == v;  // no cast out of range
        }
    }
    return integral;
#endif
}

template <int Degree, int Width, int Points, class Evaluate>
[[gnu::always_inline]] inline int evaluate_on_lattice(const double* const* points, Evaluate evaluate) {
    double rows[Points - 1][3];
    double largest = 0;
    for (int i = 0; i < Points - 1; ++i) {
        for (int k = 0; k < 3; ++k) {
            rows[i][k] = points[i][k] - points[Points - 1][k];
            largest = fabs(rows[i][k]) > largest ? fabs(rows[i][k]) : largest;  // fmax would be a call
        }
    }
    // Rounding is monotone: a rounded difference below 2^e is one of an exact difference below it.
    int g = exponent_above(largest) - Width;
    g = g < -(1074 / Degree) ? -(1074 / Degree) : g;
    if (g > 0) return NOT_ON_LATTICE;
    return integral_multiples<Points>(points, power_of_two(-g)) ? evaluate(rows) : NOT_ON_LATTICE;
}

} // namespace

int orient3d_on_lattice(const double* a, const double* b, const double* c, const double* d) {
    const double* points[4] = {a, b, c, d};
    return evaluate_on_lattice<3, 16, 4>(points, [](const double(*rows)[3]) { return orient3d_sign(rows); });
}

int insphere_on_lattice(const double* a, const double* b, const double* c, const double* d, const double* e,
                        int* orientations) {
    const double* points[5] = {a, b, c, d, e};
    return evaluate_on_lattice<5, 9, 5>(
        points, [orientations](const double(*rows)[3]) { return insphere_sign(rows, orientations); });
}

int incircle_lifted_on_lattice(const double* a, const double* b, const double* c, const double* d, int u, int v,
                               int* orientations) {
    const double* points[4] = {a, b, c, d};
    return evaluate_on_lattice<4, 12, 4>(points, [u, v, orientations](const double(*rows)[3]) {
        return incircle_lifted_sign(rows, u, v, orientations);
    });
}

int orient2d_on_lattice(const double* a, const double* b, const double* c, int u, int v) {
    const double* points[3] = {a, b, c};
    return evaluate_on_lattice<2, 25, 3>(points,
                                         [u, v](const double(*rows)[3]) { return orient2d_sign(rows, u, v); });
}

int orient3d(const double* a, const double* b, const double* c, const double* d) {
    const double* points[4] = {a, b, c, d};
    return evaluate_exactly(differences<4>(points), [](const auto* rows) { return orient3d_sign(rows); });
}

int insphere(const double* a, const double* b, const double* c, const double* d, const double* e, int* orientations) {
    const double* points[5] = {a, b, c, d, e};
    return evaluate_exactly(differences<5>(points),
                            [orientations](const auto* rows) { return insphere_sign(rows, orientations); });
}

int incircle_lifted(const double* a, const double* b, const double* c, const double* d, int u, int v,
                    int* orientations) {
    const double* points[4] = {a, b, c, d};
    return evaluate_exactly(differences<4>(points), [u, v, orientations](const auto* rows) {
        return incircle_lifted_sign(rows, u, v, orientations);
    });
}

int orient2d(const double* a, const double* b, const double* c, int u, int v) {
    const double* points[3] = {a, b, c};
    return evaluate_exactly(differences<3>(points), [u, v](const auto* rows) { return orient2d_sign(rows, u, v); });
}

} // namespace exact
} // namespace dbrg
