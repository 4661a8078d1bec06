// Region growing: extracts an oriented manifold surface S from the Delaunay tetrahedralization by
// attaching, one at a time, the most credible candidate triangle of S's boundary (paper §3 and §4).
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), sections 3 and 4.
#include "grow/region_growing.h"

#include <math.h>

#include <algorithm>

#include "core/intrinsics.h"
#include "core/status.h"
#include "delaunay/edge_ring.h"
#include "grow/surface_geometry.h"
#include "grow/triangle_geometry.h"

namespace dbrg {
namespace {

// After dropping stale entries from a full container: grow it only when they freed less than a quarter
// of it, so that a dropping pass (linear in the size) is paid for by at least that many pushes.
template <class Container>
bool reserve_after_compaction(Container& container) {
    const size_t capacity = container.capacity();
    return container.size() <= capacity - capacity / 4 || container.reserve(capacity < 8 ? 8 : 2 * capacity);
}

// Growing reports its progress every this many candidates taken from the queue: a few milliseconds at most,
// whether they add faces or, as while the last holes close, mostly do not.
const uint32_t REPORT_CANDIDATES = 1024;
// And regrowing the holes every this many half-edges looked at for a hole's edge: a few milliseconds.
const uint32_t REPORT_HALFEDGES = 1 << 16;

// A component grown from a later seed must reach this many faces to count as a second object; fewer are
// stray points (noise, outliers), removed at the end if they stay apart.
const uint32_t MIN_SEEDED_COMPONENT_FACES = 16;
// Points whose seed triangles give the typical seed radius, the first seed's open-surface test: the
// median of 64 is within a few per cent of the whole distribution's on a surface sample.
const uint32_t SEED_SAMPLES = 64;

// Orders the seed triangle so its normal points up (+z), falling back to +x, then +y, for vertical ones.
void orient_upward(const Tetrahedralization& delaunay, uint32_t corners[3]) {
    const Vec3 n = cross(load_vec3(delaunay.point(corners[1])) - load_vec3(delaunay.point(corners[0])),
                         load_vec3(delaunay.point(corners[2])) - load_vec3(delaunay.point(corners[0])));
    const bool flip = n.z != 0 ? n.z < 0 : (n.x != 0 ? n.x < 0 : n.y < 0);
    if (flip) std::swap(corners[1], corners[2]);
}

} // namespace

RegionGrower::RegionGrower(const Tetrahedralization& delaunay, Surface& surface, Context& context)
    : delaunay_(delaunay),
      surface_(surface),
      context_(context),
      cos_sliver_(cos(context.params.sliver_angle)),
      queue_(context.memory),
      postponed_(context.memory),
      causes_(context.memory),
      flipper_(delaunay, surface, context) {}

// S empty, with room for the faces of a closed surface through all n points (2n - 4) and for those hole
// filling adds (the faces it replaces keep their slots: about 3 % more on random samples), taken at once
// rather than grown by copies.
dbrg_status RegionGrower::start_surface() {
    const uint32_t n = delaunay_.vertex_count();
    const size_t expected_faces = 2 * size_t(n) + n / 8;
    if (!surface_.reset(n) || !surface_.reserve_faces(expected_faces) || !causes_.reserve_faces(expected_faces)) {
        return context_.fail_out_of_memory();
    }
    return DBRG_OK;
}

dbrg_status RegionGrower::grow() {
    const ProgressSpan stage(context_, DBRG_STAGE_GROW);
    const ProgressSpan growing = stage.part(0, GROW_PROGRESS_ISLANDS);
    DBRG_PROPAGATE(stage.report(0, 1));
    DBRG_PROPAGATE(start_surface());
    const uint32_t n = delaunay_.vertex_count();
    for (Examined& e : examined_) e = Examined();  // S's edit count starts again

    // Seeds are tried from the highest point down (§3.1.1); ties go to the smaller vertex id, which is a
    // function of the coordinates (conditioning numbers the points along a Hilbert curve). Each vertex is
    // tried once, when its turn comes, if it is unused then.
    const auto before = [&](uint32_t a, uint32_t b) {
        const double za = delaunay_.point(a)[2], zb = delaunay_.point(b)[2];
        return za != zb ? za > zb : a < b;
    };
    // The first seed is the first vertex in that order. Nothing is sorted before it has grown: usually its
    // component takes (almost) every point, and a list of all of them would be alive at growing's peak.
    uint32_t first = 0;
    for (uint32_t v = 1; v < n; ++v) first = before(v, first) ? v : first;
    if (context_.params.boundary_factor > 0 && !measure_typical_seed()) return context_.fail_out_of_memory();
    Array<uint32_t> removed(context_.memory);
    DBRG_PROPAGATE(try_seed(first, removed, growing));
    // The others: the vertices after it that are unused now, in order, and those that pinch removal frees
    // later while their turn is still to come (`freed`, kept in order, read alongside).
    Array<uint32_t> pending(context_.memory), freed(context_.memory);
    for (uint32_t v = 0; v < n; ++v) {
        if (!surface_.is_used(v) && before(first, v) && !pending.push_back(v)) return context_.fail_out_of_memory();
    }
    std::sort(pending.begin(), pending.end(), before);
    size_t next_pending = 0, next_freed = 0;
    while (components_ < context_.params.max_components) {
        const bool have_pending = next_pending < pending.size(), have_freed = next_freed < freed.size();
        if (!have_pending && !have_freed) break;
        uint32_t v;
        if (!have_freed || (have_pending && !before(freed[next_freed], pending[next_pending]))) {
            v = pending[next_pending++];
        } else {
            v = freed[next_freed++];
        }
        if (surface_.is_used(v)) continue;
        removed.clear();
        DBRG_PROPAGATE(try_seed(v, removed, growing));
        for (uint32_t f : removed) {
            for (uint32_t i = 0; i < 3; ++i) {
                const uint32_t w = surface_.corner(f, i);
                if (surface_.is_used(w) || !before(v, w) ||
                    std::binary_search(pending.begin() + next_pending, pending.end(), w, before)) {
                    continue;
                }
                uint32_t* const at = std::lower_bound(freed.begin() + next_freed, freed.end(), w, before);
                if (at != freed.end() && *at == w) continue;
                const size_t index = at - freed.begin();
                if (!freed.push_back(w)) return context_.fail_out_of_memory();
                std::rotate(freed.begin() + index, freed.end() - 1, freed.end());
            }
        }
    }
    release_queues();
    DBRG_PROPAGATE(remove_islands(stage.part(GROW_PROGRESS_ISLANDS, GROW_PROGRESS_FLIPS)));
    DBRG_PROPAGATE(flipper_.flip_all(radius_sum_, stage.part(GROW_PROGRESS_FLIPS, 1)));
    context_.stats.components = components_;  // the output stage recounts after hole filling
    return stage.report(1, 1);
}

dbrg_status RegionGrower::grow_from(const uint32_t* seeds, size_t seed_count, const uint8_t* fixed) {
    const ProgressSpan stage(context_, DBRG_STAGE_GROW);
    DBRG_PROPAGATE(stage.report(0, 1));
    DBRG_PROPAGATE(start_surface());
    const uint32_t n = delaunay_.vertex_count();
    for (size_t i = 0; i < seed_count; ++i) {
        const uint32_t a = seeds[3 * i], b = seeds[3 * i + 1], c = seeds[3 * i + 2];
        if (a >= n || b >= n || c >= n || a == b || b == c || a == c) continue;
        const FaceCheck check = surface_.check_face(a, b, c);
        if (check.verdict != FaceCheck::valid) continue;
        // A face that is no Delaunay triangle of these points gets no tetrahedron: nothing grows from it.
        const uint32_t f = surface_.add_face(a, b, c, tet_with_face(a, b, c), check);
        if (f == NO_FACE) return context_.fail_out_of_memory();
        radius_sum_ += circumradius(delaunay_.point(a), delaunay_.point(b), delaunay_.point(c));
    }
    if (!causes_.cover_faces(surface_.face_count())) return context_.fail_out_of_memory();
    fixed_ = fixed;
    for (uint32_t h = 0; h < 3 * surface_.face_count(); ++h) {
        if (surface_.is_boundary(h)) DBRG_PROPAGATE(propose(h, nullptr));
    }
    DBRG_PROPAGATE(grow_component(stage.part(0, GROW_PROGRESS_FLIPS)));
    release_queues();
    Array<uint32_t> removed(context_.memory);
    DBRG_PROPAGATE(resolve_pinches(removed));
    DBRG_PROPAGATE(flipper_.flip_all(radius_sum_, stage.part(GROW_PROGRESS_FLIPS, 1)));
    components_ = 1;
    context_.stats.components = components_;
    return stage.report(1, 1);
}

// A finite tetrahedron with face (a, b, c), or NO_TET when (a, b, c) is no Delaunay triangle.
uint32_t RegionGrower::tet_with_face(uint32_t a, uint32_t b, uint32_t c) const {
    Array<uint32_t> star(context_.memory);
    if (!delaunay_.tets_around_vertex(a, star)) return NO_TET;
    for (uint32_t t : star) {
        if (!delaunay_.tet_is_finite(t)) continue;
        bool has_b = false, has_c = false;
        for (uint32_t lv = 0; lv < 4; ++lv) {
            has_b = has_b || delaunay_.tet_vertex(t, lv) == b;
            has_c = has_c || delaunay_.tet_vertex(t, lv) == c;
        }
        if (has_b && has_c) return t;
    }
    return NO_TET;
}

// Tries vertex v as a seed: grows a component from its seed triangle, if it has one, and resolves the
// pinches left. Appends the faces that pinch resolution removed to `removed`.
dbrg_status RegionGrower::try_seed(uint32_t v, Array<uint32_t>& removed, const ProgressSpan& progress) {
    uint32_t corners[3], tet;
    const bool seeded = find_seed(v, corners, tet);
    if (context_.memory.failed()) return context_.fail_out_of_memory();
    if (!seeded) return DBRG_OK;
    const uint32_t faces_before = surface_.live_face_count();
    DBRG_PROPAGATE(add_face(corners[0], corners[1], corners[2], tet));
    DBRG_PROPAGATE(grow_component(progress));
    DBRG_PROPAGATE(resolve_pinches(removed));
    // A seed that grew only a few faces (stray points) does not count against max_components; if its
    // faces stay apart from everything else, they go with the islands below. (It may also have joined an
    // earlier component: growing can attach to any boundary vertex.)
    if (components_ == 0 || surface_.live_face_count() >= faces_before + MIN_SEEDED_COMPONENT_FACES) ++components_;
    return DBRG_OK;
}

// The smallest-circumradius Delaunay triangle at `vertex` whose corners are all unused (so it starts a
// component of its own), and its circumradius; HUGE_VAL when there is none (also for a vertex in no
// tetrahedron, which a backend may leave).
double RegionGrower::smallest_seed(uint32_t vertex, uint32_t corners[3], uint32_t& tet) const {
    Array<uint32_t> star(context_.memory);
    if (delaunay_.vertex_tet(vertex) == NO_TET || !delaunay_.tets_around_vertex(vertex, star)) return HUGE_VAL;
    double best = HUGE_VAL;
    for (uint32_t t : star) {
        if (!delaunay_.tet_is_finite(t)) continue;
        for (uint32_t lf = 0; lf < 4; ++lf) {
            uint32_t face[3], k = 0;
            for (uint32_t lv = 0; lv < 4; ++lv) {
                if (lv != lf) face[k++] = delaunay_.tet_vertex(t, lv);
            }
            if (face[0] != vertex && face[1] != vertex && face[2] != vertex) continue;
            if (surface_.is_used(face[0]) || surface_.is_used(face[1]) || surface_.is_used(face[2])) continue;
            const double r = circumradius(delaunay_.point(face[0]), delaunay_.point(face[1]), delaunay_.point(face[2]));
            std::sort(face, face + 3);
            const bool better = r < best || (r == best && std::lexicographical_compare(face, face + 3, corners, corners + 3));
            if (!better) continue;
            best = r;
            std::copy(face, face + 3, corners);
            tet = t;
        }
    }
    return best;
}

// The seed triangle at `vertex` (smallest_seed), oriented upward. With the open-surface test on, it must
// also not be much larger than the triangles grown so far, or, before any, than a typical seed: a stray
// point above the surface would otherwise seed it with a huge triangle, and the mean r_a it starts from
// would let growing reach across empty space.
bool RegionGrower::find_seed(uint32_t vertex, uint32_t corners[3], uint32_t& tet) const {
    const double best = smallest_seed(vertex, corners, tet);
    if (best == HUGE_VAL) return false;
    const double factor = context_.params.boundary_factor;
    const uint32_t faces = surface_.live_face_count();
    const double mean = faces > 0 ? radius_sum_ / faces : typical_seed_;
    if (factor > 0 && best > factor * mean) return false;
    orient_upward(delaunay_, corners);
    return true;
}

// typical_seed_: the median of smallest_seed over about SEED_SAMPLES points spread along the numbering
// (a Hilbert curve, so over the surface). Only false on allocation failure.
bool RegionGrower::measure_typical_seed() {
    const uint32_t n = delaunay_.vertex_count();
    const uint32_t samples = std::min(n, SEED_SAMPLES);
    Array<double> radii(context_.memory);
    if (!radii.reserve(samples)) return false;
    for (uint32_t k = 0; k < samples; ++k) {
        uint32_t corners[3], tet;
        const double r = smallest_seed(uint32_t(uint64_t(k) * n / samples), corners, tet);
        if (context_.memory.failed()) return false;
        if (r != HUGE_VAL) radii.push_back(r);
    }
    if (radii.empty()) return true;
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    typical_seed_ = radii[radii.size() / 2];
    return true;
}

dbrg_status RegionGrower::grow_component(const ProgressSpan& progress) {
    // Postponed candidates get one more chance each time the queue runs dry.
    for (;;) {
        DBRG_PROPAGATE(drain_queue(progress));
        if (postponed_.empty()) return DBRG_OK;
        for (const Candidate& c : postponed_) {
            if (!enqueue(c)) return context_.fail_out_of_memory();
        }
        postponed_.clear();
    }
}

dbrg_status RegionGrower::drain_queue(const ProgressSpan& progress) {
    dbrg_stats& stats = context_.stats;
    uint32_t taken = 0;
    while (!queue_.empty()) {
        if (++taken % REPORT_CANDIDATES == 0) DBRG_PROPAGATE(report_grown(progress));
        Candidate c = queue_.pop();
        // A boundary half-edge has at most one candidate, in the queue or postponed, at any time: one is
        // computed when the half-edge appears and after the last one was rejected, and regrow_holes computes
        // them while both are empty. So an entry is stale exactly when a face has covered its half-edge.
        if (!surface_.is_boundary(c.halfedge)) continue;
        ++stats.candidates_evaluated;
        double smoothness;
        FaceCheck check;
        const CandidateVerdict verdict = examine_again(c, smoothness, check);
        if (verdict == CandidateVerdict::pinch && !c.postponed) {
            DBRG_PROPAGATE(postpone(c));
            continue;
        }
        if (verdict != CandidateVerdict::valid && verdict != CandidateVerdict::pinch) {
            DBRG_PROPAGATE(reject(c, verdict));
            continue;
        }
        Candidate now = c;
        now.set_smoothness(smoothness, check.shared_edges());
        if (more_credible(c, now)) {
            // S changed around it since it was queued and it is less credible now: queue it again.
            if (!enqueue(now)) return context_.fail_out_of_memory();
            continue;
        }
        if (!passes_boundary_test(c)) {
            if (!c.postponed) {
                DBRG_PROPAGATE(postpone(c));
            } else {
                ++stats.rejected_boundary;
                causes_.mark_open(c.halfedge);
            }
            continue;
        }
        const uint32_t h = c.halfedge;
        DBRG_PROPAGATE(add_face(surface_.target(h), surface_.origin(h), c.apex, c.tet, &check));
    }
    return DBRG_OK;
}

// How far growing has come: the faces of S over the 2n - 4 or so of a closed surface through all n points.
// (The share of points reached, which the step observers see, stalls while the last holes close, with up
// to a tenth of the work left at a million points. An open surface ends short of 1.)
dbrg_status RegionGrower::report_grown(const ProgressSpan& progress) const {
    const size_t closed_faces = 2 * size_t(delaunay_.vertex_count());
    return progress.report(std::min<size_t>(surface_.live_face_count(), closed_faces), closed_faces);
}

dbrg_status RegionGrower::postpone(Candidate c) {
    c.postponed = 1;
    if (postponed_.size() == postponed_.capacity()) {
        // Most set-aside candidates go stale as the fronts move on: drop those before growing the list.
        size_t kept = 0;
        for (const Candidate& p : postponed_) {
            if (surface_.is_boundary(p.halfedge)) postponed_[kept++] = p;
        }
        postponed_.shrink(kept);
        if (!reserve_after_compaction(postponed_)) return context_.fail_out_of_memory();
    }
    return postponed_.push_back(c) ? DBRG_OK : context_.fail_out_of_memory();
}

// Queues a candidate. Entries whose half-edge has been covered by a face since stay in the heap until
// they come up (they are skipped then); before the heap's memory grows, they are dropped instead, so the
// heap holds about the fronts' candidates rather than every candidate ever computed. Faces are only
// removed while the queue is empty, so a covered half-edge stays covered as long as its entries exist:
// the candidates that come up, and their order, are the same as without dropping.
bool RegionGrower::enqueue(const Candidate& c) {
    if (queue_.full()) {
        queue_.remove_if([&](const Candidate& entry) { return !surface_.is_boundary(entry.halfedge); });
        if (!reserve_after_compaction(queue_)) return false;
    }
    return queue_.push(c);
}

dbrg_status RegionGrower::reject(const Candidate& c, CandidateVerdict verdict) {
    dbrg_stats& stats = context_.stats;
    switch (verdict) {
    case CandidateVerdict::edge_nonmanifold: ++stats.rejected_edge_nonmanifold; break;
    case CandidateVerdict::orientation: ++stats.rejected_orientation; break;
    case CandidateVerdict::bowtie: ++stats.rejected_bowtie; break;
    case CandidateVerdict::dihedral: ++stats.rejected_dihedral; break;
    case CandidateVerdict::valid:
    case CandidateVerdict::pinch:
    case CandidateVerdict::fixed: break;
    }
    // The edge moves on to its next-best candidate (§3.2.2).
    const CandidateRank rejected = rank(c);
    return propose(c.halfedge, &rejected);
}

// ct(e) (§3.1.2): among the Delaunay triangles around the edge of `halfedge`, other than its face in S,
// the first in candidate order (smallest circumradius) whose dihedral angle with that face is below
// theta_sliver. With `after`, only triangles ranked after it count, so that a rejected candidate hands
// over to the next best.
bool RegionGrower::select_candidate(uint32_t halfedge, const CandidateRank* after, Candidate& out) const {
    const uint32_t face = Surface::face_of(halfedge);
    if (surface_.face_tet(face) == NO_TET) return false;  // a hole-filling face: no tetrahedron to walk from
    const uint32_t u = surface_.origin(halfedge), v = surface_.target(halfedge);
    const uint32_t opposite = surface_.target(Surface::next(halfedge));
    const Vec3 normal_b = face_normal(delaunay_, surface_, face);
    const double* pu = delaunay_.point(u);
    const double* pv = delaunay_.point(v);
    bool found = false;
    CandidateRank best{0, 0, 0};
    // The points of a batch of triangles are requested before any is used.
    const uint32_t BATCH = 16;
    uint32_t apexes[BATCH], tets[BATCH], n = 0;
    const auto evaluate = [&]() {
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t apex = apexes[i];
            const double* pw = delaunay_.point(apex);
            const double turn = dihedral_cosine(normal_b, triangle_normal(pv, pu, pw));
            if (turn <= cos_sliver_) continue;
            const double r = circumradius(pu, pv, pw);
            const CandidateRank rank{static_cast<float>(r), turn, apex};
            // precedes is a total order: the best triangle does not depend on the order they come in.
            if ((after && !precedes(*after, rank)) || (found && !precedes(rank, best))) continue;
            best = rank;
            out.radius = r;
            out.apex = apex;
            out.tet = tets[i];
            found = true;
        }
        n = 0;
    };
    walk_edge_ring(delaunay_, surface_.face_tet(face), u, v, [&](uint32_t apex, uint32_t tet) {
        if (apex == INFINITE_VERTEX || apex == opposite) return;
        prefetch(delaunay_.point(apex));
        apexes[n] = apex;
        tets[n++] = tet;
        if (n == BATCH) evaluate();
    });
    evaluate();
    out.halfedge = halfedge;
    return found;
}

