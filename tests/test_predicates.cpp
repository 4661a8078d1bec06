// Tests of the geometric predicates against an independent exact reference: coordinates are turned into
// integers (every test coordinate is a multiple of 2^-200, the grid of conditioned points) and determinants
// are expanded by cofactors in a simple fixed-width two's-complement integer type of 32-bit limbs, with
// symbolic perturbations made explicit.
#include <doctest/doctest.h>

#include <math.h>
#include <stdint.h>

#include <algorithm>
#include <vector>

#include "core/pi.h"
#include "core/splitmix64.h"
#include "points/point_conditioning.h"
#include "delaunay/tetrahedralization.h"
#include "predicates/affine_checks.h"
#include "predicates/exact_determinants.h"
#include "predicates/filters.h"
#include "predicates/predicates.h"
#include "predicates/wide_integer.h"

#include "delaunay_test_support.h"

using namespace dbrg;

namespace {

// A signed integer of 36 x 32 bits in two's complement; products are taken modulo 2^1152, which is exact
// while the true values stay below 2^1151 (an insphere determinant of coordinates below 2^18 on the
// 2^-200 grid stays below 2^1110).
struct Big {
    static const int LIMBS = 36;
    uint32_t limb[LIMBS];
};

Big big(int64_t value) {
    Big r;
    for (int i = 0; i < Big::LIMBS; ++i) {
        r.limb[i] = static_cast<uint32_t>(value);
        value = value < 0 ? -((-(value + 1)) >> 32) - 1 : value >> 32;  // floor division by 2^32
    }
    return r;
}

Big power_of_two(int exponent) {
    Big r = big(0);
    r.limb[exponent / 32] = uint32_t(1) << (exponent % 32);
    return r;
}

Big operator+(const Big& a, const Big& b) {
    Big r;
    uint64_t carry = 0;
    for (int i = 0; i < Big::LIMBS; ++i) {
        carry += uint64_t(a.limb[i]) + b.limb[i];
        r.limb[i] = static_cast<uint32_t>(carry);
        carry >>= 32;
    }
    return r;
}

Big operator-(const Big& a) {
    Big r;
    for (int i = 0; i < Big::LIMBS; ++i) r.limb[i] = ~a.limb[i];
    return r + big(1);
}

Big operator-(const Big& a, const Big& b) { return a + (-b); }

int sign(const Big& a) {
    if (a.limb[Big::LIMBS - 1] >> 31) return -1;
    for (int i = 0; i < Big::LIMBS; ++i)
        if (a.limb[i]) return 1;
    return 0;
}

int significant_limbs(const Big& a) {
    int n = Big::LIMBS;
    while (n > 0 && a.limb[n - 1] == 0) --n;
    return n;
}

// The product of the magnitudes, schoolbook over their significant limbs, with the sign put back.
Big operator*(const Big& a, const Big& b) {
    const Big x = sign(a) < 0 ? -a : a, y = sign(b) < 0 ? -b : b;
    const int nx = significant_limbs(x), ny = significant_limbs(y);
    Big r = big(0);
    for (int i = 0; i < nx; ++i) {
        uint64_t carry = 0;
        for (int j = 0; i + j < Big::LIMBS && (j < ny || carry != 0); ++j) {
            const uint64_t t = uint64_t(x.limb[i]) * (j < ny ? y.limb[j] : 0) + r.limb[i + j] + carry;
            r.limb[i + j] = static_cast<uint32_t>(t);
            carry = t >> 32;
        }
    }
    return (sign(a) < 0) != (sign(b) < 0) ? -r : r;
}

bool equal(const Big& a, const Big& b) { return sign(a - b) == 0; }

// Determinant of an n x n matrix (row-major, n <= 5) by cofactor expansion along the first row.
Big determinant(const Big* m, int n) {
    if (n == 1) return m[0];
    Big total = big(0);
    Big sub[16];
    for (int col = 0; col < n; ++col) {
        int k = 0;
        for (int r = 1; r < n; ++r)
            for (int c = 0; c < n; ++c)
                if (c != col) sub[k++] = m[r * n + c];
        const Big term = m[col] * determinant(sub, n - 1);
        total = col % 2 == 0 ? total + term : total - term;
    }
    return total;
}

// x * 2^scale as an integer; the test inputs are built so that this is exact.
Big fixed(double x, int scale = 200) {
    double magnitude = fabs(ldexp(x, scale));
    REQUIRE(magnitude == floor(magnitude));
    REQUIRE(magnitude < ldexp(1.0, 700));
    Big r = big(0);
    for (int i = 0; magnitude > 0; ++i) {
        const double limb = fmod(magnitude, 4294967296.0);
        r.limb[i] = static_cast<uint32_t>(limb);
        magnitude = (magnitude - limb) / 4294967296.0;
    }
    return x < 0 ? -r : r;
}

int reference_orient3d(const double* a, const double* b, const double* c, const double* d) {
    const double* rows[3] = {a, b, c};
    Big m[9];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) m[3 * r + k] = fixed(rows[r][k]) - fixed(d[k]);
    return sign(determinant(m, 3));
}

int reference_insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
    const double* rows[4] = {a, b, c, d};
    Big m[16];
    for (int r = 0; r < 4; ++r) {
        Big lift = big(0);
        for (int k = 0; k < 3; ++k) {
            const Big diff = fixed(rows[r][k]) - fixed(e[k]);
            m[4 * r + k] = diff;
            lift = lift + diff * diff;
        }
        m[4 * r + 3] = lift;
    }
    return sign(determinant(m, 4));
}

// The exact sign of the determinant filter::incircle evaluates: rows (p[u] - d[u], p[v] - d[v], |p - d|^2).
int reference_incircle_lifted(const double* a, const double* b, const double* c, const double* d, int u, int v) {
    const double* rows[3] = {a, b, c};
    Big m[9];
    for (int r = 0; r < 3; ++r) {
        Big lift = big(0);
        for (int k = 0; k < 3; ++k) {
            const Big diff = fixed(rows[r][k]) - fixed(d[k]);
            lift = lift + diff * diff;
        }
        m[3 * r] = fixed(rows[r][u]) - fixed(d[u]);
        m[3 * r + 1] = fixed(rows[r][v]) - fixed(d[v]);
        m[3 * r + 2] = lift;
    }
    return sign(determinant(m, 3));
}

// The 3D in-circle meaning for coplanar points: +1 inside the circle through a, b, c, whatever their order.
int reference_incircle3d(const double* a, const double* b, const double* c, const double* d) {
    // Project along the axis of a non-zero normal component and multiply by that orientation.
    for (int drop = 0; drop < 3; ++drop) {
        const int u = (drop + 1) % 3, v = (drop + 2) % 3;
        const double* rows[3] = {a, b, c};
        Big o[9];
        for (int r = 0; r < 3; ++r) {
            o[3 * r] = fixed(rows[r][u]);
            o[3 * r + 1] = fixed(rows[r][v]);
            o[3 * r + 2] = big(1);
        }
        const int orientation = sign(determinant(o, 3));
        if (orientation != 0) return orientation * reference_incircle_lifted(a, b, c, d, u, v);
    }
    return 0;
}

// Lexicographic ranks of n distinct points (0 = smallest), computed without compare_points.
void ranks(const double* const* p, int n, int* rank) {
    for (int i = 0; i < n; ++i) {
        rank[i] = 0;
        for (int j = 0; j < n; ++j)
            if (std::lexicographical_compare(p[j], p[j] + 3, p[i], p[i] + 3)) ++rank[i];
    }
}

// The perturbed insphere with an explicit eps = 2^-step: rows (p, |p|^2 + eps^(rank+1), 1), scaled by
// 2^(5 step) so that every entry is an integer. Points must be small integers (|coordinate| <= 4); then
// step = 20 is small enough for the explicit eps to give the infinitesimal limit.
int brute_force_insphere_sos(const double* const* p) {
    const int step = 20;
    int rank[5];
    ranks(p, 5, rank);
    Big m[25];
    for (int r = 0; r < 5; ++r) {
        int64_t lift = 0;
        for (int k = 0; k < 3; ++k) {
            REQUIRE(p[r][k] == floor(p[r][k]));
            REQUIRE(fabs(p[r][k]) <= 4);
            m[5 * r + k] = big(static_cast<int64_t>(p[r][k]));
            lift += static_cast<int64_t>(p[r][k] * p[r][k]);
        }
        m[5 * r + 3] = big(lift) * power_of_two(5 * step) + power_of_two(step * (4 - rank[r]));
        m[5 * r + 4] = big(1);
    }
    return sign(determinant(m, 5));
}

// The perturbed insphere(a, b, c, q, d) with q unperturbed, times the sign of orient3d(a, b, c, q): what
// incircle3d_sos(a, b, c, d) must return. Integer points with |coordinate| <= 16.
int brute_force_incircle3d_sos(const double* a, const double* b, const double* c, const double* d, const double* q) {
    const int step = 24;
    const double* perturbed[4] = {a, b, c, d};
    int rank[4];
    ranks(perturbed, 4, rank);
    const double* rows[5] = {a, b, c, q, d};
    const int row_rank[5] = {rank[0], rank[1], rank[2], -1, rank[3]};
    Big m[25];
    for (int r = 0; r < 5; ++r) {
        int64_t lift = 0;
        for (int k = 0; k < 3; ++k) {
            REQUIRE(rows[r][k] == floor(rows[r][k]));
            REQUIRE(fabs(rows[r][k]) <= 16);
            m[5 * r + k] = big(static_cast<int64_t>(rows[r][k]));
            lift += static_cast<int64_t>(rows[r][k] * rows[r][k]);
        }
        m[5 * r + 3] = big(lift) * power_of_two(4 * step);
        if (row_rank[r] >= 0) m[5 * r + 3] = m[5 * r + 3] + power_of_two(step * (3 - row_rank[r]));
        m[5 * r + 4] = big(1);
    }
    return sign(determinant(m, 5)) * reference_orient3d(a, b, c, q);
}

