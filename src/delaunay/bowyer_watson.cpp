// Bowyer-Watson: the incremental Delaunay tetrahedralization — walk to the new point, collect the
// cavity of tetrahedra whose circumsphere holds it, and connect the point to the cavity's boundary.
//
// Based on: A. Bowyer, "Computing Dirichlet tessellations" and D. F. Watson, "Computing the
// n-dimensional Delaunay tessellation with application to Voronoi polytopes" (The Computer Journal 24,
// 1981); O. Devillers, S. Pion, M. Teillaud, "Walking in a triangulation" (IJFCS 13, 2002) for the
// randomized visibility walk.
#include <math.h>
#include <string.h>

#include <algorithm>
#include <atomic>
#include <optional>
#if defined(__linux__)
#include <errno.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "core/intrinsics.h"
#include "core/parallel.h"
#include "core/status.h"
#include "delaunay/affine_checks.h"
#include "delaunay/spatial_sort.h"
#include "delaunay/tetrahedralization.h"

namespace dbrg {
namespace {

// While a point is inserted, bit 31 of vertex slot 0 marks a tetrahedron of the cavity and bit 31 of
// slot 1 one that was tested and is not in conflict. Vertex ids stay below 2^31 (DBRG_MAX_POINTS) and
// slots 0 and 1 never hold the infinite vertex, so the bits are free; they are cleared after each point.
constexpr uint32_t IN_CAVITY_BIT = 0x80000000u;
constexpr uint32_t OUTSIDE_BIT = 0x80000000u;
constexpr uint32_t VERTEX_ID_MASK = 0x7fffffffu;
// Adjacency packs the neighbour in the upper 30 bits.
constexpr uint32_t MAX_TET_SLOTS = 1u << 30;
constexpr uint32_t NO_FACE = 4;
constexpr uint32_t PROGRESS_INTERVAL = 4096;
constexpr uint64_t WALK_SEED = 0xbb67ae8584caa73bull;
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
// Shared insertion of the last BRIO round: at most this many threads (each needs a mark below 256 and
// about 300 KB of scratch space), each with room for a cavity of this many tetrahedra and faces (a
// thousand times the usual), for this many claims at once, taking slots this many at a time, and
// remembering up to one in DEFERRED_SHARE of its points as given up.
constexpr uint32_t MAX_INSERTION_THREADS = 8;
constexpr size_t MAX_SHARED_CAVITY = 1024;
constexpr size_t MAX_SHARED_FACES = 2048;
constexpr size_t MAX_SHARED_HELD = 8192;
constexpr uint32_t CHUNK_SLOTS = 1024;
constexpr uint32_t DEFERRED_SHARE = 8;

// Face lf of a tetrahedron as three local vertices in the order that makes (face, lf) an even
// permutation of (0, 1, 2, 3): orient3d(face, v_lf) then has the sign of the tetrahedron.
constexpr uint32_t FACE_VERTEX[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

struct BoundaryFace {
    uint32_t tet;   // a cavity tetrahedron
    uint32_t face;  // its local face on the cavity boundary
};

struct NewTet {
    uint32_t vertex[4];
    uint32_t outer;  // packed adjacency across face `face` (the old cavity boundary)
    uint32_t face;   // the local index of the new point
};

// For the new point in slot lf and a face g != lf of a new tetrahedron: the slots x, y such that the
// face, oriented with the tetrahedron's own vertex g on its positive side, runs (new point, x, y).
constexpr uint8_t DIRECTED_EDGE[4][4][2] = {
    {{0, 0}, {2, 3}, {3, 1}, {1, 2}},
    {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
    {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
    {{2, 1}, {0, 2}, {1, 0}, {0, 0}},
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


// Asks the kernel to map the whole pages inside [data, data + bytes) now, in one call, instead of one
// page fault at a time as the store fills: on a virtual machine each fault is expensive, and the store is
// written in full anyway. Advice only, and only for malloc's memory: a caller's allocator may hand out
// memory the library must not give advice about. errno is left as it was.
void populate(const Memory& memory, void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    if (!memory.uses_system_allocator()) return;
    const long page_size = sysconf(_SC_PAGESIZE);
    if (page_size <= 0) return;
    const uintptr_t page = static_cast<uintptr_t>(page_size);
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + page - 1) & ~(page - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(page - 1);
    const int saved_errno = errno;
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
    errno = saved_errno;
#else
    (void)memory;
    (void)data;
    (void)bytes;
#endif
}

// Slots in the edge table for the faces of `faces` new tetrahedra: a power of two, at most half full.
size_t edge_table_size(size_t faces) {
    size_t size = 64;
    while (size < 3 * faces) size *= 2;
    return size;
}

uint32_t hash_edge(uint64_t edge) {
    const uint64_t h = edge * 0x9e3779b97f4a7c15ull;
    return static_cast<uint32_t>(h >> 40);
}

} // namespace

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
    template <bool Shared> dbrg_status take_slot(Inserter& in, uint32_t& slot);
    dbrg_status size_store(size_t slots);
    size_t projected_slots() const;
    template <bool Shared> dbrg_status link_new_tets(Inserter& in);
    void choose_hint(Inserter& in, const double* next);
    const double* point(uint32_t v) const { return points_ + 3 * size_t(v); }

    // Shared insertion of the last BRIO round.
    dbrg_status insert_last_round(uint32_t parts);
    dbrg_status prepare_inserter(Inserter& in, uint32_t part, uint32_t deferred_room);
    void insert_slice(Inserter& in, BrioOrder::Slice& slice, uint32_t part, dbrg_status& status);
    bool claim(Inserter& in, uint32_t t);
    void release_claims(Inserter& in);
    bool room_for(Inserter& in, size_t faces, size_t cavity_size);
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
    uint32_t next_random(Inserter& in) {
        // xorshift64: only a few bits per walk step are needed, and it has to be cheap.
        in.random ^= in.random << 13;
        in.random ^= in.random >> 7;
        in.random ^= in.random << 17;
        return static_cast<uint32_t>(in.random >> 32);
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
    // handed to a thread; a flag that tells the threads to stop.
    Array<uint8_t> claims_;
    std::atomic<uint32_t> next_chunk_{0};
    std::atomic<bool> stop_{false};
};

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
        if (4 * slots == out_.vertices_.size()) {
            const size_t grown = slots + slots / GROWTH_DIVISOR + 64;
            DBRG_PROPAGATE(size_store(std::min<size_t>(std::max(grown, projected_slots()), MAX_TET_SLOTS)));
        }
        slot = slot_end_++;
        return DBRG_OK;
    }
    return Shared && !claim(in, slot) ? fail_internal<Shared>(in, "a free slot was claimed (a bug in dbrg)") : DBRG_OK;
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

dbrg_status DelaunayBuilder::size_store(size_t slots) {
    // The arrays are sized (and so written) to room for `slots` slots at once, in one fill split among the
    // threads, rather than four entries per new slot: those small writes each waited for a new cache
    // line, and took a tenth of the time. slot_end_ counts the slots in use; run() cuts the arrays' size to
    // it (the spare capacity, about 1 %, stays allocated).
    Array<uint32_t>& vertices = out_.vertices_;
    Array<uint32_t>& adjacency = out_.adjacency_;
    const size_t old_size = vertices.size();
    if (!vertices.reserve(4 * slots) || !adjacency.reserve(4 * slots)) return context_.fail_out_of_memory();
    const size_t new_size = 4 * slots;
    uint32_t* const vertex_ids = vertices.data() + old_size;
    uint32_t* const neighbours = adjacency.data() + old_size;
    const uint32_t parts = part_count(context_.params.threads, new_size - old_size, MIN_ENTRIES_PER_FILL_THREAD);
    for_each_slice(new_size - old_size, parts, [&](size_t begin, size_t end) {
        populate(memory_, vertex_ids + begin, (end - begin) * sizeof(uint32_t));
        populate(memory_, neighbours + begin, (end - begin) * sizeof(uint32_t));
        std::fill(vertex_ids + begin, vertex_ids + end, 0u);
        std::fill(neighbours + begin, neighbours + end, 0u);
    });
    vertices.resize_unwritten(new_size);
    adjacency.resize_unwritten(new_size);
    refresh_pointers();
    return DBRG_OK;
}

bool DelaunayBuilder::in_conflict(Inserter& in, const uint32_t* tet, const double* p) {
    PredicateCounters& counters = in.counters;
    const double* a = point(tet[0] & VERTEX_ID_MASK);
    const double* b = point(tet[1] & VERTEX_ID_MASK);
    const double* c = point(tet[2]);
    if (tet[3] == INFINITE_VERTEX) {
        // Beyond the hull face (a, b, c), or on its plane and inside its circumcircle: the limit of the
        // circumsphere test as the fourth vertex goes to infinity.
        const int side = orient3d(a, b, c, p, counters);
        if (side != 0) return side > 0;
        return incircle3d_sos(a, b, c, p, counters) > 0;
    }
    return insphere_sos(a, b, c, point(tet[3]), p, counters) > 0;
}

// Walks from tetrahedron `start` (claimed when shared) to one that contains p, or that p is beyond.
template <bool Shared>
dbrg_status DelaunayBuilder::locate(Inserter& in, uint32_t start, const double* p, uint32_t& found) {
    found = NO_TET;
    uint32_t t = start;
    if (vertex_[4 * size_t(t) + 3] == INFINITE_VERTEX) {
        t = adjacency_[4 * size_t(t) + 3] >> 2;
        if (Shared && !claim(in, t)) return give_up<Shared>(in);
    }
    uint32_t entry = NO_FACE;  // the face we came in by: p is known to be on its inner side
    // A visibility walk in a Delaunay tetrahedralization never cycles (Edelsbrunner's acyclicity of
    // the in-front relation); the step limit only turns a bug into an error instead of a hang.
    const size_t step_limit = out_.vertices_.size() / 4 + 1000;
    for (size_t step = 0; step < step_limit; ++step) {
        const uint32_t* tv = vertex_ + 4 * size_t(t);
        const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
        const uint32_t first = next_random(in) & 3;
        uint32_t exit = NO_FACE;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t lf = (first + k) & 3;
            if (lf == entry) continue;
            // p replacing vertex lf: negative when p is on the far side of face lf.
            const double* kept = q[lf];
            q[lf] = p;
            const int side = orient3d(q[0], q[1], q[2], q[3], in.counters);
            q[lf] = kept;
            if (side < 0) {
                exit = lf;
                break;
            }
        }
        if (exit == NO_FACE) {
            found = t;  // p lies in the closed tetrahedron, hence strictly inside its circumsphere
            return DBRG_OK;
        }
        const uint32_t across = adjacency_[4 * size_t(t) + exit];
        if (Shared && !claim(in, across >> 2)) {
            // The next walk starts where this one got to, not from behind it again.
            in.hint = t;
            return give_up<Shared>(in);
        }
        t = across >> 2;
        entry = across & 3;
        if (vertex_[4 * size_t(t) + 3] == INFINITE_VERTEX) {
            found = t;  // p is strictly beyond this hull face
            return DBRG_OK;
        }
    }
    return fail_internal<Shared>(in, "point location did not terminate (a bug in dbrg)");
}

// Sequential insertion ran out of memory; a shared one leaves the point for later and every tetrahedron
// as it was.
template <bool Shared>
dbrg_status DelaunayBuilder::give_up(Inserter& in) {
    if (!Shared) return context_.fail_out_of_memory();
    for (uint32_t c : in.cavity) vertex_[4 * size_t(c)] &= VERTEX_ID_MASK;
    for (uint32_t o : in.outside) vertex_[4 * size_t(o) + 1] &= VERTEX_ID_MASK;
    in.cavity.clear();
    in.outside.clear();
    in.left_out = true;
    release_claims(in);
    return DBRG_OK;
}

// Only the calling thread may write the context's message: a shared insertion keeps its own.
template <bool Shared>
dbrg_status DelaunayBuilder::fail_internal(Inserter& in, const char* message) {
    if (!Shared) return context_.fail(DBRG_ERR_INTERNAL, "%s", message);
    in.failure = message;
    return DBRG_ERR_INTERNAL;
}

dbrg_status DelaunayBuilder::start() {
    PredicateCounters& counters = out_.counters;
    // The first four affinely independent points of the order: the first two, the next one off their
    // line, the next one off their plane. The points passed over wait in pending_, in order.
    uint32_t v[4];
    if (!order_->next(v[0]) || !order_->next(v[1])) {
        return context_.fail(DBRG_ERR_DEGENERATE_INPUT, "fewer than 2 points to insert");
    }
    const double* p0 = point(v[0]);
    const double* p1 = point(v[1]);
    bool found = false;
    while (!found && order_->next(v[2])) {
        found = !points_collinear(p0, p1, point(v[2]), counters);
        if (!found && !pending_.push_back(v[2])) return context_.fail_out_of_memory();
    }
    if (!found) return context_.fail(DBRG_ERR_DEGENERATE_INPUT, "all %u points are collinear", count_);
    found = false;
    while (!found && order_->next(v[3])) {
        found = orient3d(p0, p1, point(v[2]), point(v[3]), counters) != 0;
        if (!found && !pending_.push_back(v[3])) return context_.fail_out_of_memory();
    }
    if (!found) return context_.fail(DBRG_ERR_DEGENERATE_INPUT, "all %u points are coplanar", count_);
    if (orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3]), counters) < 0) {
        const uint32_t swap = v[0];
        v[0] = v[1];
        v[1] = swap;
    }
    const double expected = EXPECTED_TETS_PER_POINT * count_ + 64;
    DBRG_PROPAGATE(size_store(static_cast<size_t>(expected < MAX_TET_SLOTS ? expected : MAX_TET_SLOTS)));
    slot_end_ = 5;
    // Slot 0: the finite tetrahedron. Slot 1 + lf: the infinite one behind its face lf, with the face's
    // orientation reversed so that a point beyond the face sees it positively.
    memcpy(vertex_, v, sizeof v);
    for (uint32_t lf = 0; lf < 4; ++lf) {
        uint32_t* iv = vertex_ + 4 * (1 + lf);
        iv[0] = v[FACE_VERTEX[lf][1]];
        iv[1] = v[FACE_VERTEX[lf][0]];
        iv[2] = v[FACE_VERTEX[lf][2]];
        iv[3] = INFINITE_VERTEX;
        adjacency_[lf] = (1 + lf) << 2 | 3;
        adjacency_[4 * (1 + lf) + 3] = 0u << 2 | lf;
    }
    // The infinite tetrahedra meet along the hull edges: match their faces by their vertex sets.
    for (uint32_t s = 1; s < 5; ++s) {
        for (uint32_t f = 0; f < 3; ++f) {
            for (uint32_t t = 1; t < 5; ++t) {
                if (t == s) continue;
                // t shares face f of s when t lacks exactly the vertex s[f] among s's finite ones... i.e.
                // when t contains both other finite vertices of s.
                uint32_t shared = 0, missing = NO_FACE;
                for (uint32_t g = 0; g < 3; ++g) {
                    const uint32_t w = vertex_[4 * t + g];
                    bool in_s = false;
                    for (uint32_t h = 0; h < 3; ++h) in_s |= h != f && vertex_[4 * s + h] == w;
                    if (in_s) ++shared; else missing = g;
                }
                if (shared == 2) adjacency_[4 * s + f] = t << 2 | missing;
            }
        }
    }
    out_.finite_tets_ = 1;
    main_.hint = 0;
    return DBRG_OK;
}

