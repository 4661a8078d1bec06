// Vec3: the small amount of 3D vector arithmetic the geometry code needs.
#pragma once

#include <math.h>

namespace dbrg {

struct Vec3 {
    double x, y, z;
};

inline Vec3 load_vec3(const double* p) { return Vec3{p[0], p[1], p[2]}; }
inline Vec3 operator+(Vec3 a, Vec3 b) { return Vec3{a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return Vec3{a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return Vec3{s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double squared_length(Vec3 a) { return dot(a, a); }
inline double length(Vec3 a) { return sqrt(dot(a, a)); }

// Returns a / |a|, or the zero vector when a is zero.
inline Vec3 normalized(Vec3 a) {
    const double l = length(a);
    return l > 0 ? (1.0 / l) * a : Vec3{0, 0, 0};
}

} // namespace dbrg