// A fixed, portable sequence.
struct Random : SplitMix64 {
    using SplitMix64::SplitMix64;
    // Uniform in [-1, 1) with a full 53-bit significand range, always a multiple of 2^-53.
    double unit() { return ldexp(static_cast<double>(next() >> 11), -52) - 1.0; }
    int integer(int lo, int hi) { return lo + static_cast<int>(next() % uint64_t(hi - lo + 1)); }
};

struct Point {
    double c[3];
    operator const double*() const { return c; }
};

Point random_point(Random& random) { return Point{{random.unit(), random.unit(), random.unit()}}; }

Point lattice_point(Random& random, int lo, int hi) {
    return Point{{double(random.integer(lo, hi)), double(random.integer(lo, hi)), double(random.integer(lo, hi))}};
}

bool distinct(const Point* p, int n) {
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (compare_points(p[i], p[j]) == 0) return false;
    return true;
}

// The 30 integer points of the sphere of radius 5 about the origin, scaled by 1/8.
std::vector<Point> radius5_sphere() {
    std::vector<Point> points;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -5; z <= 5; ++z)
                if (x * x + y * y + z * z == 25) points.push_back(Point{{x / 8.0, y / 8.0, z / 8.0}});
    return points;
}

// 24 points (±1, ±2^-60, 0) and their coordinate permutations: all on the sphere |p|^2 = 1 + 2^-120, and
// many of their differences (1 - 2^-60) are not representable: the exact stage gets them in two parts.
std::vector<Point> wide_range_sphere() {
    const double small = ldexp(1.0, -60);
    const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    std::vector<Point> points;
    for (const auto& p : perm)
        for (int s = 0; s < 4; ++s) {
            const double value[3] = {s & 1 ? -1.0 : 1.0, s & 2 ? -small : small, 0.0};
            Point q;
            for (int k = 0; k < 3; ++k) q.c[p[k]] = value[k];
            points.push_back(q);
        }
    return points;
}

} // namespace

TEST_CASE("compare_points is lexicographic in x, then y, then z") {
    const double a[3] = {1, 2, 3}, b[3] = {1, 2, 4}, c[3] = {1, 3, 0}, d[3] = {2, 0, 0};
    CHECK(compare_points(a, a) == 0);
    CHECK(compare_points(a, b) < 0);
    CHECK(compare_points(b, a) > 0);
    CHECK(compare_points(b, c) < 0);
    CHECK(compare_points(c, d) < 0);
    CHECK(compare_points(d, a) > 0);
    const double negative_zero[3] = {-0.0, 0, 0}, zero[3] = {0, 0, 0};
    CHECK(compare_points(negative_zero, zero) == 0);
}

TEST_CASE("sign conventions on hand-checked configurations") {
    PredicateCounters counters;
    // a, b, c counterclockwise seen from +z; d below them.
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, below[3] = {0, 0, -1}, above[3] = {0, 0, 1};
    CHECK(orient3d(a, b, c, below, counters) == 1);
    CHECK(orient3d(a, b, c, above, counters) == -1);
    CHECK(orient3d(b, a, c, below, counters) == -1);
    CHECK(orient3d(a, b, c, a, counters) == 0);

    const double centre[3] = {0.25, 0.25, -0.25}, far[3] = {5, 5, 5};
    CHECK(insphere_exact(a, b, c, below, centre, counters) == 1);
    CHECK(insphere_exact(a, b, c, below, far, counters) == -1);
    CHECK(insphere_exact(b, a, c, below, centre, counters) == -1);
    CHECK(insphere_exact(b, a, c, below, far, counters) == 1);
    // (1, 1, -1) is the fourth corner of the unit cube through a, b, c, below: cospherical.
    const double corner[3] = {1, 1, -1};
    CHECK(insphere_exact(a, b, c, below, corner, counters) == 0);

    // In-circle in the plane z = 0, for both orientations of a, b, c.
    const double inside[3] = {0.25, 0.25, 0}, outside[3] = {2, 2, 0}, cocircular[3] = {1, 1, 0};
    CHECK(incircle3d_sos(a, b, c, inside, counters) == 1);
    CHECK(incircle3d_sos(b, a, c, inside, counters) == 1);
    CHECK(incircle3d_sos(a, b, c, outside, counters) == -1);
    CHECK(incircle3d_sos(c, b, a, outside, counters) == -1);
    CHECK(incircle3d_sos(a, b, c, cocircular, counters) != 0);
    const double collinear[3] = {2, 0, 0};
    CHECK(incircle3d_sos(a, b, collinear, inside, counters) == 0);
}

TEST_CASE("orient3d and insphere_exact agree with the exact reference on random points") {
    Random random(1);
    PredicateCounters counters;
    for (int trial = 0; trial < 4000; ++trial) {
        const Point p[5] = {random_point(random), random_point(random), random_point(random), random_point(random),
                            random_point(random)};
        REQUIRE(orient3d(p[0], p[1], p[2], p[3], counters) == reference_orient3d(p[0], p[1], p[2], p[3]));
        REQUIRE(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) ==
                reference_insphere(p[0], p[1], p[2], p[3], p[4]));
    }
    // Random points in general position are decided by the filter alone.
    CHECK(counters.calls == 8000);
    CHECK(counters.filter_failures == 0);
    CHECK(counters.perturbations == 0);
}

TEST_CASE("small lattice points: orient3d and insphere_exact agree with the reference, zeros included") {
    Random random(2);
    PredicateCounters counters;
    int zeros = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Point p[5];
        for (Point& q : p) q = lattice_point(random, 0, 2);
        const int o = orient3d(p[0], p[1], p[2], p[3], counters);
        REQUIRE(o == reference_orient3d(p[0], p[1], p[2], p[3]));
        const int s = insphere_exact(p[0], p[1], p[2], p[3], p[4], counters);
        REQUIRE(s == reference_insphere(p[0], p[1], p[2], p[3], p[4]));
        zeros += (o == 0) + (s == 0);
    }
    CHECK(zeros > 1000);
    CHECK(counters.filter_failures >= uint64_t(zeros));
}

TEST_CASE("every quadruple of the 3x3x3 lattice cube gets the exact orientation") {
    std::vector<Point> cube;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z) cube.push_back(Point{{x * 0.25, y * 0.25, z * 0.25}});
    PredicateCounters counters;
    const size_t n = cube.size();
    int coplanar = 0;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k)
                for (size_t l = k + 1; l < n; ++l) {
                    const int o = orient3d(cube[i], cube[j], cube[k], cube[l], counters);
                    REQUIRE(o == reference_orient3d(cube[i], cube[j], cube[k], cube[l]));
                    REQUIRE(orient3d(cube[j], cube[i], cube[k], cube[l], counters) == -o);
                    coplanar += o == 0;
                }
    CHECK(coplanar > 0);
}

TEST_CASE("five points of the radius-5 integer sphere are always cospherical") {
    const std::vector<Point> sphere = radius5_sphere();
    REQUIRE(sphere.size() == 30);
    PredicateCounters counters;
    const size_t n = sphere.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k)
                for (size_t l = k + 1; l < n; ++l)
                    for (size_t m = l + 1; m < n; ++m)
                        REQUIRE(insphere_exact(sphere[i], sphere[j], sphere[k], sphere[l], sphere[m], counters) == 0);
    // The centre is inside for any positively oriented tetrahedron of the sphere.
    const Point centre{{0, 0, 0}};
    Random random(3);
    for (int trial = 0; trial < 200; ++trial) {
        Point p[4];
        for (Point& q : p) q = sphere[random.next() % n];
        const int o = orient3d(p[0], p[1], p[2], p[3], counters);
        CHECK(insphere_exact(p[0], p[1], p[2], p[3], centre, counters) == o);
    }
}

TEST_CASE("points whose differences are not representable get exact signs") {
    const std::vector<Point> sphere = wide_range_sphere();
    PredicateCounters counters;
    const size_t n = sphere.size();
    Random random(4);
    int coplanar = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        size_t index[5];
        for (size_t& i : index) i = random.next() % n;
        const Point p[5] = {sphere[index[0]], sphere[index[1]], sphere[index[2]], sphere[index[3]], sphere[index[4]]};
        if (!distinct(p, 5)) continue;
        REQUIRE(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) == 0);
        const int o = orient3d(p[0], p[1], p[2], p[3], counters);
        REQUIRE(o == reference_orient3d(p[0], p[1], p[2], p[3]));
        coplanar += o == 0;
        // One ulp off the sphere is decided, and correctly.
        Point moved = p[4];
        for (int k = 0; k < 3; ++k)
            if (moved.c[k] != 0) {
                moved.c[k] = nextafter(moved.c[k], trial % 2 ? 2.0 : -2.0);
                break;
            }
        const int s = insphere_exact(p[0], p[1], p[2], p[3], moved, counters);
        REQUIRE(s == reference_insphere(p[0], p[1], p[2], p[3], moved));
        if (o != 0) CHECK(s != 0);
    }
    CHECK(coplanar > 0);
}