// The topological and geometrical examinations of §3.2.1 for attaching (v, u, apex) to the boundary
// half-edge u->v: no edge with a third face, compatible orientation, no neck that can never heal, and
// dihedral angles with every neighbour in S below theta_sliver. Also computes the local smooth degree
// (§3.1.3) over the neighbours the triangle would have.
RegionGrower::CandidateVerdict RegionGrower::examine(const Candidate& c, double& smoothness, FaceCheck& check) const {
    const uint32_t u = surface_.origin(c.halfedge), v = surface_.target(c.halfedge);
    if (fixed_ && (fixed_[u] || fixed_[v] || fixed_[c.apex])) {
        smoothness = -1;  // the least smooth: it is refused, never ranked
        return CandidateVerdict::fixed;
    }
    const Vec3 normal = triangle_normal(delaunay_.point(v), delaunay_.point(u), delaunay_.point(c.apex));
    check = surface_.check_face(v, u, c.apex);
    smoothness = dihedral_cosine(normal, face_normal(delaunay_, surface_, Surface::face_of(c.halfedge)));
    switch (check.verdict) {
    case FaceCheck::edge_nonmanifold: return CandidateVerdict::edge_nonmanifold;
    case FaceCheck::orientation: return CandidateVerdict::orientation;
    case FaceCheck::bowtie: return CandidateVerdict::bowtie;
    case FaceCheck::valid: break;
    }
    double cos_sum = 0;
    uint32_t neighbours = 0;
    bool too_sharp = false;
    for (uint32_t shared : check.shared) {
        if (shared == NO_HALFEDGE) continue;
        const double cos_theta = dihedral_cosine(normal, face_normal(delaunay_, surface_, Surface::face_of(shared)));
        too_sharp = too_sharp || cos_theta <= cos_sliver_;
        cos_sum += cos_theta;
        ++neighbours;
    }
    smoothness = cos_sum / neighbours;
    if (too_sharp) return CandidateVerdict::dihedral;
    // Touching S at a vertex alone pinches it: needed where two fronts meet, but only once nothing better is left.
    return check.pinches > 0 ? CandidateVerdict::pinch : CandidateVerdict::valid;
}

