// Neighbour search: a k-d tree split at the median of each node's widest axis, every leaf at one depth,
// searched nearest child first with a bounded candidate list.
//
// Based on: J. H. Friedman, J. L. Bentley, R. A. Finkel, "An algorithm for finding best matches in
// logarithmic expected time" (ACM TOMS 3(3), 1977).
#include "points/neighbour_search.h"

#include <math.h>

#include <algorithm>

#include "core/parallel.h"
#include "core/status.h"

namespace dbrg {
namespace {

// Points per leaf at most: a leaf's points are compared with the query one after another, which is cheaper
// than descending further for a handful of points (16 measured faster than 8 or 4, and as fast as 32, for
// searches of 16 neighbours).
constexpr uint32_t LEAF_POINTS = 16;
// Queries searched from the root alone after one with a tie at the k-th distance (on a grid nearly all have
// one, and the search from the query's leaf is then wasted).
constexpr uint32_t ROOT_SEARCHES_AFTER_TIE = 8;
// The most points one leaf's queries are compared with together; a leaf whose surroundings hold more has its
// queries searched one by one.
constexpr uint32_t BATCH_POINTS = 512;
// A leaf's queries are compared with the points within this many times the farthest (k + 1)-th neighbour
// found for the queries of the leaf before it: enough that nearly every query's k + 1 nearest are among them.
constexpr double BATCH_REACH = 1.1;

double squared_distance(const double* a, const double* b) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

template <class Box>
double squared_distance_to_box(const double* p, const Box& box) {
    double sum = 0;
    for (int a = 0; a < 3; ++a) {
        // At most one of the two is positive (lo <= hi), so this is the one that is, or 0.
        const double d = std::max(std::max(box.lo[a] - p[a], p[a] - box.hi[a]), 0.0);
        sum += d * d;
    }
    return sum;
}

// The squared distance between the nearest points of two boxes. Rounding is monotone and the sums run in
// squared_distance's order, so it is never above the squared_distance of a point of one from a point of the other.
template <class Box>
double squared_gap(const Box& a, const Box& b) {
    double sum = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const double d = std::max(std::max(a.lo[axis] - b.hi[axis], b.lo[axis] - a.hi[axis]), 0.0);
        sum += d * d;
    }
    return sum;
}

template <class Box, class Point>
Box box_of(const Point* points, size_t n) {
    Box box;
    for (int a = 0; a < 3; ++a) box.lo[a] = box.hi[a] = points[0].xyz[a];
    for (size_t i = 1; i < n; ++i) {
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = std::min(box.lo[a], points[i].xyz[a]);
            box.hi[a] = std::max(box.hi[a], points[i].xyz[a]);
        }
    }
    return box;
}

} // namespace

// The k nearest found so far, nearest first, and among equal distances the smaller index first.
struct NeighbourIndex::Candidates {
    uint32_t k = 0, size = 0;
    // The k-th distance once k are found, infinity until then: nothing farther can enter.
    double bound = INFINITY;
    double distance[MAX_NEIGHBOURS];
    uint32_t index[MAX_NEIGHBOURS];

    void offer(double d, uint32_t i) {
        if (d > bound || (d == bound && i > index[size - 1])) return;
        uint32_t at = size == k ? size - 1 : size++;
        while (at > 0 && (distance[at - 1] > d || (distance[at - 1] == d && index[at - 1] > i))) {
            distance[at] = distance[at - 1];
            index[at] = index[at - 1];
            --at;
        }
        distance[at] = d;
        index[at] = i;
        if (size == k) bound = distance[k - 1];
    }
};

// The k + 1 nearest found so far, nearest first; an equal distance goes after those already there (the order
// among equal distances is settled at the end). Only a point strictly nearer than the bound enters: when the
// bound is the k + 1-th distance, one at that distance cannot be among the k nearest unless the k-th is equal
// too, and then the answer is not taken from here.
struct NeighbourIndex::Gathered {
    uint32_t wanted = 0, size = 0;
    double bound = INFINITY;
    // The candidates are at 1 .. size; distance[0] is below any distance, so that an insertion stops there.
    double distance[MAX_NEIGHBOURS + 2];
    uint32_t index[MAX_NEIGHBOURS + 2];