TEST_CASE("one ulp off a plane: the filter fails and the exact sign is right") {
    Random random(5);
    PredicateCounters counters;
    int decided = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        // The plane z = x/2 + y/4 + 1/8 holds these points exactly: x and y have at most 21 bits.
        Point p[4];
        for (Point& q : p) {
            const double x = ldexp(double(random.integer(-(1 << 20), 1 << 20)), -21);
            const double y = ldexp(double(random.integer(-(1 << 20), 1 << 20)), -21);
            q = Point{{x, y, x / 2 + y / 4 + 0.125}};
        }
        if (!distinct(p, 4)) continue;
        REQUIRE(orient3d(p[0], p[1], p[2], p[3], counters) == 0);
        Point up = p[3], down = p[3];
        up.c[2] = nextafter(up.c[2], 2.0);
        down.c[2] = nextafter(down.c[2], -2.0);
        const int s_up = orient3d(p[0], p[1], p[2], up, counters);
        const int s_down = orient3d(p[0], p[1], p[2], down, counters);
        REQUIRE(s_up == reference_orient3d(p[0], p[1], p[2], up));
        REQUIRE(s_down == -s_up);
        decided += 2;
    }
    // Besides the exactly coplanar calls, nearly every one-ulp call needs the exact evaluation: the
    // filter only succeeds when all three z differences happen to be tiny.
    CHECK(decided > 3000);
    CHECK(counters.filter_failures > uint64_t(decided / 2 * 3 * 95 / 100));
}

TEST_CASE("one ulp off the radius-5 sphere: the filter fails and the exact sign is right") {
    const std::vector<Point> sphere = radius5_sphere();
    Random random(6);
    PredicateCounters counters;
    int decided = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        Point p[5];
        for (Point& q : p) q = sphere[random.next() % sphere.size()];
        if (!distinct(p, 5)) continue;
        const int o = orient3d(p[0], p[1], p[2], p[3], counters);
        if (o == 0) continue;
        for (int k = 0; k < 3; ++k) {
            if (p[4].c[k] == 0) continue;  // an ulp of zero would be a subnormal, outside the precondition
            for (double direction : {-1.0, 1.0}) {
                Point moved = p[4];
                moved.c[k] = nextafter(moved.c[k], 2 * direction);
                const uint64_t failures = counters.filter_failures;
                const int s = insphere_exact(p[0], p[1], p[2], p[3], moved, counters);
                CHECK(counters.filter_failures == failures + 1);
                REQUIRE(s == reference_insphere(p[0], p[1], p[2], p[3], moved));
                // Moving away from the centre leaves the sphere.
                const bool outward = (moved.c[k] > 0) == (direction > 0);
                REQUIRE(s == (outward ? -o : o));
                ++decided;
            }
        }
    }
    CHECK(decided > 1000);
}

TEST_CASE("nearly coplanar and nearly cospherical points with full significands") {
    Random random(7);
    PredicateCounters counters;
    for (int trial = 0; trial < 3000; ++trial) {
        const Point a = random_point(random), b = random_point(random), c = random_point(random);
        const double s = random.unit(), t = random.unit();
        Point d;
        for (int k = 0; k < 3; ++k) d.c[k] = a.c[k] + s * (b.c[k] - a.c[k]) + t * (c.c[k] - a.c[k]);
        if (fabs(d.c[0]) > 1 || fabs(d.c[1]) > 1 || fabs(d.c[2]) > 1) continue;
        REQUIRE(orient3d(a, b, c, d, counters) == reference_orient3d(a, b, c, d));
    }
    const uint64_t plane_failures = counters.filter_failures;
    CHECK(plane_failures > 100);
    for (int trial = 0; trial < 1000; ++trial) {
        const Point centre{{random.unit() / 4, random.unit() / 4, random.unit() / 4}};
        const double radius = 0.25 + random.unit() / 8;
        Point p[5];
        for (Point& q : p) {
            const Point direction = random_point(random);
            const double length = sqrt(direction.c[0] * direction.c[0] + direction.c[1] * direction.c[1] +
                                       direction.c[2] * direction.c[2]);
            for (int k = 0; k < 3; ++k) q.c[k] = centre.c[k] + radius * (direction.c[k] / length);
        }
        REQUIRE(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) ==
                reference_insphere(p[0], p[1], p[2], p[3], p[4]));
    }
    CHECK(counters.filter_failures > plane_failures + 100);
}

TEST_CASE("insphere_sos equals an explicitly perturbed determinant on small lattices") {
    Random random(8);
    PredicateCounters counters;
    int perturbed = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Point p[5];
        for (Point& q : p) q = lattice_point(random, -2, 2);
        if (!distinct(p, 5)) continue;
        const double* points[5] = {p[0], p[1], p[2], p[3], p[4]};
        const uint64_t before = counters.perturbations;
        const int s = insphere_sos(p[0], p[1], p[2], p[3], p[4], counters);
        REQUIRE(s == brute_force_insphere_sos(points));
        if (orient3d(p[0], p[1], p[2], p[3], counters) != 0) REQUIRE(s != 0);
        perturbed += counters.perturbations > before;
    }
    CHECK(perturbed > 500);
}

TEST_CASE("insphere_sos is antisymmetric and invariant under permutations times the orientation") {
    const std::vector<Point> spheres[2] = {radius5_sphere(), wide_range_sphere()};
    Random random(9);
    PredicateCounters counters;
    for (const std::vector<Point>& sphere : spheres) {
        int checked = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            Point p[5];
            for (Point& q : p) q = sphere[random.next() % sphere.size()];
            if (!distinct(p, 5)) continue;
            const int o = orient3d(p[0], p[1], p[2], p[3], counters);
            if (o == 0) continue;
            const int s = insphere_sos(p[0], p[1], p[2], p[3], p[4], counters);
            REQUIRE(s != 0);
            // Swapping any two of the five arguments flips the sign.
            for (int i = 0; i < 5; ++i)
                for (int j = i + 1; j < 5; ++j) {
                    Point q[5] = {p[0], p[1], p[2], p[3], p[4]};
                    std::swap(q[i], q[j]);
                    REQUIRE(insphere_sos(q[0], q[1], q[2], q[3], q[4], counters) == -s);
                }
            // Any order of the tetrahedron gives the same answer once multiplied by its orientation.
            int order[4] = {0, 1, 2, 3};
            do {
                const Point& a = p[order[0]];
                const Point& b = p[order[1]];
                const Point& c = p[order[2]];
                const Point& d = p[order[3]];
                REQUIRE(insphere_sos(a, b, c, d, p[4], counters) * orient3d(a, b, c, d, counters) == s * o);
            } while (std::next_permutation(order, order + 4));
            ++checked;
        }
        CHECK(checked > 500);
    }
}

TEST_CASE("incircle3d_sos on a tilted plane equals the explicitly perturbed 3D limit") {
    // s and t are orthogonal and of equal length, so circles in (i, j) are circles in space.
    const int s[3] = {1, 2, 2}, t[3] = {2, 1, -2}, normal[3] = {-2, 2, -1}, origin[3] = {1, 0, -1};
    auto on_plane = [&](int i, int j, int m) {
        Point p;
        for (int k = 0; k < 3; ++k) p.c[k] = origin[k] + i * s[k] + j * t[k] + m * normal[k];
        return p;
    };
    Random random(10);
    PredicateCounters counters;
    int cocircular = 0, collinear = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Point p[4];
        for (Point& q : p) q = on_plane(random.integer(-2, 2), random.integer(-2, 2), 0);
        if (!distinct(p, 4)) continue;
        const Point q = on_plane(random.integer(-1, 1), random.integer(-1, 1), random.integer(0, 1) ? 1 : -1);
        const uint64_t before = counters.perturbations;
        const int r = incircle3d_sos(p[0], p[1], p[2], p[3], counters);
        if (reference_orient3d(p[0], p[1], p[2], q) == 0) {
            ++collinear;
            REQUIRE(r == 0);
            continue;
        }
        REQUIRE(r != 0);
        REQUIRE(r == brute_force_incircle3d_sos(p[0], p[1], p[2], p[3], q));
        if (counters.perturbations > before) ++cocircular;
        else REQUIRE(r == reference_incircle3d(p[0], p[1], p[2], p[3]));
    }
    CHECK(cocircular > 500);
    CHECK(collinear > 0);
}

TEST_CASE("incircle3d_sos is insphere_sos with a fourth point on the positive side, near or far") {
    const int s[3] = {1, 2, 2}, t[3] = {2, 1, -2}, normal[3] = {-2, 2, -1};
    // Radius-5 lattice circle of the (i, j) plane plus its centre and a few other points, scaled by 1/16.
    const int ij[][2] = {{5, 0}, {-5, 0}, {0, 5}, {0, -5}, {3, 4}, {4, 3}, {-3, 4}, {-4, 3}, {3, -4},
                         {4, -3}, {-3, -4}, {-4, -3}, {0, 0}, {1, 2}, {-6, 1}};
    std::vector<Point> plane;
    for (const auto& c : ij) {
        Point p;
        for (int k = 0; k < 3; ++k) p.c[k] = (c[0] * s[k] + c[1] * t[k]) / 16.0;
        plane.push_back(p);
    }
    Random random(11);
    PredicateCounters counters;
    int checked = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        Point p[4];
        for (Point& q : p) q = plane[random.next() % plane.size()];
        if (!distinct(p, 4)) continue;
        const int r = incircle3d_sos(p[0], p[1], p[2], p[3], counters);
        if (r == 0) continue;  // collinear a, b, c
        // incircle3d_sos ignores the order of a, b, c.
        REQUIRE(incircle3d_sos(p[1], p[0], p[2], p[3], counters) == r);
        REQUIRE(incircle3d_sos(p[2], p[0], p[1], p[3], counters) == r);
        for (double height : {1.0 / 8, -3.0 / 16, 1024.0, -65536.0}) {
            Point q;
            for (int k = 0; k < 3; ++k) q.c[k] = random.integer(-2, 2) / 16.0 + height * normal[k];
            const int o = orient3d(p[0], p[1], p[2], q, counters);
            REQUIRE(o != 0);
            REQUIRE(insphere_sos(p[0], p[1], p[2], q, p[3], counters) == o * r);
        }
        ++checked;
    }
    CHECK(checked > 1000);
}

