// Bowyer-Watson: the incremental Delaunay tetrahedralization — walk to the new point, collect the
// cavity of tetrahedra whose circumsphere holds it, and connect the point to the cavity's boundary.
//
// Based on: A. Bowyer, "Computing Dirichlet tessellations" and D. F. Watson, "Computing the
// n-dimensional Delaunay tessellation with application to Voronoi polytopes" (The Computer Journal 24,
// 1981); O. Devillers, S. Pion, M. Teillaud, "Walking in a triangulation" (IJFCS 13, 2002) for the
// randomized visibility walk.
#include <math.h>
#include <string.h>
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

uint32_t hash_edge(uint64_t edge) {
    const uint64_t h = edge * 0x9e3779b97f4a7c15ull;
    return static_cast<uint32_t>(h >> 40);
}

} // namespace

class DelaunayBuilder {
public:
    DelaunayBuilder(Tetrahedralization& out, Context& context)
        : out_(out), context_(context), memory_(context.memory), pending_(memory_), cavity_(memory_),
          outside_(memory_), boundary_(memory_), new_tets_(memory_), new_slots_(memory_), edges_(memory_),
          filed_(memory_) {}

    // Inserts the `count` points of `points` in the order `order` gives (the four first affinely
    // independent ones first). Vertex ids are indices into `points`.
    dbrg_status run(const double* points, BrioOrder& order, uint32_t count);

private:
    dbrg_status start();
    bool next_vertex(uint32_t& v);
    // Inserts v; `next` is the point inserted after it, or null.
    dbrg_status insert(uint32_t v, const double* next);
    dbrg_status locate(const double* p, uint32_t& found);
    bool in_conflict(const uint32_t* tet, const double* p);
    dbrg_status take_slot(uint32_t& slot);
    dbrg_status size_store(size_t slots);
    dbrg_status link_new_tets();
    void choose_hint(const double* next);
    void refresh_pointers() {
        vertex_ = out_.vertices_.data();
        adjacency_ = out_.adjacency_.data();
    }
    const double* point(uint32_t v) const { return points_ + 3 * size_t(v); }
    uint32_t next_random() {
        // xorshift64: only a few bits per walk step are needed, and it has to be cheap.
        random_ ^= random_ << 13;
        random_ ^= random_ >> 7;
        random_ ^= random_ << 17;
        return static_cast<uint32_t>(random_ >> 32);
    }

    Tetrahedralization& out_;
    Context& context_;
    Memory& memory_;
    const double* points_ = nullptr;
    uint32_t* vertex_ = nullptr;     // out_.vertices_.data(), refreshed whenever the store grows
    uint32_t* adjacency_ = nullptr;  // out_.adjacency_.data()
    uint32_t free_head_ = NO_TET;    // free slots, chained through adjacency entry 0
    uint32_t slot_end_ = 0;          // slots in use or free; the arrays hold more until run() ends
    BrioOrder* order_ = nullptr;     // the insertion order
    uint32_t count_ = 0;             // points to insert
    uint32_t inserted_ = 0;          // points inserted so far
    uint32_t hint_ = 0;              // a tetrahedron made by the last insertion: the next walk starts there
    uint64_t random_ = WALK_SEED;

    Array<uint32_t> pending_;  // points the order gave before the first tetrahedron was complete
    size_t pending_next_ = 0;

    // Scratch space of one insertion.
    Array<uint32_t> cavity_;
    Array<uint32_t> outside_;
    Array<BoundaryFace> boundary_;
    Array<NewTet> new_tets_;
    Array<uint32_t> new_slots_;
    Array<EdgeEntry> edges_;
    Array<FiledFace> filed_;      // the faces one insertion filed in edges_
};