bool DelaunayBuilder::next_vertex(uint32_t& v) {
    if (pending_next_ < pending_.size()) {
        v = pending_[pending_next_++];
        return true;
    }
    return order_->next(v);
}

template <bool Shared>
dbrg_status DelaunayBuilder::insert(Inserter& in, uint32_t v, const double* next) {
    const double* p = point(v);
    in.cavity.clear();
    in.outside.clear();
    in.boundary.clear();
    in.left_out = false;
    uint32_t first;
    DBRG_PROPAGATE(locate<Shared>(in, in.hint, p, first));
    if (first == NO_TET) return DBRG_OK;  // given up
    // Giving up from here, the next walk starts where this one ended.
    const auto leave = [&]() {
        in.hint = first;
        return give_up<Shared>(in);
    };

    // The cavity: breadth-first over the tetrahedra in conflict, which are connected. Shared, each
    // tetrahedron is claimed before it is read; when one is another thread's, the point is given up.
    // Memory latency, not arithmetic, bounds this loop: the neighbours' records are requested one
    // cavity member ahead of their tests, a member's adjacency as soon as it joins, and an outside
    // neighbour's adjacency (written when the new tetrahedra are glued on) as soon as it is reached.
    // Within a shared insertion a list that reaches its fixed capacity gives the point up too (push_back
    // would allocate).
    const auto append = [](auto& list, const auto& item) {
        return Shared && list.size() == list.capacity() ? false : list.push_back(item);
    };
    if (!append(in.cavity, first)) return leave();
    vertex_[4 * size_t(first)] |= IN_CAVITY_BIT;
    size_t requested = 0;  // cavity members whose neighbours' records have been requested
    for (size_t i = 0; i < in.cavity.size(); ++i) {
        for (; requested < in.cavity.size() && requested <= i + 1; ++requested) {
            const uint32_t* adjacent = adjacency_ + 4 * size_t(in.cavity[requested]);
            for (uint32_t lf = 0; lf < 4; ++lf) prefetch(vertex_ + 4 * size_t(adjacent[lf] >> 2));
        }
        const uint32_t c = in.cavity[i];
        for (uint32_t lf = 0; lf < 4; ++lf) {
            const uint32_t n = adjacency_[4 * size_t(c) + lf] >> 2;
            if (Shared && !claim(in, n)) return leave();
            uint32_t* nv = vertex_ + 4 * size_t(n);
            if (nv[0] & IN_CAVITY_BIT) continue;
            if (!(nv[1] & OUTSIDE_BIT)) {
                prefetch(adjacency_ + 4 * size_t(n));
                if (in_conflict(in, nv, p)) {
                    if (!append(in.cavity, n)) return leave();
                    nv[0] |= IN_CAVITY_BIT;
                    continue;
                }
                if (!append(in.outside, n)) return leave();
                nv[1] |= OUTSIDE_BIT;
            }
            if (!append(in.boundary, BoundaryFace{c, lf})) return leave();
        }
    }

    // Each boundary face makes a new tetrahedron: the cavity tetrahedron behind it with the vertex
    // opposite the face replaced by v. v is on the same side of the face as that vertex (the cavity
    // is star-shaped from v), so the orientation carries over, and so does the infinite vertex's slot.
    const size_t face_count = in.boundary.size();
    const size_t cavity_size = in.cavity.size();
    if (Shared && !room_for(in, face_count, cavity_size)) return leave();
    if (!in.new_tets.resize(face_count) || !in.new_slots.resize(face_count)) return context_.fail_out_of_memory();
    for (size_t i = 0; i < face_count; ++i) {
        const BoundaryFace f = in.boundary[i];
        NewTet& made = in.new_tets[i];
        memcpy(made.vertex, vertex_ + 4 * size_t(f.tet), sizeof made.vertex);
        made.vertex[0] &= VERTEX_ID_MASK;
        made.vertex[f.face] = v;
        made.outer = adjacency_[4 * size_t(f.tet) + f.face];
        made.face = f.face;
    }
    int64_t finite_change = 0;
    for (size_t i = 0; i < cavity_size; ++i) finite_change -= vertex_[4 * size_t(in.cavity[i]) + 3] != INFINITE_VERTEX;
    for (size_t i = 0; i < face_count; ++i) {
        if (i < cavity_size) {
            in.new_slots[i] = in.cavity[i];
        } else {
            DBRG_PROPAGATE(take_slot<Shared>(in, in.new_slots[i]));
        }
    }
    for (size_t i = face_count; i < cavity_size; ++i) free_slot(in, in.cavity[i]);
    in.hint = in.new_slots[0];
    for (size_t i = 0; i < face_count; ++i) {
        const NewTet& made = in.new_tets[i];
        const uint32_t s = in.new_slots[i];
        memcpy(vertex_ + 4 * size_t(s), made.vertex, sizeof made.vertex);
        adjacency_[4 * size_t(s) + made.face] = made.outer;
        adjacency_[4 * size_t(made.outer >> 2) + (made.outer & 3)] = s << 2 | made.face;
        finite_change += made.vertex[3] != INFINITE_VERTEX;
    }
    choose_hint(in, next);
    in.finite_change += finite_change;
    for (uint32_t o : in.outside) vertex_[4 * size_t(o) + 1] &= VERTEX_ID_MASK;
    DBRG_PROPAGATE(link_new_tets<Shared>(in));
    if (Shared) release_claims(in);
    return DBRG_OK;
}

