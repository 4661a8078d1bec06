// Triangle geometry for region growing: circumradius r(t), diametral balls, circumradii of tetrahedra, unit
// normal, and the cosine of the dihedral angle between two compatibly oriented triangles (paper §3.1.2–3.1.3).
#pragma once

#include "core/vec3.h"

namespace dbrg {

// Unit normal of the counter-clockwise triangle (a, b, c); zero for a degenerate triangle.
inline Vec3 triangle_normal(const double* a, const double* b, const double* c) {
    const Vec3 pa = load_vec3(a);
    return normalized(cross(load_vec3(b) - pa, load_vec3(c) - pa));
}

// Radius of the circle through a, b, c: |ab| |bc| |ca| / (2 |ab x ac|). Infinite when degenerate.
inline double circumradius(const double* a, const double* b, const double* c) {
    const Vec3 pa = load_vec3(a), pb = load_vec3(b), pc = load_vec3(c);
    const double twice_area = length(cross(pb - pa, pc - pa));
    const double product = sqrt(squared_length(pb - pa) * squared_length(pc - pb) * squared_length(pa - pc));
    return twice_area > 0 ? product / (2 * twice_area) : HUGE_VAL;
}

// Whether d is strictly inside the smallest ball through a, b, c (the one centred on their circumcircle).
inline bool in_diametral_ball(const double* a, const double* b, const double* c, const double* d) {
    const Vec3 pa = load_vec3(a), ab = load_vec3(b) - pa, ac = load_vec3(c) - pa;
    const Vec3 n = cross(ab, ac);
    const double nn = squared_length(n);
    if (nn == 0) return false;
    const Vec3 center = (1 / (2 * nn)) * (squared_length(ac) * cross(n, ab) + squared_length(ab) * cross(ac, n));
    return squared_length(load_vec3(d) - pa - center) < squared_length(center);
}

// Radius of the sphere through a, b, c, d. Infinite when they are coplanar.
inline double tet_circumradius(const double* a, const double* b, const double* c, const double* d) {
    const Vec3 pa = load_vec3(a), ab = load_vec3(b) - pa, ac = load_vec3(c) - pa, ad = load_vec3(d) - pa;
    const double volume6 = dot(ab, cross(ac, ad));
    if (volume6 == 0) return HUGE_VAL;
    const Vec3 center = (1 / (2 * volume6)) * (squared_length(ab) * cross(ac, ad) + squared_length(ac) * cross(ad, ab) +
                                               squared_length(ad) * cross(ab, ac));
    return length(center);
}

// cos of the dihedral angle theta(t1, t2) between two triangles that share an edge and are oriented
// compatibly: 1 when they continue each other flat, -1 when t2 folds back onto t1.
inline double dihedral_cosine(Vec3 unit_normal_1, Vec3 unit_normal_2) { return dot(unit_normal_1, unit_normal_2); }

} // namespace dbrg