TEST_CASE("incircle3d_sos one ulp inside or outside a circle in a tilted plane") {
    const int s[3] = {1, 2, 2}, t[3] = {2, 1, -2};
    auto on_plane = [&](double i, double j) {
        Point p;
        for (int k = 0; k < 3; ++k) p.c[k] = (i * s[k] + j * t[k]) / 16;
        return p;
    };
    const Point a = on_plane(5, 0), b = on_plane(0, 5), c = on_plane(-3, -4);
    PredicateCounters counters;
    for (int e = 30; e <= 48; ++e) {
        const double tiny = ldexp(1.0, -e);
        for (const Point& d : {on_plane(3 + tiny, 4), on_plane(-4, 3 + tiny), on_plane(4, -3 - tiny)}) {
            CHECK(incircle3d_sos(a, b, c, d, counters) == -1);
            CHECK(incircle3d_sos(c, b, a, d, counters) == -1);
            CHECK(reference_incircle3d(a, b, c, d) == -1);
        }
        for (const Point& d : {on_plane(3 - tiny, 4), on_plane(-4, 3 - tiny), on_plane(4, -3 + tiny)}) {
            CHECK(incircle3d_sos(a, b, c, d, counters) == 1);
            CHECK(incircle3d_sos(b, a, c, d, counters) == 1);
        }
    }
    CHECK(counters.filter_failures > 0);
    CHECK(counters.perturbations == 0);
}

TEST_CASE("incircle3d_sos on great circles of the wide-range sphere, where differences are inexact") {
    const std::vector<Point> sphere = wide_range_sphere();
    PredicateCounters counters;
    for (int plane = 0; plane < 3; ++plane) {
        std::vector<Point> circle;
        for (const Point& p : sphere)
            if (p.c[plane] == 0) circle.push_back(p);
        REQUIRE(circle.size() == 8);
        Point q{{0.25, 0.25, 0.25}};
        for (size_t i = 0; i < circle.size(); ++i)
            for (size_t j = 0; j < circle.size(); ++j)
                for (size_t k = 0; k < circle.size(); ++k)
                    for (size_t l = 0; l < circle.size(); ++l) {
                        const Point p[4] = {circle[i], circle[j], circle[k], circle[l]};
                        if (!distinct(p, 4)) continue;
                        const int o = orient3d(p[0], p[1], p[2], q, counters);
                        const int r = incircle3d_sos(p[0], p[1], p[2], p[3], counters);
                        REQUIRE(r == (o == 0 ? 0 : insphere_sos(p[0], p[1], p[2], q, p[3], counters) * o));
                        if (o == 0) continue;
                        // A move of one ulp within the plane, away from or towards the centre.
                        Point moved = p[3];
                        const int axis = moved.c[(plane + 1) % 3] != 0 ? (plane + 1) % 3 : (plane + 2) % 3;
                        moved.c[axis] = nextafter(moved.c[axis], (i + l) % 2 ? 2.0 : -2.0);
                        const int expected = (moved.c[axis] > 0) == ((i + l) % 2 == 1) ? -1 : 1;
                        REQUIRE(incircle3d_sos(p[0], p[1], p[2], moved, counters) == expected);
                        REQUIRE(reference_incircle3d(p[0], p[1], p[2], moved) == expected);
                    }
    }
    CHECK(counters.perturbations > 100);
}

TEST_CASE("incircle3d_sos with a, b, c nearly collinear") {
    Random random(13);
    PredicateCounters counters;
    int checked = 0;
    for (int trial = 0; trial < 5000; ++trial) {
        // On the plane z = 1/2, with a, b, c about one rounding off a line.
        auto on_plane = [](double x, double y) { return Point{{x, y, 0.5}}; };
        const double x0 = ldexp(random.unit(), -1), y0 = ldexp(random.unit(), -1);
        const double x1 = ldexp(random.unit(), -1), y1 = ldexp(random.unit(), -1);
        const double t = random.unit();
        const Point a = on_plane(x0, y0), b = on_plane(x1, y1), c = on_plane(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
        const Point d = on_plane(ldexp(random.unit(), -1), ldexp(random.unit(), -1));
        const int expected = reference_incircle3d(a, b, c, d);
        const int r = incircle3d_sos(a, b, c, d, counters);
        if (expected == 0) continue;  // exactly collinear or cocircular: not what this case is about
        REQUIRE(r == expected);
        ++checked;
    }
    CHECK(checked > 4000);
}

namespace {

int reference_orient2d(const double* a, const double* b, const double* c, int u, int v) {
    return sign((fixed(a[u]) - fixed(c[u])) * (fixed(b[v]) - fixed(c[v])) -
                (fixed(a[v]) - fixed(c[v])) * (fixed(b[u]) - fixed(c[u])));
}

// Rounded to a multiple of 2^-60, so that fixed() is exact whatever the magnitude.
double on_grid(double x) { return ldexp(nearbyint(ldexp(x, 60)), -60); }

// c + radius * (direction / |direction|), on the grid: within about 2^-60 of the sphere.
Point on_sphere(const Point& c, double radius, const double* direction) {
    const double length = sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    Point p;
    for (int k = 0; k < 3; ++k) p.c[k] = on_grid(c.c[k] + radius * (direction[k] / length));
    return p;
}

// Moves one coordinate by `ulps` units in the last place (towards +2 or -2).
Point nudged(Point p, int axis, int ulps, bool up) {
    for (int i = 0; i < ulps; ++i) p.c[axis] = nextafter(p.c[axis], up ? 2.0 : -2.0);
    return p;
}

// What the earlier form of the insphere filter could decide: its bound was 72 x 16 roundings times the
// product of the largest difference per coordinate and the largest one overall, squared.
bool product_bound_decides(const double* a, const double* b, const double* c, const double* d, const double* e) {
    const double* rows[4] = {a, b, c, d};
    double m[4][4], max_axis[3] = {0, 0, 0};
    for (int r = 0; r < 4; ++r) {
        m[r][3] = 0;
        for (int k = 0; k < 3; ++k) {
            m[r][k] = rows[r][k] - e[k];
            m[r][3] += m[r][k] * m[r][k];
            max_axis[k] = std::max(max_axis[k], fabs(m[r][k]));
        }
    }
    // The determinant by cofactors along the lift column (rounding differs, magnitude does not).
    double det = 0;
    for (int r = 0; r < 4; ++r) {
        double minor[3][3];
        for (int i = 0, row = 0; i < 4; ++i) {
            if (i == r) continue;
            for (int k = 0; k < 3; ++k) minor[row][k] = m[i][k];
            ++row;
        }
        const double m3 = minor[0][0] * (minor[1][1] * minor[2][2] - minor[1][2] * minor[2][1]) -
                          minor[0][1] * (minor[1][0] * minor[2][2] - minor[1][2] * minor[2][0]) +
                          minor[0][2] * (minor[1][0] * minor[2][1] - minor[1][1] * minor[2][0]);
        det += (r % 2 == 0 ? -1 : 1) * m[r][3] * m3;
    }
    const double max_w = std::max(max_axis[0], std::max(max_axis[1], max_axis[2]));
    return fabs(det) > 72 * 16 * ldexp(1.0, -53) * max_axis[0] * max_axis[1] * max_axis[2] * max_w * max_w;
}

} // namespace

TEST_CASE("the filters report only signs the exact reference confirms, and hand zeros over") {
    Random random(14);
    int decided[4] = {0, 0, 0, 0}, undecided[4] = {0, 0, 0, 0};
    auto check = [&](int which, int filtered, int reference) {
        if (filtered == filter::UNDECIDED) {
            ++undecided[which];
        } else {
            REQUIRE(filtered == reference);
            ++decided[which];
        }
    };
    for (int trial = 0; trial < 3000; ++trial) {
        const int ulps = trial % 4 == 0 ? 0 : 1 << random.integer(0, 12);
        const int axis = random.integer(0, 2);
        const bool up = random.integer(0, 1) == 1;
        // orient3d: d rounded onto the plane of a, b, c, then nudged.
        const Point a = random_point(random), b = random_point(random), c = random_point(random);
        const double s = random.unit() / 2, t = random.unit() / 2;
        Point d;
        for (int k = 0; k < 3; ++k) d.c[k] = on_grid(a.c[k] + s * (b.c[k] - a.c[k]) + t * (c.c[k] - a.c[k]));
        const Point moved = nudged(d, axis, ulps, up);
        check(0, filter::orient3d(a, b, c, moved), reference_orient3d(a, b, c, moved));
        // insphere: five points rounded onto one sphere, the fifth nudged; every fourth case a needle,
        // four points within 2^-k of each other and the fifth across the sphere.
        const Point centre{{random.unit() / 4, random.unit() / 4, random.unit() / 4}};
        const double radius = 0.25 + random.unit() / 8;
        const Point axis_direction = random_point(random);
        const double spread = trial % 4 == 1 ? ldexp(1.0, -random.integer(4, 24)) : 1.0;
        Point p[5];
        for (int i = 0; i < 5; ++i) {
            double direction[3];
            for (int k = 0; k < 3; ++k) direction[k] = (i == 3 ? -1.0 : 1.0) * axis_direction.c[k] + spread * random.unit();
            p[i] = on_sphere(centre, radius, direction);
        }
        p[4] = nudged(p[4], axis, ulps, up);
        check(1, filter::insphere(p[0], p[1], p[2], p[3], p[4]), reference_insphere(p[0], p[1], p[2], p[3], p[4]));
        check(1, filter::insphere_scalar(p[0], p[1], p[2], p[3], p[4]), reference_insphere(p[0], p[1], p[2], p[3], p[4]));
        // The two-lane form evaluates the same trees: the same decision, whatever the points' order.
        REQUIRE(filter::insphere(p[0], p[1], p[2], p[3], p[4]) == filter::insphere_scalar(p[0], p[1], p[2], p[3], p[4]));
        REQUIRE(filter::insphere(p[2], p[0], p[3], p[1], p[4]) == filter::insphere_scalar(p[2], p[0], p[3], p[1], p[4]));
        // incircle (its determinant, whatever the points) and orient2d: the plane z = 1/2 and a circle in it.
        Point q[4];
        const double circle_centre[2] = {random.unit() / 4, random.unit() / 4};
        for (Point& r : q) {
            const double angle = PI * random.unit();
            r = Point{{on_grid(circle_centre[0] + radius * cos(angle)), on_grid(circle_centre[1] + radius * sin(angle)), 0.5}};
        }
        q[3] = nudged(q[3], axis == 2 ? 0 : axis, ulps, up);
        check(2, filter::incircle(q[0], q[1], q[2], q[3], 0, 1), reference_incircle_lifted(q[0], q[1], q[2], q[3], 0, 1));
        Point r;
        for (int k = 0; k < 3; ++k) r.c[k] = on_grid(q[0].c[k] + s * (q[1].c[k] - q[0].c[k]));
        r = nudged(r, axis == 2 ? 1 : axis, ulps, up);
        check(3, filter::orient2d(q[0], q[1], r, 0, 1), reference_orient2d(q[0], q[1], r, 0, 1));
    }
    // Exact zeros (lattice points, exactly coplanar or cospherical) are always handed over.
    Random lattice(15);
    for (int trial = 0; trial < 5000; ++trial) {
        Point p[5];
        for (Point& q : p) q = lattice_point(lattice, 0, 2);
        check(0, filter::orient3d(p[0], p[1], p[2], p[3]), reference_orient3d(p[0], p[1], p[2], p[3]));
        check(1, filter::insphere(p[0], p[1], p[2], p[3], p[4]), reference_insphere(p[0], p[1], p[2], p[3], p[4]));
        REQUIRE(filter::insphere(p[0], p[1], p[2], p[3], p[4]) == filter::insphere_scalar(p[0], p[1], p[2], p[3], p[4]));
        check(2, filter::incircle(p[0], p[1], p[2], p[3], 1, 2), reference_incircle_lifted(p[0], p[1], p[2], p[3], 1, 2));
        check(3, filter::orient2d(p[0], p[1], p[2], 2, 0), reference_orient2d(p[0], p[1], p[2], 2, 0));
    }
    // Both outcomes are common: the inputs straddle the bound.
    for (int which = 0; which < 4; ++which) {
        CAPTURE(which);
        CHECK(decided[which] > 1000 * (which == 1 ? 2 : 1));
        CHECK(undecided[which] > 1000);
    }
}

TEST_CASE("on needles the insphere filter decides where a bound from the largest differences could not") {
    // Four points within 2^-16 of each other on a sphere, the fifth across it, and the query point moved
    // off the sphere by 2^-40 of the radius: well decided in exact terms, but the largest differences are
    // those to the far point, which made the earlier bound useless.
    Random random(16);
    int permanent_only = 0, product_only = 0, checked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Point centre{{random.unit() / 4, random.unit() / 4, random.unit() / 4}};
        const double radius = 0.25 + random.unit() / 8;
        const Point axis_direction = random_point(random);
        Point p[5];
        for (int i = 0; i < 5; ++i) {
            double direction[3];
            for (int k = 0; k < 3; ++k) direction[k] = (i == 3 ? -1.0 : 1.0) * axis_direction.c[k] + ldexp(random.unit(), -16);
            p[i] = on_sphere(centre, radius * (i == 4 ? 1 + (trial % 2 ? 0x1p-40 : -0x1p-40) : 1.0), direction);
        }
        const int reference = reference_insphere(p[0], p[1], p[2], p[3], p[4]);
        REQUIRE(reference != 0);
        const int filtered = filter::insphere(p[0], p[1], p[2], p[3], p[4]);
        REQUIRE(filtered == filter::insphere_scalar(p[0], p[1], p[2], p[3], p[4]));
        const bool by_product = product_bound_decides(p[0], p[1], p[2], p[3], p[4]);
        if (filtered != filter::UNDECIDED) REQUIRE(filtered == reference);
        permanent_only += filtered != filter::UNDECIDED && !by_product;
        product_only += filtered == filter::UNDECIDED && by_product;
        ++checked;
    }
    CHECK(permanent_only > checked * 9 / 10);
    CHECK(product_only == 0);
}