// examine(c) with S as it is now, taken from what propose kept when S has not changed since.
RegionGrower::CandidateVerdict RegionGrower::examine_again(const Candidate& c, double& smoothness, FaceCheck& check) const {
    for (const Examined& e : examined_) {
        if (e.halfedge == c.halfedge && e.apex == c.apex && e.edits == surface_.edit_count()) {
            smoothness = e.smoothness;
            check = e.check;
            return e.verdict;
        }
    }
    return examine(c, smoothness, check);
}

// §4: a candidate much larger than the triangles of S spans an opening of an open surface.
bool RegionGrower::passes_boundary_test(const Candidate& c) const {
    const double factor = context_.params.boundary_factor;
    if (factor == 0) return true;
    const auto radius = [&](uint32_t f) { return face_radius(delaunay_, surface_, f); };
    const double mean = context_.params.boundary_mean == DBRG_BOUNDARY_MEAN_GLOBAL && !local_boundary_test_
                            ? radius_sum_ / surface_.live_face_count()
                            : mean_radius_at_ends(surface_, c.halfedge, radius);
    return c.radius <= factor * mean;
}


// The candidate's place in its edge's candidate order, as select_candidate ranked it (the turn is
// recomputed the same way rather than stored in every queue entry).
CandidateRank RegionGrower::rank(const Candidate& c) const {
    const uint32_t u = surface_.origin(c.halfedge), v = surface_.target(c.halfedge);
    const double turn = dihedral_cosine(face_normal(delaunay_, surface_, Surface::face_of(c.halfedge)),
                                        triangle_normal(delaunay_.point(v), delaunay_.point(u), delaunay_.point(c.apex)));
    return CandidateRank{static_cast<float>(c.radius), turn, c.apex};
}

