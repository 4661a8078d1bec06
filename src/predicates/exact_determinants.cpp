// Exact determinant signs by expansion arithmetic: a short evaluation on the translated points when every
// coordinate difference is exact in floating point (true of grids and most degenerate inputs), otherwise
// a longer one on the raw coordinates, which needs no differences at all.
#include "predicates/exact_determinants.h"

#include "predicates/expansion.h"

namespace dbrg {
namespace exact {
namespace {

using expansion::Accumulator;
using expansion::negate;
using expansion::product_difference;
using expansion::scale;
using expansion::squared_norm;
using expansion::sum;

// out = p - q rounded; returns whether all three differences were exact.
bool exact_difference(const double* p, const double* q, double* out) {
    double tail[3];
    for (int k = 0; k < 3; ++k) expansion::two_diff(p[k], q[k], out[k], tail[k]);
    return tail[0] == 0 && tail[1] == 0 && tail[2] == 0;
}

// h (24) = det[p; q; r], expanded along the z column.
int det3(const double* p, const double* q, const double* r, double* h) {
    double qr[4], pr[4], pq[4];
    const int n_qr = product_difference(q[0], r[1], r[0], q[1], qr);
    const int n_pr = product_difference(p[0], r[1], r[0], p[1], pr);
    const int n_pq = product_difference(p[0], q[1], q[0], p[1], pq);
    double term1[8], term2[8], term3[8], term12[16];
    const int n1 = scale(qr, n_qr, p[2], term1);
    const int n2 = scale(pr, n_pr, -q[2], term2);
    const int n3 = scale(pq, n_pq, r[2], term3);
    const int n12 = sum(term1, n1, term2, n2, term12);
    return sum(term12, n12, term3, n3, h);
}

// The raw-coordinate determinants of up to five points, built from shared parts: the 2x2 xy-minors of
// each pair of points, then the 3x3 determinants of each triple (expanded along z over those minors, as
// det3), then the 4x4 ones of each quadruple as alternating sums of 3x3 ones. Computed once each, where
// evaluating every 4x4 determinant on its own computed each 2x2 minor six times and each 3x3 one twice.
class RawMinors {
public:
    RawMinors(const double* const* points, int n) : points_(points) {
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                pair_length_[i][j] = product_difference(points[i][0], points[j][1], points[j][0], points[i][1], pair_[i][j]);
        int count = 0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                for (int k = j + 1; k < n; ++k) {
                    index_[i][j][k] = static_cast<signed char>(count);
                    triple_length_[count] = triple(i, j, k, triple_[count]);
                    ++count;
                }
    }

    // h (96) = det of the rows (p, 1) for the points i < j < k < l, which equals det[pi-pl; pj-pl; pk-pl].
    int quadruple(int i, int j, int k, int l, double* h) const {
        const int ijk = index_[i][j][k], ijl = index_[i][j][l], ikl = index_[i][k][l], jkl = index_[j][k][l];
        double negated_ijl[24], negated_jkl[24], left[48], right[48];
        const int n_ijl = negate(triple_[ijl], triple_length_[ijl], negated_ijl);
        const int n_jkl = negate(triple_[jkl], triple_length_[jkl], negated_jkl);
        const int n_left = sum(triple_[ijk], triple_length_[ijk], negated_ijl, n_ijl, left);
        const int n_right = sum(triple_[ikl], triple_length_[ikl], negated_jkl, n_jkl, right);
        return sum(left, n_left, right, n_right, h);
    }

private:
    // h (24) = det[p_i; p_j; p_k], expanded along the z column as det3 does.
    int triple(int i, int j, int k, double* h) const {
        double term1[8], term2[8], term3[8], term12[16];
        const int n1 = scale(pair_[j][k], pair_length_[j][k], points_[i][2], term1);
        const int n2 = scale(pair_[i][k], pair_length_[i][k], -points_[j][2], term2);
        const int n3 = scale(pair_[i][j], pair_length_[i][j], points_[k][2], term3);
        const int n12 = sum(term1, n1, term2, n2, term12);
        return sum(term12, n12, term3, n3, h);
    }