namespace {

// An Int<N> as a Big, sign-extended.
template <int N>
Big big_of(const wide::Int<N>& a) {
    const uint32_t extension = (a.limb[N - 1] >> 63) ? 0xffffffffu : 0;
    Big r;
    for (int i = 0; i < Big::LIMBS; ++i) r.limb[i] = i < 2 * N ? static_cast<uint32_t>(a.limb[i / 2] >> (32 * (i % 2))) : extension;
    return r;
}

Big unsigned_big(uint64_t value) {
    Big r = big(0);
    r.limb[0] = static_cast<uint32_t>(value);
    r.limb[1] = static_cast<uint32_t>(value >> 32);
    return r;
}

// a modulo 2^(64 n), as a signed value of n limbs.
Big truncated(const Big& a, int n) {
    Big r = a;
    const uint32_t extension = (r.limb[2 * n - 1] >> 31) ? 0xffffffffu : 0;
    for (int i = 2 * n; i < Big::LIMBS; ++i) r.limb[i] = extension;
    return r;
}

// Random limbs, the top one often 0, all ones or 2^63 (small values of either sign, the most negative).
template <int N>
wide::Int<N> random_int(Random& random) {
    wide::Int<N> a;
    for (int i = 0; i < N; ++i) a.limb[i] = random.next();
    const uint64_t tops[3] = {0, ~uint64_t(0), uint64_t(1) << 63};
    const uint64_t choice = random.next() % 6;
    if (choice < 3) a.limb[N - 1] = tops[choice];
    return a;
}

template <int N, int M>
void check_wide_arithmetic(Random& random) {
    const wide::Int<N> a = random_int<N>(random), b = random_int<N>(random);
    const wide::Int<M> c = random_int<M>(random);
    REQUIRE(equal(big_of(a + b), truncated(big_of(a) + big_of(b), N)));
    REQUIRE(equal(big_of(a - b), truncated(big_of(a) - big_of(b), N)));
    REQUIRE(equal(big_of(a * c), big_of(a) * big_of(c)));  // never wraps: |a c| <= 2^(64 (N + M) - 2)
    REQUIRE(wide::sign(a) == sign(big_of(a)));
}

// An odd integer of exactly `bits` bits, 1 <= bits <= 53.
double odd_of_bits(Random& random, int bits) {
    const uint64_t top = uint64_t(1) << (bits - 1);
    return static_cast<double>(top | (random.next() & (top - 1)) | 1);
}

// (x, y, z), all below 1/2: x in [1/4, 1/2) with min(width, 53) bits, y with about width / 2 bits, z of
// grain 2^-(width + 1). Differences of points made of these components span about width + 2 bits, from
// the largest to the finest grain: width 1 to 198 reaches every integer type of the exact stage.
void wide_vector(Random& random, int width, double r[3]) {
    const int x_bits = std::min(width, 53), y_bits = std::min(std::max(width / 2, 1), 53);
    r[0] = ldexp(odd_of_bits(random, x_bits), -(x_bits + 1));
    r[1] = ldexp(odd_of_bits(random, y_bits), -(width / 2 + 2));
    r[2] = ldexp(odd_of_bits(random, std::min(width, 20)), -(width + 1));
}

// The 48 signed permutations of r: all on the sphere of radius |r| about the origin.
std::vector<Point> signed_permutations(const double r[3]) {
    static const int ORDERS[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    std::vector<Point> points;
    for (const auto& order : ORDERS)
        for (int signs = 0; signs < 8; ++signs) {
            Point p;
            for (int k = 0; k < 3; ++k) p.c[k] = (signs >> k & 1) ? -r[order[k]] : r[order[k]];
            points.push_back(p);
        }
    return points;
}

// n distinct points drawn from `set`.
void draw_distinct(Random& random, const std::vector<Point>& set, int n, Point* out) {
    do {
        for (int i = 0; i < n; ++i) out[i] = set[random.next() % set.size()];
    } while (!distinct(out, n));
}

// insphere_sos from its definition, on the reference determinants: the exact sign, else the lift
// cofactor of the lexicographically smallest point whose cofactor is not zero.
int reference_insphere_sos(const Point* p) {
    const int exact = reference_insphere(p[0], p[1], p[2], p[3], p[4]);
    if (exact != 0) return exact;
    const double* points[5] = {p[0], p[1], p[2], p[3], p[4]};
    int rank[5];
    ranks(points, 5, rank);
    for (int r = 0; r < 5; ++r) {
        const int i = static_cast<int>(std::find(rank, rank + 5, r) - rank);
        const double* other[4];
        for (int j = 0, k = 0; j < 5; ++j)
            if (j != i) other[k++] = points[j];
        const int orientation = reference_orient3d(other[0], other[1], other[2], other[3]);
        if (orientation != 0) return i % 2 == 0 ? -orientation : orientation;
    }
    return 0;
}

// The axis of a coordinate of p equal to +-z, the finest component of a wide_vector: moving it by its
// grain keeps it exact.
int finest_axis(const Point& p, double z) {
    for (int k = 0; k < 3; ++k)
        if (fabs(p.c[k]) == z) return k;
    return -1;
}

} // namespace

TEST_CASE("wide integers: sums, differences and signed products agree with the reference") {
    Random random(18);
    for (int trial = 0; trial < 3000; ++trial) {
        check_wide_arithmetic<1, 1>(random);
        check_wide_arithmetic<1, 2>(random);
        check_wide_arithmetic<2, 1>(random);
        check_wide_arithmetic<2, 3>(random);
        check_wide_arithmetic<3, 2>(random);
        check_wide_arithmetic<4, 4>(random);
    }
}

TEST_CASE("the portable limb operations agree with the reference") {
    Random random(19);
    const Big two_to_64 = power_of_two(64);
    for (int trial = 0; trial < 20000; ++trial) {
        uint64_t x[4];
        for (uint64_t& value : x) {
            const uint64_t choice = random.next() % 8;
            value = choice == 0 ? 0 : choice == 1 ? ~uint64_t(0) : random.next();
        }
        const uint64_t carry_in = random.next() & 1;
        uint64_t carry = carry_in, carry_portable = carry_in;
        const uint64_t sum = wide::add(x[0], x[1], carry), sum_portable = wide::portable::add(x[0], x[1], carry_portable);
        REQUIRE(equal(unsigned_big(sum) + unsigned_big(carry) * two_to_64,
                      unsigned_big(x[0]) + unsigned_big(x[1]) + unsigned_big(carry_in)));
        REQUIRE((sum_portable == sum && carry_portable == carry));

        uint64_t borrow = carry_in, borrow_portable = carry_in;
        const uint64_t difference = wide::subtract(x[0], x[1], borrow);
        const uint64_t difference_portable = wide::portable::subtract(x[0], x[1], borrow_portable);
        REQUIRE(equal(unsigned_big(difference) - unsigned_big(borrow) * two_to_64,
                      unsigned_big(x[0]) - unsigned_big(x[1]) - unsigned_big(carry_in)));
        REQUIRE((difference_portable == difference && borrow_portable == borrow));

        uint64_t hi = 0, hi_portable = 0;
        const uint64_t lo = wide::multiply_add(x[0], x[1], x[2], x[3], hi);
        const uint64_t lo_portable = wide::portable::multiply_add(x[0], x[1], x[2], x[3], hi_portable);
        REQUIRE(equal(unsigned_big(lo) + unsigned_big(hi) * two_to_64,
                      unsigned_big(x[0]) * unsigned_big(x[1]) + unsigned_big(x[2]) + unsigned_big(x[3])));
        REQUIRE((lo_portable == lo && hi_portable == hi));
    }
}

TEST_CASE("decompose and scaled give a double's exact multiple of a power of two") {
    Random random(20);
    for (int trial = 0; trial < 20000; ++trial) {
        const double magnitude = ldexp(odd_of_bits(random, random.integer(1, 53)), -random.integer(0, 200));
        const double x = trial % 50 == 0 ? (trial % 100 == 0 ? 0.0 : -0.0) : (random.next() & 1 ? -magnitude : magnitude);
        const wide::Binary b = wide::decompose(x);
        if (x == 0) {
            REQUIRE(b.odd == 0);
            continue;
        }
        REQUIRE(b.odd % 2 == 1);
        REQUIRE((b.negative ? -1.0 : 1.0) * ldexp(static_cast<double>(b.odd), b.exponent) == x);
        const int unit = b.exponent - random.integer(0, 150);
        REQUIRE(equal(big_of(wide::scaled<1>(b, unit)), truncated(fixed(x, -unit), 1)));
        REQUIRE(equal(big_of(wide::scaled<4>(b, unit)), truncated(fixed(x, -unit), 4)));
    }
}

TEST_CASE("exactly cospherical points of every width: zero, and one grain off decided exactly") {
    Random random(21);
    PredicateCounters counters;
    int decided = 0;
    for (int width = 1; width <= 198; ++width) {
        double r[3];
        wide_vector(random, width, r);
        const std::vector<Point> sphere = signed_permutations(r);
        const double grain = ldexp(1.0, -(width + 1));
        for (int trial = 0; trial < 12; ++trial) {
            Point p[5];
            draw_distinct(random, sphere, 5, p);
            REQUIRE(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) == 0);
            REQUIRE(reference_insphere(p[0], p[1], p[2], p[3], p[4]) == 0);
            const int o = orient3d(p[0], p[1], p[2], p[3], counters);
            REQUIRE(o == reference_orient3d(p[0], p[1], p[2], p[3]));
            REQUIRE(insphere_sos(p[0], p[1], p[2], p[3], p[4], counters) == reference_insphere_sos(p));
            if (o == 0) continue;
            // One grain away from the centre leaves the sphere: outside, so the sign is -o; towards it, o.
            const int axis = finest_axis(p[4], r[2]);
            REQUIRE(axis >= 0);
            for (const bool outward : {true, false}) {
                Point moved = p[4];
                moved.c[axis] += ((moved.c[axis] > 0) == outward ? 1 : -1) * grain;
                const int s = insphere_exact(p[0], p[1], p[2], p[3], moved, counters);
                REQUIRE(s == (outward ? -o : o));
                REQUIRE(s == reference_insphere(p[0], p[1], p[2], p[3], moved));
                ++decided;
            }
        }
    }
    CHECK(decided > 2000);
}

