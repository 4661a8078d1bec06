// Flat test regions: point sets that lie exactly in one plane (a disk, a square with a square hole, the
// letter E), sampled on a grid or jittered, in an axis-aligned or a tilted plane, each with the region it
// samples so that a result can be judged against it.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/splitmix64.h"

namespace dbrg::test {

enum class FlatShape { disk, square_with_hole, letter_e };
enum class FlatSampling { grid, jittered };
enum class FlatPlane { axis_aligned, tilted };

// The regions in grid steps, closed sets.
inline bool inside_region(FlatShape shape, double u, double v) {
    const auto in_box = [&](double u0, double v0, double u1, double v1) { return u >= u0 && u <= u1 && v >= v0 && v <= v1; };
    switch (shape) {
    case FlatShape::disk: return u * u + v * v <= 15.0 * 15.0;
    case FlatShape::square_with_hole: return in_box(-15, -15, 15, 15) && !(std::fabs(u) < 6 && std::fabs(v) < 6);
    case FlatShape::letter_e:
        return in_box(0, 0, 6, 30) || in_box(0, 0, 20, 6) || in_box(0, 12, 16, 18) || in_box(0, 24, 20, 30);
    }
    return false;
}

// Boundary loops and Euler characteristic of the region.
inline int region_loops(FlatShape shape) { return shape == FlatShape::square_with_hole ? 2 : 1; }
inline int region_euler(FlatShape shape) { return shape == FlatShape::square_with_hole ? 0 : 1; }

struct FlatSet {
    std::string name;
    FlatShape shape;
    std::vector<double> uv;   // in grid steps, multiples of 1/256
    std::vector<double> xyz;  // origin + u * u_axis + v * v_axis, exactly
    // The plane's normal u_axis x v_axis, along which (u, v) turn counter-clockwise.
    std::array<double, 3> normal;
};

// The plane's frame. The tilted one has orthogonal axes of equal length (7/8), so circles in (u, v) are
// circles in space; its coordinates are sums of small dyadic products, exact in doubles.
inline void plane_frame(FlatPlane plane, std::array<double, 3>& origin, std::array<double, 3>& u_axis,
                        std::array<double, 3>& v_axis) {
    if (plane == FlatPlane::axis_aligned) {
        origin = {0, 0, 0.75};
        u_axis = {1, 0, 0};
        v_axis = {0, 1, 0};
    } else {
        origin = {3, -2, 1};
        u_axis = {2 / 8.0, 3 / 8.0, 6 / 8.0};
        v_axis = {6 / 8.0, 2 / 8.0, -3 / 8.0};
    }
}

inline FlatSet flat_set(FlatShape shape, FlatSampling sampling, FlatPlane plane) {
    static const char* const shape_names[] = {"disk", "square with a hole", "letter E"};
    FlatSet set;
    set.shape = shape;
    set.name = std::string(shape_names[int(shape)]) + (sampling == FlatSampling::grid ? ", grid" : ", jittered") +
               (plane == FlatPlane::axis_aligned ? ", axis-aligned" : ", tilted");
    std::array<double, 3> origin, u_axis, v_axis;
    plane_frame(plane, origin, u_axis, v_axis);
    set.normal = {u_axis[1] * v_axis[2] - u_axis[2] * v_axis[1], u_axis[2] * v_axis[0] - u_axis[0] * v_axis[2],
                  u_axis[0] * v_axis[1] - u_axis[1] * v_axis[0]};
    SplitMix64 random(0x5eed + 7 * uint64_t(shape) + 3 * uint64_t(plane));
    for (int i = -16; i <= 31; ++i) {
        for (int j = -16; j <= 31; ++j) {
            double u = i, v = j;
            if (sampling == FlatSampling::jittered) {
                // Up to a quarter step each way, in steps of 1/256.
                u += (double(random.next() % 129) - 64) / 256;
                v += (double(random.next() % 129) - 64) / 256;
            }
            if (!inside_region(shape, u, v)) continue;
            set.uv.insert(set.uv.end(), {u, v});
            for (int k = 0; k < 3; ++k) set.xyz.push_back(origin[k] + u * u_axis[k] + v * v_axis[k]);
        }
    }
    return set;
}

// Every flat set the tests use.
inline std::vector<FlatSet> all_flat_sets() {
    std::vector<FlatSet> sets;
    for (FlatShape shape : {FlatShape::disk, FlatShape::square_with_hole, FlatShape::letter_e}) {
        for (FlatSampling sampling : {FlatSampling::grid, FlatSampling::jittered}) {
            for (FlatPlane plane : {FlatPlane::axis_aligned, FlatPlane::tilted}) sets.push_back(flat_set(shape, sampling, plane));
        }
    }
    return sets;
}

} // namespace dbrg::test
