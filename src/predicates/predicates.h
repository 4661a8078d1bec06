// Geometric predicates: orient3d and insphere with a floating-point filter, an exact expansion-arithmetic
// fallback and symbolic perturbation, so that Delaunay decisions are exact and never ambiguous.
//
// Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates" (1997) for the expansion arithmetic; H. Edelsbrunner and E. P. Mücke, "Simulation of
// Simplicity" (1990) for the perturbation of the lifted coordinate, ordered by point coordinates.
//
// Points are `const double*` to three coordinates. Inputs are expected to be conditioned (finite,
// scaled near unit size by a power of two) so that no intermediate product overflows or underflows.
#pragma once

#include <stdint.h>

namespace dbrg {

// How often each path was taken; one instance per computation (no global state).
struct PredicateCounters {
    uint64_t calls = 0;            // every orient3d / insphere / incircle evaluation
    uint64_t filter_failures = 0;  // the floating-point filter could not decide; exact arithmetic ran
    uint64_t perturbations = 0;    // the exact value was zero; symbolic perturbation decided
};

// Sign of the volume of tetrahedron (a, b, c, d): +1 when d lies below the plane through a, b, c,
// "below" being the side from which a, b, c appear clockwise; -1 above; 0 when the four are coplanar.
// Equal to the sign of det[a-d; b-d; c-d] (Shewchuk's convention). Exact.
int orient3d(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters);

// Exact sign of insphere(a, b, c, d, e): +1 when e lies inside the sphere through a, b, c, d and
// orient3d(a, b, c, d) > 0 (the sign flips when the tetrahedron is negatively oriented); 0 when the
// five points are cospherical (or the four are coplanar).
int insphere_exact(const double* a, const double* b, const double* c, const double* d, const double* e,
                   PredicateCounters& counters);

// As insphere_exact, but never 0 when orient3d(a, b, c, d) != 0: cospherical configurations are
// resolved by perturbing each point's lifted coordinate |p|^2 by eps^k, with k the rank of p in
// lexicographic (x, y, z) order among all points, so that the result depends only on coordinates,
// never on argument order or on input positions. Consistent with incircle3d_sos for hull faces.
int insphere_sos(const double* a, const double* b, const double* c, const double* d, const double* e,
                 PredicateCounters& counters);

// For four coplanar points (orient3d(a, b, c, d) == 0, a, b, c not collinear): +1 when d lies inside
// the circle through a, b, c, -1 outside, with cocircular cases resolved by the same lifted-coordinate
// perturbation as insphere_sos, so that the result equals the limit of insphere_sos(a, b, c, q, d) for a
// point q going to infinity on the side of plane (a, b, c) where orient3d(a, b, c, q) > 0.
// Never 0 for non-collinear a, b, c.
int incircle3d_sos(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters);

// Lexicographic comparison of (x, y, z): negative, zero or positive. The order used by the perturbation
// and by every tie-break in the library.
int compare_points(const double* a, const double* b);

} // namespace dbrg
