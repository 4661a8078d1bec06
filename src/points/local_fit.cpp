// Local fit: principal components by Jacobi rotations, then a least-squares quadric height function over the
// tangent plane (normal equations, Cholesky).
#include "points/local_fit.h"

#include <math.h>

namespace dbrg {
namespace {

// Eigenvalues (ascending) and unit eigenvectors (columns of `vectors`) of the symmetric 3x3 matrix `a`, by
// cyclic Jacobi rotations: a handful of sweeps reach rounding level, and it needs no special cases.
void symmetric_eigen(double a[3][3], double values[3], double vectors[3][3]) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) vectors[i][j] = i == j ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (off <= 1e-30 * diagonal || off == 0.0) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < 3; ++k) {  // a <- a J (columns p and q)
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) {  // a <- J^T a (rows p and q)
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = vectors[k][p], vkq = vectors[k][q];
                    vectors[k][p] = c * vkp - s * vkq;
                    vectors[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (a[order[j]][order[j]] < a[order[i]][order[i]]) {
                const int swap = order[i];
                order[i] = order[j];
                order[j] = swap;
            }
    double sorted[3][3];
    for (int i = 0; i < 3; ++i) {
        values[i] = a[order[i]][order[i]];
        for (int k = 0; k < 3; ++k) sorted[k][i] = vectors[k][order[i]];
    }
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) vectors[k][i] = sorted[k][i];
}

constexpr int TERMS = 6;

// Solves m x = b for a symmetric positive definite m by Cholesky; false when m is not (numerically) so.
bool solve_cholesky(double m[TERMS][TERMS], double b[TERMS], double x[TERMS]) {
    double largest = 0;
    for (int i = 0; i < TERMS; ++i) largest = fmax(largest, m[i][i]);
    for (int j = 0; j < TERMS; ++j) {
        double d = m[j][j];
        for (int k = 0; k < j; ++k) d -= m[j][k] * m[j][k];
        // A pivot this small relative to the largest diagonal entry: the points do not determine the term.
        if (!(d > 1e-10 * largest)) return false;
        m[j][j] = sqrt(d);
        for (int i = j + 1; i < TERMS; ++i) {
            double s = m[i][j];
            for (int k = 0; k < j; ++k) s -= m[i][k] * m[j][k];
            m[i][j] = s / m[j][j];
        }
    }
    for (int i = 0; i < TERMS; ++i) {
        double s = b[i];
        for (int k = 0; k < i; ++k) s -= m[i][k] * x[k];
        x[i] = s / m[i][i];
    }
    for (int i = TERMS - 1; i >= 0; --i) {
        double s = x[i];
        for (int k = i + 1; k < TERMS; ++k) s -= m[k][i] * x[k];
        x[i] = s / m[i][i];
    }
    return true;
}

} // namespace

LocalFit fit_local_quadric(const Vec3* points, uint32_t count) {
    const Vec3 point{0, 0, 0};
    Vec3 centroid{0, 0, 0};
    for (uint32_t i = 0; i < count; ++i) centroid = centroid + points[i];
    centroid = (1.0 / count) * centroid;
    double covariance[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double mean_distance = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 d = points[i] - centroid;
        const double c[3] = {d.x, d.y, d.z};
        for (int r = 0; r < 3; ++r)
            for (int s = 0; s < 3; ++s) covariance[r][s] += c[r] * c[s];
        mean_distance += length(points[i] - point);
    }
    mean_distance /= count;
    double values[3], vectors[3][3];
    symmetric_eigen(covariance, values, vectors);
    const Vec3 normal{vectors[0][0], vectors[1][0], vectors[2][0]};
    const Vec3 u{vectors[0][1], vectors[1][1], vectors[2][1]}, v{vectors[0][2], vectors[1][2], vectors[2][2]};
    LocalFit plane{normal, dot(centroid - point, normal), sqrt(fmax(values[0], 0.0) / count)};
    if (count < TERMS || !(mean_distance > 0)) return plane;

    // Tangent coordinates in units of the mean distance, so the normal equations are well scaled.
    const double unit = 1.0 / mean_distance;
    double m[TERMS][TERMS] = {}, b[TERMS] = {};
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 d = points[i] - point;
        const double x = unit * dot(d, u), y = unit * dot(d, v), z = unit * dot(d, normal);
        const double terms[TERMS] = {1.0, x, y, x * x, x * y, y * y};
        for (int r = 0; r < TERMS; ++r) {
            b[r] += terms[r] * z;
            for (int s = 0; s <= r; ++s) m[r][s] += terms[r] * terms[s];
        }
    }
    for (int r = 0; r < TERMS; ++r)
        for (int s = r + 1; s < TERMS; ++s) m[r][s] = m[s][r];
    double c[TERMS];
    if (!solve_cholesky(m, b, c)) return plane;
    double squares = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 d = points[i] - point;
        const double x = unit * dot(d, u), y = unit * dot(d, v), z = unit * dot(d, normal);
        const double residual = z - (c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y);
        squares += residual * residual;
    }
    return LocalFit{normal, mean_distance * c[0], mean_distance * sqrt(squares / count)};
}

} // namespace dbrg