    Gathered() { distance[0] = -1; }

    void offer(double d, uint32_t i) {
        if (!(d < bound)) return;
        uint32_t at = size == wanted ? size : ++size;
        for (; distance[at - 1] > d; --at) {
            distance[at] = distance[at - 1];
            index[at] = index[at - 1];
        }
        distance[at] = d;
        index[at] = i;
        if (size == wanted) bound = distance[wanted];
    }
    // Once k + 1 are found: writes the k nearest to `out` and returns true, unless the k-th and the (k + 1)-th
    // are at one distance. Which of the equal points are among the k is then the root search's choice, and
    // this returns false.
    bool take_nearest(uint32_t k, uint32_t* out) {
        if (!(distance[k] < distance[k + 1])) return false;
        // Equal distances in the order of their indices.
        for (uint32_t j = 2; j <= size; ++j) {
            for (uint32_t at = j; at > 1 && distance[at - 1] == distance[at] && index[at - 1] > index[at]; --at) {
                std::swap(index[at - 1], index[at]);
            }
        }
        for (uint32_t j = 0; j < k; ++j) out[j] = index[j + 1];
        return true;
    }
};

// Offers to `found` the n points (at most MAX) numbered index[j] at (x[j], y[j], z[j]) that are not beyond its
// bound, the query itself left out: all their distances first, a loop the compiler can vectorize (the same
// sums as squared_distance's, so the same values), then those within the bound listed without a branch (about
// which way it goes there is no telling), then offered.
template <uint32_t MAX, class Found>
void offer_points(const double* q, uint32_t query, const double* x, const double* y, const double* z,
                  const uint32_t* index, uint32_t n, Found& found) {
    double distance[MAX];
    for (uint32_t j = 0; j < n; ++j) {
        const double dx = q[0] - x[j], dy = q[1] - y[j], dz = q[2] - z[j];
        distance[j] = dx * dx + dy * dy + dz * dz;
    }
    uint32_t near[MAX], m = 0;
    for (uint32_t j = 0; j < n; ++j) {
        near[m] = j;
        m += !(distance[j] > found.bound);
    }
    for (uint32_t t = 0; t < m; ++t) {
        const uint32_t p = index[near[t]];
        if (p != query) found.offer(distance[near[t]], p);
    }
}

// The points near one leaf, their coordinates by axis.
struct NeighbourIndex::Batch {
    uint32_t size = 0;
    double x[BATCH_POINTS], y[BATCH_POINTS], z[BATCH_POINTS];
    uint32_t index[BATCH_POINTS];
};

size_t NeighbourIndex::range_begin(uint32_t node, int level) const {
    return part_begin(count_, 1u << level, node - (1u << level));
}

// Splits every node of one level at the median of its widest axis (ties by index, so the split depends on
// the coordinates and the numbering only: the halves are the same sets whatever order a node's points are
// in). The points move with their coordinates, which the comparisons then read in order.
void NeighbourIndex::split_level(int level, uint32_t parts, TreePoint* points) const {
    const uint32_t nodes = 1u << level;
    for_each_slice(nodes, parts, [&](size_t first, size_t last) {
        for (size_t position = first; position < last; ++position) {
            const uint32_t node = nodes + static_cast<uint32_t>(position);
            const size_t begin = range_begin(node, level), end = range_begin(node + 1, level);
            if (end - begin < 2) continue;
            const Box box = box_of<Box>(points + begin, end - begin);
            int axis = 0;
            for (int a = 1; a < 3; ++a) {
                if (box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]) axis = a;
            }
            const size_t middle = range_begin(2 * node + 1, level + 1);
            const auto below = [axis](const TreePoint& a, const TreePoint& b) {
                return a.xyz[axis] < b.xyz[axis] || (a.xyz[axis] == b.xyz[axis] && a.index < b.index);
            };
            std::nth_element(points + begin, points + middle, points + end, below);
        }
    });
}

