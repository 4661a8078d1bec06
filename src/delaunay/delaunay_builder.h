// Delaunay builder: the state the built-in engine shares between its sequential insertion
// (bowyer_watson.cpp), its tetrahedron slots (tet_slots.cpp) and its parallel insertion
// (parallel_insertion.cpp). Private to the engine.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include <atomic>

#include "core/array.h"
#include "core/context.h"
#include "points/spatial_sort.h"
#include "delaunay/tetrahedralization.h"

namespace dbrg {

// Insertion reports progress every this many points: a few milliseconds even where insertions are slow
// (surface samples with many needle-shaped tetrahedra). Context passes on steps of 0.1 % of the stage.
constexpr uint32_t PROGRESS_INTERVAL = 256;
// The store is written or mapped in steps of this many slots: a millisecond or two each.
constexpr size_t WRITE_STEP_SLOTS = 1 << 17;
constexpr uint64_t WALK_SEED = 0xbb67ae8584caa73bull;
// Shared insertion of the last BRIO round runs on at most this many threads: each needs a mark below
// 256 and about 300 KB of scratch space.
constexpr uint32_t MAX_INSERTION_THREADS = 8;

struct BoundaryFace {
    uint32_t tet;   // a cavity tetrahedron
    uint32_t face;  // its local face on the cavity boundary
};

struct NewTet {
    uint32_t vertex[4];
    uint32_t outer;  // packed adjacency across face `face` (the cavity boundary it replaces)
    uint32_t face;   // the local index of the new point
};

struct EdgeEntry {
    uint64_t edge;  // x << 32 | y, a directed edge; EMPTY_EDGE if unused
    uint32_t link;  // the new tetrahedron and its local face filed under the edge
};
constexpr uint64_t EMPTY_EDGE = UINT64_MAX;

struct FiledFace {
    uint64_t edge;   // x << 32 | y for the face running v -> x -> y
    uint32_t link;   // the new tetrahedron and its local face
    uint32_t entry;  // where in the table it was filed (faces filed only)
};

// Slots in the edge table for the faces of `faces` new tetrahedra: a power of two, at most half full.
inline size_t edge_table_size(size_t faces) {
    size_t size = 64;
    while (size < 3 * faces) size *= 2;
    return size;
}

// What one thread needs to insert points: where its next walk starts, its random bits and predicate
// counts, its free slots and the scratch space of one insertion. While several threads insert at once,
// each also has a mark, the tetrahedra it has claimed with it, the unused slots handed to it and the
// points it left for later.
struct Inserter {
    explicit Inserter(Memory& memory)
        : cavity(memory), outside(memory), boundary(memory), new_tets(memory), new_slots(memory), edges(memory),
          filed(memory), held(memory), deferred(memory) {}

    uint32_t hint = 0;  // where the next walk starts: a tetrahedron of the last insertion, or where one given up got to
    uint64_t random = WALK_SEED;
    PredicateCounters counters;
    int64_t finite_change = 0;    // finite tetrahedra made less those removed
    uint32_t free_head = NO_TET;  // free slots, chained through adjacency entry 0
    uint32_t free_count = 0;
    uint32_t chunk_next = 0, chunk_end = 0;  // unused slots handed to this thread (shared insertion)
    uint8_t mark = 0;                        // its mark in the claims (shared insertion)
    bool left_out = false;                   // the last shared insertion gave its point up
    uint32_t inserted = 0;                   // points a shared insertion put in
    bool out_of_slots = false;               // the store is full (shared insertion)
    const char* failure = nullptr;           // why a shared insertion failed (reported by the calling thread)

    Array<uint32_t> cavity;
    Array<uint32_t> outside;
    Array<BoundaryFace> boundary;
    Array<NewTet> new_tets;
    Array<uint32_t> new_slots;
    Array<EdgeEntry> edges;
    Array<FiledFace> filed;     // the faces one insertion filed in edges
    Array<uint32_t> held;       // the tetrahedra claimed with `mark`
    Array<uint32_t> deferred;   // points given up, for the calling thread to insert after the others
};

class DelaunayBuilder {
public:
    DelaunayBuilder(Tetrahedralization& out, Context& context)
        : out_(out), context_(context), memory_(context.memory), main_(memory_), pending_(memory_), claims_(memory_) {}

