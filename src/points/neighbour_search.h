// Neighbour search: the k nearest neighbours of every point, through a k-d tree over the points.
#pragma once

#include <stdint.h>

#include <algorithm>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"

namespace dbrg {

// The most neighbours a search may ask for.
constexpr uint32_t MAX_NEIGHBOURS = 32;

// What one search tells the next: where to stop (its query and the distance to that query's k + 1-th nearest;
// a search from a query near the last one, as consecutive points along the Hilbert curve are, visits fewer
// points), and whether equal distances are common.
struct NearestHint {
    uint32_t query = UINT32_MAX, k = 0;
    double reach = 0;
    uint32_t from_root = 0;  // queries still to search from the root alone (after a tie at the k-th distance)
};

// A k-d tree over `count` distinct points (x, y, z triples, which must outlive it) answering k-nearest-
// neighbour queries. A search prunes every part of the tree not strictly nearer than the k-th neighbour found
// so far, so a point among many equal distances (a grid, a sphere's centre) costs about what any other does;
// among equal distances at the k-th it keeps the points a search from the root meets first, ties in one leaf
// going to the smaller index. The tree and the searches depend on the coordinates and their numbering only, so
// the answers are the same for any number of threads and, for points numbered by their coordinates
// (conditioned points), any input order.
class NeighbourIndex {
public:
    explicit NeighbourIndex(Memory& memory)
        : order_(memory), leaf_begin_(memory), boxes_(memory), leaf_of_(memory), leaf_xyz_(memory) {}

    // Builds the tree with up to context.params.threads threads. Reports to `progress`; returns DBRG_OK,
    // DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
    dbrg_status build(const double* xyz, uint32_t count, const ProgressSpan& progress);

    // Writes the min(k, count - 1) nearest neighbours of point `query` to `out`, nearest first, the point
    // itself left out, and returns how many. k is at most MAX_NEIGHBOURS. Safe to call from several threads.
    // `hint`, if not null, is read and then set for the next query (any query may follow any: the answers do
    // not depend on it).
    uint32_t nearest(uint32_t query, uint32_t k, uint32_t* out, NearestHint* hint = nullptr) const;
    // The same answer through one search from the root, nearest child first, skipping a node at exactly the
    // bound: where the k-th distance is shared with the (k + 1)-th, this is the search that decides which points
    // among the equal ones `nearest` gives.
    uint32_t nearest_from_root(uint32_t query, uint32_t k, uint32_t* out) const;

    // How many neighbours a search for k gives: min(k, MAX_NEIGHBOURS, size() - 1).
    uint32_t neighbours_for(uint32_t k) const {
        return std::min(std::min(k, MAX_NEIGHBOURS), count_ > 0 ? count_ - 1 : 0);
    }
    // The tree's leaves, numbered from 0; leaves with numbers close together hold points close together.
    uint32_t leaf_count() const { return count_ > 0 ? 1u << depth_ : 0; }
    // Writes the k nearest neighbours of every point p of leaves [first, last) to out + k * p, as `nearest`
    // gives them; k must be neighbours_for(k). Safe to call from several threads on disjoint ranges.
    void nearest_of_leaves(uint32_t first, uint32_t last, uint32_t k, uint32_t* out) const;

    uint32_t size() const { return count_; }

private:
    struct Box {
        double lo[3], hi[3];
    };
    // A point and its coordinates, moved together while the tree is built.
    struct TreePoint {
        double xyz[3];
        uint32_t index;
    };
    struct Candidates;
    struct Gathered;
    struct Batch;
    size_t range_begin(uint32_t node, int level) const;
    bool gather(const Box& box, double bound, Batch& batch) const;
    template <class Found>
    void search(const double* q, uint32_t query, uint32_t node, Found& found) const;
    void split_level(int level, uint32_t parts, TreePoint* points) const;

    // The tree in heap layout: node 1 holds points order_[0 .. count_), node v's children are 2v and 2v + 1,
    // each with half of v's range (the first the smaller half); the nodes at depth_ are the leaves.
    const double* xyz_ = nullptr;
    uint32_t count_ = 0;
    int depth_ = 0;
    Array<uint32_t> order_;
    // Leaf l (node 2^depth_ + l) holds positions leaf_begin_[l] .. leaf_begin_[l + 1] of order_.
    Array<uint32_t> leaf_begin_;
    Array<Box> boxes_;
    // The leaf holding each point, and the points' x coordinates in the order of order_, then their y, then z.
    Array<uint32_t> leaf_of_;
    Array<double> leaf_xyz_;
};

// The k nearest neighbours of every point: neighbours[k * i + j] is the (j + 1)-th nearest neighbour of point
// i (as NeighbourIndex::nearest gives them); k is min(wanted, count - 1), wanted at most MAX_NEIGHBOURS. Uses
// up to context.params.threads threads; reports to `progress`; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or
// DBRG_ERR_CANCELLED.
dbrg_status find_nearest_neighbours(const double* xyz, uint32_t count, uint32_t wanted, const ProgressSpan& progress,
                                    uint32_t& k, Array<uint32_t>& neighbours);
// The same through an index already built.
dbrg_status find_nearest_neighbours(const NeighbourIndex& index, uint32_t wanted, const ProgressSpan& progress,
                                    uint32_t& k, Array<uint32_t>& neighbours);

} // namespace dbrg
