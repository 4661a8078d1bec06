// Spatial sort: the insertion order of the tetrahedralization — BRIO rounds, Hilbert order inside each.
//
// Based on: N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO" (SoCG 2003) for the rounds;
// J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004) for the curve index.
#include "delaunay/spatial_sort.h"

#include <algorithm>

#include "core/status.h"

namespace dbrg {
namespace {

// Rounds shrink by this factor going backwards from the last one; the first round holds whatever is
// left below MIN_ROUND points.
constexpr uint32_t ROUND_RATIO = 4;
constexpr uint32_t MIN_ROUND = 256;
constexpr uint64_t SHUFFLE_SEED = 0x6a09e667f3bcc909ull;

// splitmix64: a small, well-mixed generator; one instance per call, seeded with a constant.
uint64_t next_random(uint64_t& state) {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// Spreads the low 21 bits of v so that bit i lands on bit 3i.
uint64_t spread_bits(uint32_t v) {
    uint64_t x = v & 0x1fffffu;
    x = (x | x << 32) & 0x001f00000000ffffull;
    x = (x | x << 16) & 0x001f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

struct KeyedIndex {
    uint64_t key;
    uint32_t index;
};

} // namespace

uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits) {
    // Skilling's method: turn the axes into the "transposed" Hilbert index level by level from the
    // top, undoing the rotations and reflections of the sub-cubes, then Gray-code across the axes.
    uint32_t a[3] = {x, y, z};
    const uint32_t top = 1u << (bits - 1);
    for (uint32_t q = top; q > 1; q >>= 1) {
        const uint32_t low = q - 1;
        for (int i = 0; i < 3; ++i) {
            if (a[i] & q) {
                a[0] ^= low;  // reflect
            } else {
                const uint32_t swap = (a[0] ^ a[i]) & low;  // exchange the low bits of axis 0 and axis i
                a[0] ^= swap;
                a[i] ^= swap;
            }
        }
    }
    a[1] ^= a[0];
    a[2] ^= a[1];
    uint32_t flip = 0;
    for (uint32_t q = top; q > 1; q >>= 1) {
        if (a[2] & q) flip ^= q - 1;
    }
    for (int i = 0; i < 3; ++i) a[i] ^= flip;
    // The transposed index: level b of the curve is bit b of each axis, axis 0 most significant.
    return spread_bits(a[0]) << 2 | spread_bits(a[1]) << 1 | spread_bits(a[2]);
}

dbrg_status brio_hilbert_order(const double* points, uint32_t count, Context& context, Array<uint32_t>& order) {
    DBRG_PROPAGATE(context.report(DBRG_STAGE_SORT, 0.0));
    if (!order.resize(count)) return context.fail_out_of_memory();
    for (uint32_t i = 0; i < count; ++i) order[i] = i;
    if (count == 0) return DBRG_OK;

    // Fisher-Yates with a fixed seed: a random draw of which points go into which round.
    uint64_t state = SHUFFLE_SEED;
    for (uint32_t i = count - 1; i > 0; --i) {
        const uint32_t j = static_cast<uint32_t>(next_random(state) % (uint64_t(i) + 1));
        const uint32_t t = order[i];
        order[i] = order[j];
        order[j] = t;
    }

    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = points[k];
    for (uint32_t i = 1; i < count; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double v = points[3 * size_t(i) + k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    }
    double extent = 0;
    for (int k = 0; k < 3; ++k) extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
    const uint32_t cells = 1u << HILBERT_BITS;
    const double scale = extent > 0 ? cells / extent : 0.0;

    // The largest round is the last: count - count / ROUND_RATIO points, or all of them when the set is
    // too small to split.
    Array<KeyedIndex> keyed(context.memory);
    const uint32_t largest_round = count / ROUND_RATIO >= MIN_ROUND ? count - count / ROUND_RATIO : count;
    if (!keyed.resize(largest_round)) return context.fail_out_of_memory();
    uint32_t end = count;
    while (end > 0) {
        const uint32_t begin = end / ROUND_RATIO >= MIN_ROUND ? end / ROUND_RATIO : 0;
        for (uint32_t i = begin; i < end; ++i) {
            const double* p = points + 3 * size_t(order[i]);
            uint32_t q[3];
            for (int k = 0; k < 3; ++k) {
                const double c = (p[k] - lo[k]) * scale;
                q[k] = c >= cells - 1 ? cells - 1 : static_cast<uint32_t>(c);
            }
            keyed[i - begin] = KeyedIndex{hilbert_index(q[0], q[1], q[2], HILBERT_BITS), order[i]};
        }
        // Ties (points in one grid cell) go by vertex id, which keeps the order a function of the points.
        std::sort(keyed.begin(), keyed.begin() + (end - begin), [](const KeyedIndex& a, const KeyedIndex& b) {
            return a.key != b.key ? a.key < b.key : a.index < b.index;
        });
        for (uint32_t i = begin; i < end; ++i) order[i] = keyed[i - begin].index;
        end = begin;
    }
    return context.report(DBRG_STAGE_SORT, 1.0);
}

} // namespace dbrg