    const double* const* points_;
    double pair_[5][5][4];
    int pair_length_[5][5];
    signed char index_[5][5][5];  // where triple i < j < k is kept
    double triple_[10][24];
    int triple_length_[10];
};

// h (96) = det of the rows (p, 1), (q, 1), (r, 1), (s, 1), which equals det[p-s; q-s; r-s].
int orient3d_raw(const double* p, const double* q, const double* r, const double* s, double* h) {
    const double* points[4] = {p, q, r, s};
    const RawMinors minors(points, 4);
    return minors.quadruple(0, 1, 2, 3, h);
}

// h (4) = p[u] * q[v] - q[u] * p[v].
int minor2(const double* p, const double* q, int u, int v, double* h) {
    return product_difference(p[u], q[v], q[u], p[v], h);
}

// h (12) = det of the rows (p[u], p[v], 1), (q[u], q[v], 1), (r[u], r[v], 1).
int orient2d_raw(const double* p, const double* q, const double* r, int u, int v, double* h) {
    double qr[4], pr[4], pq[4], left[8];
    const int n_qr = minor2(q, r, u, v, qr);
    const int n_pr = minor2(p, r, u, v, pr);
    const int n_pq = minor2(p, q, u, v, pq);
    negate(pr, n_pr, pr);
    const int n_left = sum(qr, n_qr, pr, n_pr, left);
    return sum(left, n_left, pq, n_pq, h);
}

// Rows (r_i, |r_i|^2) for the four translated points, expanded along the lift column.
int insphere_translated(const double (*rows)[3]) {
    Accumulator<4 * 6 * 48> total;
    for (int i = 0; i < 4; ++i) {
        const double* other[3];
        for (int j = 0, k = 0; j < 4; ++j)
            if (j != i) other[k++] = rows[j];
        double minor[24], lift[6];
        const int n_minor = det3(other[0], other[1], other[2], minor);
        if (i % 2 == 0) negate(minor, n_minor, minor);
        const int n_lift = squared_norm(rows[i][0], rows[i][1], rows[i][2], lift);
        total.add_product<48>(minor, n_minor, lift, n_lift);
    }
    return total.sign();
}

// Rows (p, |p|^2, 1) for the five points, expanded along the lift column. Its two buffers take about
// 92 KB of stack; only inputs whose differences are inexact and whose filter failed get here.
int insphere_raw(const double* const* points) {
    const RawMinors minors(points, 5);
    Accumulator<5 * 6 * 192> total;
    for (int i = 0; i < 5; ++i) {
        int other[4];
        for (int j = 0, k = 0; j < 5; ++j)
            if (j != i) other[k++] = j;
        double minor[96], lift[6];
        const int n_minor = minors.quadruple(other[0], other[1], other[2], other[3], minor);
        if (i % 2 == 0) negate(minor, n_minor, minor);
        const int n_lift = squared_norm(points[i][0], points[i][1], points[i][2], lift);
        total.add_product<192>(minor, n_minor, lift, n_lift);
    }
    return total.sign();
}

// Rows (r_i[u], r_i[v], |r_i|^2) for the three translated points, expanded along the lift column.
int incircle_translated(const double (*rows)[3], int u, int v) {
    Accumulator<3 * 6 * 8> total;
    for (int i = 0; i < 3; ++i) {
        const double* other[2];
        for (int j = 0, k = 0; j < 3; ++j)
            if (j != i) other[k++] = rows[j];
        double minor[4], lift[6];
        const int n_minor = minor2(other[0], other[1], u, v, minor);
        if (i % 2 == 1) negate(minor, n_minor, minor);
        const int n_lift = squared_norm(rows[i][0], rows[i][1], rows[i][2], lift);
        total.add_product<8>(minor, n_minor, lift, n_lift);
    }
    return total.sign();
}

// Rows (p[u], p[v], |p|^2, 1) for the four points, expanded along the lift column.
int incircle_raw(const double* const* points, int u, int v) {
    Accumulator<4 * 6 * 24> total;
    for (int i = 0; i < 4; ++i) {
        const double* other[3];
        for (int j = 0, k = 0; j < 4; ++j)
            if (j != i) other[k++] = points[j];
        double minor[12], lift[6];
        const int n_minor = orient2d_raw(other[0], other[1], other[2], u, v, minor);
        if (i % 2 == 1) negate(minor, n_minor, minor);
        const int n_lift = squared_norm(points[i][0], points[i][1], points[i][2], lift);
        total.add_product<24>(minor, n_minor, lift, n_lift);
    }
    return total.sign();
}

} // namespace

int orient3d(const double* a, const double* b, const double* c, const double* d) {
    double rows[3][3];
    const bool exact_rows = exact_difference(a, d, rows[0]) && exact_difference(b, d, rows[1]) &&
                            exact_difference(c, d, rows[2]);
    if (exact_rows) {
        double h[24];
        return expansion::sign(h, det3(rows[0], rows[1], rows[2], h));
    }
    double h[96];
    return expansion::sign(h, orient3d_raw(a, b, c, d, h));
}

int insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
    double rows[4][3];
    const bool exact_rows = exact_difference(a, e, rows[0]) && exact_difference(b, e, rows[1]) &&
                            exact_difference(c, e, rows[2]) && exact_difference(d, e, rows[3]);
    if (exact_rows) return insphere_translated(rows);
    const double* points[5] = {a, b, c, d, e};
    return insphere_raw(points);
}

int incircle_lifted(const double* a, const double* b, const double* c, const double* d, int u, int v) {
    double rows[3][3];
    const bool exact_rows = exact_difference(a, d, rows[0]) && exact_difference(b, d, rows[1]) &&
                            exact_difference(c, d, rows[2]);
    if (exact_rows) return incircle_translated(rows, u, v);
    const double* points[4] = {a, b, c, d};
    return incircle_raw(points, u, v);
}

int orient2d(const double* a, const double* b, const double* c, int u, int v) {
    double h[12];
    return expansion::sign(h, orient2d_raw(a, b, c, u, v, h));
}

} // namespace exact
} // namespace dbrg
