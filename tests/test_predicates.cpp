// Tests of the geometric predicates against an independent exact reference: coordinates are turned into
// integers (every test coordinate is a multiple of 2^-120) and determinants are expanded by cofactors in a
// small fixed-width two's-complement integer type, with symbolic perturbations made explicit.
#include <doctest/doctest.h>

#include <math.h>
#include <stdint.h>

#include <algorithm>
#include <vector>

#include "core/splitmix64.h"
#include "predicates/expansion.h"
#include "predicates/filters.h"
#include "predicates/predicates.h"

using namespace dbrg;

namespace {

// A signed integer of 24 x 32 bits in two's complement; products are taken modulo 2^768, which is exact
// while the true values stay below 2^767 (the tests stay below 2^640).
struct Big {
    static const int LIMBS = 24;
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

Big operator*(const Big& a, const Big& b) {
    Big r = big(0);
    for (int i = 0; i < Big::LIMBS; ++i) {
        uint64_t carry = 0;
        for (int j = 0; i + j < Big::LIMBS; ++j) {
            const uint64_t t = uint64_t(a.limb[i]) * b.limb[j] + r.limb[i + j] + carry;
            r.limb[i + j] = static_cast<uint32_t>(t);
            carry = t >> 32;
        }
    }
    return r;
}

int sign(const Big& a) {
    if (a.limb[Big::LIMBS - 1] >> 31) return -1;
    for (int i = 0; i < Big::LIMBS; ++i)
        if (a.limb[i]) return 1;
    return 0;
}

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
Big fixed(double x, int scale = 120) {
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
// many of their differences (1 - 2^-60) are not representable, which forces the raw-coordinate fallback.
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

TEST_CASE("points whose differences are inexact use the raw-coordinate fallback exactly") {
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
            const double angle = 3.141592653589793 * random.unit();
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

// Whether the components of e are non-zero (but for a lone zero), increase in magnitude and do not overlap:
// each one is a multiple of a power of two larger than the previous one's magnitude.
bool well_formed(const double* e, int n) {
    for (int i = 0; i < n; ++i) {
        if (e[i] == 0 && n > 1) return false;
        if (i == 0) continue;
        int exponent;
        frexp(e[i - 1], &exponent);  // |e[i - 1]| < 2^exponent
        if (fmod(e[i], ldexp(1.0, exponent)) != 0) return false;
    }
    return true;
}

Big big_sum(const double* e, int n, int scale) {
    Big total = big(0);
    for (int i = 0; i < n; ++i) total = total + fixed(e[i], scale);
    return total;
}

bool equal(const Big& a, const Big& b) { return sign(a - b) == 0; }

TEST_CASE("expansion arithmetic is exact") {
    Random random(12);
    // Full significands over a wide range of exponents (multiples of 2^-113), so that most roundings matter.
    auto value = [&]() { return ldexp(random.unit(), -random.integer(0, 60)); };
    for (int trial = 0; trial < 20000; ++trial) {
        const double a = value(), b = value(), c = value(), d = value();
        double hi, lo;
        expansion::two_product(a, b, hi, lo);
        REQUIRE(hi == a * b);
        REQUIRE(equal((fixed(hi, 240) + fixed(lo, 240)), fixed(a, 120) * fixed(b, 120)));
        expansion::two_sum(a, b, hi, lo);
        REQUIRE(hi == a + b);
        REQUIRE(equal(fixed(hi) + fixed(lo), fixed(a) + fixed(b)));

        double h4[4];
        const int n4 = expansion::product_difference(a, b, c, d, h4);
        REQUIRE(well_formed(h4, n4));
        REQUIRE(equal(big_sum(h4, n4, 240), fixed(a) * fixed(b) - fixed(c) * fixed(d)));

        double h6[6];
        const int n6 = expansion::squared_norm(a, b, c, h6);
        REQUIRE(well_formed(h6, n6));
        REQUIRE(equal(big_sum(h6, n6, 240), fixed(a) * fixed(a) + fixed(b) * fixed(b) + fixed(c) * fixed(c)));

        // (a b - c d) * (a^2 + b^2 + c^2) through scale, sum and the accumulator.
        double scaled[8];
        const int n_scaled = expansion::scale(h4, n4, d, scaled);
        REQUIRE(well_formed(scaled, n_scaled));
        REQUIRE(equal(big_sum(scaled, n_scaled, 360), (fixed(a) * fixed(b) - fixed(c) * fixed(d)) * fixed(d)));
        double summed[12];
        const int n_summed = expansion::sum(h4, n4, h6, n6, summed);
        REQUIRE(well_formed(summed, n_summed));
        REQUIRE(equal(big_sum(summed, n_summed, 240), big_sum(h4, n4, 240) + big_sum(h6, n6, 240)));
        expansion::Accumulator<48> product;
        product.add_product<8>(h4, n4, h6, n6);
        const Big expected = big_sum(h4, n4, 240) * big_sum(h6, n6, 240);
        REQUIRE(product.sign() == sign(expected));
    }
    double zero[1] = {0};
    CHECK(expansion::sign(zero, 1) == 0);
    expansion::Accumulator<4> empty;
    CHECK(empty.sign() == 0);
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
