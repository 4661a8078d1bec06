// Fuzz target: orient3d, insphere_exact, insphere_sos and incircle3d_sos on random and near-degenerate
// quadruples and quintuples. On integer coordinates (|x| <= 2^16, then translated and scaled by exact
// amounts) the signs must agree with 128-bit integer references; on exactly cospherical points whose
// differences span up to 200 bits, insphere must be 0, and one grain off the sphere it must say which side;
// on any input the perturbed predicates must never answer 0 where they promise a decision, must agree with
// the exact ones wherever those are not 0, and must change sign exactly with the parity of a permutation
// of their arguments.
#include <math.h>
#include <string.h>

#include <algorithm>

#include "exact_geometry.h"
#include "fuzz_check.h"
#include "fuzz_input.h"
#include "predicates/predicates.h"

using namespace dbrg;
using namespace dbrg::fuzz;

namespace {

enum class Mode { wide_integers, small_integers, near_coplanar, near_cospherical, raw_doubles, wide_cospherical };
constexpr uint32_t MODE_COUNT = 6;

int64_t signed_value(FuzzInput& input, int64_t limit) {
    return static_cast<int64_t>(input.u32() % static_cast<uint32_t>(2 * limit + 1)) - limit;
}

// Five integer points: unrelated, crowded on a tiny grid, or on a common plane or sphere with one point
// then nudged by at most 2 units (relative distance about 2^-14: the floating-point filters cannot decide).
void integer_points(Mode mode, FuzzInput& input, IntPoint points[5]) {
    if (mode == Mode::wide_integers || mode == Mode::small_integers) {
        const int64_t limit = mode == Mode::small_integers ? 2 : EXACT_COORDINATE_LIMIT;
        for (int i = 0; i < 5; ++i) points[i] = {signed_value(input, limit), signed_value(input, limit), signed_value(input, limit)};
        return;
    }
    const IntPoint base = {signed_value(input, 1 << 14), signed_value(input, 1 << 14), signed_value(input, 1 << 14)};
    if (mode == Mode::near_coplanar) {
        // base + i u + j v with |i|, |j| <= 3: coordinates stay below 2^14 + 6 * 2^10.
        const IntPoint u = {signed_value(input, 1 << 10), signed_value(input, 1 << 10), signed_value(input, 1 << 10)};
        const IntPoint v = {signed_value(input, 1 << 10), signed_value(input, 1 << 10), signed_value(input, 1 << 10)};
        for (int i = 0; i < 5; ++i) {
            const int64_t s = signed_value(input, 3), t = signed_value(input, 3);
            points[i] = {base.x + s * u.x + t * v.x, base.y + s * u.y + t * v.y, base.z + s * u.z + t * v.z};
        }
    } else {
        // Signed permutations of one vector all have its length: five points on one sphere around base.
        const int64_t r[3] = {signed_value(input, 1 << 11), signed_value(input, 1 << 11), signed_value(input, 1 << 11)};
        for (int i = 0; i < 5; ++i) {
            const uint32_t choice = input.byte();
            int64_t q[3] = {r[0], r[1], r[2]};
            static const int ORDERS[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
            const int* order = ORDERS[choice % 6];
            for (int k = 0; k < 3; ++k) q[k] = (choice >> (3 + k) & 1) ? -r[order[k]] : r[order[k]];
            points[i] = {base.x + q[0], base.y + q[1], base.z + q[2]};
        }
    }
    IntPoint& nudged = points[input.below(5)];
    nudged.x += signed_value(input, 2);
    nudged.y += signed_value(input, 2);
    nudged.z += signed_value(input, 2);
}

// One of the 120 orders of five arguments, and its parity (+1 even, -1 odd).
int permutation(uint32_t index, int order[5]) {
    for (int i = 0; i < 5; ++i) order[i] = i;
    for (uint32_t k = 0; k < index % 120; ++k) std::next_permutation(order, order + 5);
    int parity = 1;
    for (int i = 0; i < 5; ++i) {
        for (int j = i + 1; j < 5; ++j) parity *= order[i] > order[j] ? -1 : 1;
    }
    return parity;
}

// What the library answers for five points; sos is meaningful only where orient != 0.
struct Answers {
    int orient;
    int exact;
    int sos;
};

Answers ask(const double* p[5], PredicateCounters& counters) {
    return {orient3d(p[0], p[1], p[2], p[3], counters), insphere_exact(p[0], p[1], p[2], p[3], p[4], counters),
            insphere_sos(p[0], p[1], p[2], p[3], p[4], counters)};
}

// The promises that hold on any input.
void check_consistency(const double coordinates[5][3], uint32_t permutation_index, PredicateCounters& counters) {
    const double* p[5] = {coordinates[0], coordinates[1], coordinates[2], coordinates[3], coordinates[4]};
    const Answers base = ask(p, counters);
    if (base.orient != 0) FUZZ_CHECK_WHY(base.sos != 0, "insphere_sos is 0 for a non-degenerate tetrahedron");
    if (base.exact != 0) FUZZ_CHECK_WHY(base.sos == base.exact, "insphere_sos disagrees with insphere_exact");

    int order[5];
    const int parity = permutation(permutation_index, order);
    const double* q[5] = {p[order[0]], p[order[1]], p[order[2]], p[order[3]], p[order[4]]};
    const Answers moved = ask(q, counters);
    FUZZ_CHECK_WHY(moved.exact == parity * base.exact, "insphere_exact is not alternating");
    // The perturbed determinant alternates too, for distinct points (ranks of equal points follow argument order).
    bool distinct = true;
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < i; ++j) distinct = distinct && compare_points(p[i], p[j]) != 0;
    }
    if (distinct) FUZZ_CHECK_WHY(moved.sos == parity * base.sos, "insphere_sos is not alternating");
    if (order[4] == 4) {
        // The first four are a permutation of the original four: orient3d alternates with the same parity.
        FUZZ_CHECK_WHY(moved.orient == parity * base.orient, "orient3d is not alternating");
    }

