// Exact signs of the determinants behind the predicates, for when the floating-point filter cannot
// decide. Private to the predicates module.
#pragma once

namespace dbrg {
namespace exact {

// Sign of det[a-d; b-d; c-d].
int orient3d(const double* a, const double* b, const double* c, const double* d);

// Sign of the determinant with rows (p - e, |p - e|^2) for p = a, b, c, d (Shewchuk's insphere).
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e);

// Sign of the determinant with rows (p[u] - d[u], p[v] - d[v], |p - d|^2) for p = a, b, c, where
// |p - d|^2 is the full 3D squared distance. Requires a, b, c, d exactly coplanar: the raw-coordinate
// fallback evaluates the equivalent determinant with rows (p[u], p[v], |p|^2, 1), which agrees with the
// translated form only in that case.
int incircle_lifted(const double* a, const double* b, const double* c, const double* d, int u, int v);

// Sign of det[a - c; b - c] for the projections onto the coordinates u, v.
int orient2d(const double* a, const double* b, const double* c, int u, int v);

} // namespace exact
} // namespace dbrg
