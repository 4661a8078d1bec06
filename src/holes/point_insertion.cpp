// Point insertion: fans from the points growing and hole filling passed over, replacing the patch of S each
// one sees through Delaunay tetrahedra (point_insertion.h).
#include "holes/point_insertion.h"

#include <math.h>

#include <algorithm>

#include "core/status.h"
#include "grow/surface_geometry.h"
#include "grow/triangle_geometry.h"
#include "holes/face_journal.h"

namespace dbrg {
namespace {

// A point inserted can uncover a close neighbour's patch; three points closer than the spacing are rare,
// so a few rounds reach every point that can be reached.
constexpr uint32_t MAX_ROUNDS = 4;
// A patch larger than this is no flat tetrahedron's face and its neighbours: the point is far from S.
constexpr uint32_t MAX_PATCH_FACES = 16;
// Reports every this many points examined.
constexpr uint32_t REPORT_STEP = 1u << 14;

} // namespace

PointInsertion::PointInsertion(const Tetrahedralization& delaunay, Surface& surface, Context& context)
    : delaunay_(delaunay),
      surface_(surface),
      context_(context),
      cos_sliver_(cos(context.params.sliver_angle)),
      tets_(context.memory),
      patch_(context.memory),
      disk_(context.memory),
      rim_(context.memory) {}

dbrg_status PointInsertion::insert_left_out(const ProgressSpan& progress) {
    for (uint32_t round = 0; round < MAX_ROUNDS; ++round) {
        uint32_t inserted = 0;
        // Each round takes half of what is left of the progress.
        const double begin = 1 - ldexp(1, -int(round)), end = 1 - ldexp(1, -int(round) - 1);
        DBRG_PROPAGATE(insert_round(progress.part(begin, end), inserted));
        context_.stats.points_inserted += inserted;
        if (inserted == 0) break;
    }
    return progress.report(1, 1);
}

dbrg_status PointInsertion::insert_round(const ProgressSpan& progress, uint32_t& inserted) {
    const uint32_t vertices = surface_.vertex_count();
    for (uint32_t q = 0; q < vertices; ++q) {
        if (q % REPORT_STEP == 0) DBRG_PROPAGATE(progress.report(q, vertices));
        if (surface_.is_used(q) || delaunay_.vertex_tet(q) == NO_TET || (fixed_ && fixed_[q])) continue;
        if (!find_patch(q)) return context_.fail_out_of_memory();
        if (patch_.empty() || patch_.size() > MAX_PATCH_FACES) continue;
        bool done = false;
        DBRG_PROPAGATE(insert_over_a_disk(q, done));
        inserted += done ? 1 : 0;
    }
    return DBRG_OK;
}

dbrg_status PointInsertion::insert_over_a_disk(uint32_t q, bool& inserted) {
    inserted = false;
    // The faces q sees can fall apart into pieces (q spans tetrahedra with two faces of S that share no
    // edge); each piece's fan is made of Delaunay triangles all the same. Larger pieces first. One fan is
    // tried at most: a fan refused and taken back restores the faces under new ids, so patch_ is stale.
    for (uint32_t size = uint32_t(patch_.size()); size > 0; --size) {
        for (uint32_t first = 0; first < patch_.size(); ++first) {
            const bool disk = take_piece(first, size) && !disk_touches_fixed() && find_rim();
            if (context_.memory.failed()) return context_.fail_out_of_memory();
            if (disk && fan_is_valid(q)) return replace_by_fan(q, inserted);
        }
    }
    return DBRG_OK;
}

bool PointInsertion::take_piece(uint32_t first, uint32_t size) {
    // The piece is patch_[first]'s: the faces reached from it across edges shared within the patch. It is
    // taken once, from its first face, and only when it has `size` faces.
    disk_.clear();
    if (!disk_.push_back(patch_[first])) return false;
    for (uint32_t i = 0; i < disk_.size(); ++i) {
        for (uint32_t h = 3 * disk_[i].face; h < 3 * disk_[i].face + 3; ++h) {
            if (surface_.is_boundary(h)) continue;
            const uint32_t neighbour = Surface::face_of(surface_.twin(h));
            const uint32_t at = patch_index(neighbour);
            if (at == NO_FACE || disk_index(neighbour) != NO_FACE) continue;
            if (at < first) return false;  // taken from an earlier face
            if (!disk_.push_back(patch_[at])) return false;
        }
    }
    return disk_.size() == size;
}

bool PointInsertion::find_patch(uint32_t q) {
    patch_.clear();
    if (!delaunay_.tets_around_vertex(q, tets_)) return false;
    for (uint32_t t : tets_) {
        if (!delaunay_.tet_is_finite(t)) continue;
        const uint32_t lq = delaunay_.tet_local_index(t, q);
        const uint32_t f = find_face(delaunay_.tet_vertex(t, FACE_VERTEX[lq][0]), delaunay_.tet_vertex(t, FACE_VERTEX[lq][1]),
                                     delaunay_.tet_vertex(t, FACE_VERTEX[lq][2]));
        if (f != NO_FACE && !patch_.push_back({f, t})) return false;
    }
    std::sort(patch_.begin(), patch_.end(), [](const PatchFace& a, const PatchFace& b) { return a.face < b.face; });
    return true;
}

uint32_t PointInsertion::find_face(uint32_t a, uint32_t b, uint32_t c) const {
    if (!surface_.is_used(a) || !surface_.is_used(b) || !surface_.is_used(c)) return NO_FACE;
    for (const uint32_t h : {surface_.find_halfedge(a, b), surface_.find_halfedge(b, a)}) {
        if (h != NO_HALFEDGE && surface_.origin(Surface::prev(h)) == c) return Surface::face_of(h);
    }
    return NO_FACE;
}

uint32_t PointInsertion::patch_index(uint32_t f) const { return index_in(patch_, f); }

uint32_t PointInsertion::disk_index(uint32_t f) const { return index_in(disk_, f); }

uint32_t PointInsertion::index_in(const Array<PatchFace>& faces, uint32_t f) {
    for (uint32_t i = 0; i < faces.size(); ++i) {
        if (faces[i].face == f) return i;
    }
    return NO_FACE;
}

bool PointInsertion::disk_touches_fixed() const {
    if (!fixed_) return false;
    for (const PatchFace& p : disk_) {
        for (uint32_t i = 0; i < 3; ++i) {
            if (fixed_[surface_.corner(p.face, i)]) return true;
        }
    }
    return false;
}

bool PointInsertion::find_rim() {
    rim_.clear();
    for (const PatchFace& p : disk_) {
        for (uint32_t h = 3 * p.face; h < 3 * p.face + 3; ++h) {
            const bool inside = !surface_.is_boundary(h) && disk_index(Surface::face_of(surface_.twin(h))) != NO_FACE;
            if (!inside && !rim_.push_back(h)) return false;
        }
    }
    // A disk whose vertices are all on its rim has two faces fewer than rim edges (Euler), and a simple
    // rim has each vertex once; together with the rim being one loop, that makes it such a disk.
    const size_t edges = rim_.size();
    if (edges != disk_.size() + 2) return false;
    for (size_t i = 0; i + 1 < edges; ++i) {
        // Order the rim: the edge leaving where edge i ends goes next.
        const uint32_t end = surface_.target(rim_[i]);
        if (end == surface_.origin(rim_[0])) return false;  // back at the start early: a pinched or second rim
        size_t next = edges;
        for (size_t j = i + 1; j < edges; ++j) {
            if (surface_.origin(rim_[j]) != end) continue;
            if (next != edges) return false;  // the rim passes twice through `end`
            next = j;
        }
        if (next == edges) return false;  // no edge goes on from `end`: the rim does not close
        const uint32_t swapped = rim_[i + 1];
        rim_[i + 1] = rim_[next];
        rim_[next] = swapped;
    }
    return surface_.target(rim_[edges - 1]) == surface_.origin(rim_[0]);
}

Vec3 PointInsertion::fan_normal(uint32_t q, uint32_t rim_halfedge) const {
    return triangle_normal(delaunay_.point(surface_.origin(rim_halfedge)), delaunay_.point(surface_.target(rim_halfedge)),
                           delaunay_.point(q));
}

bool PointInsertion::fan_is_valid(uint32_t q) const {
    const PointTriples points{delaunay_.points()};
    Vec3 previous = fan_normal(q, rim_.back());
    for (uint32_t h : rim_) {
        const Vec3 normal = fan_normal(q, h);
        if (squared_length(normal) == 0 || dihedral_cosine(normal, previous) <= cos_sliver_) return false;
        // A point under a flat tetrahedron's face makes fan faces that turn little from the faces they
        // replace (measured on random spheres: under 20 degrees but for a few in a thousand); one that turns
        // past a right angle stands across the surface: the point is on another sheet of a thin part.
        if (dihedral_cosine(normal, face_normal(points, surface_, Surface::face_of(h))) <= 0) return false;
        const uint32_t outside = surface_.twin(h);
        if (outside != NO_HALFEDGE &&
            dihedral_cosine(normal, face_normal(points, surface_, Surface::face_of(outside))) <= cos_sliver_) {
            return false;
        }
        previous = normal;
    }
    return true;
}

dbrg_status PointInsertion::replace_by_fan(uint32_t q, bool& inserted) {
    inserted = false;
    // Each fan face by its rim edge, with the tetrahedron its patch face spans with q (the fan face is one
    // of that tetrahedron's faces) and that face's flags (a fan over a filled face is filled), read before
    // the patch goes.
    struct FanFace {
        uint32_t a, b, tet;
        uint8_t flags;
    };
    Array<FanFace> fan(context_.memory);
    if (!fan.reserve(rim_.size())) return context_.fail_out_of_memory();
    for (uint32_t h : rim_) {
        const uint32_t f = Surface::face_of(h);
        fan.push_back({surface_.origin(h), surface_.target(h), disk_[disk_index(f)].tet, surface_.face_flags(f)});
    }
    FaceJournal journal(context_.memory);
    const uint8_t no_causes[3] = {0, 0, 0};
    for (const PatchFace& p : disk_) {
        if (!journal.record_removed(surface_, p.face, no_causes) || !surface_.remove_face(p.face)) {
            return context_.fail_out_of_memory();
        }
    }
    for (const FanFace& face : fan) {
        const FaceCheck check = surface_.check_face(face.a, face.b, q);
        if (check.verdict != FaceCheck::valid) break;
        const uint32_t added = surface_.add_face(face.a, face.b, q, face.tet, check);
        if (added == NO_FACE || !journal.record_added(surface_, added)) return context_.fail_out_of_memory();
        surface_.set_face_flags(added, face.flags);
    }
    inserted = journal.added_count() == fan.size();
    if (inserted) return DBRG_OK;
    const bool undone = journal.undo(surface_, 0, [&](const FaceJournal::Entry& entry) {
        const uint32_t f = surface_.add_face(entry.corners[0], entry.corners[1], entry.corners[2], entry.tet);
        if (f != NO_FACE) surface_.set_face_flags(f, entry.flags);
        return f != NO_FACE;
    });
    if (undone) return DBRG_OK;
    return context_.memory.failed() ? context_.fail_out_of_memory()
                                    : context_.fail(DBRG_ERR_INTERNAL, "undoing a point's fan did not find a face it had added");
}

} // namespace dbrg