dbrg_status NeighbourIndex::build(const double* xyz, uint32_t count, const ProgressSpan& progress) {
    Context& context = progress.context();
    xyz_ = xyz;
    count_ = count;
    depth_ = 0;
    while ((size_t(count) + (size_t(1) << depth_) - 1) >> depth_ > LEAF_POINTS) ++depth_;
    const uint32_t leaves = 1u << depth_;
    Array<TreePoint> points(context.memory);
    if (!points.resize(count) || !order_.resize(count) || !boxes_.resize(size_t(2) << depth_) ||
        !leaf_begin_.resize(size_t(leaves) + 1) || !leaf_of_.resize(count) || !leaf_xyz_.resize(3 * size_t(count))) {
        return context.fail_out_of_memory();
    }
    if (count == 0) return progress.report(1, 1);
    for (uint32_t i = 0; i < count; ++i) {
        const double* p = xyz + 3 * size_t(i);
        points[i] = TreePoint{{p[0], p[1], p[2]}, i};
    }
    const uint32_t parts = part_count(context.params.threads, count, MIN_POINTS_PER_THREAD);
    for (int level = 0; level < depth_; ++level) {
        DBRG_PROPAGATE(progress.report(size_t(level), size_t(depth_) + 1));
        split_level(level, parts, points.data());
    }
    // Boxes bottom-up: a leaf's from its points, a node's from its children's. No leaf is empty: the depth is
    // the smallest with at most LEAF_POINTS a leaf, so count >= leaves.
    for (uint32_t leaf = 0; leaf <= leaves; ++leaf) leaf_begin_[leaf] = uint32_t(range_begin(leaves + leaf, depth_));
    for (uint32_t leaf = 0; leaf < leaves; ++leaf) {
        const size_t begin = leaf_begin_[leaf], end = leaf_begin_[leaf + 1];
        for (size_t position = begin; position < end; ++position) {
            order_[position] = points[position].index;
            leaf_of_[points[position].index] = leaf;
            for (int a = 0; a < 3; ++a) leaf_xyz_[a * size_t(count) + position] = points[position].xyz[a];
        }
        boxes_[leaves + leaf] = box_of<Box>(points.data() + begin, end - begin);
    }
    for (uint32_t node = leaves - 1; node >= 1; --node) {
        const Box &a = boxes_[2 * node], &b = boxes_[2 * node + 1];
        for (int axis = 0; axis < 3; ++axis) {
            boxes_[node].lo[axis] = std::min(a.lo[axis], b.lo[axis]);
            boxes_[node].hi[axis] = std::max(a.hi[axis], b.hi[axis]);
        }
    }
    return progress.report(1, 1);
}

// Offers to `found` the points of the subtree under `node` that may be strictly nearer to q than its bound,
// nearest child first, `query` itself left out.
template <class Found>
void NeighbourIndex::search(const double* q, uint32_t query, uint32_t node, Found& found) const {
    const uint32_t leaves = 1u << depth_;
    struct Pending {
        uint32_t node;
        double distance;
    };
    // The farther child of each node on the way down waits here: at most one a level.
    Pending stack[32];
    uint32_t top = 0;
    for (;;) {
        if (node >= leaves) {
            const uint32_t leaf = node - leaves;
            const uint32_t begin = leaf_begin_[leaf], n = leaf_begin_[leaf + 1] - begin;
            const double* x = leaf_xyz_.data() + begin;
            offer_points<LEAF_POINTS>(q, query, x, x + count_, x + 2 * size_t(count_), order_.data() + begin, n,
                                      found);
        } else {
            const uint32_t left = 2 * node, right = left + 1;
            const double to_left = squared_distance_to_box(q, boxes_[left]);
            const double to_right = squared_distance_to_box(q, boxes_[right]);
            const bool left_first = to_left <= to_right;
            const double nearer = left_first ? to_left : to_right, farther = left_first ? to_right : to_left;
            // The bound only shrinks: a child not strictly nearer than it now never will be.
            if (farther < found.bound) stack[top++] = Pending{left_first ? right : left, farther};
            if (nearer < found.bound) {
                node = left_first ? left : right;
                continue;
            }
        }
        while (top > 0 && !(stack[top - 1].distance < found.bound)) --top;
        if (top == 0) break;
        node = stack[--top].node;
    }
}

