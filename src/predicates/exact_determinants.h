// Exact signs of the determinants behind the predicates, for when the floating-point filter cannot
// decide. Private to the predicates module. Each needs the coordinates of its points to be multiples of
// one power of two 2^g with every coordinate difference below 2^(g + 254): true of conditioned points
// (|x| <= 1, multiples of 2^-200), and of any points whose coordinates are integers below 2^250.
#pragma once

namespace dbrg {
namespace exact {

// Sign of det[a-d; b-d; c-d].
int orient3d(const double* a, const double* b, const double* c, const double* d);

// Sign of the determinant with rows (p - e, |p - e|^2) for p = a, b, c, d (Shewchuk's insphere). When it
// is 0 and orientations is not null, orientations[i] is set, for i = 0..4, to the sign of orient3d of the
// other four of a, b, c, d, e in argument order: the lift cofactors that decide the perturbation.
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e, int* orientations);

// Sign of the determinant with rows (p[u] - d[u], p[v] - d[v], |p - d|^2) for p = a, b, c, where
// |p - d|^2 is the full 3D squared distance. When it is 0 and orientations is not null, orientations[i]
// is set, for i = 0..3, to the sign of orient2d (u, v) of the other three of a, b, c, d in argument order.
int incircle_lifted(const double* a, const double* b, const double* c, const double* d, int u, int v,
                    int* orientations);

// Sign of det[a - c; b - c] for the projections onto the coordinates u, v.
int orient2d(const double* a, const double* b, const double* c, int u, int v);

// The same four in doubles, for points on a coarse lattice (grids; every coordinate of the call a
// multiple of one power of two, with differences of at most a few hundred to a few million units, see
// exact_determinants.cpp), where that evaluation has no rounding: each returns what the function above
// returns, orientations included, or NOT_ON_LATTICE, leaving orientations as they were, when the points
// do not qualify. About a third of the cost of the integer stage.
constexpr int NOT_ON_LATTICE = 2;
int orient3d_on_lattice(const double* a, const double* b, const double* c, const double* d);
int insphere_on_lattice(const double* a, const double* b, const double* c, const double* d, const double* e,
                        int* orientations);
int incircle_lifted_on_lattice(const double* a, const double* b, const double* c, const double* d, int u, int v,
                               int* orientations);
int orient2d_on_lattice(const double* a, const double* b, const double* c, int u, int v);

} // namespace exact
} // namespace dbrg