    // Inserts the `count` points of `points` in the order `order` gives (the four first affinely
    // independent ones first). Vertex ids are indices into `points`.
    dbrg_status run(const double* points, BrioOrder& order, uint32_t count);

private:
    // Sequential insertion (bowyer_watson.cpp).
    dbrg_status start();
    bool next_vertex(uint32_t& v);
    // Inserts v; `next` is the point inserted after it, or null. Shared: other threads insert at the same
    // time; where a tetrahedron it needs is claimed by one of them, or its fixed scratch space or slots do
    // not suffice, it changes nothing and sets `left_out`.
    template <bool Shared> dbrg_status insert(Inserter& in, uint32_t v, const double* next);
    template <bool Shared> dbrg_status locate(Inserter& in, uint32_t start, const double* p, uint32_t& found);
    template <bool Shared> dbrg_status give_up(Inserter& in);
    template <bool Shared> dbrg_status fail_internal(Inserter& in, const char* message);
    bool in_conflict(Inserter& in, const uint32_t* tet, const double* p);
    template <bool Shared> dbrg_status link_new_tets(Inserter& in);
    dbrg_status size_edge_table(Inserter& in, size_t faces);
    void choose_hint(Inserter& in, const double* next);
    const double* point(uint32_t v) const { return points_ + 3 * size_t(v); }
    uint32_t next_random(Inserter& in) {
        // xorshift64: only a few bits per walk step are needed, and it has to be cheap.
        in.random ^= in.random << 13;
        in.random ^= in.random >> 7;
        in.random ^= in.random << 17;
        return static_cast<uint32_t>(in.random >> 32);
    }

    // Tetrahedron slots (tet_slots.cpp). The store's arrays have room (capacity) for more slots than they
    // have written (size), and written more than are in use (slot_end_).
    template <bool Shared> dbrg_status take_slot(Inserter& in, uint32_t& slot);
    dbrg_status size_initial_store();
    dbrg_status reserve_store(size_t slots);
    dbrg_status write_store(size_t slots);
    dbrg_status extend_store();
    dbrg_status write_store_ahead();
    void map_store(size_t from, size_t to);
    size_t projected_slots() const;
    void hand_back_chunk(Inserter& in);
    void refresh_pointers() {
        vertex_ = out_.vertices_.data();
        adjacency_ = out_.adjacency_.data();
    }
    void free_slot(Inserter& in, uint32_t s) {
        vertex_[4 * size_t(s)] = Tetrahedralization::FREE_MARK;
        adjacency_[4 * size_t(s)] = in.free_head;
        in.free_head = s;
        ++in.free_count;
    }

    // Shared insertion of the last BRIO round (parallel_insertion.cpp).
    dbrg_status insert_last_round(uint32_t parts);
    dbrg_status prepare_inserter(Inserter& in, uint32_t part, uint32_t deferred_room);
    void insert_slice(Inserter& in, BrioOrder::Slice& slice, bool reporting, dbrg_status& status);
    dbrg_status report_round();
    void release_claims(Inserter& in);
    bool room_for(Inserter& in, size_t faces, size_t cavity_size);
    // Claims tetrahedron t for the thread, or answers false when another thread holds it or the thread's
    // list of claims is full. Defined here because the walk and the cavity search call it for every
    // tetrahedron they touch.
    bool claim(Inserter& in, uint32_t t) {
        uint8_t* mark = claims_.data() + t;
        if (__atomic_load_n(mark, __ATOMIC_RELAXED) == in.mark) return true;
        if (in.held.size() == in.held.capacity()) return false;
        uint8_t unclaimed = 0;
        if (!__atomic_compare_exchange_n(mark, &unclaimed, in.mark, false, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED)) {
            return false;
        }
        in.held.push_back(t);
        return true;
    }

    Tetrahedralization& out_;
    Context& context_;
    Memory& memory_;
    const double* points_ = nullptr;
    uint32_t* vertex_ = nullptr;     // out_.vertices_.data(), refreshed whenever the store grows
    uint32_t* adjacency_ = nullptr;  // out_.adjacency_.data()
    uint32_t slot_end_ = 0;          // slots in use or free; the arrays hold more until run() ends
    BrioOrder* order_ = nullptr;     // the insertion order
    uint32_t count_ = 0;             // points to insert
    uint32_t inserted_ = 0;          // points inserted so far
    Inserter main_;                  // the calling thread's

    Array<uint32_t> pending_;  // points the order gave before the first tetrahedron was complete
    size_t pending_next_ = 0;

    // Shared insertion: per slot, the mark of the thread that claimed it (0: none); the next slot not yet
    // handed to a thread; a flag that tells the threads to stop; about how many points the threads have
    // inserted (each adds its count in steps), for the calling thread's progress reports.
    Array<uint8_t> claims_;
    std::atomic<uint32_t> next_chunk_{0};
    std::atomic<bool> stop_{false};
    std::atomic<uint32_t> round_inserted_{0};
};

} // namespace dbrg