void DelaunayBuilder::choose_hint(Inserter& in, const double* q) {
    // Any start is correct, but on surface samples the tetrahedra around v are long needles, and a walk
    // from an arbitrary one of them wanders; the one whose centroid is nearest to the next point in
    // insertion order cuts the walk to a fraction. Plain floating point: only speed depends on it.
    if (!q) return;
    double best = HUGE_VAL;
    for (size_t i = 0; i < in.new_tets.size(); ++i) {
        const NewTet& made = in.new_tets[i];
        if (made.vertex[3] == INFINITE_VERTEX) continue;
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double c = point(made.vertex[0])[k] + point(made.vertex[1])[k] + point(made.vertex[2])[k] +
                             point(made.vertex[3])[k] - 4 * q[k];
            d2 += c * c;
        }
        if (d2 < best) {
            best = d2;
            in.hint = in.new_slots[i];
        }
    }
}

template <bool Shared>
dbrg_status DelaunayBuilder::link_new_tets(Inserter& in) {
    // The three faces of a new tetrahedron that contain v meet the other new tetrahedra along the edges
    // of the cavity boundary. Seen from the new tetrahedron, with v first, such a face runs v -> x -> y;
    // the tetrahedron on the other side sees the same face reversed, v -> y -> x. Of each such pair, the
    // face with x > y is filed under (x, y) and the one with x < y looks up (y, x) and links both: half
    // the table work of filing and looking up every face. The faces are first sorted into the two kinds
    // without a branch (each is written at both ends of filed, and one end advances), so that the loops
    // that follow have no unpredictable found/not-found or filed/looked-up branch.
    const size_t face_count = in.new_tets.size();
    const size_t table_size = edge_table_size(face_count);
    if (in.edges.size() < table_size) {  // never when shared: room_for checked it
        if (!in.edges.resize(table_size)) return context_.fail_out_of_memory();
        for (EdgeEntry& e : in.edges) e.edge = EMPTY_EDGE;
    }
    const size_t total = 3 * face_count;
    if (!in.filed.resize(total)) return context_.fail_out_of_memory();
    const uint32_t mask = static_cast<uint32_t>(in.edges.size() - 1);
    EdgeEntry* table = in.edges.data();
    FiledFace* filed = in.filed.data();
    size_t to_file = 0, to_look_up = 0;  // filed[0, to_file) are filed, filed[total - to_look_up, total) look up
    for (size_t i = 0; i < face_count; ++i) {
        const uint32_t s = in.new_slots[i];
        const NewTet& made = in.new_tets[i];
        for (uint32_t g = 0; g < 4; ++g) {
            if (g == made.face) continue;
            const uint32_t x = made.vertex[DIRECTED_EDGE[made.face][g][0]];
            const uint32_t y = made.vertex[DIRECTED_EDGE[made.face][g][1]];
            const FiledFace face{uint64_t(x) << 32 | y, s << 2 | g, 0};
            filed[to_file] = face;
            filed[total - 1 - to_look_up] = face;
            const bool file = x > y;
            to_file += file;
            to_look_up += !file;
        }
    }
    for (size_t j = 0; j < to_file; ++j) {
        const uint64_t edge = filed[j].edge;
        uint32_t k = hash_edge(edge) & mask;
        while (table[k].edge != EMPTY_EDGE) k = (k + 1) & mask;
        table[k].edge = edge;
        table[k].link = filed[j].link;
        filed[j].entry = k;
    }
    bool complete = to_file == to_look_up;
    for (size_t j = total - to_look_up; j < total; ++j) {
        const uint64_t edge = filed[j].edge;
        const uint64_t reversed = edge << 32 | edge >> 32;
        uint32_t k = hash_edge(reversed) & mask;
        while (table[k].edge != reversed && table[k].edge != EMPTY_EDGE) k = (k + 1) & mask;
        complete &= table[k].edge == reversed;
        // A link is slot << 2 | face: the face's index in adjacency_.
        adjacency_[filed[j].link] = table[k].link;
        adjacency_[table[k].link] = filed[j].link;
    }
    for (size_t j = 0; j < to_file; ++j) table[filed[j].entry].edge = EMPTY_EDGE;
    if (!complete) return fail_internal<Shared>(in, "the cavity boundary is not a closed surface (a bug in dbrg)");
    return DBRG_OK;
}

