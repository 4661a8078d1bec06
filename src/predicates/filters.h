// Semi-static floating-point filters: each evaluates a determinant in doubles together with a bound on its
// rounding error computed from the magnitudes of the coordinate differences, and reports a sign only when
// the bound proves it.
//
// Based on: A. Meyer and S. Pion, "FPG: A code generator for fast and certified geometric predicates"
// (2008), for the form of the bound (a constant times the product of the largest difference in each
// coordinate). The constants are derived here, not taken from there:
//
// With u = 2^-53, every operation on doubles rounds once, so a computed sum of monomials differs from the
// exact one by at most gamma_n * (sum of |monomials|), gamma_n = n u / (1 - n u), where n is the largest
// number of roundings (input differences included, a squared difference counted twice) on the path of any
// monomial. Each |monomial| is bounded by the product of the column maxima of the differences; using the
// rounded differences' maxima and rounding the bound itself shift it by a few u relative, covered by
// inflating n u by 2^-20. Fused multiply-adds would only remove roundings, so the bounds also hold if the
// caller's compiler contracts this code. Products that underflow add an absolute error below 2^-1060 in
// total for inputs of magnitude <= 1; UNDERFLOW_GUARD, added to every bound, absorbs it.
#pragma once

#include <math.h>

namespace dbrg {
namespace filter {

// What a filter returns when the bound does not exclude the other sign or zero.
constexpr int UNDECIDED = 2;

constexpr double UNIT_ROUNDOFF = 0x1p-53;
constexpr double SLACK = 1 + 0x1p-20;
constexpr double UNDERFLOW_GUARD = 0x1p-960;
// monomials x roundings: orient3d 6 x 8; insphere 4 rows x 3 lift terms x 6 minor terms (each bounded
// by w^2 x y z, w the largest of x, y, z) x 16; incircle 3 x 3 x 2 (w^2 u v) x 12; orient2d 2 x 4.
constexpr double ORIENT3D_BOUND = 6 * 8 * UNIT_ROUNDOFF * SLACK;
constexpr double INSPHERE_BOUND = 72 * 16 * UNIT_ROUNDOFF * SLACK;
constexpr double INCIRCLE_BOUND = 18 * 12 * UNIT_ROUNDOFF * SLACK;
constexpr double ORIENT2D_BOUND = 2 * 4 * UNIT_ROUNDOFF * SLACK;

inline double max2(double a, double b) { return a > b ? a : b; }
inline double max3(double a, double b, double c) { return max2(max2(a, b), c); }
inline double max4(double a, double b, double c, double d) { return max2(max2(a, b), max2(c, d)); }

// One well-predicted branch; the sign itself is selected without branching, since it is as likely
// positive as negative.
inline int certain_sign(double value, double bound) {
    return fabs(value) > bound ? (value > 0 ? 1 : -1) : UNDECIDED;
}

// det[a-d; b-d; c-d]
inline int orient3d(const double* a, const double* b, const double* c, const double* d) {
    const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    const double det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
    const double max_x = max3(fabs(adx), fabs(bdx), fabs(cdx));
    const double max_y = max3(fabs(ady), fabs(bdy), fabs(cdy));
    const double max_z = max3(fabs(adz), fabs(bdz), fabs(cdz));
    return certain_sign(det, ORIENT3D_BOUND * max_x * max_y * max_z + UNDERFLOW_GUARD);
}

// The determinant with rows (p - e, |p - e|^2), p = a, b, c, d, expanded along the lift column; the 3x3
// minors are expanded along z over the 2x2 xy-minors.
inline int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
    const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
    const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
    const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
    const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];
    const double ab = aex * bey - bex * aey, ac = aex * cey - cex * aey, ad = aex * dey - dex * aey;
    const double bc = bex * cey - cex * bey, bd = bex * dey - dex * bey, cd = cex * dey - dex * cey;
    const double abc = aez * bc - bez * ac + cez * ab;
    const double abd = aez * bd - bez * ad + dez * ab;
    const double acd = aez * cd - cez * ad + dez * ac;
    const double bcd = bez * cd - cez * bd + dez * bc;
    const double a_lift = aex * aex + aey * aey + aez * aez;
    const double b_lift = bex * bex + bey * bey + bez * bez;
    const double c_lift = cex * cex + cey * cey + cez * cez;
    const double d_lift = dex * dex + dey * dey + dez * dez;
    const double det = (d_lift * abc - c_lift * abd) + (b_lift * acd - a_lift * bcd);
    const double max_x = max4(fabs(aex), fabs(bex), fabs(cex), fabs(dex));
    const double max_y = max4(fabs(aey), fabs(bey), fabs(cey), fabs(dey));
    const double max_z = max4(fabs(aez), fabs(bez), fabs(cez), fabs(dez));
    const double max_w = max3(max_x, max_y, max_z);
    return certain_sign(det, INSPHERE_BOUND * max_x * max_y * max_z * max_w * max_w + UNDERFLOW_GUARD);
}

// The determinant with rows (p[u] - d[u], p[v] - d[v], |p - d|^2), p = a, b, c, with the full 3D lift.
inline int incircle(const double* a, const double* b, const double* c, const double* d, int u, int v) {
    double ad[3], bd[3], cd[3];
    for (int k = 0; k < 3; ++k) {
        ad[k] = a[k] - d[k];
        bd[k] = b[k] - d[k];
        cd[k] = c[k] - d[k];
    }
    const double bc = bd[u] * cd[v] - cd[u] * bd[v];
    const double ac = ad[u] * cd[v] - cd[u] * ad[v];
    const double ab = ad[u] * bd[v] - bd[u] * ad[v];
    const double a_lift = ad[0] * ad[0] + ad[1] * ad[1] + ad[2] * ad[2];
    const double b_lift = bd[0] * bd[0] + bd[1] * bd[1] + bd[2] * bd[2];
    const double c_lift = cd[0] * cd[0] + cd[1] * cd[1] + cd[2] * cd[2];
    const double det = a_lift * bc - b_lift * ac + c_lift * ab;
    double max_axis[3];
    for (int k = 0; k < 3; ++k) max_axis[k] = max3(fabs(ad[k]), fabs(bd[k]), fabs(cd[k]));
    const double max_w = max3(max_axis[0], max_axis[1], max_axis[2]);
    return certain_sign(det, INCIRCLE_BOUND * max_axis[u] * max_axis[v] * max_w * max_w + UNDERFLOW_GUARD);
}

// det[a - c; b - c] over the coordinates u, v.
inline int orient2d(const double* a, const double* b, const double* c, int u, int v) {
    const double acu = a[u] - c[u], acv = a[v] - c[v];
    const double bcu = b[u] - c[u], bcv = b[v] - c[v];
    const double det = acu * bcv - acv * bcu;
    return certain_sign(det, ORIENT2D_BOUND * max2(fabs(acu), fabs(bcu)) * max2(fabs(acv), fabs(bcv)) + UNDERFLOW_GUARD);
}

} // namespace filter
} // namespace dbrg
