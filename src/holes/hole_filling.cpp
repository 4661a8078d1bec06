// Hole filling: closes the holes that region growing left where every candidate was invalid with ear
// triangles over each hole's own vertices, enlarging a hole that cannot be filled validly and trying again
// (paper §5).
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), section 5.
#include "holes/hole_filling.h"

#include <assert.h>
#include <math.h>

#include <algorithm>

#include "core/status.h"
#include "grow/surface_geometry.h"
#include "grow/triangle_geometry.h"

namespace dbrg {

HoleFiller::HoleFiller(const double* points, Surface& surface, const BoundaryCauses& causes, Context& context)
    : points_{points},
      surface_(surface),
      causes_(causes),
      context_(context),
      restored_open_(context.memory) {}

dbrg_status HoleFiller::find_holes(bool& found) {
    context_.stats.holes_found = count_holes();
    found = context_.stats.holes_found > 0;
    return DBRG_OK;
}

dbrg_status HoleFiller::fill_with_ears(const ProgressSpan& ears, const ProgressSpan& islands_progress) {
    dbrg_stats& stats = context_.stats;
    // Holes are listed first, as filling adds half-edges, and by the corners of one boundary edge each:
    // enlarging one hole can remove a face of another, and undoing that attempt puts the face back under
    // a new id, so a listed half-edge id can go stale while the hole is still there.
    added_base_ = surface_.face_count();
    Array<uint32_t> starts(context_.memory);  // two corners per hole
    Array<uint8_t> listed(context_.memory);
    Array<uint32_t> loop(context_.memory);
    if (!listed.resize(3 * size_t(added_base_), 0)) return context_.fail_out_of_memory();
    for (uint32_t h = 0; h < 3 * added_base_; ++h) {
        if (!surface_.is_boundary(h) || listed[h]) continue;
        surface_.walk_loop(h, [&](uint32_t g) { listed[g] = 1; });
        if (!starts.push_back(surface_.origin(h)) || !starts.push_back(surface_.target(h))) {
            return context_.fail_out_of_memory();
        }
    }
    FaceJournal journal(context_.memory);
    for (size_t i = 0; i < starts.size(); i += 2) {
        DBRG_PROPAGATE(ears.report(i, starts.size()));
        journal.clear();
        const uint32_t u = starts[i], v = starts[i + 1];
        const uint32_t start = surface_.find_halfedge(u, v);
        if (start == NO_HALFEDGE || !surface_.is_boundary(start)) continue;  // filled with another hole already
        if (!collect_hole(start, loop)) continue;
        // A long, wide loop that some edges call a border (is_hole) is filled over its own vertices only:
        // removing grown faces to fill it would trade surface the data support for a closure they only half
        // support. A narrow one is a crack in a surface the data support on both sides.
        const bool border_like = count_open_edges(loop) > 0 && loop.size() > SHORT_LOOP_EDGES && !is_narrow(loop);
        bool filled = false;
        DBRG_PROPAGATE(fill_within_fold_limits(u, v, border_like ? 0 : MAX_ENLARGEMENTS, journal, filled));
        if (!filled && loop.size() <= MAX_CORNER_DROPPING_EDGES) {
            DBRG_PROPAGATE(fill_without_a_corner(u, v, static_cast<uint32_t>(loop.size()), journal, filled));
        }
        if (!filled) continue;
        stats.hole_triangles_added += journal.added_count();
        stats.hole_triangles_removed += journal.removed_count();
    }
    // Enlarging holes can cut a few faces off the rest; such an island is no object of its own.
    Array<uint32_t> islands(context_.memory);
    dbrg_status status = DBRG_OK;
    const auto between = [&](size_t done, size_t total) { return (status = islands_progress.report(done, total)) == DBRG_OK; };
    if (!surface_.remove_small_components(MIN_ISLAND_FACES, islands, between)) {
        return status != DBRG_OK ? status : context_.fail_out_of_memory();
    }
    stats.hole_triangles_removed += static_cast<uint32_t>(islands.size());
    stats.holes_left_open = count_holes();
    stats.holes_filled = stats.holes_found > stats.holes_left_open ? stats.holes_found - stats.holes_left_open : 0;
    return context_.memory.failed() ? context_.fail_out_of_memory() : DBRG_OK;
}

bool HoleFiller::is_open_boundary(uint32_t h) const {
    if (h < 3 * added_base_ || added_base_ == 0) return causes_.of(h) == BOUNDARY_OPEN;
    const size_t k = h - 3 * size_t(added_base_);
    return k < restored_open_.size() && restored_open_[k] != 0;
}

uint32_t HoleFiller::count_open_edges(const Array<uint32_t>& loop) const {
    uint32_t open_edges = 0;
    for (uint32_t h : loop) open_edges += is_open_boundary(h) ? 1 : 0;
    return open_edges;
}

bool HoleFiller::collect_hole(uint32_t start, Array<uint32_t>& loop) const {
    loop.clear();
    const bool collected = surface_.walk_loop(start, [&](uint32_t h) {
        return loop.size() < context_.params.max_hole_edges && loop.push_back(h);
    });
    return collected && !through_fixed(loop) && (filling_cut_ || is_hole(loop));
}

bool HoleFiller::through_fixed(const Array<uint32_t>& loop) const {
    if (!fixed_) return false;
    for (uint32_t h : loop) {
        if (fixed_[surface_.origin(h)]) return true;
    }
    return false;
}

bool HoleFiller::is_hole(const Array<uint32_t>& loop) const {
    const size_t edges = loop.size();
    return 2 * size_t(count_open_edges(loop)) <= edges || edges <= SHORT_LOOP_EDGES || is_narrow(loop);
}

bool HoleFiller::is_narrow(const Array<uint32_t>& loop) const {
    const double factor = context_.params.boundary_factor;
    if (factor == 0) return true;  // no test, no border
    Vec3 centre{0, 0, 0};
    for (uint32_t h : loop) centre = centre + load_vec3(points_.point(surface_.origin(h)));
    centre = (1.0 / double(loop.size())) * centre;
    Vec3 twice_area{0, 0, 0};
    double perimeter = 0, radius_sum = 0;
    for (uint32_t h : loop) {
        const Vec3 a = load_vec3(points_.point(surface_.origin(h))) - centre;
        const Vec3 b = load_vec3(points_.point(surface_.target(h))) - centre;
        twice_area = twice_area + cross(a, b);
        perimeter += length(b - a);
        radius_sum += face_radius(points_, surface_, Surface::face_of(h));
    }
    // width <= factor * mean radius, both sides multiplied by the perimeter and the loop's length
    return length(twice_area) * double(loop.size()) <= factor * radius_sum * perimeter;
}

// Boundary loops that are holes (is_hole), of any length.
uint32_t HoleFiller::count_holes() const {
    Array<uint8_t> seen(context_.memory);
    Array<uint32_t> loop(context_.memory);
    const uint32_t halfedges = 3 * surface_.face_count();
    if (!seen.resize(halfedges, 0)) return 0;
    uint32_t holes = 0;
    for (uint32_t h = 0; h < halfedges; ++h) {
        if (!surface_.is_boundary(h) || seen[h]) continue;
        loop.clear();
        const bool collected = surface_.walk_loop(h, [&](uint32_t g) {
            seen[g] = 1;
            return loop.push_back(g);
        });
        if (!collected) return 0;
        holes += is_hole(loop) && !through_fixed(loop) ? 1 : 0;
    }
    return holes;
}

dbrg_status HoleFiller::fill_within_fold_limits(uint32_t u, uint32_t v, uint32_t enlargements, FaceJournal& journal,
                                                bool& filled) {
    filled = false;
    const size_t position = journal.size();
    for (double fold_limit : {context_.params.sliver_angle, LAST_RESORT_FOLD_ANGLE}) {
        if (fold_limit < context_.params.sliver_angle) continue;
        cos_fold_limit_ = cos(fold_limit);
        // An undone attempt restores faces under new ids: find the hole again by its edge, which the
        // exact undo has made a boundary edge again.
        const uint32_t edge = surface_.find_halfedge(u, v);
        assert(edge != NO_HALFEDGE && surface_.is_boundary(edge));
        if (edge == NO_HALFEDGE || !surface_.is_boundary(edge)) {
            return context_.fail(DBRG_ERR_INTERNAL, "a hole's edge %u-%u was not found again after an undo", u, v);
        }
        DBRG_PROPAGATE(fill_hole(edge, enlargements, journal, filled));
        if (filled) return DBRG_OK;
        DBRG_PROPAGATE(undo(journal, position));
    }
    return DBRG_OK;
}

dbrg_status HoleFiller::fill_hole(uint32_t start, uint32_t enlargements, FaceJournal& journal, bool& filled) {
    filled = false;
    Array<uint32_t> loop(context_.memory);
    Array<uint32_t> corners(context_.memory);
    if (!collect_hole(start, loop)) return context_.memory.failed() ? context_.fail_out_of_memory() : DBRG_OK;
    if (!corners.reserve(loop.size())) return context_.fail_out_of_memory();
    for (uint32_t h : loop) corners.push_back(surface_.origin(h));

    const size_t before_ears = journal.size();
    DBRG_PROPAGATE(clip_ears(corners, journal, filled));
    if (filled || enlargements == 0) return DBRG_OK;

    // §5: an ear is invalid, so take this attempt back, remove the hole's boundary triangles too, and fill
    // the larger hole that leaves instead.
    DBRG_PROPAGATE(undo(journal, before_ears));
    Array<uint32_t> new_starts(context_.memory);
    DBRG_PROPAGATE(enlarge(loop, journal, new_starts));
    if (enlargements <= MAX_ENLARGEMENTS - SPLITTING_ENLARGEMENTS && !on_one_loop(new_starts)) {
        return context_.memory.failed() ? context_.fail_out_of_memory() : DBRG_OK;
    }
    for (uint32_t s : new_starts) {
        if (surface_.face_removed(Surface::face_of(s)) || !surface_.is_boundary(s)) continue;  // filled with another
        bool sub_filled = false;
        DBRG_PROPAGATE(fill_hole(s, enlargements - 1, journal, sub_filled));
        if (!sub_filled) return DBRG_OK;
    }
    filled = true;
    return DBRG_OK;
}

// A small hole whose every ear folds, with a corner of few faces: growing pulled that corner across the
// hole (a pleat of one vertex), so its fan and the hole together form one disk around it. Removing the
// corner's faces leaves a hole over the disk's rim, which ears can fill; the corner is left out
// (PointInsertion may put it back where it lies). Enlarging cannot close such a hole next to a border: the
// enlarged hole runs into the border and is no hole any more.
dbrg_status HoleFiller::fill_without_a_corner(uint32_t u, uint32_t v, uint32_t edges, FaceJournal& journal, bool& filled) {
    filled = false;
    cos_fold_limit_ = cos(context_.params.sliver_angle);
    Array<uint32_t> fan(context_.memory), rim(context_.memory), corners(context_.memory);
    for (uint32_t k = 0; k < edges; ++k) {
        // An undone attempt gives the faces new ids: find the loop again by its edge each time.
        uint32_t out = surface_.find_halfedge(u, v);
        if (out == NO_HALFEDGE || !surface_.is_boundary(out)) return DBRG_OK;
        for (uint32_t i = 0; i < k; ++i) out = surface_.fan_exit(out);
        const uint32_t corner = surface_.origin(out);
        const bool fixed = fixed_ && fixed_[corner];
        if (fixed || surface_.is_pinched(corner) || surface_.fan_size(out) > MAX_DROPPED_FAN) continue;
        // The loop runs previous -> corner -> next; the fan's faces, turning from `out`, are (corner, next,
        // rim 1), (corner, rim 1, rim 2), ..., (corner, rim k - 1, previous). Without them the hole runs
        // from next along the rest of the loop to previous, then back along the rim.
        corners.clear();
        surface_.walk_loop(out, [&](uint32_t h) {
            return corners.size() <= context_.params.max_hole_edges && corners.push_back(surface_.target(h));
        });
        if (corners.empty() || corners.back() != corner) continue;  // longer than any hole
        corners.pop_back();
        fan.clear();
        rim.clear();
        surface_.walk_fan(out, [&](uint32_t h) {
            return fan.push_back(Surface::face_of(h)) && rim.push_back(surface_.target(Surface::next(h)));
        });
        if (context_.memory.failed()) return context_.fail_out_of_memory();
        rim.pop_back();  // previous, already in the loop
        // A rim through the loop's own corners is no disk around the corner alone.
        const bool disk = std::none_of(rim.begin(), rim.end(), [&](uint32_t w) {
            return std::find(corners.begin(), corners.end(), w) != corners.end();
        });
        if (!disk || corners.size() + rim.size() < 3) continue;
        for (size_t i = rim.size(); i-- > 0;) corners.push_back(rim[i]);
        if (context_.memory.failed()) return context_.fail_out_of_memory();
        const size_t position = journal.size();
        for (uint32_t f : fan) DBRG_PROPAGATE(remove_and_record(f, journal));
        DBRG_PROPAGATE(clip_ears(corners, journal, filled));
        if (filled) return DBRG_OK;
        DBRG_PROPAGATE(undo(journal, position));
    }
    return DBRG_OK;
}

// Paper §5, Fig. 9: ears at the concave corners (where the hole turns towards itself), smallest circumradius
// first, each through the topological and geometrical examinations, until the hole is a triangle and closes.
dbrg_status HoleFiller::clip_ears(Array<uint32_t>& corners, FaceJournal& journal, bool& filled) {
    filled = false;
    while (corners.size() >= 3) {
        const size_t n = corners.size();
        size_t best = n;
        // Concave corners first; where none has a valid ear (averaged normals on a sharp or badly sampled
        // rim can call every corner convex), any corner.
        for (const bool concave_only : {true, false}) {
            double best_radius = HUGE_VAL;
            for (size_t i = 0; i < n; ++i) {
                const uint32_t previous = corners[(i + n - 1) % n], apex = corners[i], next = corners[(i + 1) % n];
                const Vec3 a = load_vec3(points_.point(previous)), p = load_vec3(points_.point(apex)),
                           b = load_vec3(points_.point(next));
                if (concave_only && n > 3 && dot(vertex_normal(apex), cross(p - a, b - p)) >= 0) continue;
                const double r = circumradius(points_.point(previous), points_.point(apex), points_.point(next));
                if (r < best_radius && ear_is_valid(apex, previous, next, n == 3)) {
                    best = i;
                    best_radius = r;
                }
            }
            if (best != n) break;
        }
        if (best == n) return DBRG_OK;
        const uint32_t apex = corners[best];
        DBRG_PROPAGATE(add_face(apex, corners[(best + n - 1) % n], corners[(best + 1) % n], NO_TET, nullptr, FACE_FILLED, &journal));
        if (n == 3) break;
        for (size_t i = best; i + 1 < n; ++i) corners[i] = corners[i + 1];
        corners.pop_back();
    }
    filled = true;
    return DBRG_OK;
}

// The ear (apex, previous, next) must keep S an oriented manifold without pinching it, must not reuse an
// edge that S has elsewhere (unless it closes the hole), and must not fold onto its neighbours.
bool HoleFiller::ear_is_valid(uint32_t apex, uint32_t previous, uint32_t next, bool closes_hole) const {
    const FaceCheck check = surface_.check_face(apex, previous, next);
    if (check.verdict != FaceCheck::valid || check.pinches > 0) return false;
    if (!closes_hole && check.shared[1] != NO_HALFEDGE) return false;
    const Vec3 normal = triangle_normal(points_.point(apex), points_.point(previous), points_.point(next));
    if (squared_length(normal) == 0) return false;
    for (uint32_t shared : check.shared) {
        if (shared != NO_HALFEDGE && dihedral_cosine(normal, face_normal(points_, surface_, Surface::face_of(shared))) <= cos_fold_limit_) {
            return false;
        }
    }
    return true;
}

// Removes the faces along the hole (and any face whose removal pinched a vertex) and returns boundary
// half-edges from which the larger hole or holes can be found.
dbrg_status HoleFiller::enlarge(const Array<uint32_t>& loop, FaceJournal& journal, Array<uint32_t>& new_starts) {
    Array<uint32_t> pinched(context_.memory);
    for (uint32_t h : loop) {
        const uint32_t f = Surface::face_of(h);
        if (surface_.face_removed(f)) continue;
        for (uint32_t g = 3 * f; g < 3 * f + 3; ++g) {
            if (!surface_.is_boundary(g) && !new_starts.push_back(surface_.twin(g))) return context_.fail_out_of_memory();
        }
        DBRG_PROPAGATE(remove_and_record(f, journal));
    }
    // Removing faces can pinch a vertex; the surface must stay a manifold in between.
    if (!surface_.remove_pinches(pinched, fixed_)) return context_.fail_out_of_memory();
    bool grown = true;
    for (uint32_t f : pinched) {
        grown = grown && record_removed(f, journal);
        for (uint32_t i = 0; i < 3; ++i) {
            surface_.for_each_fan(surface_.corner(f, i), [&](uint32_t start) { grown = grown && new_starts.push_back(start); });
        }
    }
    if (!grown) return context_.fail_out_of_memory();
    // Keep only starts that are boundary half-edges of live faces now.
    size_t kept = 0;
    for (uint32_t s : new_starts) {
        if (!surface_.face_removed(Surface::face_of(s)) && surface_.is_boundary(s)) new_starts[kept++] = s;
    }
    new_starts.shrink(kept);
    return DBRG_OK;
}

bool HoleFiller::on_one_loop(const Array<uint32_t>& starts) const {
    if (starts.empty()) return true;
    Array<uint32_t> loop(context_.memory);
    surface_.walk_loop(starts[0], [&](uint32_t h) {
        return loop.size() < context_.params.max_hole_edges && loop.push_back(h);
    });
    for (uint32_t s : starts) {
        if (std::find(loop.begin(), loop.end(), s) == loop.end()) return false;
    }
    return true;
}

dbrg_status HoleFiller::remove_and_record(uint32_t f, FaceJournal& journal) {
    if (!record_removed(f, journal) || !surface_.remove_face(f)) return context_.fail_out_of_memory();
    return DBRG_OK;
}

// Records face f (removed or about to be) with what it takes to put it back as it was: which of its edges
// the open-surface test left.
bool HoleFiller::record_removed(uint32_t f, FaceJournal& journal) const {
    uint8_t causes[3];
    for (uint32_t i = 0; i < 3; ++i) causes[i] = is_open_boundary(3 * f + i) ? 1 : 0;
    return journal.record_removed(surface_, f, causes);
}

// Takes back the journal's entries from `position` on; restored faces get their open-surface marks and
// their flags back (a grown face put back is no filled one).
dbrg_status HoleFiller::undo(FaceJournal& journal, size_t position) {
    const bool undone = journal.undo(surface_, position, [&](const FaceJournal::Entry& face) {
        return add_face(face.corners[0], face.corners[1], face.corners[2], face.tet, face.causes, face.flags, nullptr) == DBRG_OK;
    });
    if (undone) return DBRG_OK;
    return context_.memory.failed() ? context_.fail_out_of_memory()
                                    : context_.fail(DBRG_ERR_INTERNAL, "undoing a hole filling did not find a face it had added");
}

dbrg_status HoleFiller::add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const uint8_t* causes, uint8_t flags,
                                 FaceJournal* journal) {
    const uint32_t f = surface_.add_face(a, b, c, tet);
    if (f == NO_FACE) return context_.fail_out_of_memory();
    surface_.set_face_flags(f, flags);
    for (uint32_t i = 0; i < 3; ++i) {
        if (!restored_open_.push_back(causes ? causes[i] : 0)) return context_.fail_out_of_memory();
    }
    if (journal && !journal->record_added(surface_, f)) return context_.fail_out_of_memory();
    return DBRG_OK;
}

// The mean of the unit normals of the faces around v (paper §5).
Vec3 HoleFiller::vertex_normal(uint32_t v) const {
    Vec3 sum{0, 0, 0};
    surface_.walk_vertex(v, [&](uint32_t h) { sum = sum + face_normal(points_, surface_, Surface::face_of(h)); });
    return normalized(sum);
}

} // namespace dbrg
