// Geometric predicates: the floating-point filter first, exact arithmetic when it cannot decide (in doubles
// for points on a coarse lattice, else in integers), and symbolic perturbation of the lifted coordinate
// when the exact value is zero.
//
// Based on: H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity" (1990), applied to the lift only
// as in O. Devillers and M. Teillaud, "Perturbations for Delaunay and weighted Delaunay 3D
// triangulations" (2011).
//
// The perturbation: the point of lexicographic rank k among the points involved has its lift |p|^2
// raised by eps^(k+1), eps > 0 infinitesimal. The insphere determinant, with rows (p, |p|^2, 1), is linear
// in the lift column, so the perturbed value is det + sum over points p of eps^(k_p + 1) * cofactor_p:
// its sign is the sign of det if non-zero, otherwise that of the first non-zero cofactor taken from the
// lexicographically smallest point up. The cofactors are orient3d determinants of the other four points;
// the one of e is -orient3d(a, b, c, d), so the result is never zero for a proper tetrahedron. The
// perturbed lifts define a weighted Delaunay triangulation with infinitesimal weights, so all decisions
// are mutually consistent; ranks among five points agree with ranks among all points, so they depend
// only on coordinates.
#include "predicates/predicates.h"

#include <math.h>

#include "predicates/exact_determinants.h"
#include "predicates/filters.h"