uint32_t NeighbourIndex::nearest(uint32_t query, uint32_t k, uint32_t* out, NearestHint* hint) const {
    k = neighbours_for(k);
    if (k == 0) return 0;
    const double* q = xyz_ + 3 * size_t(query);
    // First the k + 1 nearest, from the query's own leaf outwards. When the (k + 1)-th is strictly farther than
    // the k-th, the k nearest are the only k points that near, whatever the order of the search; among equal
    // distances at the k-th, though, which points the search from the root keeps depends on its order (it
    // skips a node exactly at the bound), so it runs again.
    // After a tie at the k-th distance the next queries likely have one too (a grid): they go to the search
    // from the root at once for a while.
    if (hint != nullptr && hint->from_root > 0) {
        --hint->from_root;
        return nearest_from_root(query, k, out);
    }
    if (k < count_ - 1) {
        Gathered gathered;
        gathered.wanted = k + 1;
        // The last query's k + 1 nearest and itself, less this query, are k + 1 points within its reach plus
        // the way from there: a bound to start from (a little above it, for the rounding). Should fewer than
        // k + 1 be nearer than that after all, the search runs again without it.
        if (hint != nullptr && hint->k == k && hint->query < count_) {
            const double way = sqrt(squared_distance(q, xyz_ + 3 * size_t(hint->query)));
            const double reach = (hint->reach + way) * (1 + 0x1p-40);
            gathered.bound = reach * reach;
        }
        for (;;) {
            uint32_t node = (1u << depth_) + leaf_of_[query];
            search(q, query, node, gathered);
            for (; node > 1; node >>= 1) {
                const uint32_t sibling = node ^ 1;
                if (squared_distance_to_box(q, boxes_[sibling]) < gathered.bound) search(q, query, sibling, gathered);
            }
            if (gathered.size > k) break;
            gathered.size = 0;
            gathered.bound = INFINITY;
        }
        const bool taken = gathered.take_nearest(k, out);
        if (hint != nullptr) {
            *hint = NearestHint{query, k, sqrt(gathered.distance[k + 1]), taken ? 0 : ROOT_SEARCHES_AFTER_TIE};
        }
        if (taken) return k;
    }
    return nearest_from_root(query, k, out);
}

uint32_t NeighbourIndex::nearest_from_root(uint32_t query, uint32_t k, uint32_t* out) const {
    Candidates found;
    found.k = neighbours_for(k);
    if (found.k == 0) return 0;
    search(xyz_ + 3 * size_t(query), query, 1, found);
    for (uint32_t j = 0; j < found.size; ++j) out[j] = found.index[j];
    return found.size;
}

// Lists in `batch` the points of every leaf whose box is nearer than the square root of `bound` to `box`: every
// point nearer than that to a point in `box` among them. Returns false if they are more than fit.
bool NeighbourIndex::gather(const Box& box, double bound, Batch& batch) const {
    const uint32_t leaves = 1u << depth_;
    uint32_t stack[64], top = 0;
    stack[top++] = 1;
    batch.size = 0;
    while (top > 0) {
        const uint32_t node = stack[--top];
        if (!(squared_gap(box, boxes_[node]) < bound)) continue;
        if (node < leaves) {
            stack[top++] = 2 * node + 1;
            stack[top++] = 2 * node;
            continue;
        }
        const uint32_t begin = leaf_begin_[node - leaves], n = leaf_begin_[node - leaves + 1] - begin;
        if (batch.size + n > BATCH_POINTS) return false;
        const double *x = leaf_xyz_.data() + begin, *y = x + count_, *z = y + count_;
        for (uint32_t j = 0; j < n; ++j) {
            batch.x[batch.size + j] = x[j];
            batch.y[batch.size + j] = y[j];
            batch.z[batch.size + j] = z[j];
            batch.index[batch.size + j] = order_[begin + j];
        }
        batch.size += n;
    }
    return true;
}

