// Semi-static floating-point filters: each evaluates a determinant in doubles together with a bound on its
// rounding error computed alongside it, and reports a sign only when the bound proves it.
//
// Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates" (1997), for the form of the bound (a constant times the permanent of the determinant); the
// constants are derived here, not taken from there.
//
// Why the bound is safe. Each filter evaluates its determinant by a fixed expression tree over the
// coordinate differences. Expanding the tree writes the exact value as a sum of monomials m_i, each a
// product of exact differences, and the computed value as sum_i m_i (1 + theta_i), where theta_i collects
// the roundings on the path of m_i: one per difference it contains (two for a squared difference), one per
// product and one per sum or difference above it. With u = 2^-53 and at most n roundings on any path,
// |theta_i| <= gamma_n = n u / (1 - n u) (Higham, "Accuracy and Stability of Numerical Algorithms",
// Lemma 3.1), so
//     |computed - exact| <= gamma_n * P,   P = sum_i |m_i|,
// the tree's permanent: the same tree with every difference of coordinates replaced by its absolute value
// and every subtraction above them by an addition (the lifts, sums of squares, are their own absolute
// values). Each filter computes P along that tree from the rounded differences; every operation there acts
// on non-negative values, so each of its terms loses at most a factor (1 - u) per rounding, and with n'
// roundings on its longest path the computed P is at least (1 - u)^n' P. The bound actually compared is
// fl(fl(n u (1 + 2^-20) * P) + UNDERFLOW_GUARD) >= n u (1 + 2^-20) (1 - u)^(n' + 2) P, which is at least
// gamma_n P whenever (1 + 2^-20) (1 - u)^(n' + 2) (1 - n u) >= 1, true for any n + n' + 2 < 2^32 (here
// n, n' < 40). So when |computed| exceeds the bound, the exact value is non-zero and has the computed sign.
// The path counts n are written next to each constant. Fused multiply-adds only remove roundings (a
// product feeding a sum is not rounded), so the bound also holds if a caller's compiler contracts this code.
// Underflow: for inputs of magnitude <= 1 (as the predicates require), every rounding that underflows adds
// an absolute error below 2^-1074, which the later operations multiply by at most 2^12 and the tree sums
// over fewer than 2^11 paths, to both the value and P: far below UNDERFLOW_GUARD = 2^-960.
//
// P is never larger than the earlier form of the bound, a constant times the product of the largest
// difference in each coordinate (A. Meyer and S. Pion, "FPG", 2008): each |m_i| is at most that product.
// It is much smaller on needles, the tetrahedra inside a densely sampled closed surface that have one vertex
// far away and the rest close to the query point, where the product form failed on a large share of calls.
#pragma once

#include <float.h>
#include <math.h>