dbrg_status DelaunayBuilder::run(const double* points, BrioOrder& order, uint32_t n) {
    points_ = points;
    order_ = &order;
    count_ = n;
    DBRG_PROPAGATE(start());
    inserted_ = 4;
    const uint32_t parts = std::min(part_count(context_.params.threads, n, MIN_POINTS_PER_THREAD), MAX_INSERTION_THREADS);
    uint32_t v = 0, next = 0;
    bool more = next_vertex(next);
    while (more) {
        v = next;
        more = next_vertex(next);
        if (inserted_ % PROGRESS_INTERVAL == 0) DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, double(inserted_) / n));
        DBRG_PROPAGATE(insert<false>(main_, v, more ? point(next) : nullptr));
        ++inserted_;
        if (more && parts > 1 && pending_next_ == pending_.size() && order.in_last_round()) {
            // What is still to come is the last round (three quarters of the points): `next`, then the rest
            // split among the threads.
            DBRG_PROPAGATE(insert<false>(main_, next, nullptr));
            ++inserted_;
            DBRG_PROPAGATE(insert_last_round(parts));
            more = false;
        }
    }
    pending_.release();
    out_.finite_tets_ = static_cast<uint32_t>(int64_t(out_.finite_tets_) + main_.finite_change);
    out_.counters += main_.counters;
    out_.vertices_.shrink(4 * size_t(slot_end_));
    out_.adjacency_.shrink(4 * size_t(slot_end_));
    return context_.report(DBRG_STAGE_DELAUNAY, 1.0);
}