// A leaf's queries are compared with the points around the leaf, gathered once for all of them (a search of
// the tree for each query costs more, mostly in mispredicted branches). A query whose k + 1 nearest are not
// all among them is searched alone; one with a tie at the k-th distance from the root, as `nearest` does.
void NeighbourIndex::nearest_of_leaves(uint32_t first, uint32_t last, uint32_t k, uint32_t* out) const {
    if (k == 0) return;
    const uint32_t leaves = 1u << depth_;
    Batch batch;
    NearestHint hint;
    double reach = INFINITY;
    for (uint32_t leaf = first; leaf < last; ++leaf) {
        const uint32_t begin = leaf_begin_[leaf], end = leaf_begin_[leaf + 1];
        // Gathered for the first query that is not searched from the root.
        enum { NOT_YET, GATHERED, TOO_MANY } batch_state = k < count_ - 1 ? NOT_YET : TOO_MANY;
        double farthest = 0;  // squared
        for (uint32_t position = begin; position < end; ++position) {
            const uint32_t query = order_[position];
            uint32_t* row = out + size_t(k) * query;
            if (hint.from_root == 0 && batch_state == NOT_YET) {
                batch_state = gather(boxes_[leaves + leaf], reach * reach, batch) ? GATHERED : TOO_MANY;
            }
            if (hint.from_root == 0 && batch_state == GATHERED) {
                Gathered found;
                found.wanted = k + 1;
                found.bound = reach * reach;
                offer_points<BATCH_POINTS>(xyz_ + 3 * size_t(query), query, batch.x, batch.y, batch.z, batch.index,
                                           batch.size, found);
                if (found.size > k) {
                    farthest = std::max(farthest, found.distance[k + 1]);
                    if (!found.take_nearest(k, row)) {
                        hint.from_root = ROOT_SEARCHES_AFTER_TIE;
                        nearest_from_root(query, k, row);
                    }
                    continue;
                }
            }
            // After a tie (`nearest` counts down the searches from the root), or too many points or too few near.
            nearest(query, k, row, &hint);
            if (hint.query == query) farthest = std::max(farthest, hint.reach * hint.reach);
        }
        if (farthest > 0) reach = BATCH_REACH * sqrt(farthest);
    }
}

dbrg_status find_nearest_neighbours(const NeighbourIndex& index, uint32_t wanted, const ProgressSpan& progress,
                                    uint32_t& k, Array<uint32_t>& neighbours) {
    Context& context = progress.context();
    const uint32_t count = index.size();
    k = index.neighbours_for(wanted);
    neighbours.clear();
    if (k == 0) return progress.report(1, 1);
    if (!neighbours.resize_for_overwrite(size_t(k) * count)) return context.fail_out_of_memory();
    const uint32_t parts = part_count(context.params.threads, count, MIN_POINTS_PER_THREAD);
    // A search costs about as much as sorting a few dozen points: steps of a sixteenth of the usual size, in
    // leaves (of count / leaves points each).
    const uint32_t leaves = index.leaf_count();
    const size_t step = size_t(std::max(uint64_t(1), uint64_t(step_items(parts) / 16) * leaves / count));
    for (size_t first = 0; first < leaves; first += step) {
        DBRG_PROPAGATE(progress.report(first, leaves));
        const size_t last = std::min(size_t(leaves), first + step);
        for_each_slice(last - first, parts, [&](size_t begin, size_t end) {
            index.nearest_of_leaves(uint32_t(first + begin), uint32_t(first + end), k, neighbours.data());
        });
    }
    return progress.report(1, 1);
}

dbrg_status find_nearest_neighbours(const double* xyz, uint32_t count, uint32_t wanted, const ProgressSpan& progress,
                                    uint32_t& k, Array<uint32_t>& neighbours) {
    NeighbourIndex index(progress.context().memory);
    DBRG_PROPAGATE(index.build(xyz, count, progress.part(0.0, 0.3)));
    return find_nearest_neighbours(index, wanted, progress.part(0.3, 1.0), k, neighbours);
}

} // namespace dbrg