// The bounds assume that each operation on doubles rounds once, to double: not so with x87 arithmetic.
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "dbrg's floating-point filters need FLT_EVAL_METHOD == 0 (SSE2 arithmetic on x86)"
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace dbrg {
namespace filter {

// What a filter returns when the bound does not exclude the other sign or zero.
constexpr int UNDECIDED = 2;

constexpr double UNIT_ROUNDOFF = 0x1p-53;
constexpr double SLACK = 1 + 0x1p-20;
constexpr double UNDERFLOW_GUARD = 0x1p-960;
// Roundings on the longest path of a monomial:
// orient3d: 3 differences + 2 products + 1 subtraction in a 2x2 minor and the product with the third
//   column (6), + 2 sums of the three terms = 8.
// insphere: lift 2 (a difference squared) + 1 product + 2 sums = 5; 3x3 minor as orient3d = 8; the product
//   lift x minor 1; the sum of the four terms 2: 16.
// incircle: lift 5; 2x2 minor 4; lift x minor 1; the sum of three terms 2: 12.
// orient2d: 2 differences + 1 product + 1 subtraction = 4.
constexpr double ORIENT3D_BOUND = 8 * UNIT_ROUNDOFF * SLACK;
constexpr double INSPHERE_BOUND = 16 * UNIT_ROUNDOFF * SLACK;
constexpr double INCIRCLE_BOUND = 12 * UNIT_ROUNDOFF * SLACK;
constexpr double ORIENT2D_BOUND = 4 * UNIT_ROUNDOFF * SLACK;

// One well-predicted branch; the sign itself is selected without branching, since it is as likely
// positive as negative.
inline int certain_sign(double value, double bound) {
    return fabs(value) > bound ? (value > 0 ? 1 : -1) : UNDECIDED;
}

// det[a-d; b-d; c-d], expanded along z over the 2x2 xy-minors.
inline int orient3d(const double* a, const double* b, const double* c, const double* d) {
    const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = fabs(adz) * (fabs(bdxcdy) + fabs(cdxbdy)) + fabs(bdz) * (fabs(cdxady) + fabs(adxcdy)) +
                             fabs(cdz) * (fabs(adxbdy) + fabs(bdxady));
    return certain_sign(det, ORIENT3D_BOUND * permanent + UNDERFLOW_GUARD);
}

// The determinant with rows (p - e, |p - e|^2), p = a, b, c, d, expanded along the lift column; the 3x3
// minors are expanded along z over the 2x2 xy-minors. insphere below evaluates the same trees two lanes at
// a time where SSE2 is available; this form is the reference for it.
inline int insphere_scalar(const double* a, const double* b, const double* c, const double* d, const double* e) {
    const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
    const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
    const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
    const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];
    const double aexbey = aex * bey, bexaey = bex * aey, aexcey = aex * cey, cexaey = cex * aey;
    const double aexdey = aex * dey, dexaey = dex * aey, bexcey = bex * cey, cexbey = cex * bey;
    const double bexdey = bex * dey, dexbey = dex * bey, cexdey = cex * dey, dexcey = dex * cey;
    const double ab = aexbey - bexaey, ac = aexcey - cexaey, ad = aexdey - dexaey;
    const double bc = bexcey - cexbey, bd = bexdey - dexbey, cd = cexdey - dexcey;
    const double abc = aez * bc - bez * ac + cez * ab;
    const double abd = aez * bd - bez * ad + dez * ab;
    const double acd = aez * cd - cez * ad + dez * ac;
    const double bcd = bez * cd - cez * bd + dez * bc;
    const double a_lift = aex * aex + aey * aey + aez * aez;
    const double b_lift = bex * bex + bey * bey + bez * bez;
    const double c_lift = cex * cex + cey * cey + cez * cez;
    const double d_lift = dex * dex + dey * dey + dez * dez;
    const double det = (d_lift * abc - c_lift * abd) + (b_lift * acd - a_lift * bcd);
    const double pab = fabs(aexbey) + fabs(bexaey), pac = fabs(aexcey) + fabs(cexaey);
    const double pad = fabs(aexdey) + fabs(dexaey), pbc = fabs(bexcey) + fabs(cexbey);
    const double pbd = fabs(bexdey) + fabs(dexbey), pcd = fabs(cexdey) + fabs(dexcey);
    const double az = fabs(aez), bz = fabs(bez), cz = fabs(cez), dz = fabs(dez);
    const double permanent = (d_lift * (az * pbc + bz * pac + cz * pab) + c_lift * (az * pbd + bz * pad + dz * pab)) +
                             (b_lift * (az * pcd + cz * pad + dz * pac) + a_lift * (bz * pcd + cz * pbd + dz * pbc));
    return certain_sign(det, INSPHERE_BOUND * permanent + UNDERFLOW_GUARD);
}

#if defined(__SSE2__)
// insphere_scalar with every operation of its two trees (determinant and permanent) done on two lanes at
// once: each lane rounds exactly as the scalar operation it replaces, so the value, the bound and the
// result are the same bit for bit, and so is the derivation of the bound. It is the Delaunay engine's
// most frequent computation.
inline int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
    const __m128d exy = _mm_loadu_pd(e);
    const __m128d ez = _mm_set1_pd(e[2]);
    const __m128d A = _mm_sub_pd(_mm_loadu_pd(a), exy);  // (aex, aey)
    const __m128d B = _mm_sub_pd(_mm_loadu_pd(b), exy);
    const __m128d C = _mm_sub_pd(_mm_loadu_pd(c), exy);
    const __m128d D = _mm_sub_pd(_mm_loadu_pd(d), exy);
    const __m128d zab = _mm_sub_pd(_mm_set_pd(b[2], a[2]), ez);  // (aez, bez)
    const __m128d zcd = _mm_sub_pd(_mm_set_pd(d[2], c[2]), ez);  // (cez, dez)
    const __m128d xab = _mm_unpacklo_pd(A, B), yab = _mm_unpackhi_pd(A, B);  // (aex, bex), (aey, bey)
    const __m128d xcd = _mm_unpacklo_pd(C, D), ycd = _mm_unpackhi_pd(C, D);
    const __m128d xac = _mm_unpacklo_pd(A, C), yac = _mm_unpackhi_pd(A, C);
    const __m128d xbd = _mm_unpacklo_pd(B, D), ybd = _mm_unpackhi_pd(B, D);
    const __m128d xdc = _mm_unpacklo_pd(D, C), ydc = _mm_unpackhi_pd(D, C);
    // The products of the 2x2 xy-minors, each pair of lanes one minor: (ab, cd), (ac, bd), (ad, bc).
    const __m128d l1 = _mm_mul_pd(xac, ybd), r1 = _mm_mul_pd(xbd, yac);  // aex bey, cex dey; bex aey, dex cey
    const __m128d l2 = _mm_mul_pd(xab, ycd), r2 = _mm_mul_pd(xcd, yab);  // aex cey, bex dey; cex aey, dex bey
    const __m128d l3 = _mm_mul_pd(xab, ydc), r3 = _mm_mul_pd(xdc, yab);  // aex dey, bex cey; dex aey, cex bey
    const __m128d m1 = _mm_sub_pd(l1, r1), m2 = _mm_sub_pd(l2, r2), m3 = _mm_sub_pd(l3, r3);
    const __m128d sign_bit = _mm_set1_pd(-0.0);
    const __m128d p1 = _mm_add_pd(_mm_andnot_pd(sign_bit, l1), _mm_andnot_pd(sign_bit, r1));  // (pab, pcd)
    const __m128d p2 = _mm_add_pd(_mm_andnot_pd(sign_bit, l2), _mm_andnot_pd(sign_bit, r2));  // (pac, pbd)
    const __m128d p3 = _mm_add_pd(_mm_andnot_pd(sign_bit, l3), _mm_andnot_pd(sign_bit, r3));  // (pad, pbc)
    const __m128d za = _mm_unpacklo_pd(zab, zab), zb = _mm_unpackhi_pd(zab, zab);
    const __m128d zc = _mm_unpacklo_pd(zcd, zcd), zd = _mm_unpackhi_pd(zcd, zcd);
    // (abc, abd) = (aez, aez) (bc, bd) - (bez, bez) (ac, ad) + (cez, dez) (ab, ab), and
    // (acd, bcd) = (aez, bez) (cd, cd) - (cez, cez) (ad, bd) + (dez, dez) (ac, bc).
    const __m128d k1 = _mm_add_pd(_mm_sub_pd(_mm_mul_pd(za, _mm_unpackhi_pd(m3, m2)), _mm_mul_pd(zb, _mm_unpacklo_pd(m2, m3))),
                                  _mm_mul_pd(zcd, _mm_unpacklo_pd(m1, m1)));
    const __m128d k2 = _mm_add_pd(_mm_sub_pd(_mm_mul_pd(zab, _mm_unpackhi_pd(m1, m1)), _mm_mul_pd(zc, _mm_shuffle_pd(m3, m2, 2))),
                                  _mm_mul_pd(zd, _mm_shuffle_pd(m2, m3, 2)));
    // The same with magnitudes: the permanent's factors of the lifts.
    const __m128d aza = _mm_andnot_pd(sign_bit, za), azb = _mm_andnot_pd(sign_bit, zb);
    const __m128d azc = _mm_andnot_pd(sign_bit, zc), azd = _mm_andnot_pd(sign_bit, zd);
    const __m128d azab = _mm_andnot_pd(sign_bit, zab), azcd = _mm_andnot_pd(sign_bit, zcd);
    const __m128d q1 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(aza, _mm_unpackhi_pd(p3, p2)), _mm_mul_pd(azb, _mm_unpacklo_pd(p2, p3))),
                                  _mm_mul_pd(azcd, _mm_unpacklo_pd(p1, p1)));
    const __m128d q2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(azab, _mm_unpackhi_pd(p1, p1)), _mm_mul_pd(azc, _mm_shuffle_pd(p3, p2, 2))),
                                  _mm_mul_pd(azd, _mm_shuffle_pd(p2, p3, 2)));
    // Lifts (a, b) and (c, d), summed x + y first, then z, as in the scalar form.
    const __m128d lab = _mm_add_pd(_mm_add_pd(_mm_mul_pd(xab, xab), _mm_mul_pd(yab, yab)), _mm_mul_pd(zab, zab));
    const __m128d lcd = _mm_add_pd(_mm_add_pd(_mm_mul_pd(xcd, xcd), _mm_mul_pd(ycd, ycd)), _mm_mul_pd(zcd, zcd));
    const __m128d ldb = _mm_shuffle_pd(lcd, lab, 3), lca = _mm_shuffle_pd(lcd, lab, 0);  // (d, b), (c, a)
    // (d_lift abc - c_lift abd, b_lift acd - a_lift bcd), then the sum of the two lanes.
    const __m128d halves = _mm_sub_pd(_mm_mul_pd(ldb, _mm_unpacklo_pd(k1, k2)), _mm_mul_pd(lca, _mm_unpackhi_pd(k1, k2)));
    const __m128d magnitudes = _mm_add_pd(_mm_mul_pd(ldb, _mm_unpacklo_pd(q1, q2)), _mm_mul_pd(lca, _mm_unpackhi_pd(q1, q2)));
    const double det = _mm_cvtsd_f64(halves) + _mm_cvtsd_f64(_mm_unpackhi_pd(halves, halves));
    const double permanent = _mm_cvtsd_f64(magnitudes) + _mm_cvtsd_f64(_mm_unpackhi_pd(magnitudes, magnitudes));
    return certain_sign(det, INSPHERE_BOUND * permanent + UNDERFLOW_GUARD);
}
#else
inline int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
    return insphere_scalar(a, b, c, d, e);
}
#endif