namespace dbrg {
namespace {

// The exact sign: from the lattice stage when the points qualify (counted), else from the integer stage.
// The lattice stage pays on grids, where it decides nearly every call, and costs its refusal (about 60
// instructions, 4% of an exact insphere) on point clouds with full significands, where it decides none:
// after a computation's first 256 exact evaluations it is only tried while it has decided at least one
// in 16. Both stages give the same answers, so this moves the cost, never a result.
template <class OnLattice, class InIntegers>
int exact_sign(PredicateCounters& counters, OnLattice on_lattice, InIntegers in_integers) {
    if (counters.filter_failures > 256 && counters.lattice * 16 < counters.filter_failures) return in_integers();
    const int sign = on_lattice();
    if (sign == exact::NOT_ON_LATTICE) return in_integers();
    ++counters.lattice;
    return sign;
}

int exact_orient2d(const double* a, const double* b, const double* c, int u, int v, PredicateCounters& counters) {
    return exact_sign(
        counters, [&] { return exact::orient2d_on_lattice(a, b, c, u, v); }, [&] { return exact::orient2d(a, b, c, u, v); });
}

// incircle3d_sos's choice of a projection, which the counters do not see.
int orient2d_sign(const double* a, const double* b, const double* c, int u, int v) {
    const int sign = filter::orient2d(a, b, c, u, v);
    if (sign != filter::UNDECIDED) return sign;
    PredicateCounters uncounted;
    return exact_orient2d(a, b, c, u, v, uncounted);
}

// The point that decides a perturbation: among the n points whose lift cofactor is not zero, the
// lexicographically smallest (the first in argument order among equal ones), or -1 when all are zero.
// Lexicographic order without branches: on grids the points of a call often share coordinates, and the
// branches of compare_points were mispredicted there.
int deciding_point(const double* const* points, const int* cofactor_signs, int n) {
    const auto before = [](const double* p, const double* q) {
        return (p[0] < q[0]) | ((p[0] == q[0]) & ((p[1] < q[1]) | ((p[1] == q[1]) & (p[2] < q[2]))));
    };
    int best = -1;
    for (int i = 0; i < n; ++i) {
        if (cofactor_signs[i] != 0 && (best < 0 || before(points[i], points[best]))) best = i;
    }
    return best;
}

// The sign of the perturbed insphere determinant when the unperturbed one is zero. Row i of the 5x5
// determinant (rows a..e, lift in column 4) has lift cofactor (-1)^(i+1) orient3d(the other four).
int insphere_perturbation_sign(const double* const* points, const int* orientations) {
    const int i = deciding_point(points, orientations, 5);
    if (i < 0) return 0;
    return i % 2 == 0 ? -orientations[i] : orientations[i];
}

// The same for the coplanar determinant with rows (p[u], p[v], |p|^2, 1), p = a, b, c, d, whose lift
// cofactors are (-1)^i orient2d(the other three).
int incircle_perturbation_sign(const double* const* points, const int* orientations) {
    const int i = deciding_point(points, orientations, 4);
    if (i < 0) return 0;
    return i % 2 == 1 ? -orientations[i] : orientations[i];
}

} // namespace

namespace slow_path {

int orient3d(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters) {
    ++counters.filter_failures;
    return exact_sign(
        counters, [&] { return exact::orient3d_on_lattice(a, b, c, d); }, [&] { return exact::orient3d(a, b, c, d); });
}

int insphere_exact(const double* a, const double* b, const double* c, const double* d, const double* e,
                   PredicateCounters& counters) {
    ++counters.filter_failures;
    return exact_sign(
        counters, [&] { return exact::insphere_on_lattice(a, b, c, d, e, nullptr); },
        [&] { return exact::insphere(a, b, c, d, e, nullptr); });
}

int insphere_sos(const double* a, const double* b, const double* c, const double* d, const double* e,
                 PredicateCounters& counters) {
    ++counters.filter_failures;
    int orientations[5];
    const int sign = exact_sign(
        counters, [&] { return exact::insphere_on_lattice(a, b, c, d, e, orientations); },
        [&] { return exact::insphere(a, b, c, d, e, orientations); });
    if (sign != 0) return sign;
    ++counters.perturbations;
    const double* points[5] = {a, b, c, d, e};
    return insphere_perturbation_sign(points, orientations);
}

} // namespace slow_path

// Works in the coordinate plane that drops the axis of the largest normal component of abc, where the
// projection is best conditioned. On the plane of the points every linear function of the 3D coordinates
// is a linear function of the two kept ones, so the lifted determinant with the full 3D |p|^2 is the
// exact 3D circle test up to the sign of the projected orient2d(a, b, c), which the result is multiplied by.
// The same holds for each perturbation cofactor, which makes the result equal to insphere_sos(a, b, c, q, d)
// for every q with orient3d(a, b, c, q) > 0: q's own cofactor is orient3d(a, b, c, d) = 0, so q's rank,
// even for a point at infinity, never matters.
int incircle3d_sos(const double* a, const double* b, const double* c, const double* d, PredicateCounters& counters) {
    ++counters.calls;
    double normal[3];
    {
        const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        normal[0] = fabs(ab[1] * ac[2] - ab[2] * ac[1]);
        normal[1] = fabs(ab[2] * ac[0] - ab[0] * ac[2]);
        normal[2] = fabs(ab[0] * ac[1] - ab[1] * ac[0]);
    }
    int axes[3] = {0, 1, 2};
    for (int i = 1; i < 3; ++i)
        for (int j = i; j > 0 && normal[axes[j]] > normal[axes[j - 1]]; --j) {
            const int t = axes[j];
            axes[j] = axes[j - 1];
            axes[j - 1] = t;
        }
    // The rounded normal only ranks the axes; an exactly zero projected orientation rules an axis out.
    for (int k = 0; k < 3; ++k) {
        const int u = (axes[k] + 1) % 3, v = (axes[k] + 2) % 3;
        const int abc_sign = orient2d_sign(a, b, c, u, v);
        if (abc_sign == 0) continue;
        // The filter never reports 0: a zero comes from the exact stage, with the perturbation's cofactors.
        int sign = filter::incircle(a, b, c, d, u, v);
        int orientations[4];
        if (sign == filter::UNDECIDED) {
            ++counters.filter_failures;
            sign = exact_sign(
                counters, [&] { return exact::incircle_lifted_on_lattice(a, b, c, d, u, v, orientations); },
                [&] { return exact::incircle_lifted(a, b, c, d, u, v, orientations); });
        }
        if (sign == 0) {
            ++counters.perturbations;
            const double* points[4] = {a, b, c, d};
            sign = incircle_perturbation_sign(points, orientations);
        }
        return abc_sign * sign;
    }
    return 0;
}

int orient2d(const double* a, const double* b, const double* c, int u, int v, PredicateCounters& counters) {
    ++counters.calls;
    const int sign = filter::orient2d(a, b, c, u, v);
    if (sign != filter::UNDECIDED) return sign;
    ++counters.filter_failures;
    return exact_orient2d(a, b, c, u, v, counters);
}

int compare_points(const double* a, const double* b) {
    for (int k = 0; k < 3; ++k) {
        if (a[k] < b[k]) return -1;
        if (a[k] > b[k]) return 1;
    }
    return 0;
}

} // namespace dbrg
