// Spatial sort: the insertion order of the tetrahedralization — BRIO rounds, Hilbert order inside each.
//
// Based on: N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO" (SoCG 2003) for the rounds;
// J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004) for the curve index.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"

namespace dbrg {

// How points are numbered: in any order, or along the Hilbert curve over their bounding box (as
// renumber_spatially leaves them), which the insertion order can then take as it is.
enum class PointOrder { any, hilbert };

// Bits per axis of the grid the Hilbert order is computed on (the sort key keeps 7 bits for the round).
constexpr int HILBERT_BITS = 19;

// Position of grid cell (x, y, z), each coordinate below 2^bits, along a 3D Hilbert curve filling the
// 2^bits cube: consecutive positions are face-adjacent cells. bits is in 1..21.
uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits);

// The bounding box of `count` points given as x, y, z triples (all zero when there are none). Reports to
// `progress`; returns DBRG_OK or DBRG_ERR_CANCELLED.
dbrg_status bounding_box(const double* points, size_t count, const ProgressSpan& progress, double lo[3], double hi[3]);

// Fills `order` with a permutation of 0 .. count - 1: rounds of geometrically growing size drawn by a
// pseudo-random generator seeded with each point's index (so the order depends on the point array and
// nothing else), each round sorted along a Hilbert curve over the points' bounding box, using up to
// params.threads threads (the order is the same for any number). Reports to `progress`; returns DBRG_OK,
// DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
dbrg_status brio_hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, Array<uint32_t>& order);

// The insertion order of brio_hilbert_order, produced one point at a time. When the points are already
// numbered along the Hilbert curve over their bounding box (as renumber_spatially leaves them), each round
// in Hilbert order is that round's points in index order, and the order is streamed without any memory
// and without sorting; otherwise it is computed by brio_hilbert_order and read from its array (4 bytes
// per point, 36 while sorting). Either way the sequence is the same.
class BrioOrder {
public:
    explicit BrioOrder(Memory& memory) : order_(memory) {}

    // `known` says how the points are numbered, when the caller knows (PointOrder::any: it is checked).
    // Reports DBRG_STAGE_SORT progress; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
    dbrg_status prepare(const double* points, uint32_t count, PointOrder known, Context& context);

    // The next point of the order into v; false once all have been given.
    bool next(uint32_t& v) {
        if (!streamed_) {
            if (position_ == order_.size()) return false;
            v = order_[position_++];
            return true;
        }
        for (;;) {
            while (position_ < count_) {
                const uint32_t i = position_++;
                if (brio_round(i) == round_) {
                    v = i;
                    return true;
                }
            }
            if (++round_ >= rounds_) return false;
            position_ = 0;
        }
    }

    // Whether the points still to come are all of the last round.
    bool in_last_round() const { return streamed_ ? round_ == rounds_ - 1 : position_ >= last_round_begin_; }

    // Share `part` of `parts` of the points still to come, once in_last_round(): consecutive stretches of
    // the order, for threads that insert them at once (the order itself is then done with).
    class Slice {
    public:
        bool next(uint32_t& v) {
            while (position_ < end_) {
                const uint32_t i = position_++;
                if (array_) {
                    v = array_[i];
                    return true;
                }
                if (round_of(i, rounds_) == rounds_ - 1) {
                    v = i;
                    return true;
                }
            }
            return false;
        }
        // How many positions of the order the slice spans: at least the points it gives.
        uint32_t span() const { return end_ - position_; }
        // Where it is, and going back there: next() gives the same points again from there.
        uint32_t position() const { return position_; }
        void rewind(uint32_t position) { position_ = position; }

    private:
        friend class BrioOrder;
        const uint32_t* array_ = nullptr;  // null when streamed: positions are point indices
        uint32_t position_ = 0, end_ = 0;
        int rounds_ = 1;
    };
    Slice last_round_slice(uint32_t part, uint32_t parts) const;

    // Gives the array's memory back.
    void release() { order_.release(); }

    // Whether the order is streamed (no array).
    bool streamed() const { return streamed_; }

    // The number of rounds for `count` points, and the round of point `index` among them.
    static int round_count(uint32_t count);
    static int round_of(uint32_t index, int rounds);

private:
    int brio_round(uint32_t index) const { return rounds_ == 1 ? 0 : round_of(index, rounds_); }

    Array<uint32_t> order_;
    bool streamed_ = false;
    uint32_t count_ = 0;
    uint32_t position_ = 0;
    uint32_t last_round_begin_ = 0;  // with an array: where the last round starts in it
    int rounds_ = 1;
    int round_ = 0;
};

// Sets `ordered` to whether the points are numbered along the Hilbert curve over their bounding box: their
// curve positions (as hilbert_order computes them) never decrease. Uses up to params.threads threads.
// Reports to `progress`; returns DBRG_OK or DBRG_ERR_CANCELLED.
dbrg_status in_hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, bool& ordered);

// Fills `order` with the permutation of 0 .. count - 1 along a Hilbert curve over the points' bounding box,
// ties by index, using up to params.threads threads (the order is the same for any number). Reports to
// `progress`; returns DBRG_OK, DBRG_ERR_OUT_OF_MEMORY or DBRG_ERR_CANCELLED.
dbrg_status hilbert_order(const double* points, uint32_t count, const ProgressSpan& progress, Array<uint32_t>& order);

} // namespace dbrg