// The last BRIO round, split into consecutive stretches of the order (so into separate regions of
// space), one per thread, inserted at once. Each thread claims a tetrahedron (an atomic mark per slot)
// before it reads it, and keeps its claims until its point is in; a cavity's tetrahedra and all their
// neighbours are claimed before anything changes, so no thread ever reads a tetrahedron another is
// rewriting. Where another thread has one, the point is given up, and the calling thread inserts it
// afterwards. The tetrahedralization of a point set does not depend on the insertion order, so the
// tetrahedra are the same as with one thread (their slots differ). Threads take new slots in chunks
// from a store sized beforehand and never allocate: what needs more room than their fixed scratch space
// is given up too. A thread that finds the store full stops; the store grows and they go on.
dbrg_status DelaunayBuilder::insert_last_round(uint32_t parts) {
    std::optional<Inserter> others[MAX_INSERTION_THREADS];
    Inserter* inserters[MAX_INSERTION_THREADS] = {&main_};
    BrioOrder::Slice slices[MAX_INSERTION_THREADS];
    dbrg_status statuses[MAX_INSERTION_THREADS];
    // Whether a part's hint is a tetrahedron of the tetrahedralization as it is now: the calling thread's
    // is, from its last insertion; after a phase, those of the parts that ran (each held its own). A part
    // that sat a phase out while others inserted finds a start again: its tetrahedron may be gone.
    bool hint_live[MAX_INSERTION_THREADS] = {true};
    for (uint32_t part = 0; part < parts; ++part) {
        if (part > 0) inserters[part] = &others[part].emplace(memory_);
        slices[part] = order_->last_round_slice(part, parts);
        DBRG_PROPAGATE(prepare_inserter(*inserters[part], part, slices[part].span() / DEFERRED_SHARE + 64));
        inserters[part]->random ^= part;  // other walks, the same result
    }
    uint32_t anchor = main_.hint;  // a live tetrahedron
    bool store_full = true;
    while (store_full) {
        const size_t slots = std::max(projected_slots(), size_t(slot_end_) + size_t(CHUNK_SLOTS) * parts);
        if (4 * slots > out_.vertices_.size()) DBRG_PROPAGATE(size_store(std::min<size_t>(slots, MAX_TET_SLOTS)));
        const uint32_t capacity = static_cast<uint32_t>(out_.vertices_.size() / 4);
        claims_.clear();
        if (!claims_.resize(capacity, 0)) return context_.fail_out_of_memory();
        next_chunk_.store(slot_end_, std::memory_order_relaxed);
        stop_.store(false, std::memory_order_relaxed);
        bool active[MAX_INSERTION_THREADS] = {};
        for (uint32_t part = 0; part < parts; ++part) {
            Inserter& in = *inserters[part];
            statuses[part] = DBRG_OK;
            in.out_of_slots = false;
            in.held.clear();
            BrioOrder::Slice rest = slices[part];
            uint32_t first;
            if (!rest.next(first) || in.deferred.size() == in.deferred.capacity()) continue;
            if (!hint_live[part]) {
                // Found by the calling thread, walking from a live tetrahedron to the part's next point.
                DBRG_PROPAGATE(locate<false>(main_, anchor, point(first), in.hint));
                hint_live[part] = true;
            }
            if (claims_[in.hint] != 0) continue;  // the same start as another part's: this one waits
            claims_[in.hint] = in.mark;
            in.held.push_back(in.hint);  // within the capacity prepare_inserter reserved
            active[part] = true;
        }
        run_parts(parts, [&](uint32_t part) {
            if (active[part]) insert_slice(*inserters[part], slices[part], part, statuses[part]);
        });
        // The calling thread alone again.
        slot_end_ = std::min(next_chunk_.load(std::memory_order_relaxed), capacity);
        store_full = false;
        uint32_t inserted = 0;
        for (uint32_t part = 0; part < parts; ++part) {
            Inserter& in = *inserters[part];
            if (statuses[part] != DBRG_OK) {
                return in.failure ? context_.fail(statuses[part], "%s", in.failure) : statuses[part];
            }
            hand_back_chunk(in);
            inserted += in.inserted;
            in.inserted = 0;
            store_full = store_full || in.out_of_slots;
        }
        inserted_ += inserted;
        for (uint32_t part = 0; part < parts; ++part) {
            hint_live[part] = active[part] || (hint_live[part] && inserted == 0);
            if (hint_live[part]) anchor = inserters[part]->hint;
        }
        store_full = store_full && inserted > 0;
    }
    claims_.release();
    if (!hint_live[0]) main_.hint = anchor;
    for (uint32_t part = 1; part < parts; ++part) {
        Inserter& in = *inserters[part];
        while (in.free_head != NO_TET) {
            const uint32_t s = in.free_head;
            in.free_head = adjacency_[4 * size_t(s)];
            free_slot(main_, s);
        }
        main_.finite_change += in.finite_change;
        main_.counters += in.counters;
    }
    // What the threads left: the points they set aside, and the rest of a stretch they stopped in.
    const auto insert_left = [&](uint32_t v) {
        if (inserted_ % PROGRESS_INTERVAL == 0) DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, double(inserted_) / count_));
        ++inserted_;
        return insert<false>(main_, v, nullptr);
    };
    for (uint32_t part = 0; part < parts; ++part) {
        for (uint32_t v : inserters[part]->deferred) DBRG_PROPAGATE(insert_left(v));
        uint32_t v;
        while (slices[part].next(v)) DBRG_PROPAGATE(insert_left(v));
    }
    return DBRG_OK;
}