TEST_CASE("exactly coplanar points of every width: zero, and one grain off decided exactly") {
    Random random(22);
    PredicateCounters counters;
    int decided = 0;
    for (int width = 1; width <= 198; ++width) {
        double r[3];
        wide_vector(random, width, r);
        // On the plane x = y (or y = z, or z = x): every coordinate value is +-x, +-y or +-z.
        const int plane = width % 3;
        std::vector<Point> points;
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) {
                const double same = (i % 2 ? -1 : 1) * r[i / 2], other = (j % 2 ? -1 : 1) * r[j / 2];
                Point p;
                p.c[plane] = p.c[(plane + 1) % 3] = same;
                p.c[(plane + 2) % 3] = other;
                points.push_back(p);
            }
        const double grain = ldexp(1.0, -(width + 1));
        for (int trial = 0; trial < 12; ++trial) {
            Point p[4];
            draw_distinct(random, points, 4, p);
            REQUIRE(orient3d(p[0], p[1], p[2], p[3], counters) == 0);
            // One grain off the plane: moves one of the two equal coordinates, where they are +-z.
            const int axis = plane;
            if (fabs(p[3].c[axis]) != r[2]) continue;
            for (const double step : {grain, -grain}) {
                Point moved = p[3];
                moved.c[axis] += step;
                const int s = orient3d(p[0], p[1], p[2], moved, counters);
                REQUIRE(s == reference_orient3d(p[0], p[1], p[2], moved));
                if (reference_orient3d(p[0], p[1], p[2], p[3]) == 0 && s != 0) ++decided;
            }
        }
    }
    CHECK(decided > 300);
}

TEST_CASE("exactly cocircular points of every width: incircle3d_sos is the limit of insphere_sos, one grain off decides") {
    Random random(23);
    PredicateCounters counters;
    int checked = 0, decided = 0;
    for (int width = 1; width <= 198; ++width) {
        double r[3];
        wide_vector(random, width, r);
        // The circle of radius |(x, z)| in the plane through the origin normal to one axis.
        const int normal = width % 3, u = (normal + 1) % 3, v = (normal + 2) % 3;
        std::vector<Point> circle;
        for (int swap = 0; swap < 2; ++swap)
            for (int signs = 0; signs < 4; ++signs) {
                Point p;
                p.c[normal] = 0;
                p.c[u] = (signs & 1 ? -1 : 1) * (swap ? r[2] : r[0]);
                p.c[v] = (signs & 2 ? -1 : 1) * (swap ? r[0] : r[2]);
                circle.push_back(p);
            }
        const double grain = ldexp(1.0, -(width + 1));
        for (int trial = 0; trial < 12; ++trial) {
            Point p[4];
            draw_distinct(random, circle, 4, p);
            const int answer = incircle3d_sos(p[0], p[1], p[2], p[3], counters);
            REQUIRE(answer != 0);  // three distinct points of a circle are never collinear
            Point q;
            q.c[normal] = trial % 2 ? 0.25 : -0.375;
            q.c[u] = q.c[v] = 0.125;
            const int o = orient3d(p[0], p[1], p[2], q, counters);
            REQUIRE(o != 0);
            REQUIRE(insphere_exact(p[0], p[1], p[2], q, p[3], counters) == 0);
            REQUIRE(insphere_sos(p[0], p[1], p[2], q, p[3], counters) * o == answer);
            ++checked;
            const int axis = finest_axis(p[3], r[2]);
            REQUIRE(axis >= 0);
            for (const bool outward : {true, false}) {
                Point moved = p[3];
                moved.c[axis] += ((moved.c[axis] > 0) == outward ? 1 : -1) * grain;
                REQUIRE(incircle3d_sos(p[0], p[1], p[2], moved, counters) == (outward ? -1 : 1));
                REQUIRE(reference_incircle3d(p[0], p[1], p[2], moved) == (outward ? -1 : 1));
                ++decided;
            }
        }
    }
    CHECK(checked > 2000);
    CHECK(decided == 2 * checked);
}