// Computes the next candidate of a boundary half-edge and queues it; without one, the edge stays open.
dbrg_status RegionGrower::propose(uint32_t halfedge, const CandidateRank* after) {
    Candidate c;
    if (!select_candidate(halfedge, after, c)) return DBRG_OK;
    Examined& kept = examined_[examined_next_++ % EXAMINED_KEPT];
    double smoothness;
    kept.verdict = examine(c, smoothness, kept.check);
    kept.halfedge = halfedge;
    kept.apex = c.apex;
    kept.edits = surface_.edit_count();
    kept.smoothness = smoothness;
    c.set_smoothness(smoothness, kept.check.shared_edges());
    c.postponed = 0;
    return enqueue(c) ? DBRG_OK : context_.fail_out_of_memory();
}

// Inserts face (a, b, c) into S and queues candidates for its new boundary edges (§3.2.2).
dbrg_status RegionGrower::add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const FaceCheck* check) {
    const uint32_t f = check ? surface_.add_face(a, b, c, tet, *check) : surface_.add_face(a, b, c, tet);
    if (f == NO_FACE) return context_.fail_out_of_memory();
    surface_.set_face_flags(f, new_face_flags_);
    const double *pa = delaunay_.point(a), *pb = delaunay_.point(b), *pc = delaunay_.point(c);
    const double r = circumradius(pa, pb, pc);
    radius_sum_ += r;
    if (!causes_.cover_faces(f + 1)) return context_.fail_out_of_memory();
    DBRG_PROPAGATE(report_step());
    for (uint32_t i = 0; i < 3; ++i) {
        if (surface_.is_boundary(3 * f + i)) DBRG_PROPAGATE(propose(3 * f + i, nullptr));
    }
    return DBRG_OK;
}

