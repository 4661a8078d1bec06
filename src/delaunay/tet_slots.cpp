// Tetrahedron slots during construction: taken from a thread's free list or chunk or from the end of the
// store, which is reserved ahead of need and written in steps.
#include <algorithm>

#include "core/parallel.h"
#include "core/status.h"
#include "delaunay/delaunay_builder.h"

namespace dbrg {
namespace {

// Finite tetrahedra per point of a uniform random set are about 6.77 (24 pi^2 / 35), of the real meshes'
// vertices 5.8 to 7, of dense samples of closed surfaces up to three times as many. The store is reserved
// for the low end of that; when it is full, the tetrahedra per point inserted so far (BRIO spreads every
// round over the whole set, so that ratio hardly changes as points come in) project the final count, and
// the store grows to that plus a margin on the part still to come, at least a sixteenth. So the unused
// capacity at the end, and with it the peak, stays within a few percent of the store.
constexpr double EXPECTED_TETS_PER_POINT = 6.0;
constexpr size_t GROWTH_DIVISOR = 16;
constexpr double PROJECTION_MARGIN = 1.05;
// Below this many new store entries per thread, a thread costs more to start than the fill it takes over.
constexpr size_t MIN_ENTRIES_PER_FILL_THREAD = 1 << 18;
// Sequential insertion writes the reserved store in steps of WRITE_STEP_SLOTS slots (a millisecond or two
// each, between progress reports) as it needs them, and ahead of need while fewer than this many per point
// inserted are written: the initial reservation (6 per point) is then written within the first fifth of
// the points, before the last BRIO round (three quarters of them) starts.
constexpr size_t SLOTS_AHEAD_PER_POINT = 32;

} // namespace

template <bool Shared>
dbrg_status DelaunayBuilder::take_slot(Inserter& in, uint32_t& slot) {
    if (in.free_head != NO_TET) {
        slot = in.free_head;
        in.free_head = adjacency_[4 * size_t(slot)];
        --in.free_count;
    } else if (Shared) {
        slot = in.chunk_next++;  // room_for made sure there is one
    } else {
        const size_t slots = slot_end_;
        if (slots >= MAX_TET_SLOTS) {
            return context_.fail(DBRG_ERR_TOO_MANY_POINTS, "the tetrahedralization needs more than %u tetrahedra",
                                 MAX_TET_SLOTS);
        }
        if (4 * slots == out_.vertices_.size()) DBRG_PROPAGATE(extend_store());
        slot = slot_end_++;
        return DBRG_OK;
    }
    return Shared && !claim(in, slot) ? fail_internal<Shared>(in, "a free slot was claimed (a bug in dbrg)") : DBRG_OK;
}

// Sequential and shared insertion (bowyer_watson.cpp) both take slots.
template dbrg_status DelaunayBuilder::take_slot<false>(Inserter& in, uint32_t& slot);
template dbrg_status DelaunayBuilder::take_slot<true>(Inserter& in, uint32_t& slot);

// The store for the first points: room for the expected tetrahedra of all of them, its first step written.
dbrg_status DelaunayBuilder::size_initial_store() {
    const double expected = EXPECTED_TETS_PER_POINT * count_ + 64;
    DBRG_PROPAGATE(reserve_store(static_cast<size_t>(expected < MAX_TET_SLOTS ? expected : MAX_TET_SLOTS)));
    return write_store(WRITE_STEP_SLOTS);
}

// Sequential insertion has used every written slot: the next step of the reserved ones, after reserving
// more when those are all written.
dbrg_status DelaunayBuilder::extend_store() {
    const size_t slots = slot_end_;
    if (4 * slots == out_.vertices_.capacity()) {
        const size_t grown = slots + slots / GROWTH_DIVISOR + 64;
        DBRG_PROPAGATE(reserve_store(std::min<size_t>(std::max(grown, projected_slots()), MAX_TET_SLOTS)));
    }
    return write_store(slots + WRITE_STEP_SLOTS);
}

// Called at every progress interval of sequential insertion.
dbrg_status DelaunayBuilder::write_store_ahead() {
    const size_t written = out_.vertices_.size() / 4;
    return written < SLOTS_AHEAD_PER_POINT * inserted_ ? write_store(written + WRITE_STEP_SLOTS) : DBRG_OK;
}

// The slots the tetrahedralization will need: the tetrahedra per point inserted so far (BRIO spreads
// every round over the whole set, so that ratio hardly changes as points come in) for all the points,
// with a margin on the part still to come.
size_t DelaunayBuilder::projected_slots() const {
    if (inserted_ == 0 || inserted_ >= count_) return slot_end_;
    // Clamped while still a double: the cast of a value beyond size_t's range is undefined.
    const double projected = slot_end_ + double(slot_end_) / inserted_ * (count_ - inserted_) * PROJECTION_MARGIN + 64;
    return projected < MAX_TET_SLOTS ? static_cast<size_t>(projected) : MAX_TET_SLOTS;
}

// Room for `slots` slots; nothing is written.
dbrg_status DelaunayBuilder::reserve_store(size_t slots) {
    if (!out_.vertices_.reserve(4 * slots) || !out_.adjacency_.reserve(4 * slots)) return context_.fail_out_of_memory();
    refresh_pointers();
    return DBRG_OK;
}

// Writes the reserved slots up to `slots` (at most the room there is).
dbrg_status DelaunayBuilder::write_store(size_t slots) {
    // The arrays are sized (and so written) for many slots at once, in one fill split among the threads,
    // rather than four entries as each slot is taken: such small writes each wait for a new cache line, at
    // a cost of about a tenth of the insertion time. slot_end_ counts the slots in use; run() cuts the
    // arrays' size to it (the spare capacity, about 1 %, stays allocated).
    Array<uint32_t>& vertices = out_.vertices_;
    Array<uint32_t>& adjacency = out_.adjacency_;
    const size_t old_size = vertices.size();
    const size_t new_size = std::min(4 * slots, vertices.capacity());
    if (new_size <= old_size) return DBRG_OK;
    uint32_t* const vertex_ids = vertices.data() + old_size;
    uint32_t* const neighbours = adjacency.data() + old_size;
    const uint32_t parts = part_count(context_.params.threads, new_size - old_size, MIN_ENTRIES_PER_FILL_THREAD);
    for_each_slice(new_size - old_size, parts, [&](size_t begin, size_t end) {
        memory_.populate(vertex_ids + begin, (end - begin) * sizeof(uint32_t));
        memory_.populate(neighbours + begin, (end - begin) * sizeof(uint32_t));
        std::fill(vertex_ids + begin, vertex_ids + end, 0u);
        std::fill(neighbours + begin, neighbours + end, 0u);
    });
    vertices.resize_unwritten(new_size);
    adjacency.resize_unwritten(new_size);
    refresh_pointers();
    return DBRG_OK;
}

// Maps the pages of slots `from` to `to` without writing them: the threads of the last round may be
// writing some of those slots meanwhile, and mapping leaves what a page holds as it is.
void DelaunayBuilder::map_store(size_t from, size_t to) {
    memory_.populate(vertex_ + 4 * from, 4 * (to - from) * sizeof(uint32_t));
    memory_.populate(adjacency_ + 4 * from, 4 * (to - from) * sizeof(uint32_t));
}

// The unused rest of the thread's chunk goes onto its free list.
void DelaunayBuilder::hand_back_chunk(Inserter& in) {
    while (in.chunk_next < in.chunk_end) free_slot(in, in.chunk_next++);
}

} // namespace dbrg