TEST_CASE("the exact stage is scale-free: signs and cofactors unchanged from 2^-1000 to 2^900 times the points") {
    // The radius-5 sphere (all cospherical, many coplanar) and a small lattice, so that zeros are common.
    std::vector<Point> points = radius5_sphere();
    Random random(25);
    for (int i = 0; i < 20; ++i) points.push_back(lattice_point(random, -3, 3));
    int zeros = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        Point p[5];
        for (Point& q : p) q = points[random.next() % points.size()];
        int orientations[5] = {9, 9, 9, 9, 9}, circle[4] = {9, 9, 9, 9};
        const int o = exact::orient3d(p[0], p[1], p[2], p[3]);
        const int s = exact::insphere(p[0], p[1], p[2], p[3], p[4], orientations);
        const int c = exact::incircle_lifted(p[0], p[1], p[2], p[3], 0, 2, circle);
        const int o2 = exact::orient2d(p[0], p[1], p[2], 1, 2);
        REQUIRE(o == reference_orient3d(p[0], p[1], p[2], p[3]));
        REQUIRE(s == reference_insphere(p[0], p[1], p[2], p[3], p[4]));
        REQUIRE(c == reference_incircle_lifted(p[0], p[1], p[2], p[3], 0, 2));
        REQUIRE(o2 == reference_orient2d(p[0], p[1], p[2], 1, 2));
        zeros += s == 0;
        for (const int exponent : {-1000, -600, -200, -60, 60, 200, 600, 900}) {
            CAPTURE(exponent);
            Point q[5];
            for (int i = 0; i < 5; ++i)
                for (int k = 0; k < 3; ++k) q[i].c[k] = ldexp(p[i].c[k], exponent);
            int scaled_orientations[5] = {9, 9, 9, 9, 9}, scaled_circle[4] = {9, 9, 9, 9};
            REQUIRE(exact::orient3d(q[0], q[1], q[2], q[3]) == o);
            REQUIRE(exact::insphere(q[0], q[1], q[2], q[3], q[4], scaled_orientations) == s);
            REQUIRE(exact::incircle_lifted(q[0], q[1], q[2], q[3], 0, 2, scaled_circle) == c);
            REQUIRE(exact::orient2d(q[0], q[1], q[2], 1, 2) == o2);
            if (s == 0)
                for (int i = 0; i < 5; ++i) REQUIRE(scaled_orientations[i] == orientations[i]);
            if (c == 0)
                for (int i = 0; i < 4; ++i) REQUIRE(scaled_circle[i] == circle[i]);
        }
    }
    CHECK(zeros > 300);
}

TEST_CASE("the exact stage at the limits of each of its integer types") {
    // Corners of the box [-x, x] x [-y, y] x [-z, z] beside q = (g, 0, 0): the differences to q reach
    // 2^width - 1 units of g, the most the integer type chosen for that width must hold, and their
    // determinants come near the largest the type was sized for. The box's eight corners are cospherical
    // and each face's four cocircular; q lies inside both. Unequal sides keep wrapped values from
    // cancelling by accident.
    for (const int width : {5, 11, 12, 13, 40, 61, 62, 63, 64, 100, 125, 126, 127, 128, 129, 200, 253, 254}) {
        for (const double depth : {0.375, 0.6875, 0.9375}) {
            CAPTURE(width);
            CAPTURE(depth);
            const double g = ldexp(1.0, -width);
            const double ulp = width <= 54 ? g : ldexp(1.0, -53);
            const double x = 1 - 2 * ulp, y = 1 - 6 * ulp, z = depth - ulp;  // x + g < 1 = 2^top
            const double a[3] = {x, y, z}, b[3] = {x, -y, -z}, c[3] = {-x, y, -z}, d[3] = {-x, -y, z};
            const double q[3] = {g, 0, 0}, corner[3] = {-x, -y, -z}, face_corner[3] = {x, -y, z};
            REQUIRE(exact::orient3d(a, b, c, d) == 1);
            REQUIRE(exact::orient3d(b, a, c, d) == -1);
            REQUIRE(exact::orient3d(a, b, c, q) == 1);  // q is on the side of the plane abc where d is
            int orientations[5];
            REQUIRE(exact::insphere(a, b, c, d, q, orientations) == 1);
            REQUIRE(exact::insphere(b, a, c, d, q, orientations) == -1);
            REQUIRE(exact::insphere(a, b, c, d, corner, orientations) == 0);
            for (int i = 0; i < 5; ++i) {
                const double* points[5] = {a, b, c, d, corner};
                const double* other[4];
                for (int j = 0, k = 0; j < 5; ++j)
                    if (j != i) other[k++] = points[j];
                REQUIRE(orientations[i] == exact::orient3d(other[0], other[1], other[2], other[3]));
            }
            // The face at x: (x, y, z), (x, -y, -z), (x, y, -z) and (x, -y, z); q moved onto it stays inside.
            const double f1[3] = {x, y, z}, f2[3] = {x, -y, -z}, f3[3] = {x, y, -z}, on_face[3] = {x, g, 0};
            const int turn = exact::orient2d(f1, f2, f3, 1, 2);
            REQUIRE(turn != 0);
            REQUIRE(exact::incircle_lifted(f1, f2, f3, on_face, 1, 2, orientations) == turn);
            REQUIRE(exact::incircle_lifted(f1, f2, f3, face_corner, 1, 2, orientations) == 0);
        }
    }
}

namespace {

// How often the lattice stage answered and how often it left a call to the integer stage.
struct LatticeTally {
    int decided = 0, declined = 0;
};

// Each answer of the lattice stage against the integer stage's on the same points: the same sign, and for
// a zero the same perturbation cofactors; orientations untouched when it declines.
void check_lattice_stage(const Point* q, LatticeTally& tally) {
    const auto count = [&tally](int sign) {
        ++(sign == exact::NOT_ON_LATTICE ? tally.declined : tally.decided);
        return sign != exact::NOT_ON_LATTICE;
    };
    const int o = exact::orient3d_on_lattice(q[0], q[1], q[2], q[3]);
    if (count(o)) REQUIRE(o == exact::orient3d(q[0], q[1], q[2], q[3]));
    const int o2 = exact::orient2d_on_lattice(q[0], q[1], q[2], 2, 0);
    if (count(o2)) REQUIRE(o2 == exact::orient2d(q[0], q[1], q[2], 2, 0));

    int lattice[5] = {9, 9, 9, 9, 9}, integer[5] = {9, 9, 9, 9, 9};
    const int s = exact::insphere_on_lattice(q[0], q[1], q[2], q[3], q[4], lattice);
    if (count(s)) {
        REQUIRE(s == exact::insphere(q[0], q[1], q[2], q[3], q[4], integer));
        for (int i = 0; i < 5; ++i) REQUIRE(lattice[i] == integer[i]);
    } else {
        for (int i = 0; i < 5; ++i) REQUIRE(lattice[i] == 9);
    }
    int lattice_circle[4] = {9, 9, 9, 9}, integer_circle[4] = {9, 9, 9, 9};
    const int c = exact::incircle_lifted_on_lattice(q[0], q[1], q[2], q[3], 1, 2, lattice_circle);
    if (count(c)) {
        REQUIRE(c == exact::incircle_lifted(q[0], q[1], q[2], q[3], 1, 2, integer_circle));
        for (int i = 0; i < 4; ++i) REQUIRE(lattice_circle[i] == integer_circle[i]);
    }
}

// Three integers below 2^bits, the first with its top bit set.
void integer_vector(Random& random, int bits, double r[3]) {
    const uint64_t top = uint64_t(1) << (bits - 1);
    r[0] = static_cast<double>(top | (random.next() & (top - 1)));
    r[1] = static_cast<double>(random.next() & (2 * top - 1));
    r[2] = static_cast<double>(random.next() & (2 * top - 1));
}

} // namespace

TEST_CASE("the lattice stage gives the integer stage's signs and cofactors, 2^-500 to 2^500 times the points") {
    // Signed permutations of an integer vector (cospherical), those of them in the plane x = y (coplanar)
    // and with x = 0 (cocircular on a sphere), about an integer centre, some moved by one unit: exact
    // zeros and the smallest non-zero values, with differences up to 2^19 units, beyond the widest the
    // stage takes for each determinant. Then scaled: the stage works for units from 2^-214 (insphere) to 1.
    Random random(26);
    LatticeTally tally, at_unit_scale;
    for (int bits = 1; bits <= 18; ++bits) {
        CAPTURE(bits);
        double r[3];
        integer_vector(random, bits, r);
        std::vector<Point> sphere = signed_permutations(r), plane, circle;
        // Zeros among r repeat points: keep one of each.
        const auto before = [](const Point& a, const Point& b) { return compare_points(a, b) < 0; };
        const auto same = [](const Point& a, const Point& b) { return compare_points(a, b) == 0; };
        std::sort(sphere.begin(), sphere.end(), before);
        sphere.erase(std::unique(sphere.begin(), sphere.end(), same), sphere.end());
        for (const Point& p : sphere) {
            if (p.c[0] == p.c[1]) plane.push_back(p);
            if (p.c[0] == 0) circle.push_back(p);
        }
        for (int trial = 0; trial < 60; ++trial) {
            Point p[5];
            const std::vector<Point>& set = trial % 3 == 0 ? sphere : trial % 3 == 1 ? plane : circle;
            if (set.size() < 5) continue;
            draw_distinct(random, set, 5, p);
            if (trial % 2 == 1) p[random.next() % 5].c[random.next() % 3] += 1;
            const double centre[3] = {double(random.integer(-1000, 1000)), double(random.integer(-1000, 1000)), 0};
            for (Point& q : p)
                for (int k = 0; k < 3; ++k) q.c[k] += centre[k];
            check_lattice_stage(p, at_unit_scale);
            for (const int exponent : {-500, -300, -214, -200, -100, -20, -9, 9, 40, 500}) {
                CAPTURE(exponent);
                Point q[5];
                for (int i = 0; i < 5; ++i)
                    for (int k = 0; k < 3; ++k) q[i].c[k] = ldexp(p[i].c[k], exponent);
                check_lattice_stage(q, tally);
            }
        }
    }
    // Taken at some widths and scales, left to the integer stage at others.
    CHECK(at_unit_scale.decided > 1000);
    CHECK(tally.decided > 4000);
    CHECK(tally.declined > 4000);
}