dbrg_status DelaunayBuilder::prepare_inserter(Inserter& in, uint32_t part, uint32_t deferred_room) {
    in.mark = static_cast<uint8_t>(part + 1);
    in.held.clear();
    in.deferred.clear();
    const bool room = in.cavity.reserve(MAX_SHARED_CAVITY) && in.outside.reserve(MAX_SHARED_CAVITY) &&
                      in.boundary.reserve(MAX_SHARED_FACES) && in.new_tets.reserve(MAX_SHARED_FACES) &&
                      in.new_slots.reserve(MAX_SHARED_FACES) && in.filed.reserve(3 * MAX_SHARED_FACES) &&
                      in.held.reserve(MAX_SHARED_HELD) && in.deferred.reserve(deferred_room);
    if (!room) return context_.fail_out_of_memory();
    const size_t table_size = edge_table_size(MAX_SHARED_FACES);
    if (in.edges.size() < table_size) {
        if (!in.edges.resize(table_size)) return context_.fail_out_of_memory();
        for (EdgeEntry& e : in.edges) e.edge = EMPTY_EDGE;
    }
    return DBRG_OK;
}

// One thread's stretch. Points it sets aside are listed for the calling thread; once that list is full,
// or the store is, the thread stops and leaves the rest of its stretch in `slice`. The calling thread's
// part also reports progress (counting its own points only, so that the fraction never runs ahead) and
// stops every part when the caller cancels.
void DelaunayBuilder::insert_slice(Inserter& in, BrioOrder::Slice& slice, uint32_t part, dbrg_status& status) {
    uint32_t next_at = slice.position(), next, steps = 0;
    bool more = slice.next(next);
    while (more && !stop_.load(std::memory_order_relaxed)) {
        const uint32_t v = next, v_at = next_at;
        next_at = slice.position();
        more = slice.next(next);
        status = insert<true>(in, v, more ? point(next) : nullptr);
        if (status != DBRG_OK) {
            stop_.store(true, std::memory_order_relaxed);
            return;
        }
        if (!in.left_out) {
            ++in.inserted;
        } else if (!in.out_of_slots && in.deferred.size() < in.deferred.capacity()) {
            in.deferred.push_back(v);
        } else {
            slice.rewind(v_at);
            return;
        }
        if (part == 0 && ++steps % PROGRESS_INTERVAL == 0) {
            status = context_.report(DBRG_STAGE_DELAUNAY, double(inserted_ + in.inserted) / count_);
            if (status != DBRG_OK) {
                stop_.store(true, std::memory_order_relaxed);
                return;
            }
        }
    }
    if (more) slice.rewind(next_at);
}