// Tells the step observer, if any, that S has changed.
dbrg_status RegionGrower::report_step() const {
    return observer_ ? observer_(observer_user_, surface_, points_reached(delaunay_, surface_)) : DBRG_OK;
}

dbrg_status RegionGrower::regrow_holes(const ProgressSpan& progress) {
    local_boundary_test_ = true;
    new_face_flags_ = FACE_FILLED;
    const uint32_t before = surface_.live_face_count();
    const uint32_t halfedges = 3 * surface_.face_count();
    const ProgressSpan proposing = progress.part(0, REGROW_PROGRESS_GROWING);
    for (uint32_t h = 0; h < halfedges; ++h) {
        DBRG_PROPAGATE(proposing.report_at(h, halfedges, REPORT_HALFEDGES));
        if (surface_.is_boundary(h) && causes_.of(h) == BOUNDARY_UNRESOLVED) DBRG_PROPAGATE(propose(h, nullptr));
    }
    DBRG_PROPAGATE(grow_component(progress.part(REGROW_PROGRESS_GROWING, 1)));
    release_queues();
    Array<uint32_t> removed(context_.memory);
    DBRG_PROPAGATE(resolve_pinches(removed));
    const uint32_t after = surface_.live_face_count();
    context_.stats.hole_triangles_delaunay += after > before ? after - before : 0;
    local_boundary_test_ = false;
    new_face_flags_ = 0;
    return DBRG_OK;
}

