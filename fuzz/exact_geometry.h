// Exact integer geometry for the fuzzers' oracles: orientation, in-sphere and in-circle signs computed
// with 128-bit integers, independent of the library's floating-point filters and expansion arithmetic.
// Every function is exact for coordinates with |x| <= 2^16 (the worst term, of the in-circle test, stays
// below 2^126).
#pragma once

#include <stddef.h>
#include <stdint.h>

namespace dbrg::fuzz {

__extension__ typedef __int128 Int128;  // __extension__: -Wpedantic knows no 128-bit type

struct IntPoint {
    int64_t x, y, z;
};

const int64_t EXACT_COORDINATE_LIMIT = int64_t(1) << 16;

inline int sign_of(Int128 value) { return value > 0 ? 1 : (value < 0 ? -1 : 0); }

inline IntPoint minus(const IntPoint& a, const IntPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

inline Int128 dot(const IntPoint& a, const IntPoint& b) {
    return Int128(a.x) * b.x + Int128(a.y) * b.y + Int128(a.z) * b.z;
}

// Cross products of differences stay below 2^35 per component, so they fit back into an IntPoint.
inline IntPoint cross(const IntPoint& a, const IntPoint& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline bool collinear(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
    const IntPoint n = cross(minus(b, a), minus(c, a));
    return n.x == 0 && n.y == 0 && n.z == 0;
}

// det[a-d; b-d; c-d]: the library's orient3d convention.
inline Int128 orient3d(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
    const IntPoint ad = minus(a, d), bd = minus(b, d), cd = minus(c, d);
    return dot(ad, cross(bd, cd));
}

// Positive when e lies inside the sphere through a, b, c, d and orient3d(a, b, c, d) > 0 (the sign flips
// with the orientation); zero when the five points are cospherical or a, b, c, d coplanar.
inline Int128 insphere(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d, const IntPoint& e) {
    // Rows (p - e, |p - e|^2); expanded along the lifted column.
    const IntPoint ae = minus(a, e), be = minus(b, e), ce = minus(c, e), de = minus(d, e);
    const Int128 la = dot(ae, ae), lb = dot(be, be), lc = dot(ce, ce), ld = dot(de, de);
    const Int128 bcd = dot(be, cross(ce, de));
    const Int128 acd = dot(ae, cross(ce, de));
    const Int128 abd = dot(ae, cross(be, de));
    const Int128 abc = dot(ae, cross(be, ce));
    return -la * bcd + lb * acd - lc * abd + ld * abc;
}

// For coplanar a, b, c, d with a, b, c not collinear: +1 when d lies inside the circle through a, b, c,
// -1 outside, 0 on it. The power of d with respect to the circle, scaled by 2 |w|^2 > 0, is
// |e|^2 |w|^2 - e . (|u|^2 (v x w) + |v|^2 (w x u)), with u = b - a, v = c - a, w = u x v, e = d - a.
inline int incircle3d(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
    const IntPoint u = minus(b, a), v = minus(c, a), e = minus(d, a);
    const IntPoint w = cross(u, v);
    const Int128 uu = dot(u, u), vv = dot(v, v);
    // v x w and w x u have components below 2^54: 128-bit products with |u|^2 < 2^36 stay exact.
    const Int128 vw[3] = {Int128(v.y) * w.z - Int128(v.z) * w.y, Int128(v.z) * w.x - Int128(v.x) * w.z,
                          Int128(v.x) * w.y - Int128(v.y) * w.x};
    const Int128 wu[3] = {Int128(w.y) * u.z - Int128(w.z) * u.y, Int128(w.z) * u.x - Int128(w.x) * u.z,
                          Int128(w.x) * u.y - Int128(w.y) * u.x};
    const Int128 ex[3] = {e.x, e.y, e.z};
    Int128 power = dot(e, e) * dot(w, w);
    for (int k = 0; k < 3; ++k) power -= ex[k] * (uu * vw[k] + vv * wu[k]);
    return -sign_of(power);
}

// True when every point lies on one line (fewer than three affinely independent points).
inline bool all_collinear(const IntPoint* points, size_t count) {
    size_t b = 1;
    while (b < count && points[b].x == points[0].x && points[b].y == points[0].y && points[b].z == points[0].z) ++b;
    for (size_t c = b + 1; c < count; ++c) {
        if (!collinear(points[0], points[b], points[c])) return false;
    }
    return true;
}

} // namespace dbrg::fuzz