TEST_CASE("the lattice stage at the edge of its widths: exact zeros of full-significand integers") {
    // Integer points on spheres of radius 2^7 to 2^14 (differences to either side of insphere's width,
    // 2^9 units) and on planes spanned by random integer vectors of 2^13 to 2^18 (either side of
    // orient3d's, 2^16): their determinants' terms have all their bits, so a width far too large for
    // doubles turns the exact zeros into rounding noise. The widths' bounds are worst cases, a few bits
    // above the values these reach: a width one or two too large passes here.
    Random random(28);
    LatticeTally tally;
    for (int bits = 7; bits <= 14; ++bits) {
        // (2 (m q + n p), 2 (n q - m p), m^2 + n^2 - p^2 - q^2) has length m^2 + n^2 + p^2 + q^2 (Euler's
        // four-square identity): many full-bit points of one sphere from the ways to write its radius.
        const int radius = (1 << bits) + random.integer(0, 1 << (bits - 2));
        std::vector<Point> sphere;
        const int bound = static_cast<int>(sqrt(double(radius)));
        for (int m = 0; m <= bound; ++m)
            for (int n = -bound; n <= bound; ++n)
                for (int q = -bound; q <= bound; ++q) {
                    const int rest = radius - m * m - n * n - q * q;
                    const int p = rest < 0 ? -1 : static_cast<int>(sqrt(double(rest)) + 0.5);
                    if (p < 0 || p * p != rest) continue;
                    sphere.push_back(Point{{2.0 * (m * q + n * p), 2.0 * (n * q - m * p), double(m * m + n * n - p * p - q * q)}});
                }
        std::sort(sphere.begin(), sphere.end(), [](const Point& a, const Point& b) { return compare_points(a, b) < 0; });
        sphere.erase(std::unique(sphere.begin(), sphere.end(), [](const Point& a, const Point& b) { return compare_points(a, b) == 0; }),
                     sphere.end());
        REQUIRE(sphere.size() >= 20);
        for (int trial = 0; trial < 400; ++trial) {
            Point p[5];
            draw_distinct(random, sphere, 5, p);
            check_lattice_stage(p, tally);
        }
    }
    for (int bits = 13; bits <= 18; ++bits) {
        double a[3], b[3];
        integer_vector(random, bits, a);
        integer_vector(random, bits, b);
        for (int trial = 0; trial < 400; ++trial) {
            Point p[5];
            for (int i = 0; i < 5; ++i) {
                // Four on the plane through the origin spanned by a and b, the fifth anywhere near.
                const int s = random.integer(-1, 1), t = random.integer(-1, 1);
                for (int k = 0; k < 3; ++k) p[i].c[k] = i < 4 ? s * a[k] + t * b[k] : double(random.integer(-1000, 1000));
            }
            check_lattice_stage(p, tally);
        }
    }
    CHECK(tally.decided > 2000);
    CHECK(tally.declined > 2000);
}

TEST_CASE("the public predicates on a grid: exact zeros decided on the lattice, as the reference decides them") {
    // The integer points of a 5^3 cube times 2^-3 and times 2^-190 (multiples of 2^-200 either way):
    // cospherical, coplanar and cocircular everywhere.
    Random random(27);
    for (const int exponent : {-3, -190}) {
        CAPTURE(exponent);
        PredicateCounters counters;
        for (int trial = 0; trial < 4000; ++trial) {
            Point u[5];
            do {
                for (Point& q : u) q = lattice_point(random, -2, 2);
            } while (!distinct(u, 5));
            Point p[5];
            for (int i = 0; i < 5; ++i)
                for (int k = 0; k < 3; ++k) p[i].c[k] = ldexp(u[i].c[k], exponent);
            REQUIRE(orient3d(p[0], p[1], p[2], p[3], counters) == reference_orient3d(p[0], p[1], p[2], p[3]));
            REQUIRE(insphere_exact(p[0], p[1], p[2], p[3], p[4], counters) ==
                    reference_insphere(p[0], p[1], p[2], p[3], p[4]));
            REQUIRE(insphere_sos(p[0], p[1], p[2], p[3], p[4], counters) == reference_insphere_sos(p));
            if (reference_orient3d(u[0], u[1], u[2], u[3]) == 0 && !points_collinear(u[0], u[1], u[2], counters)) {
                // Coplanar: incircle3d_sos is the limit of the explicit perturbation with a point q off the plane.
                Point q;
                do q = lattice_point(random, -8, 8);
                while (reference_orient3d(u[0], u[1], u[2], q) == 0);
                REQUIRE(incircle3d_sos(p[0], p[1], p[2], p[3], counters) == brute_force_incircle3d_sos(u[0], u[1], u[2], u[3], q));
            }
        }
        // Nearly all exact work was done on the lattice.
        CHECK(counters.filter_failures > 500);
        CHECK(counters.lattice * 10 >= counters.filter_failures * 9);
    }
}

TEST_CASE("tetrahedralizations with exactly cospherical, cocircular and coplanar sets 2^-20 to 2^-150 small are Delaunay") {
    // Beside a unit cloud, so that the conditioned coordinates of the small sets span up to about 190 bits.
    const int scales[][2] = {{20, 40}, {60, 100}, {100, 80}, {150, 30}, {180, 8}};  // (2^-k, width)
    Random random(24);
    for (const auto& scale_and_width : scales) {
        const int k = scale_and_width[0], width = scale_and_width[1];
        CAPTURE(k);
        std::vector<double> xyz;
        for (int i = 0; i < 24; ++i) xyz.insert(xyz.end(), {random.unit(), random.unit(), random.unit()});
        double r[3];
        wide_vector(random, width, r);
        const std::vector<Point> sphere = signed_permutations(r);
        for (size_t i = 0; i < sphere.size(); i += 2)
            for (int c = 0; c < 3; ++c) xyz.push_back(ldexp(sphere[i].c[c], -k));
        // A circle and a 3x3 grid in the plane z = 2^-k r_x (exactly), off the sphere's centre.
        for (int signs = 0; signs < 4; ++signs)
            xyz.insert(xyz.end(), {ldexp((signs & 1 ? -1 : 1) * r[0], -k), ldexp((signs & 2 ? -1 : 1) * r[2], -k), ldexp(r[0], -k)});
        for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j) xyz.insert(xyz.end(), {ldexp(i * r[2], -k), ldexp(j * r[1], -k), ldexp(r[0], -k)});

        const dbrg_params params = dbrg_test::test_params();
        Context context(params);
        ConditionedPoints points(context.memory);
        REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
        Tetrahedralization tets(context.memory);
        REQUIRE(tets.build(points.coordinates.data(), points.size(), context) == DBRG_OK);
        char message[256];
        REQUIRE_MESSAGE(tets.validate(message, sizeof message), message);
        // No point lies strictly inside the circumsphere of a tetrahedron, by the reference's determinants.
        int strictly_inside = 0, on_sphere = 0;
        for (uint32_t t = 0; t < tets.tet_slots(); ++t) {
            if (tets.tet_is_free(t) || !tets.tet_is_finite(t)) continue;
            const double* corner[4];
            for (uint32_t lv = 0; lv < 4; ++lv) corner[lv] = points.point(tets.tet_vertex(t, lv));
            REQUIRE(reference_orient3d(corner[0], corner[1], corner[2], corner[3]) == 1);
            for (uint32_t v = 0; v < points.size(); ++v) {
                if (tets.tet_local_index(t, v) < 4) continue;
                const int s = reference_insphere(corner[0], corner[1], corner[2], corner[3], points.point(v));
                strictly_inside += s > 0;
                on_sphere += s == 0;
            }
        }
        CHECK(strictly_inside == 0);
        CHECK(on_sphere > 0);
    }
}

TEST_CASE("counters count calls, filter failures and perturbations") {
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, 0, -1};
    const double centre[3] = {0.25, 0.25, -0.25}, corner[3] = {1, 1, -1}, coplanar[3] = {1, 1, 0};
    PredicateCounters counters;
    CHECK(orient3d(a, b, c, d, counters) == 1);
    CHECK((counters.calls == 1 && counters.filter_failures == 0 && counters.perturbations == 0));
    CHECK(orient3d(a, b, c, coplanar, counters) == 0);
    CHECK((counters.calls == 2 && counters.filter_failures == 1 && counters.perturbations == 0));
    CHECK(insphere_exact(a, b, c, d, corner, counters) == 0);
    CHECK((counters.calls == 3 && counters.filter_failures == 2 && counters.perturbations == 0));
    CHECK(insphere_sos(a, b, c, d, centre, counters) == 1);
    CHECK((counters.calls == 4 && counters.filter_failures == 2 && counters.perturbations == 0));
    CHECK(insphere_sos(a, b, c, d, corner, counters) != 0);
    CHECK((counters.calls == 5 && counters.filter_failures == 3 && counters.perturbations == 1));
    CHECK(incircle3d_sos(a, b, c, coplanar, counters) != 0);
    CHECK((counters.calls == 6 && counters.filter_failures == 4 && counters.perturbations == 2));
    PredicateCounters other;
    CHECK(other.calls == 0);
}
