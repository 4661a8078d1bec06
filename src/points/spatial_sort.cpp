// Spatial sort: the insertion order of the tetrahedralization — BRIO rounds, Hilbert order inside each.
//
// Based on: N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO" (SoCG 2003) for the rounds;
// J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004) for the curve index.
#include "points/spatial_sort.h"

#include <algorithm>
#include <atomic>

#include "core/parallel.h"
#include "core/splitmix64.h"
#include "core/status.h"

namespace dbrg {
namespace {

// Rounds shrink by this factor going backwards from the last one, down to about MIN_ROUND points; the
// round number sits above the Hilbert index in the sort key, so there are at most MAX_ROUNDS.
constexpr uint32_t ROUND_RATIO = 4;
constexpr uint32_t MIN_ROUND = 256;
constexpr int MAX_ROUNDS = 1 << (64 - 3 * HILBERT_BITS);
constexpr uint64_t SHUFFLE_SEED = 0x6a09e667f3bcc909ull;

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

// Maps points to the cells of the 2^HILBERT_BITS grid over a box.
class HilbertGrid {
public:
    HilbertGrid() = default;
    HilbertGrid(const double lo[3], const double hi[3]) {
        double extent = 0;
        for (int k = 0; k < 3; ++k) {
            lo_[k] = lo[k];
            extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
        }
        scale_ = extent > 0 ? CELLS / extent : 0.0;
    }

    uint64_t key(const double* p) const {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k) {
            const double c = (p[k] - lo_[k]) * scale_;
            q[k] = c >= CELLS - 1 ? CELLS - 1 : static_cast<uint32_t>(c);
        }
        return hilbert_index(q[0], q[1], q[2], HILBERT_BITS);
    }

private:
    static constexpr uint32_t CELLS = 1u << HILBERT_BITS;
    double lo_[3] = {0, 0, 0};
    double scale_ = 0;
};

// The grid over the points' bounding box; its share of the progress is the first 10% of `progress`.
dbrg_status grid_over(const double* points, uint32_t count, const ProgressSpan& progress, HilbertGrid& grid) {
    double lo[3], hi[3];
    DBRG_PROPAGATE(bounding_box(points, count, progress.part(0.0, 0.1), lo, hi));
    grid = HilbertGrid(lo, hi);
    return DBRG_OK;
}

// Sorted by key; ties (points in one grid cell) go by index, which keeps the order a function of the points.
// A type rather than a function, so that the sort inlines it rather than calling through a pointer.
struct ByKeyThenIndex {
    bool operator()(const KeyedIndex& a, const KeyedIndex& b) const {
        return a.key != b.key ? a.key < b.key : a.index < b.index;
    }
};

} // namespace

dbrg_status bounding_box(const double* points, size_t count, const ProgressSpan& progress, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = count > 0 ? points[k] : 0.0;
    for (size_t i = 0; i < count; ++i) {
        DBRG_PROPAGATE(progress.report_at(i, count));
        for (int k = 0; k < 3; ++k) {
            const double v = points[3 * i + k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    }
    return progress.report(count, count);
}

uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits) {
    // Skilling's method: turn the axes into the "transposed" Hilbert index level by level from the
    // top, undoing the rotations and reflections of the sub-cubes, then Gray-code across the axes.
    // Without branches: the bits decide through masks, since they are as likely set as not.
    uint32_t a[3] = {x, y, z};
    const int top = bits - 1;
    for (int level = top; level > 0; --level) {
        const uint32_t low = (1u << level) - 1;
        for (int i = 0; i < 3; ++i) {
            const uint32_t set = 0u - ((a[i] >> level) & 1u);  // all ones when bit `level` of axis i is set
            // Set: reflect the low bits of axis 0. Clear: exchange the low bits of axis 0 and axis i
            // (nothing for i = 0).
            const uint32_t swap = (a[0] ^ a[i]) & low & ~set;
            a[0] ^= (low & set) | swap;
            a[i] ^= swap;
        }
    }
    a[1] ^= a[0];
    a[2] ^= a[1];
    uint32_t flip = 0;
    for (int level = top; level > 0; --level) flip ^= (0u - ((a[2] >> level) & 1u)) & ((1u << level) - 1);
    for (int i = 0; i < 3; ++i) a[i] ^= flip;
    // The transposed index: level b of the curve is bit b of each axis, axis 0 most significant.
    return spread_bits(a[0]) << 2 | spread_bits(a[1]) << 1 | spread_bits(a[2]);
}

namespace {

// Fills `order` with 0 .. count - 1 sorted by key(grid, i), ties by index, where grid is the Hilbert grid
// over the points' bounding box: the one sort behind both orders below.
template <class Key>
dbrg_status order_by_key(const double* points, uint32_t count, const ProgressSpan& progress, Array<uint32_t>& order,
                         const Key& key) {
    Context& context = progress.context();
    const uint32_t parts = part_count(context.params.threads, count, MIN_POINTS_PER_THREAD);
    Array<KeyedIndex> keyed(context.memory);
    Array<KeyedIndex> scratch(context.memory);
    if (!order.resize(count) || !keyed.resize(count) || (sort_needs_scratch(count, parts) && !scratch.resize(count))) {
        return context.fail_out_of_memory();
    }
    if (count == 0) return progress.report(1, 1);
    HilbertGrid grid;
    DBRG_PROPAGATE(grid_over(points, count, progress, grid));
    DBRG_PROPAGATE(progress.part(0.1, 0.3).for_each_step(count, parts, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) keyed[i] = KeyedIndex{key(grid, i), static_cast<uint32_t>(i)};
    }));
    DBRG_PROPAGATE(progress.part(0.3, 0.9).sort(keyed.data(), count, scratch.data(), parts, ByKeyThenIndex{}));
    return progress.part(0.9, 1.0).for_each_step(count, parts, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) order[i] = keyed[i].index;
    });
}

} // namespace