bool DelaunayBuilder::claim(Inserter& in, uint32_t t) {
    uint8_t* mark = claims_.data() + t;
    if (__atomic_load_n(mark, __ATOMIC_RELAXED) == in.mark) return true;
    if (in.held.size() == in.held.capacity()) return false;
    uint8_t unclaimed = 0;
    if (!__atomic_compare_exchange_n(mark, &unclaimed, in.mark, false, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED)) return false;
    in.held.push_back(t);
    return true;
}

// Lets go of every claim but the hint's, which the next walk starts from.
void DelaunayBuilder::release_claims(Inserter& in) {
    for (uint32_t t : in.held) {
        if (t != in.hint) __atomic_store_n(claims_.data() + t, uint8_t(0), __ATOMIC_RELEASE);
    }
    in.held.clear();
    in.held.push_back(in.hint);
}

// Whether a shared insertion that replaces `cavity_size` tetrahedra by `faces` new ones fits in the
// thread's scratch space and slots; takes another chunk of the store if it needs one.
bool DelaunayBuilder::room_for(Inserter& in, size_t faces, size_t cavity_size) {
    if (faces > in.new_tets.capacity() || faces > in.new_slots.capacity() || 3 * faces > in.filed.capacity() ||
        edge_table_size(faces) > in.edges.size()) {
        return false;
    }
    const size_t needed = faces > cavity_size ? faces - cavity_size : 0;
    if (in.held.size() + needed > in.held.capacity()) return false;
    const uint32_t capacity = static_cast<uint32_t>(claims_.size());
    while (in.free_count + (in.chunk_end - in.chunk_next) < needed) {
        // Checked before adding, so that threads out of room cannot wrap the counter around.
        in.out_of_slots = next_chunk_.load(std::memory_order_relaxed) >= capacity;
        if (in.out_of_slots) return false;
        const uint32_t begin = next_chunk_.fetch_add(CHUNK_SLOTS, std::memory_order_relaxed);
        in.out_of_slots = begin >= capacity;
        if (in.out_of_slots) return false;
        hand_back_chunk(in);
        in.chunk_next = begin;
        in.chunk_end = std::min(begin + CHUNK_SLOTS, capacity);
    }
    return true;
}

