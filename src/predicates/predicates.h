// Geometric predicates: orient3d and insphere with a floating-point filter, an exact fallback (in doubles on
// coarse lattices, where they are exact, else in fixed-width integers) and symbolic perturbation, so that
// Delaunay decisions are exact and never ambiguous.
//
// Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates" (1997) for the filters' error bounds; H. Edelsbrunner and E. P. Mücke, "Simulation of
// Simplicity" (1990) for the perturbation of the lifted coordinate, ordered by point coordinates.
//
// Points are `const double*` to three coordinates, expected conditioned as point_conditioning does it:
// finite, |coordinate| <= 1, and each coordinate zero or a multiple of 2^-200 (every double of magnitude
// at least 2^-147 is). The filters are sound for any finite input of moderate size; the exact fallback
// needs the coordinates of one call to span at most 254 bits (exact_determinants.h), which this ensures.
// orient3d, insphere_exact and insphere_sos are inline: the filter (filters.h) decides almost every call,
// and the Delaunay engine's conflict tests and walk steps measured faster with it in their loops. What
// follows the filter (exact arithmetic, perturbation) stays out of line.
#pragma once

#include <stdint.h>

#include "predicates/filters.h"

namespace dbrg {

// How often each path was taken; one instance per computation (no global state). Each public call counts
// once; the orient3d/orient2d evaluations a perturbation runs internally are not counted separately.
struct PredicateCounters {
    uint64_t calls = 0;            // every orient3d / insphere_exact / insphere_sos / incircle3d_sos / orient2d call
    uint64_t filter_failures = 0;  // the floating-point filter could not decide; exact arithmetic ran
    uint64_t perturbations = 0;    // the exact value was zero; symbolic perturbation decided
    uint64_t lattice = 0;          // exact evaluations done in doubles, the points being on a coarse lattice

    // Adds another set of counts (each thread of a parallel insertion keeps its own).
    PredicateCounters& operator+=(const PredicateCounters& other) {
        calls += other.calls;
        filter_failures += other.filter_failures;
        perturbations += other.perturbations;
        lattice += other.lattice;
        return *this;
    }
};

// Sign of the volume of tetrahedron (a, b, c, d): +1 when d lies below the plane through a, b, c,
// "below" being the side from which a, b, c appear clockwise; -1 above; 0 when the four are coplanar.
// Equal to the sign of det[a-d; b-d; c-d] (Shewchuk's convention). Exact.
inline int orient3d(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters);

// Exact sign of insphere(a, b, c, d, e), the determinant with rows (p - e, |p - e|^2) for p = a, b, c, d:
// +1 when e lies inside the sphere through a, b, c, d and orient3d(a, b, c, d) > 0 (the sign flips when
// the tetrahedron is negatively oriented); 0 when the five points are cospherical. When a, b, c, d are
// coplanar it is still the exact sign of that determinant, which then does not tell inside from outside.
inline int insphere_exact(const double* a, const double* b, const double* c, const double* d, const double* e,
                          PredicateCounters& counters);

// As insphere_exact, but never 0 when orient3d(a, b, c, d) != 0: cospherical configurations are
// resolved by raising each point's lifted coordinate |p|^2 by eps^(k+1), eps infinitesimal, with k the
// rank of p in lexicographic (x, y, z) order (compare_points; 0 = smallest, perturbed most), so that the
// result depends only on coordinates, never on input positions. Antisymmetric in all five arguments.
// 0 only when all five points are coplanar. Points must be pairwise distinct for the result to be
// independent of argument order. Consistent with incircle3d_sos for hull faces.
inline int insphere_sos(const double* a, const double* b, const double* c, const double* d, const double* e,
                        PredicateCounters& counters);

// For four exactly coplanar points (orient3d(a, b, c, d) == 0, a precondition): +1 when d lies inside
// the circle through a, b, c, -1 outside, whatever the order of a, b, c; cocircular cases are resolved
// by the same lifted-coordinate perturbation as insphere_sos. The result equals
// insphere_sos(a, b, c, q, d) for every q with orient3d(a, b, c, q) > 0, near or far (hence also its
// limit for q going to infinity on that side): q's own cofactor is orient3d(a, b, c, d) = 0, so the rank
// given to q, or to an infinite vertex, never matters. Never 0 for non-collinear a, b, c; 0 when collinear.
int incircle3d_sos(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters);

// Sign of det[a - c; b - c] over the coordinates u, v: +1 when the projections of a, b, c onto those two
// coordinates turn counter-clockwise, -1 clockwise, 0 when they are collinear. Exact. For points in one
// plane whose normal has a non-zero component on the third axis w, with (u, v) = (w + 1, w + 2) mod 3, it is
// the sign of (b - a) x (c - a) along that axis: the orientation in the plane seen from the side w points to.
int orient2d(const double* a, const double* b, const double* c, int u, int v, PredicateCounters& counters);

// Lexicographic comparison of (x, y, z): negative, zero or positive. The order used by the perturbation
// and by every tie-break in the library.
int compare_points(const double* a, const double* b);

// The out-of-line paths behind the inline predicates: each counts a filter failure and decides exactly.
namespace slow_path {
int orient3d(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters);
int insphere_exact(const double* a, const double* b, const double* c, const double* d, const double* e,
                   PredicateCounters& counters);
int insphere_sos(const double* a, const double* b, const double* c, const double* d, const double* e,
                 PredicateCounters& counters);
} // namespace slow_path

inline int orient3d(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters) {
    ++counters.calls;
    const int sign = filter::orient3d(a, b, c, d);
    return sign != filter::UNDECIDED ? sign : slow_path::orient3d(a, b, c, d, counters);
}

inline int insphere_exact(const double* a, const double* b, const double* c, const double* d, const double* e,
                          PredicateCounters& counters) {
    ++counters.calls;
    const int sign = filter::insphere(a, b, c, d, e);
    return sign != filter::UNDECIDED ? sign : slow_path::insphere_exact(a, b, c, d, e, counters);
}

// A sign the filter proves is never 0, so the perturbation is only ever needed on the slow path.
inline int insphere_sos(const double* a, const double* b, const double* c, const double* d, const double* e,
                        PredicateCounters& counters) {
    ++counters.calls;
    const int sign = filter::insphere(a, b, c, d, e);
    return sign != filter::UNDECIDED ? sign : slow_path::insphere_sos(a, b, c, d, e, counters);
}

} // namespace dbrg