dbrg_status brio_hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, Array<uint32_t>& order) {
    // One sort by (round, Hilbert index) orders everything.
    const int rounds = BrioOrder::round_count(count);
    return order_by_key(points, count, progress, order, [&](const HilbertGrid& grid, size_t i) {
        const uint64_t round = uint64_t(BrioOrder::round_of(static_cast<uint32_t>(i), rounds));
        return round << (3 * HILBERT_BITS) | grid.key(points + 3 * i);
    });
}

int BrioOrder::round_count(uint32_t count) {
    int rounds = 1;
    for (uint64_t size = count; size / ROUND_RATIO >= MIN_ROUND && rounds < MAX_ROUNDS; size /= ROUND_RATIO) ++rounds;
    return rounds;
}

// Rounds: the last one takes each point with probability 1 - 1/ROUND_RATIO, the one before it each
// remaining point with the same probability, and so on; the first takes the rest. The draw for a point
// comes from a generator seeded with its index, so the rounds depend on nothing but the points.
int BrioOrder::round_of(uint32_t index, int rounds) {
    uint64_t draw = SplitMix64(SHUFFLE_SEED ^ (uint64_t(index) * 0xd1b54a32d192ed03ull)).next();
    int earlier = 0;  // how many rounds before the last one
    while (earlier + 1 < rounds && draw % ROUND_RATIO == 0) {
        ++earlier;
        draw /= ROUND_RATIO;
    }
    return rounds - 1 - earlier;
}

dbrg_status BrioOrder::prepare(const double* points, uint32_t count, PointOrder known, Context& context) {
    order_.release();
    count_ = count;
    position_ = 0;
    round_ = 0;
    rounds_ = round_count(count);
    const ProgressSpan progress(context, DBRG_STAGE_SORT);
    DBRG_PROPAGATE(progress.report(0, 1));
    // The pipeline's points were just numbered along the curve: their keys need not be computed again.
    streamed_ = known == PointOrder::hilbert;
    if (!streamed_) DBRG_PROPAGATE(in_hilbert_order(points, count, progress.part(0.0, 0.5), streamed_));
    if (streamed_) return progress.report(1, 1);
    DBRG_PROPAGATE(brio_hilbert_order(points, count, progress.part(0.5, 1.0), order_));
    // The order lists the rounds one after the other.
    last_round_begin_ = static_cast<uint32_t>(
        std::partition_point(order_.begin(), order_.end(), [&](uint32_t v) { return brio_round(v) != rounds_ - 1; }) -
        order_.begin());
    return DBRG_OK;
}

BrioOrder::Slice BrioOrder::last_round_slice(uint32_t part, uint32_t parts) const {
    // Streamed, the last round's points are those of its round among the indices from position_ on.
    const uint32_t end = streamed_ ? count_ : static_cast<uint32_t>(order_.size());
    Slice slice;
    slice.array_ = streamed_ ? nullptr : order_.data();
    slice.rounds_ = rounds_;
    slice.position_ = position_ + static_cast<uint32_t>(part_begin(end - position_, parts, part));
    slice.end_ = position_ + static_cast<uint32_t>(part_begin(end - position_, parts, part + 1));
    return slice;
}

dbrg_status in_hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, bool& ordered) {
    ordered = true;
    if (count == 0) return progress.report(1, 1);
    HilbertGrid grid;
    DBRG_PROPAGATE(grid_over(points, count, progress, grid));
    // Each slice also compares its first point with the one before it. A descent is written to the shared
    // flag once, not per point.
    std::atomic<bool> descent(false);
    const uint32_t parts = part_count(progress.context().params.threads, count, MIN_POINTS_PER_THREAD);
    DBRG_PROPAGATE(progress.part(0.1, 1.0).for_each_step(count, parts, [&](size_t begin, size_t end) {
        if (descent.load(std::memory_order_relaxed)) return;
        uint64_t previous = begin == 0 ? 0 : grid.key(points + 3 * (begin - 1));
        bool in_order = true;
        for (size_t i = begin; i < end && in_order; ++i) {
            const uint64_t key = grid.key(points + 3 * i);
            in_order = key >= previous;
            previous = key;
        }
        if (!in_order) descent.store(true, std::memory_order_relaxed);
    }));
    ordered = !descent.load(std::memory_order_relaxed);
    return DBRG_OK;
}

dbrg_status hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, Array<uint32_t>& order) {
    return order_by_key(points, count, progress, order,
                        [&](const HilbertGrid& grid, size_t i) { return grid.key(points + 3 * i); });
}

} // namespace dbrg