    for (int i = 0; i < 5; ++i) {
        FUZZ_CHECK(compare_points(p[i], p[i]) == 0);
        for (int j = 0; j < i; ++j) FUZZ_CHECK(compare_points(p[i], p[j]) == -compare_points(p[j], p[i]));
    }
}

// In-circle answers for coplanar a, b, c, d: never 0 for a non-collinear triangle, symmetric in its
// corners (inside a circle does not depend on how the circle is named). Returns the answer.
int check_incircle(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters) {
    const double* corners[3] = {a, b, c};
    static const int ORDERS[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}};
    const int answer = incircle3d_sos(a, b, c, d, counters);
    FUZZ_CHECK_WHY(answer == 1 || answer == -1, "incircle3d_sos is not decided for a non-collinear triangle");
    for (const auto& order : ORDERS) {
        FUZZ_CHECK_WHY(incircle3d_sos(corners[order[0]], corners[order[1]], corners[order[2]], d, counters) == answer,
                       "incircle3d_sos depends on the order of the triangle's corners");
    }
    return answer;
}

// Five of the 48 signed permutations of (x, y, z), with x below 1/2 of up to 53 bits, y below 1/4 of up to
// 32 bits and z below 1/2, odd, of grain 2^-(w + 1) for a drawn w <= 198: all on one sphere about the
// origin, with differences spanning up to about 200 bits (every integer type of the exact stage). insphere
// must be 0; then the fifth point moves by one grain along its coordinate +-z, away from the centre or
// towards it, which takes it outside or inside. Leaves the moved points in coordinates.
void check_wide_cospherical(FuzzInput& input, double coordinates[5][3], PredicateCounters& counters) {
    const int width = 1 + static_cast<int>(input.below(198));
    const double grain = ldexp(1.0, -(width + 1));
    const uint64_t x_high = input.u32();
    const uint64_t x_bits = (x_high << 21 ^ input.u32()) | 1;  // odd, below 2^53
    const uint32_t z_bits = (input.u32() & ((uint32_t(1) << (width < 20 ? width : 20)) - 1)) | 1;
    const double r[3] = {ldexp(static_cast<double>(x_bits), -54), ldexp(static_cast<double>(input.u32()), -34),
                         static_cast<double>(z_bits) * grain};
    static const int ORDERS[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int i = 0; i < 5; ++i) {
        const uint32_t choice = input.byte();
        const int* order = ORDERS[choice % 6];
        for (int k = 0; k < 3; ++k) coordinates[i][k] = (choice >> (3 + k) & 1) ? -r[order[k]] : r[order[k]];
    }
    const double* p[5] = {coordinates[0], coordinates[1], coordinates[2], coordinates[3], coordinates[4]};
    FUZZ_CHECK_WHY(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) == 0,
                   "insphere_exact is not 0 on exactly cospherical points");
    const int axis = fabs(p[4][0]) == r[2] ? 0 : fabs(p[4][1]) == r[2] ? 1 : 2;
    const bool outward = input.flag();
    coordinates[4][axis] += ((coordinates[4][axis] > 0) == outward ? 1 : -1) * grain;
    const int o = orient3d(p[0], p[1], p[2], p[3], counters);
    if (o != 0 && fabs(r[2]) != fabs(r[0]) && fabs(r[2]) != fabs(r[1])) {
        FUZZ_CHECK_WHY(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) == (outward ? -o : o),
                       "insphere_exact gets the side of a point one grain off a sphere wrong");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzInput input(data, size);
    const Mode mode = static_cast<Mode>(input.below(MODE_COUNT));
    const uint32_t permutation_index = input.byte();
    PredicateCounters counters;
    double coordinates[5][3];

    if (mode == Mode::raw_doubles) {
        // 53-bit integers scaled by 2^-60 .. 2^0: conditioned sizes, within the span the exact stage needs.
        for (auto& point : coordinates) {
            for (double& x : point) {
                const int64_t mantissa = static_cast<int64_t>(static_cast<uint64_t>(input.u32()) << 21 ^ input.u32()) >> 10;
                x = ldexp(static_cast<double>(mantissa), -53 - static_cast<int>(input.below(61)));
            }
        }
        check_consistency(coordinates, permutation_index, counters);
        return 0;
    }

    if (mode == Mode::wide_cospherical) {
        check_wide_cospherical(input, coordinates, counters);
        check_consistency(coordinates, permutation_index, counters);
        return 0;
    }

    IntPoint points[5];
    integer_points(mode, input, points);
    // An exact change of frame: translation by integers below 2^20, then a power-of-two scale.
    const int64_t shift[3] = {signed_value(input, 1 << 20), signed_value(input, 1 << 20), signed_value(input, 1 << 20)};
    const int scale = static_cast<int>(input.below(61)) - 40;
    for (int i = 0; i < 5; ++i) {
        const int64_t xyz[3] = {points[i].x, points[i].y, points[i].z};
        for (int k = 0; k < 3; ++k) coordinates[i][k] = ldexp(static_cast<double>(xyz[k] + shift[k]), scale);
    }
    const double* p[5] = {coordinates[0], coordinates[1], coordinates[2], coordinates[3], coordinates[4]};

    FUZZ_CHECK_WHY(orient3d(p[0], p[1], p[2], p[3], counters) == sign_of(orient3d(points[0], points[1], points[2], points[3])),
                   "orient3d disagrees with the integer reference");
    FUZZ_CHECK_WHY(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) ==
                       sign_of(insphere(points[0], points[1], points[2], points[3], points[4])),
                   "insphere_exact disagrees with the integer reference");
    check_consistency(coordinates, permutation_index, counters);

    if (orient3d(points[0], points[1], points[2], points[3]) == 0 && !collinear(points[0], points[1], points[2])) {
        const int reference = incircle3d(points[0], points[1], points[2], points[3]);
        const int answer = check_incircle(p[0], p[1], p[2], p[3], counters);
        if (reference != 0) FUZZ_CHECK_WHY(answer == reference, "incircle3d_sos disagrees with the integer reference");
    }
    FUZZ_CHECK(counters.calls > 0 && counters.filter_failures <= counters.calls && counters.perturbations <= counters.calls);
    return 0;
}
