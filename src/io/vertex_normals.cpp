// Angle-weighted vertex normals.
// Based on: G. Thürmer and C. A. Wüthrich, "Computing vertex normals from polygonal facets", Journal of
// Graphics Tools 3(1), 1998.
#include "io/vertex_normals.h"

#include <algorithm>
#include <cmath>

#include "core/intrinsics.h"
#include "core/pi.h"

namespace dbrg::io {
namespace {

// Triangles between the one whose corners are requested and the one being summed.
constexpr size_t PREFETCH_AHEAD = 8;

struct Vector {
    double x, y, z;
};

Vector operator-(const Vector& a, const Vector& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vector cross(const Vector& a, const Vector& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(const Vector& a, const Vector& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Vector& a) { return std::sqrt(dot(a, a)); }

Vector position(const std::vector<double>& positions, uint32_t vertex) {
    const double* p = &positions[3 * size_t(vertex)];
    return {p[0], p[1], p[2]};
}

} // namespace

std::vector<float> vertex_normals(const std::vector<double>& positions, const std::vector<uint32_t>& triangles) {
    std::vector<double> sums(positions.size(), 0.0);
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        // The corners of a triangle some way ahead are requested now: the vertices lie anywhere in the
        // caller's order, and each triangle's would otherwise wait on memory one after another.
        if (t + 3 * PREFETCH_AHEAD + 2 < triangles.size()) {
            for (size_t k = 0; k < 3; ++k) {
                const size_t v = triangles[t + 3 * PREFETCH_AHEAD + k];
                prefetch(&positions[3 * v]);
                prefetch(&sums[3 * v]);
            }
        }
        const Vector corner[3] = {position(positions, triangles[t]), position(positions, triangles[t + 1]),
                                  position(positions, triangles[t + 2])};
        const Vector normal = cross(corner[1] - corner[0], corner[2] - corner[0]);
        const double area_twice = length(normal);
        if (!(area_twice > 0.0) || !std::isfinite(area_twice)) continue;
        const Vector unit = {normal.x / area_twice, normal.y / area_twice, normal.z / area_twice};
        // atan2 of |u x v| and u . v stays accurate for angles near 0 and pi, where acos does not; |u x v|
        // at every corner is twice the area. The third angle is what the first two leave of pi.
        double angle[3];
        for (size_t k = 0; k < 2; ++k) {
            angle[k] = std::atan2(area_twice, dot(corner[(k + 1) % 3] - corner[k], corner[(k + 2) % 3] - corner[k]));
        }
        angle[2] = std::max(PI - angle[0] - angle[1], 0.0);
        for (size_t k = 0; k < 3; ++k) {
            double* sum = &sums[3 * size_t(triangles[t + k])];
            sum[0] += angle[k] * unit.x;
            sum[1] += angle[k] * unit.y;
            sum[2] += angle[k] * unit.z;
        }
    }
    std::vector<float> normals(sums.size(), 0.0f);
    for (size_t v = 0; v + 2 < sums.size(); v += 3) {
        const double norm = length({sums[v], sums[v + 1], sums[v + 2]});
        if (!(norm > 0.0)) continue;
        for (size_t k = 0; k < 3; ++k) normals[v + k] = static_cast<float>(sums[v + k] / norm);
    }
    return normals;
}

} // namespace dbrg::io
