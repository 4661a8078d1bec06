// Zero area decided exactly: a floating-point filter first, the same filter on rescaled corners, and an
// exact sum of products for what both leave undecided.
#include "measure/zero_area.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "predicates/filters.h"

namespace dbrg::measure {
namespace {

// An exact sum of absolute products of finite doubles. frexp writes any finite double as m 2^e with m an
// integer below 2^53 and e >= -1126, so each product is a whole number of units of 2^-2252 below 2^4300, and
// the sum is kept as such a whole number in 68 words, room for far more products than are ever added.
class ExactProductSum {
public:
    // Adds |x y|.
    void add_product(double x, double y) {
        int x_exponent, y_exponent;
        const uint64_t x_mantissa = integer_mantissa(x, x_exponent), y_mantissa = integer_mantissa(y, y_exponent);
        const int bit = x_exponent + y_exponent - UNIT_EXPONENT;
        // In 32-bit halves, so that each partial product fits in 64 bits.
        const uint64_t x_half[2] = {x_mantissa & 0xffffffffu, x_mantissa >> 32};
        const uint64_t y_half[2] = {y_mantissa & 0xffffffffu, y_mantissa >> 32};
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) add_shifted(x_half[i] * y_half[j], bit + 32 * (i + j));
        }
    }

    bool operator==(const ExactProductSum& other) const { return words_ == other.words_; }

private:
    static constexpr int UNIT_EXPONENT = -2252;
    static constexpr size_t WORDS = 68;

    // |x| = mantissa 2^exponent, the mantissa a whole number below 2^53 (0 for x = 0, exponent then -53).
    static uint64_t integer_mantissa(double x, int& exponent) {
        const double fraction = std::frexp(std::fabs(x), &exponent);
        exponent -= 53;
        return static_cast<uint64_t>(std::ldexp(fraction, 53));
    }

    // Adds value 2^bit units.
    void add_shifted(uint64_t value, int bit) {
        const size_t word = size_t(bit) / 64;
        const int shift = bit % 64;
        const uint64_t parts[2] = {value << shift, shift == 0 ? 0 : value >> (64 - shift)};
        uint64_t carry = 0;
        for (size_t i = word; i < WORDS && (i < word + 2 || carry != 0); ++i) {
            const uint64_t addend = i < word + 2 ? parts[i - word] : 0;
            const uint64_t partial = words_[i] + addend;
            const uint64_t total = partial + carry;
            carry = uint64_t(partial < addend) + uint64_t(total < carry);
            words_[i] = total;
        }
    }

    std::array<uint64_t, WORDS> words_ = {};
};

// Whether det[a - c; b - c] of the three corners over the coordinates u, v is exactly zero, for finite
// coordinates of any size. The determinant is the sum over the sides (p, q) of p_u q_v - p_v q_u: zero
// exactly when its positive terms add up to its negative ones.
bool orientation_is_zero(const double* const* corners, int u, int v) {
    ExactProductSum positive, negative;
    const auto add_term = [&](double x, double y, bool subtracted) {
        const bool negative_term = ((x < 0) != (y < 0)) != subtracted;
        (negative_term ? negative : positive).add_product(x, y);
    };
    for (int k = 0; k < 3; ++k) {
        const double* p = corners[k];
        const double* q = corners[(k + 1) % 3];
        add_term(p[u], q[v], false);
        add_term(p[v], q[u], true);
    }
    return positive == negative;
}

// The coordinate planes (u, v) a triangle is projected onto.
const int PLANES[3][2] = {{0, 1}, {1, 2}, {2, 0}};

// Whether the floating-point filter proves one of the triangle's projections to have non-zero area. It is
// sound at any size: a product that underflows errs by less than its guard of 2^-960, one that overflows
// leaves it undecided.
bool filter_proves_area(const double* const* corners) {
    for (const auto& plane : PLANES) {
        if (filter::orient2d(corners[0], corners[1], corners[2], plane[0], plane[1]) != filter::UNDECIDED) return true;
    }
    return false;
}

} // namespace

// A triangle has zero area when its corners are collinear, that is when its projections onto the three
// coordinate planes all have zero area.
bool has_zero_area(const std::vector<double>& p, const uint32_t* corner) {
    const double* corners[3] = {&p[3 * size_t(corner[0])], &p[3 * size_t(corner[1])], &p[3 * size_t(corner[2])]};
    if (filter_proves_area(corners)) return false;
    double largest = 0;
    for (const double* point : corners) {
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(point[k])) return false;
            largest = std::max(largest, std::fabs(point[k]));
        }
    }
    // Tiny or huge coordinates leave the filter undecided: again with the corners times the power of two
    // that brings the largest coordinate near 1 (2^1023 at most, the largest a double holds). Scaling is
    // exact but where a coordinate falls below 2^-1022 and moves by less than 2^-1074; the projected areas
    // then move by less than 2^-1070, so what the filter proves of the scaled corners holds for these.
    int exponent;
    std::frexp(largest, &exponent);
    const double scale = std::ldexp(1.0, std::min(-exponent, 1023));
    double scaled[3][3];
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) scaled[i][k] = corners[i][k] * scale;
    }
    const double* scaled_corners[3] = {scaled[0], scaled[1], scaled[2]};
    if (filter_proves_area(scaled_corners)) return false;
    for (const auto& plane : PLANES) {
        if (!orientation_is_zero(corners, plane[0], plane[1])) return false;
    }
    return true;
}

} // namespace dbrg::measure