// The determinant with rows (p[u] - d[u], p[v] - d[v], |p - d|^2), p = a, b, c, with the full 3D lift.
inline int incircle(const double* a, const double* b, const double* c, const double* d, int u, int v) {
    double ad[3], bd[3], cd[3];
    for (int k = 0; k < 3; ++k) {
        ad[k] = a[k] - d[k];
        bd[k] = b[k] - d[k];
        cd[k] = c[k] - d[k];
    }
    const double bucv = bd[u] * cd[v], cubv = cd[u] * bd[v];
    const double aucv = ad[u] * cd[v], cuav = cd[u] * ad[v];
    const double aubv = ad[u] * bd[v], buav = bd[u] * ad[v];
    const double a_lift = ad[0] * ad[0] + ad[1] * ad[1] + ad[2] * ad[2];
    const double b_lift = bd[0] * bd[0] + bd[1] * bd[1] + bd[2] * bd[2];
    const double c_lift = cd[0] * cd[0] + cd[1] * cd[1] + cd[2] * cd[2];
    const double det = a_lift * (bucv - cubv) - b_lift * (aucv - cuav) + c_lift * (aubv - buav);
    const double permanent = a_lift * (fabs(bucv) + fabs(cubv)) + b_lift * (fabs(aucv) + fabs(cuav)) +
                             c_lift * (fabs(aubv) + fabs(buav));
    return certain_sign(det, INCIRCLE_BOUND * permanent + UNDERFLOW_GUARD);
}

// det[a - c; b - c] over the coordinates u, v.
inline int orient2d(const double* a, const double* b, const double* c, int u, int v) {
    const double acu = a[u] - c[u], acv = a[v] - c[v];
    const double bcu = b[u] - c[u], bcv = b[v] - c[v];
    const double left = acu * bcv, right = acv * bcu;
    return certain_sign(left - right, ORIENT2D_BOUND * (fabs(left) + fabs(right)) + UNDERFLOW_GUARD);
}

} // namespace filter
} // namespace dbrg
