// Helpers shared by the Delaunay and point-conditioning tests: point generators with a fixed seed, a
// counting allocator that can fail on request, and a Context built without the C API.
#pragma once

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <vector>

#include "core/context.h"
#include "core/splitmix64.h"

namespace dbrg_test {

// A deterministic generator so that every run sees the same points.
struct Random : dbrg::SplitMix64 {
    using SplitMix64::SplitMix64;
    double normal() {
        const double u = uniform() + 1e-300, v = uniform();
        return sqrt(-2 * log(u)) * cos(6.283185307179586 * v);
    }
};

inline std::vector<double> random_cube(size_t n, uint64_t seed) {
    Random r(seed);
    std::vector<double> xyz(3 * n);
    for (double& c : xyz) c = r.uniform();
    return xyz;
}

inline std::vector<double> random_sphere(size_t n, uint64_t seed) {
    Random r(seed);
    std::vector<double> xyz(3 * n);
    for (size_t i = 0; i < n; ++i) {
        double p[3] = {r.normal(), r.normal(), r.normal()};
        const double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        for (int k = 0; k < 3; ++k) xyz[3 * i + k] = p[k] / l;
    }
    return xyz;
}

inline std::vector<double> lattice(int n, double jitter, uint64_t seed) {
    Random r(seed);
    std::vector<double> xyz;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                xyz.push_back(i + jitter * (r.uniform() - 0.5));
                xyz.push_back(j + jitter * (r.uniform() - 0.5));
                xyz.push_back(k + jitter * (r.uniform() - 0.5));
            }
    return xyz;
}

// The grid points on the surface of an n x n x n cube: massively cospherical and coplanar.
inline std::vector<double> cube_surface_lattice(int n) {
    std::vector<double> xyz;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                if (i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1) {
                    xyz.push_back(i);
                    xyz.push_back(j);
                    xyz.push_back(k);
                }
            }
    return xyz;
}

// An allocator over malloc that counts allocations and live bytes, and refuses allocation number
// `fail_at` (1-based; 0 never fails). Reallocations count as allocations.
struct CountingAllocator {
    dbrg_allocator allocator;
    uint64_t allocations = 0;
    uint64_t fail_at = 0;
    int64_t live_blocks = 0;
    int64_t live_bytes = 0;

    CountingAllocator() {
        allocator.allocate = [](void* user, size_t size) -> void* {
            CountingAllocator& self = *static_cast<CountingAllocator*>(user);
            if (++self.allocations == self.fail_at) return nullptr;
            void* block = malloc(size);
            if (block) {
                ++self.live_blocks;
                self.live_bytes += int64_t(size);
            }
            return block;
        };
        allocator.reallocate = [](void* user, void* block, size_t old_size, size_t new_size) -> void* {
            CountingAllocator& self = *static_cast<CountingAllocator*>(user);
            if (++self.allocations == self.fail_at) return nullptr;
            void* moved = realloc(block, new_size);
            if (moved) self.live_bytes += int64_t(new_size) - int64_t(old_size);
            return moved;
        };
        allocator.deallocate = [](void* user, void* block, size_t size) {
            CountingAllocator& self = *static_cast<CountingAllocator*>(user);
            --self.live_blocks;
            self.live_bytes -= int64_t(size);
            free(block);
        };
        allocator.user = this;
    }
};

inline dbrg_params test_params(const dbrg_allocator* allocator = nullptr, dbrg_progress_fn progress = nullptr,
                               void* progress_user = nullptr) {
    dbrg_params params;
    memset(&params, 0, sizeof params);
    params.struct_size = sizeof params;
    params.allocator = allocator;
    params.progress = progress;
    params.progress_user = progress_user;
    return params;
}

} // namespace dbrg_test
