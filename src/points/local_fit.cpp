// Local fit: the normal of least variance from the covariance's characteristic cubic, then a least-squares
// quadric height function over the tangent plane (normal equations, square-root-free Cholesky).
#include "points/local_fit.h"

#include <math.h>

namespace dbrg {
namespace {

// Unit vectors u and v that make (u, v, n) orthonormal, for a unit vector n, without a square root (the
// rotation taking the z axis to n applied to the x and y axes; T. Duff et al., "Building an orthonormal basis,
// revisited", JCGT 6(1), 2017).
void orthonormal_basis(Vec3 n, Vec3& u, Vec3& v) {
    const double sign = n.z >= 0 ? 1.0 : -1.0;
    const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    u = Vec3{1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    v = Vec3{b, sign + n.y * n.y * a, -n.y};
}

// The smallest eigenvalue of the symmetric positive semidefinite matrix `a` (a covariance) and a unit
// eigenvector of it. The eigenvalue is the smallest root of the characteristic cubic, by Newton's method from 0:
// left of that root the cubic rises and is concave, so each step stays left of the root and comes closer (a
// point cloud about a surface has one eigenvalue far below the others, reached in two or three steps). The
// rows of a - eigenvalue I span the plane orthogonal to the eigenvector: their largest cross product is it.
// Where the eigenvalues are too close to tell apart, it is a unit vector orthogonal to the largest ones'.
Vec3 least_eigenvector(const double a[3][3], double& value) {
    const double trace = a[0][0] + a[1][1] + a[2][2];
    const Vec3 r0{a[0][0], a[0][1], a[0][2]}, r1{a[1][0], a[1][1], a[1][2]}, r2{a[2][0], a[2][1], a[2][2]};
    // The sum of the eigenvalues' products by pairs, and their product.
    const double pairs = a[0][0] * a[1][1] - a[0][1] * a[0][1] + a[0][0] * a[2][2] - a[0][2] * a[0][2] +
                         a[1][1] * a[2][2] - a[1][2] * a[1][2];
    const double determinant = dot(r0, cross(r1, r2));
    value = 0;
    // Pairs below rounding of trace^2: the points lie on a line (or on one spot); the Newton steps would
    // divide rounding by rounding.
    const bool line = !(pairs > 1e-12 * trace * trace);
    // A double or triple root slows Newton to cutting the distance by 1/2 or 1/3 a step: the eigenvector is
    // then arbitrary within the eigenspace anyway, and 64 steps leave the eigenvalue within 1e-11 of it.
    for (int step = 0; step < 64 && !line; ++step) {
        const double polynomial = ((value - trace) * value + pairs) * value - determinant;
        const double slope = (3 * value - 2 * trace) * value + pairs;
        if (!(polynomial < 0 && slope > 0)) break;
        const double next = value - polynomial / slope;
        // The smallest eigenvalue is at most the mean: beyond it, a step is rounding.
        if (!(next > value && next <= trace / 3)) break;
        value = next;
    }
    const Vec3 rows[3] = {{r0.x - value, r0.y, r0.z}, {r1.x, r1.y - value, r1.z}, {r2.x, r2.y, r2.z - value}};
    Vec3 best{0, 0, 0};
    double best_squared = 0, best_rows_squared = 0;
    for (int i = 0; i < 2; ++i) {
        for (int j = i + 1; j < 3; ++j) {
            const Vec3 c = cross(rows[i], rows[j]);
            if (squared_length(c) > best_squared) {
                best = c;
                best_squared = squared_length(c);
                best_rows_squared = squared_length(rows[i]) * squared_length(rows[j]);
            }
        }
    }
    // Rows parallel to within 1e-8 radians: their cross product is mostly rounding. The points then lie on a
    // line to within a 1e-4 of its length, and any vector orthogonal to it will do.
    if (!line && best_squared > 1e-16 * best_rows_squared) return normalized(best);
    int longest = 0;
    for (int r = 1; r < 3; ++r) {
        if (squared_length(rows[r]) > squared_length(rows[longest])) longest = r;
    }
    if (!(squared_length(rows[longest]) > 0)) return Vec3{0, 0, 1};
    Vec3 u, v;
    orthonormal_basis(normalized(rows[longest]), u, v);
    return u;
}

constexpr int TERMS = 6;

// Solves m x = b for a symmetric positive definite m by its factors L D L^T (L unit lower triangular, no
// square roots); false when m is not (numerically) positive definite.
bool solve_cholesky(double m[TERMS][TERMS], const double b[TERMS], double x[TERMS]) {
    double largest = 0;
    for (int i = 0; i < TERMS; ++i) largest = fmax(largest, m[i][i]);
    double pivot[TERMS], inverse[TERMS];
    for (int j = 0; j < TERMS; ++j) {
        // Row j of L D, in the strict lower triangle, before it is divided by the pivots.
        double scaled[TERMS];
        double d = m[j][j];
        for (int k = 0; k < j; ++k) {
            scaled[k] = m[j][k] * pivot[k];
            d -= m[j][k] * scaled[k];
        }
        // A pivot this small relative to the largest diagonal entry: the points do not determine the term.
        if (!(d > 1e-10 * largest)) return false;
        pivot[j] = d;
        inverse[j] = 1.0 / d;
        for (int i = j + 1; i < TERMS; ++i) {
            double s = m[i][j];
            for (int k = 0; k < j; ++k) s -= m[i][k] * scaled[k];
            m[i][j] = s * inverse[j];
        }
    }
    for (int i = 0; i < TERMS; ++i) {
        double s = b[i];
        for (int k = 0; k < i; ++k) s -= m[i][k] * x[k];
        x[i] = s;
    }
    for (int i = TERMS - 1; i >= 0; --i) {
        double s = x[i] * inverse[i];
        for (int k = i + 1; k < TERMS; ++k) s -= m[k][i] * x[k];
        x[i] = s;
    }
    return true;
}

} // namespace

// The offsets are from the point fitted around: it is the origin throughout.
LocalFit fit_local_quadric(const Vec3* points, uint32_t count) {
    Vec3 centroid{0, 0, 0};
    for (uint32_t i = 0; i < count; ++i) centroid = centroid + points[i];
    centroid = (1.0 / count) * centroid;
    double covariance[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double mean_distance = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 d = points[i] - centroid;
        covariance[0][0] += d.x * d.x;
        covariance[0][1] += d.x * d.y;
        covariance[0][2] += d.x * d.z;
        covariance[1][1] += d.y * d.y;
        covariance[1][2] += d.y * d.z;
        covariance[2][2] += d.z * d.z;
        mean_distance += length(points[i]);
    }
    covariance[1][0] = covariance[0][1];
    covariance[2][0] = covariance[0][2];
    covariance[2][1] = covariance[1][2];
    mean_distance /= count;
    double least = 0;
    const Vec3 normal = least_eigenvector(covariance, least);
    LocalFit plane{normal, dot(centroid, normal), sqrt(least / count)};
    if (count < TERMS || !(mean_distance > 0)) return plane;
    // Any orthonormal tangent axes give the same quadric: its terms span all polynomials of degree 2 in them.
    Vec3 u, v;
    orthonormal_basis(normal, u, v);

    // Tangent coordinates in units of the mean distance, so the normal equations are well scaled. Their
    // entries are sums of the monomials x^i y^j up to degree 4, and of z x^i y^j up to degree 2.
    const double unit = 1.0 / mean_distance;
    const Vec3 su = unit * u, sv = unit * v, sn = unit * normal;
    double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, sxxx = 0, sxxy = 0, sxyy = 0, syyy = 0;
    double sxxxx = 0, sxxxy = 0, sxxyy = 0, sxyyy = 0, syyyy = 0;
    double b[TERMS] = {}, szz = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const double x = dot(points[i], su), y = dot(points[i], sv), z = dot(points[i], sn);
        const double xx = x * x, xy = x * y, yy = y * y;
        s1 += 1;
        sx += x;
        sy += y;
        sxx += xx;
        sxy += xy;
        syy += yy;
        sxxx += xx * x;
        sxxy += xx * y;
        sxyy += x * yy;
        syyy += y * yy;
        sxxxx += xx * xx;
        sxxxy += xx * xy;
        sxxyy += xx * yy;
        sxyyy += xy * yy;
        syyyy += yy * yy;
        b[0] += z;
        b[1] += x * z;
        b[2] += y * z;
        b[3] += xx * z;
        b[4] += xy * z;
        b[5] += yy * z;
        szz += z * z;
    }
    // Terms 1, x, y, x^2, xy, y^2.
    double m[TERMS][TERMS] = {{s1, sx, sy, sxx, sxy, syy},
                              {sx, sxx, sxy, sxxx, sxxy, sxyy},
                              {sy, sxy, syy, sxxy, sxyy, syyy},
                              {sxx, sxxx, sxxy, sxxxx, sxxxy, sxxyy},
                              {sxy, sxxy, sxyy, sxxxy, sxxyy, sxyyy},
                              {syy, sxyy, syyy, sxxyy, sxyyy, syyyy}};
    double c[TERMS];
    if (!solve_cholesky(m, b, c)) return plane;
    // The least-squares residual: sum z^2 - c . b (rounding, where the fit is near exact, is far below any
    // level the cleaning compares it with).
    double squares = szz;
    for (int r = 0; r < TERMS; ++r) squares -= c[r] * b[r];
    squares = fmax(squares, 0.0);
    return LocalFit{normal, mean_distance * c[0], mean_distance * sqrt(squares / count)};
}

} // namespace dbrg
