// Point insertion: puts back the sample points that growing and hole filling passed over. Where two
// points lie closer together than the spacing (a uniformly random sample has hundreds of such pairs),
// the four corners of a flat Delaunay tetrahedron are on the surface. Growing takes the tetrahedron's
// smoothest face, and the point on the other side is left under it. Such a point sees a patch of S
// through Delaunay tetrahedra: the faces f of S for which f and the point span one. When that patch, or a
// piece of it (its faces joined across edges), is a disk, a fan from the point over the disk's rim is made
// of Delaunay triangles too (the tetrahedra's other faces), and replaces the disk without changing the
// topology of S.
#pragma once

#include <stdint.h>

#include "core/array.h"
#include "core/context.h"
#include "core/progress_span.h"
#include "core/vec3.h"
#include "delaunay/tetrahedralization.h"
#include "surface/surface.h"

namespace dbrg {

class PointInsertion {
public:
    PointInsertion(const Tetrahedralization& delaunay, Surface& surface, Context& context);

    // No patch touching a vertex marked in `fixed` (NULL: none) is replaced: a fixed vertex's fan is
    // complete outside the points at hand (RegionGrower::grow_from).
    void keep_fixed(const uint8_t* fixed) { fixed_ = fixed; }

    // Inserts every point S does not use whose patch, or a piece of it, is a disk and whose fan passes
    // fan_is_valid and growing's topological examination, in rounds while a round inserts any: a point
    // inserted can uncover its close neighbour's patch.
    // Adds context.stats.points_inserted. Reports to `progress`.
    dbrg_status insert_left_out(const ProgressSpan& progress);

private:
    // A face of S that spans a Delaunay tetrahedron with the point at hand.
    struct PatchFace {
        uint32_t face, tet;
    };

    // A round over the points S does not use; `inserted` counts those it put in.
    dbrg_status insert_round(const ProgressSpan& progress, uint32_t& inserted);
    // Fills patch_ for point q, ordered by face id (not by tetrahedron slot, which depends on the threads
    // that built the tetrahedralization); false on allocation failure.
    bool find_patch(uint32_t q);
    // Tries the pieces of the patch, larger first, until one is a disk with a valid fan, and replaces it.
    dbrg_status insert_over_a_disk(uint32_t q, bool& inserted);
    // Fills disk_ with the piece of the patch that patch_[first] is in, when no earlier face of patch_ is
    // in it and it has `size` faces; false otherwise or on allocation failure.
    bool take_piece(uint32_t first, uint32_t size);
    // The face of S with corners a, b and c in either orientation, or NO_FACE.
    uint32_t find_face(uint32_t a, uint32_t b, uint32_t c) const;
    // Fills rim_ with disk_'s boundary half-edges in order along its one rim, when disk_ is a disk with
    // every vertex on the rim (a vertex inside would be left out by the fan); false otherwise.
    bool find_rim();
    // Whether the fan from q over the rim folds nowhere past the sliver angle, and turns less than a right
    // angle from the disk it replaces.
    bool fan_is_valid(uint32_t q) const;
    // Replaces disk_ by the fan; `inserted` tells whether it did (the topological examination of every
    // fan face is run once more as it is added, and a fan it refuses is taken back).
    dbrg_status replace_by_fan(uint32_t q, bool& inserted);
    // The entry of patch_, disk_ or `faces` for face f, or NO_FACE.
    uint32_t patch_index(uint32_t f) const;
    uint32_t disk_index(uint32_t f) const;
    static uint32_t index_in(const Array<PatchFace>& faces, uint32_t f);
    // Whether a corner of disk_ is fixed (keep_fixed).
    bool disk_touches_fixed() const;
    // The unit normal of the fan face over a rim half-edge (zero when the face is degenerate).
    Vec3 fan_normal(uint32_t q, uint32_t rim_halfedge) const;

    const Tetrahedralization& delaunay_;
    Surface& surface_;
    Context& context_;
    double cos_sliver_;
    const uint8_t* fixed_ = nullptr;
    Array<uint32_t> tets_;        // around the point at hand
    Array<PatchFace> patch_;      // its patch
    Array<PatchFace> disk_;       // the piece of the patch at hand
    Array<uint32_t> rim_;         // disk_'s rim, in order
};

} // namespace dbrg
