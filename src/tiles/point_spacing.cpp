// Point spacing: a high percentile of nearest-neighbour distances over a hash-chosen sample (see
// point_spacing.h).
#include "tiles/point_spacing.h"

#include <math.h>
#include <string.h>

#include <algorithm>

#include "core/array.h"
#include "core/splitmix64.h"

namespace dbrg {
namespace {

const size_t SAMPLE_POINTS = 4096;
// Rings of cells searched around a sample point before it is given up (an isolated outlier).
const int MAX_RINGS = 16;

struct CellEntry {
    uint64_t key;
    uint32_t point;
};

// The cell grid: cells of side `cell` from `low`, keyed by 21 bits per axis.
struct CellGrid {
    double low[3];
    double cell;

    int64_t coordinate(const double* p, int axis) const { return static_cast<int64_t>((p[axis] - low[axis]) / cell); }
    static uint64_t key(int64_t x, int64_t y, int64_t z) { return uint64_t(x) << 42 | uint64_t(y) << 21 | uint64_t(z); }
};

// The points filed by cell in hashed buckets (a bucket holds its cells' entries together, with their
// keys): one counting pass instead of a sort of all the points, and a lookup without a binary search.
struct CellBuckets {
    explicit CellBuckets(Memory& memory) : first(memory), entries(memory) {}

    uint64_t bucket(uint64_t key) const { return SplitMix64(key).next() >> shift; }

    int shift = 64;
    Array<uint32_t> first;  // bucket b's entries are entries[first[b]] to entries[first[b + 1]]
    Array<CellEntry> entries;
};

// One or two points a bucket on average: the bucket starts take at most a quarter of the entries' memory.
bool file_points(const double* xyz, size_t count, const CellGrid& grid, CellBuckets& buckets) {
    int bits = 1;
    while ((size_t(2) << bits) < count) ++bits;
    buckets.shift = 64 - bits;
    if (!buckets.first.resize((size_t(1) << bits) + 1, 0) || !buckets.entries.resize(count)) return false;
    const auto key_of = [&](size_t i) {
        const double* p = xyz + 3 * i;
        return CellGrid::key(grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2));
    };
    for (size_t i = 0; i < count; ++i) ++buckets.first[buckets.bucket(key_of(i)) + 1];
    for (size_t b = 1; b < buckets.first.size(); ++b) buckets.first[b] += buckets.first[b - 1];
    for (size_t i = 0; i < count; ++i) {
        const uint64_t key = key_of(i);
        buckets.entries[buckets.first[buckets.bucket(key)]++] = CellEntry{key, static_cast<uint32_t>(i)};
    }
    // Each bucket's end moved to its start's place: shift back.
    for (size_t b = buckets.first.size() - 1; b > 0; --b) buckets.first[b] = buckets.first[b - 1];
    buckets.first[0] = 0;
    return true;
}

// Distance from point `i` to its nearest other point, searching rings of cells outward; HUGE_VAL when
// none is within MAX_RINGS cells.
double nearest_distance(const double* xyz, size_t i, const CellGrid& grid, const CellBuckets& buckets) {
    const double* p = xyz + 3 * i;
    const int64_t c[3] = {grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2)};
    const int64_t limit = int64_t(1) << 21;
    double best = HUGE_VAL;
    for (int ring = 0; ring <= MAX_RINGS; ++ring) {
        for (int64_t x = c[0] - ring; x <= c[0] + ring; ++x) {
            for (int64_t y = c[1] - ring; y <= c[1] + ring; ++y) {
                for (int64_t z = c[2] - ring; z <= c[2] + ring; ++z) {
                    const bool shell = x == c[0] - ring || x == c[0] + ring || y == c[1] - ring ||
                                       y == c[1] + ring || z == c[2] - ring || z == c[2] + ring;
                    if (!shell || x < 0 || y < 0 || z < 0 || x >= limit || y >= limit || z >= limit) continue;
                    const uint64_t key = CellGrid::key(x, y, z);
                    const uint64_t b = buckets.bucket(key);
                    for (uint32_t e = buckets.first[b]; e < buckets.first[b + 1]; ++e) {
                        const CellEntry& entry = buckets.entries[e];
                        if (entry.key != key) continue;  // another cell in the same bucket
                        const double* q = xyz + 3 * size_t(entry.point);
                        const double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
                        const double d = sqrt(dx * dx + dy * dy + dz * dz);
                        if (d > 0 && d < best) best = d;
                    }
                }
            }
        }
        // Every point of a later ring is at least `ring` cells away.
        if (best <= ring * grid.cell) break;
    }
    return best;
}

} // namespace

uint64_t coordinate_hash(const double* p) {
    uint64_t bits[3];
    memcpy(bits, p, sizeof bits);
    return SplitMix64(bits[0] ^ SplitMix64(bits[1] ^ SplitMix64(bits[2]).next()).next()).next();
}

double spacing_grid_cell(double extent, size_t count) {
    // Points on a surface of about the box's size are about extent / sqrt(count) apart: a cell or two.
    return std::max(extent / sqrt(double(count)), extent * 0x1p-20);
}

uint64_t spacing_sample_stride(size_t count) { return std::max<uint64_t>(1, count / SAMPLE_POINTS); }

dbrg_status estimate_spacing(const double* xyz, size_t count, Context& context, double& spacing) {
    spacing = 0;
    if (count < 2) return DBRG_OK;
    CellGrid grid;
    double high[3];
    for (int axis = 0; axis < 3; ++axis) grid.low[axis] = high[axis] = xyz[axis];
    for (size_t i = 0; i < count; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            grid.low[axis] = std::min(grid.low[axis], xyz[3 * i + axis]);
            high[axis] = std::max(high[axis], xyz[3 * i + axis]);
        }
    }
    const double extent = std::max({high[0] - grid.low[0], high[1] - grid.low[1], high[2] - grid.low[2]});
    if (!(extent > 0)) return DBRG_OK;
    grid.cell = spacing_grid_cell(extent, count);
    CellBuckets buckets(context.memory);
    if (!file_points(xyz, count, grid, buckets)) return context.fail_out_of_memory();
    const uint64_t stride = spacing_sample_stride(count);
    Array<double> distances(context.memory);
    for (size_t i = 0; i < count; ++i) {
        if (coordinate_hash(xyz + 3 * i) % stride != 0) continue;
        const double d = nearest_distance(xyz, i, grid, buckets);
        if (d != HUGE_VAL && !distances.push_back(d)) return context.fail_out_of_memory();
    }
    if (distances.empty()) {
        spacing = grid.cell;
        return DBRG_OK;
    }
    double* percentile = distances.begin() + distances.size() * 9 / 10;
    std::nth_element(distances.begin(), percentile, distances.end());
    spacing = *percentile;
    return DBRG_OK;
}

} // namespace dbrg