// The unused rest of the thread's chunk goes onto its free list.
void DelaunayBuilder::hand_back_chunk(Inserter& in) {
    while (in.chunk_next < in.chunk_end) free_slot(in, in.chunk_next++);
}

dbrg_status Tetrahedralization::build(const double* points, uint32_t count, Context& context) {
    clear();
    if (count < 4) {
        return context.fail(DBRG_ERR_TOO_FEW_POINTS, "%u points given; at least 4 distinct points are needed", count);
    }
    if (count > DBRG_MAX_POINTS) {
        return context.fail(DBRG_ERR_TOO_MANY_POINTS, "%u points given; at most %zu are supported", count,
                            static_cast<size_t>(DBRG_MAX_POINTS));
    }
    points_ = points;
    vertex_count_ = count;
    counters = PredicateCounters();

    const double sort_start = seconds_now();
    // The engine reads the caller's points in place, with the caller's vertex ids: the pipeline numbers
    // them along a Hilbert curve (renumber_spatially), so points close in space are already close in
    // memory (a copy in insertion order would cost 24 bytes per point at the peak), and the insertion
    // order is then streamed instead of sorted and stored.
    BrioOrder order(context.memory);
    dbrg_status status = order.prepare(points, count, context);
    const double insert_start = seconds_now();
    if (status == DBRG_OK) {
        DelaunayBuilder builder(*this, context);
        status = builder.run(points, order, count);
    }
    order.release();
    if (status == DBRG_OK) {
        // One incident tetrahedron per vertex, the first slot that has it.
        if (!vertex_tet_.resize(count, NO_TET)) {
            status = context.fail_out_of_memory();
        } else {
            const uint32_t slots = tet_slots();
            for (uint32_t t = slots; t-- > 0;) {
                if (tet_is_free(t)) continue;
                for (uint32_t lv = 0; lv < 4; ++lv) {
                    const uint32_t w = vertices_[4 * size_t(t) + lv];
                    if (w != INFINITE_VERTEX) vertex_tet_[w] = t;
                }
            }
        }
    }
    const double end = seconds_now();
    context.stats.seconds_sort += insert_start - sort_start;
    context.stats.seconds_delaunay += end - insert_start;
    context.stats.predicate_calls += counters.calls;
    context.stats.predicate_filter_failures += counters.filter_failures;
    context.stats.predicate_perturbations += counters.perturbations;
    if (status != DBRG_OK) {
        clear();
        return status;
    }
    context.stats.tetrahedra = finite_tets_;
    return DBRG_OK;
}

} // namespace dbrg