dbrg_status DelaunayBuilder::take_slot(uint32_t& slot) {
    if (free_head_ != NO_TET) {
        slot = free_head_;
        free_head_ = adjacency_[4 * size_t(slot)];
        return DBRG_OK;
    }
    const size_t slots = slot_end_;
    if (slots >= MAX_TET_SLOTS) {
        return context_.fail(DBRG_ERR_TOO_MANY_POINTS, "the tetrahedralization needs more than %u tetrahedra",
                             MAX_TET_SLOTS);
    }
    if (4 * slots == out_.vertices_.size()) {
        size_t grown = slots + slots / GROWTH_DIVISOR + 64;
        if (inserted_ > 0 && inserted_ < count_) {
            // Clamped while still a double: the cast of a value beyond size_t's range is undefined.
            double projected = slots + double(slots) / inserted_ * (count_ - inserted_) * PROJECTION_MARGIN + 64;
            projected = projected < MAX_TET_SLOTS ? projected : MAX_TET_SLOTS;
            grown = static_cast<size_t>(projected) > grown ? static_cast<size_t>(projected) : grown;
        }
        grown = grown > MAX_TET_SLOTS ? MAX_TET_SLOTS : grown;
        DBRG_PROPAGATE(size_store(grown));
    }
    slot = slot_end_++;
    return DBRG_OK;
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

bool DelaunayBuilder::in_conflict(const uint32_t* tet, const double* p) {
    PredicateCounters& counters = out_.counters;
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

dbrg_status DelaunayBuilder::locate(const double* p, uint32_t& found) {
    PredicateCounters& counters = out_.counters;
    uint32_t t = hint_;
    if (vertex_[4 * size_t(t) + 3] == INFINITE_VERTEX) t = adjacency_[4 * size_t(t) + 3] >> 2;
    uint32_t entry = NO_FACE;  // the face we came in by: p is known to be on its inner side
    // A visibility walk in a Delaunay tetrahedralization never cycles (Edelsbrunner's acyclicity of
    // the in-front relation); the step limit only turns a bug into an error instead of a hang.
    const size_t step_limit = size_t(slot_end_) + 1000;
    for (size_t step = 0; step < step_limit; ++step) {
        const uint32_t* tv = vertex_ + 4 * size_t(t);
        const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
        const uint32_t first = next_random() & 3;
        uint32_t exit = NO_FACE;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t lf = (first + k) & 3;
            if (lf == entry) continue;
            // p replacing vertex lf: negative when p is on the far side of face lf.
            const double* kept = q[lf];
            q[lf] = p;
            const int side = orient3d(q[0], q[1], q[2], q[3], counters);
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
        t = across >> 2;
        entry = across & 3;
        if (vertex_[4 * size_t(t) + 3] == INFINITE_VERTEX) {
            found = t;  // p is strictly beyond this hull face
            return DBRG_OK;
        }
    }
    return context_.fail(DBRG_ERR_INTERNAL, "point location did not terminate (a bug in dbrg)");
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
    hint_ = 0;
    return DBRG_OK;
}

bool DelaunayBuilder::next_vertex(uint32_t& v) {
    if (pending_next_ < pending_.size()) {
        v = pending_[pending_next_++];
        return true;
    }
    return order_->next(v);
}

dbrg_status DelaunayBuilder::insert(uint32_t v, const double* next) {
    const double* p = point(v);
    uint32_t first;
    DBRG_PROPAGATE(locate(p, first));

    // The cavity: breadth-first over the tetrahedra in conflict, which are connected.
    cavity_.clear();
    outside_.clear();
    boundary_.clear();
    vertex_[4 * size_t(first)] |= IN_CAVITY_BIT;
    if (!cavity_.push_back(first)) return context_.fail_out_of_memory();
    // Memory latency, not arithmetic, bounds this loop: the neighbours' records are requested one
    // cavity member ahead of their tests, a member's adjacency as soon as it joins, and an outside
    // neighbour's adjacency (written when the new tetrahedra are glued on) as soon as it is reached.
    size_t requested = 0;  // cavity members whose neighbours' records have been requested
    for (size_t i = 0; i < cavity_.size(); ++i) {
        for (; requested < cavity_.size() && requested <= i + 1; ++requested) {
            const uint32_t* adjacent = adjacency_ + 4 * size_t(cavity_[requested]);
            for (uint32_t lf = 0; lf < 4; ++lf) prefetch(vertex_ + 4 * size_t(adjacent[lf] >> 2));
        }
        const uint32_t c = cavity_[i];
        for (uint32_t lf = 0; lf < 4; ++lf) {
            const uint32_t n = adjacency_[4 * size_t(c) + lf] >> 2;
            uint32_t* nv = vertex_ + 4 * size_t(n);
            if (nv[0] & IN_CAVITY_BIT) continue;
            if (!(nv[1] & OUTSIDE_BIT)) {
                prefetch(adjacency_ + 4 * size_t(n));
                if (in_conflict(nv, p)) {
                    nv[0] |= IN_CAVITY_BIT;
                    if (!cavity_.push_back(n)) return context_.fail_out_of_memory();
                    continue;
                }
                nv[1] |= OUTSIDE_BIT;
                if (!outside_.push_back(n)) return context_.fail_out_of_memory();
            }
            if (!boundary_.push_back(BoundaryFace{c, lf})) return context_.fail_out_of_memory();
        }
    }

    // Each boundary face makes a new tetrahedron: the cavity tetrahedron behind it with the vertex
    // opposite the face replaced by v. v is on the same side of the face as that vertex (the cavity
    // is star-shaped from v), so the orientation carries over, and so does the infinite vertex's slot.
    const size_t face_count = boundary_.size();
    const size_t cavity_size = cavity_.size();
    if (!new_tets_.resize(face_count) || !new_slots_.resize(face_count)) return context_.fail_out_of_memory();
    for (size_t i = 0; i < face_count; ++i) {
        const BoundaryFace f = boundary_[i];
        NewTet& made = new_tets_[i];
        memcpy(made.vertex, vertex_ + 4 * size_t(f.tet), sizeof made.vertex);
        made.vertex[0] &= VERTEX_ID_MASK;
        made.vertex[f.face] = v;
        made.outer = adjacency_[4 * size_t(f.tet) + f.face];
        made.face = f.face;
    }
    uint32_t finite_removed = 0;
    for (size_t i = 0; i < cavity_size; ++i) finite_removed += vertex_[4 * size_t(cavity_[i]) + 3] != INFINITE_VERTEX;
    for (size_t i = 0; i < face_count; ++i) {
        if (i < cavity_size) {
            new_slots_[i] = cavity_[i];
        } else {
            DBRG_PROPAGATE(take_slot(new_slots_[i]));
        }
    }
    for (size_t i = face_count; i < cavity_size; ++i) {
        const uint32_t s = cavity_[i];
        vertex_[4 * size_t(s)] = Tetrahedralization::FREE_MARK;
        adjacency_[4 * size_t(s)] = free_head_;
        free_head_ = s;
    }
    uint32_t finite_added = 0;
    hint_ = new_slots_[0];
    for (size_t i = 0; i < face_count; ++i) {
        const NewTet& made = new_tets_[i];
        const uint32_t s = new_slots_[i];
        memcpy(vertex_ + 4 * size_t(s), made.vertex, sizeof made.vertex);
        adjacency_[4 * size_t(s) + made.face] = made.outer;
        adjacency_[4 * size_t(made.outer >> 2) + (made.outer & 3)] = s << 2 | made.face;
        finite_added += made.vertex[3] != INFINITE_VERTEX;
    }
    choose_hint(next);
    out_.finite_tets_ += finite_added - finite_removed;
    for (size_t i = 0; i < outside_.size(); ++i) vertex_[4 * size_t(outside_[i]) + 1] &= VERTEX_ID_MASK;
    return link_new_tets();
}

void DelaunayBuilder::choose_hint(const double* q) {
    // Any start is correct, but on surface samples the tetrahedra around v are long needles, and a walk
    // from an arbitrary one of them wanders; the one whose centroid is nearest to the next point in
    // insertion order cuts the walk to a fraction. Plain floating point: only speed depends on it.
    if (!q) return;
    double best = HUGE_VAL;
    for (size_t i = 0; i < new_tets_.size(); ++i) {
        const NewTet& made = new_tets_[i];
        if (made.vertex[3] == INFINITE_VERTEX) continue;
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double c = point(made.vertex[0])[k] + point(made.vertex[1])[k] + point(made.vertex[2])[k] +
                             point(made.vertex[3])[k] - 4 * q[k];
            d2 += c * c;
        }
        if (d2 < best) {
            best = d2;
            hint_ = new_slots_[i];
        }
    }
}

dbrg_status DelaunayBuilder::link_new_tets() {
    // The three faces of a new tetrahedron that contain v meet the other new tetrahedra along the edges
    // of the cavity boundary. Seen from the new tetrahedron, with v first, such a face runs v -> x -> y;
    // the tetrahedron on the other side sees the same face reversed, v -> y -> x. Of each such pair, the
    // face with x > y is filed under (x, y) and the one with x < y looks up (y, x) and links both: half
    // the table work of filing and looking up every face. The faces are first sorted into the two kinds
    // without a branch (each is written at both ends of filed_, and one end advances), so that the loops
    // that follow have no unpredictable found/not-found or filed/looked-up branch.
    const size_t face_count = new_tets_.size();
    size_t capacity = 64;
    while (capacity < 3 * face_count) capacity *= 2;
    if (edges_.size() < capacity) {
        if (!edges_.resize(capacity)) return context_.fail_out_of_memory();
        for (EdgeEntry& e : edges_) e.edge = EMPTY_EDGE;
    }
    const size_t total = 3 * face_count;
    if (!filed_.resize(total)) return context_.fail_out_of_memory();
    const uint32_t mask = static_cast<uint32_t>(edges_.size() - 1);
    EdgeEntry* table = edges_.data();
    FiledFace* filed = filed_.data();
    size_t to_file = 0, to_look_up = 0;  // filed[0, to_file) are filed, filed[total - to_look_up, total) look up
    for (size_t i = 0; i < face_count; ++i) {
        const uint32_t s = new_slots_[i];
        const NewTet& made = new_tets_[i];
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
    if (!complete) return context_.fail(DBRG_ERR_INTERNAL, "the cavity boundary is not a closed surface (a bug in dbrg)");
    return DBRG_OK;
}

dbrg_status DelaunayBuilder::run(const double* points, BrioOrder& order, uint32_t n) {
    points_ = points;
    order_ = &order;
    count_ = n;
    DBRG_PROPAGATE(start());
    inserted_ = 4;
    uint32_t v = 0, next = 0;
    bool more = next_vertex(next);
    while (more) {
        v = next;
        more = next_vertex(next);
        if (inserted_ % PROGRESS_INTERVAL == 0) DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, double(inserted_) / n));
        DBRG_PROPAGATE(insert(v, more ? point(next) : nullptr));
        ++inserted_;
    }
    pending_.release();
    out_.vertices_.shrink(4 * size_t(slot_end_));
    out_.adjacency_.shrink(4 * size_t(slot_end_));
    return context_.report(DBRG_STAGE_DELAUNAY, 1.0);
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
