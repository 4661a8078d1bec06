// Bowyer-Watson: the incremental Delaunay tetrahedralization, one point at a time — walk to the new
// point, collect the cavity of tetrahedra whose circumsphere holds it, and connect the point to the
// cavity's boundary. The last round of a large input is shared among threads (parallel_insertion.cpp).
//
// Based on: A. Bowyer, "Computing Dirichlet tessellations" and D. F. Watson, "Computing the
// n-dimensional Delaunay tessellation with application to Voronoi polytopes" (The Computer Journal 24,
// 1981); O. Devillers, S. Pion, M. Teillaud, "Walking in a triangulation" (IJFCS 13, 2002) for the
// randomized visibility walk.
#include <math.h>
#include <string.h>

#include <algorithm>

#include "core/intrinsics.h"
#include "core/parallel.h"
#include "core/status.h"
#include "delaunay/delaunay_builder.h"
#include "points/point_input.h"
#include "predicates/affine_checks.h"

namespace dbrg {
namespace {

// While a point is inserted, bit 31 of vertex slot 0 marks a tetrahedron of the cavity and bit 31 of
// slot 1 one that was tested and is not in conflict. Vertex ids stay below 2^31 (DBRG_MAX_POINTS) and
// slots 0 and 1 never hold the infinite vertex, so the bits are free; they are cleared after each point.
constexpr uint32_t IN_CAVITY_BIT = 0x80000000u;
constexpr uint32_t OUTSIDE_BIT = 0x80000000u;
constexpr uint32_t VERTEX_ID_MASK = 0x7fffffffu;

// For the new point in slot lf and a face g != lf of a new tetrahedron: the slots x, y such that the
// face, oriented with the tetrahedron's own vertex g on its positive side, runs (new point, x, y).
constexpr uint8_t DIRECTED_EDGE[4][4][2] = {
    {{0, 0}, {2, 3}, {3, 1}, {1, 2}},
    {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
    {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
    {{2, 1}, {0, 2}, {1, 0}, {0, 0}},
};

uint32_t hash_edge(uint64_t edge) {
    const uint64_t h = edge * 0x9e3779b97f4a7c15ull;
    return static_cast<uint32_t>(h >> 40);
}

} // namespace

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
    uint32_t entry = NO_LOCAL_INDEX;  // the face we came in by: p is known to be on its inner side
    // A visibility walk in a Delaunay tetrahedralization never cycles (Edelsbrunner's acyclicity of
    // the in-front relation); the step limit only turns a bug into an error instead of a hang.
    const size_t step_limit = out_.vertices_.size() / 4 + 1000;
    for (size_t step = 0; step < step_limit; ++step) {
        const uint32_t* tv = vertex_ + 4 * size_t(t);
        const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
        const uint32_t first = next_random(in) & 3;
        uint32_t exit = NO_LOCAL_INDEX;
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
        if (exit == NO_LOCAL_INDEX) {
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
    DBRG_PROPAGATE(size_initial_store());
    slot_end_ = 5;
    // Slot 0: the finite tetrahedron. Slot 1 + lf: the infinite one behind its face lf.
    memcpy(vertex_, v, sizeof v);
    for (uint32_t lf = 0; lf < 4; ++lf) {
        infinite_tet_behind(v, lf, vertex_ + 4 * (1 + lf));
        adjacency_[lf] = (1 + lf) << 2 | 3;
        adjacency_[4 * (1 + lf) + 3] = 0u << 2 | lf;
    }
    // The infinite tetrahedra meet along the hull edges: match their faces by their vertex sets.
    for (uint32_t s = 1; s < 5; ++s) {
        for (uint32_t f = 0; f < 3; ++f) {
            for (uint32_t t = 1; t < 5; ++t) {
                if (t == s) continue;
                // t is across face f of s when it holds both finite vertices of s other than s[f].
                uint32_t shared = 0, missing = NO_LOCAL_INDEX;
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
    DBRG_PROPAGATE(size_edge_table(in, face_count));  // never grows when shared: room_for checked it
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

// Makes the edge table big enough for the faces of `faces` new tetrahedra, every entry empty.
dbrg_status DelaunayBuilder::size_edge_table(Inserter& in, size_t faces) {
    const size_t table_size = edge_table_size(faces);
    if (in.edges.size() < table_size) {
        if (!in.edges.resize(table_size)) return context_.fail_out_of_memory();
        for (EdgeEntry& e : in.edges) e.edge = EMPTY_EDGE;
    }
    return DBRG_OK;
}

dbrg_status DelaunayBuilder::run(const double* points, BrioOrder& order, uint32_t n) {
    points_ = points;
    order_ = &order;
    count_ = n;
    DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, 0.0));
    DBRG_PROPAGATE(start());
    inserted_ = 4;
    const uint32_t parts = std::min(part_count(context_.params.threads, n, MIN_POINTS_PER_THREAD), MAX_INSERTION_THREADS);
    uint32_t v = 0, next = 0;
    bool more = next_vertex(next);
    while (more) {
        v = next;
        more = next_vertex(next);
        if (inserted_ % PROGRESS_INTERVAL == 0) {
            DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, double(inserted_) / n));
            DBRG_PROPAGATE(write_store_ahead());
        }
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

// Defined here and called from the other files of the engine too: insert and locate by the shared
// insertion of the last round (parallel_insertion.cpp), fail_internal by take_slot (tet_slots.cpp).
template dbrg_status DelaunayBuilder::insert<false>(Inserter& in, uint32_t v, const double* next);
template dbrg_status DelaunayBuilder::insert<true>(Inserter& in, uint32_t v, const double* next);
template dbrg_status DelaunayBuilder::locate<false>(Inserter& in, uint32_t start, const double* p, uint32_t& found);
template dbrg_status DelaunayBuilder::fail_internal<false>(Inserter& in, const char* message);
template dbrg_status DelaunayBuilder::fail_internal<true>(Inserter& in, const char* message);

dbrg_status Tetrahedralization::build(const double* points, uint32_t count, Context& context, PointOrder point_order) {
    clear();
    DBRG_PROPAGATE(check_point_count(count, context));
    points_ = points;
    vertex_count_ = count;
    counters = PredicateCounters();

    const double sort_start = seconds_now();
    // The engine reads the caller's points in place, with the caller's vertex ids: the pipeline numbers
    // them along a Hilbert curve (renumber_spatially), so points close in space are already close in
    // memory (a copy in insertion order would cost 24 bytes per point at the peak), and the insertion
    // order is then streamed instead of sorted and stored.
    BrioOrder order(context.memory);
    dbrg_status status = order.prepare(points, count, point_order, context);
    const double insert_start = seconds_now();
    if (status == DBRG_OK) {
        DelaunayBuilder builder(*this, context);
        status = builder.run(points, order, count);
    }
    order.release();
    if (status == DBRG_OK && !index_vertex_tets()) status = context.fail_out_of_memory();
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