// Growing has drained both: give their memory back before the next stage allocates.
void RegionGrower::release_queues() {
    queue_.release();
    postponed_.release();
}

// Cutting pinches can leave a few faces joined to nothing else: an island is no object of its own.
dbrg_status RegionGrower::remove_islands(const ProgressSpan& progress) {
    Array<uint32_t> removed(context_.memory);
    dbrg_status status = DBRG_OK;
    const auto between = [&](size_t done, size_t total) { return (status = progress.report(done, total)) == DBRG_OK; };
    if (!surface_.remove_small_components(MIN_SEEDED_COMPONENT_FACES, removed, between)) {
        return status != DBRG_OK ? status : context_.fail_out_of_memory();
    }
    for (uint32_t f : removed) radius_sum_ -= face_radius(delaunay_, surface_, f);
    context_.stats.pinch_faces_removed += static_cast<uint32_t>(removed.size());
    return DBRG_OK;
}

// Vertices still pinched when growing stops keep only their largest fan (Surface::remove_pinches).
dbrg_status RegionGrower::resolve_pinches(Array<uint32_t>& removed) {
    const size_t first = removed.size();
    if (!surface_.remove_pinches(removed, fixed_)) return context_.fail_out_of_memory();
    for (size_t i = first; i < removed.size(); ++i) radius_sum_ -= face_radius(delaunay_, surface_, removed[i]);
    context_.stats.pinch_faces_removed += static_cast<uint32_t>(removed.size() - first);
    return DBRG_OK;
}

} // namespace dbrg
