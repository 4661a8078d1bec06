// Surface: the growing triangulated surface S (paper §2.2) as an array-based half-edge structure, with the
// topological examination (§3.2.1) of a face before it is added.
//
// Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
// reconstruction from unorganized points", Computer-Aided Design 37 (2005), sections 2.2 and 3.2.1.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include <type_traits>

#include "core/array.h"

namespace dbrg {

constexpr uint32_t NO_HALFEDGE = UINT32_MAX;
constexpr uint32_t NO_FACE = UINT32_MAX;

// Per-face flag bits, with the values of dbrg_face_flag (dbrg.h).
constexpr uint8_t FACE_FILLED = 1;  // made by hole filling, not grown from the sample

// What adding a face would do to the topology of S.
struct FaceCheck {
    enum Verdict {
        valid,
        edge_nonmanifold,  // an edge would get a third face
        orientation,       // an edge would be traversed twice in the same direction
        bowtie,            // a vertex would be left with a closed fan and another one (a neck that can never heal)
    } verdict = valid;
    // Which of the face's half-edges (corner i to corner i + 1) would be linked to a boundary half-edge of S.
    uint32_t shared[3] = {NO_HALFEDGE, NO_HALFEDGE, NO_HALFEDGE};
    // Corners that S already uses but that the face would touch through no edge: each gets a new fan and
    // is pinched (two sheets meet at it) until later faces join the fans.
    uint32_t pinches = 0;

    // How many faces of S the face would share an edge with.
    uint8_t shared_edges() const {
        return static_cast<uint8_t>((shared[0] != NO_HALFEDGE) + (shared[1] != NO_HALFEDGE) + (shared[2] != NO_HALFEDGE));
    }
};

// Half-edge h = 3 f + i of face f runs from corner i to corner (i + 1) % 3; next and prev are implicit,
// so a face costs its three corners, its three twins and the tetrahedron it was taken from.
//
// Invariants kept by every mutation: every edge has at most two faces and two faces on an edge traverse
// it in opposite directions. The faces around a vertex form fans (maximal runs of faces joined through
// edges at the vertex); a vertex normally has one, but while two fronts of the growing surface meet it can
// have several open fans — a pinched vertex. A closed fan is always a vertex's only fan. Each open fan is
// known by its outgoing boundary half-edge: vertex_halfedge() for the first, a short side list for the
// others. Faces are never moved: removal leaves a hole in the numbering (face_removed).
class Surface {
public:
    explicit Surface(Memory& memory);

    // Prepares per-vertex storage for vertices 0 .. vertex_count - 1. Returns false on allocation failure.
    bool reset(uint32_t vertex_count);

    // Makes room for `faces` faces in one allocation. Returns false on allocation failure.
    bool reserve_faces(size_t faces) {
        return corners_.reserve(3 * faces) && twins_.reserve(3 * faces) && tets_.reserve(faces) && flags_.reserve(faces);
    }

    // Face slots, removed ones included.
    uint32_t face_count() const { return static_cast<uint32_t>(corners_.size() / 3); }
    uint32_t live_face_count() const { return face_count() - removed_faces_; }
    // Faces added and removed so far: S is unchanged for as long as this is.
    uint32_t edit_count() const { return face_count() + removed_faces_; }
    uint32_t vertex_count() const { return static_cast<uint32_t>(vertex_halfedge_.size()); }

    static uint32_t face_of(uint32_t h) { return h / 3; }
    static uint32_t next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
    static uint32_t prev(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
    uint32_t origin(uint32_t h) const { return corners_[h]; }
    uint32_t target(uint32_t h) const { return corners_[next(h)]; }
    uint32_t twin(uint32_t h) const { return twins_[h]; }
    // True for a half-edge with no face on its other side (a removed face's half-edges are not boundary).
    bool is_boundary(uint32_t h) const { return twins_[h] == NO_HALFEDGE; }
    uint32_t corner(uint32_t f, uint32_t i) const { return corners_[3 * size_t(f) + i]; }
    uint32_t face_tet(uint32_t f) const { return tets_[f]; }
    bool face_removed(uint32_t f) const { return twins_[3 * size_t(f)] == REMOVED; }
    // The FACE_* bits of face f: 0 when added, kept when it is removed (so an undo can hand them back).
    uint8_t face_flags(uint32_t f) const { return flags_[f]; }
    void set_face_flags(uint32_t f, uint8_t flags) { flags_[f] = flags; }

    // An outgoing half-edge of v, its first fan's outgoing boundary half-edge when v is on the boundary;
    // NO_HALFEDGE when v has no face.
    uint32_t vertex_halfedge(uint32_t v) const { return vertex_halfedge_[v]; }
    bool is_used(uint32_t v) const { return vertex_halfedge_[v] != NO_HALFEDGE; }
    // True when v has faces and an open fan.
    bool is_boundary_vertex(uint32_t v) const { return is_used(v) && is_boundary(vertex_halfedge_[v]); }
    bool is_pinched(uint32_t v) const { return first_extra_[v] != NO_EXTRA_FAN; }
    uint32_t pinched_vertex_count() const { return pinched_vertices_; }
    // Vertices with at least one face now.
    uint32_t used_vertex_count() const { return used_vertices_; }
    // Some pinched vertex, or NO_HALFEDGE when there is none.
    uint32_t first_pinched_vertex() const { return extra_fans_.empty() ? NO_HALFEDGE : extra_fans_[0].vertex; }
    // The number of faces in the open fan that starts at outgoing boundary half-edge `start`.
    uint32_t fan_size(uint32_t start) const {
        uint32_t size = 0;
        walk_fan(start, [&](uint32_t) { ++size; });
        return size;
    }

    // The next outgoing half-edge of origin(h), turning one way within h's fan, or NO_HALFEDGE past the
    // fan's end. From a fan's outgoing boundary half-edge it visits the whole fan.
    uint32_t rotate(uint32_t h) const { return twins_[prev(h)]; }
    // Calls visit(h) for the outgoing half-edge that starts each fan of v (none when v is unused).
    template <class Visit>
    void for_each_fan(uint32_t v, Visit&& visit) const;

    // The one walk around a vertex: calls visit(h) for each outgoing half-edge of origin(start) in the fan
    // of `start`, turning with rotate(), until the fan ends or comes back to `start` (so from a fan's
    // start it visits the whole fan, one face per h). visit may return void, or bool: false stops the
    // walk. Returns false when a visit stopped it.
    template <class Visit>
    bool walk_fan(uint32_t start, Visit&& visit) const;
    // walk_fan over every fan of v in turn (nothing when v is unused); returns false when a visit stopped it.
    template <class Visit>
    bool walk_vertex(uint32_t v, Visit&& visit) const;

    // The one walk along a boundary loop: calls visit(h) for each boundary half-edge of the loop through
    // boundary half-edge `start`, in order (fan_exit), until the loop comes back to `start`. visit may
    // return void, or bool: false stops the walk. Returns false when a visit stopped it.
    template <class Visit>
    bool walk_loop(uint32_t start, Visit&& visit) const;

    // The half-edge from a to b, or NO_HALFEDGE. O(degree of a).
    uint32_t find_halfedge(uint32_t a, uint32_t b) const;
    // The outgoing boundary half-edge that ends the fan entered by the incoming boundary half-edge h.
    uint32_t fan_exit(uint32_t incoming_boundary) const;

    // The topological examination of face (a, b, c), counter-clockwise, without changing anything.
    FaceCheck check_face(uint32_t a, uint32_t b, uint32_t c) const;

    // Adds face (a, b, c), remembering tetrahedron `tet`, linked to the boundary half-edges it shares.
    // check_face must have found it valid. Returns the face id, or NO_FACE on allocation failure.
    uint32_t add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet);
    // The same with `check`, what check_face(a, b, c) returned with S as it is now, which saves looking
    // up the shared half-edges again.
    uint32_t add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const FaceCheck& check);

    // Removes face f; its neighbours' half-edges become boundary. May pinch a corner whose fan it split.
    // Returns false on allocation failure.
    bool remove_face(uint32_t f);

    // Leaves every pinched vertex with its largest fan alone by removing the faces of its other fans (the
    // removals can pinch further vertices, which are treated in turn). Appends the ids of the removed faces
    // to `removed`. Vertices marked in `spared` (NULL: none) stay pinched: their other faces lie outside
    // this surface (RegionGrower::grow_from's fixed vertices). Returns false on allocation failure.
    bool remove_pinches(Array<uint32_t>& removed, const uint8_t* spared = nullptr);

    // Numbers the connected components (faces joined through edges) 0, 1, ...: face_component[f] for each
    // live face, NO_FACE for removed ones. Returns the number of components, or NO_FACE on allocation failure
    // or when `between` stopped it. Before each step of LABEL_STEP_FACES faces labelled, calls
    // between(labelled, face_count()), which returns false to stop (for progress reports and cancelling).
    template <class Between>
    uint32_t label_components(Array<uint32_t>& face_component, const Between& between) const;
    uint32_t label_components(Array<uint32_t>& face_component) const {
        return label_components(face_component, [](size_t, size_t) { return true; });
    }
    // A few milliseconds of labelling.
    static constexpr uint32_t LABEL_STEP_FACES = 1u << 16;

    // Removes every component with fewer than `min_faces` faces, except the largest one. Appends the ids of
    // the removed faces to `removed`. Returns false on allocation failure or when `between` stopped the
    // labelling (see label_components).
    template <class Between>
    bool remove_small_components(uint32_t min_faces, Array<uint32_t>& removed, const Between& between);
    bool remove_small_components(uint32_t min_faces, Array<uint32_t>& removed) {
        return remove_small_components(min_faces, removed, [](size_t, size_t) { return true; });
    }

    // Checks every invariant above from scratch. On failure writes a sentence into message.
    bool validate(char* message, size_t message_capacity) const;

    // Marks removed faces in twins_[3 f]; never a half-edge id.
    static constexpr uint32_t REMOVED = UINT32_MAX - 1;

private:
    struct ExtraFan {
        uint32_t vertex;
        uint32_t halfedge;  // the fan's outgoing boundary half-edge
        uint32_t next;      // the vertex's next entry in extra_fans_, in array order, or NO_EXTRA_FAN
    };
    static constexpr uint32_t NO_EXTRA_FAN = UINT32_MAX;

    // The half-edges between x and y and between x and z, both ways (NO_HALFEDGE where there is none), in one
    // turn around x: each face at x has one half-edge out of x and the one before it into x.
    void find_edges(uint32_t x, uint32_t y, uint32_t z, uint32_t& xy, uint32_t& yx, uint32_t& xz, uint32_t& zx) const;
    bool add_fan(uint32_t v, uint32_t h);
    void replace_fan(uint32_t v, uint32_t old_h, uint32_t new_h);
    void drop_fan(uint32_t v, uint32_t h);
    // Entry `position` of extra_fans_ into or out of its vertex's chain (kept in array order).
    void link_extra_fan(uint32_t position);
    void unlink_extra_fan(uint32_t position);
    // Removes entry `position` of extra_fans_, the last entry taking its place.
    void remove_extra_fan(uint32_t position);

    Array<uint32_t> corners_;          // 3 per face
    Array<uint32_t> twins_;            // 3 per face
    Array<uint32_t> tets_;             // 1 per face
    Array<uint8_t> flags_;             // 1 per face: FACE_* bits
    Array<uint32_t> vertex_halfedge_;  // 1 per vertex
    // Second and later fans of pinched vertices, chained per vertex from first_extra_ so that a vertex's
    // entries are found without a pass over all of them (thousands while fronts meet on a large sample).
    Array<ExtraFan> extra_fans_;
    Array<uint32_t> first_extra_;      // 1 per vertex: its first entry in extra_fans_, or NO_EXTRA_FAN
    uint32_t pinched_vertices_ = 0;
    uint32_t used_vertices_ = 0;
    uint32_t removed_faces_ = 0;
};

namespace surface_detail {

// visit(h), or what it returns when it returns bool: whether a walk goes on.
template <class Visit>
inline bool keep_walking(Visit& visit, uint32_t h) {
    if constexpr (std::is_void_v<decltype(visit(h))>) {
        visit(h);
        return true;
    } else {
        return visit(h);
    }
}

} // namespace surface_detail

template <class Visit>
bool Surface::walk_fan(uint32_t start, Visit&& visit) const {
    uint32_t h = start;
    do {
        if (!surface_detail::keep_walking(visit, h)) return false;
        h = rotate(h);
    } while (h != NO_HALFEDGE && h != start);
    return true;
}

template <class Visit>
bool Surface::walk_loop(uint32_t start, Visit&& visit) const {
    uint32_t h = start;
    do {
        if (!surface_detail::keep_walking(visit, h)) return false;
        h = fan_exit(h);
    } while (h != start);
    return true;
}

template <class Visit>
bool Surface::walk_vertex(uint32_t v, Visit&& visit) const {
    bool walking = true;
    for_each_fan(v, [&](uint32_t start) { walking = walking && walk_fan(start, visit); });
    return walking;
}

template <class Between>
uint32_t Surface::label_components(Array<uint32_t>& face_component, const Between& between) const {
    Array<uint32_t> stack(corners_.memory());
    if (!face_component.resize(face_count(), NO_FACE)) return NO_FACE;
    uint32_t components = 0, labelled = 0;
    for (uint32_t seed = 0; seed < face_count(); ++seed) {
        if (face_removed(seed) || face_component[seed] != NO_FACE) continue;
        face_component[seed] = components;
        if (!stack.push_back(seed)) return NO_FACE;
        while (!stack.empty()) {
            if (labelled % LABEL_STEP_FACES == 0 && !between(labelled, face_count())) return NO_FACE;
            ++labelled;
            const uint32_t f = stack.back();
            stack.pop_back();
            for (uint32_t h = 3 * f; h < 3 * f + 3; ++h) {
                if (is_boundary(h)) continue;
                const uint32_t neighbour = face_of(twins_[h]);
                if (face_component[neighbour] != NO_FACE) continue;
                face_component[neighbour] = components;
                if (!stack.push_back(neighbour)) return NO_FACE;
            }
        }
        ++components;
    }
    return components;
}

template <class Between>
bool Surface::remove_small_components(uint32_t min_faces, Array<uint32_t>& removed, const Between& between) {
    Array<uint32_t> face_component(corners_.memory());
    Array<uint32_t> sizes(corners_.memory());
    const uint32_t components = label_components(face_component, between);
    if (components == NO_FACE || !sizes.resize(components, 0)) return false;
    for (uint32_t f = 0; f < face_count(); ++f) {
        if (face_component[f] != NO_FACE) ++sizes[face_component[f]];
    }
    uint32_t largest = 0;
    for (uint32_t k = 1; k < components; ++k) largest = sizes[k] > sizes[largest] ? k : largest;
    for (uint32_t f = 0; f < face_count(); ++f) {
        const uint32_t k = face_component[f];
        if (k == NO_FACE || k == largest || sizes[k] >= min_faces) continue;
        if (!removed.push_back(f) || !remove_face(f)) return false;
    }
    return true;
}

template <class Visit>
void Surface::for_each_fan(uint32_t v, Visit&& visit) const {
    if (vertex_halfedge_[v] == NO_HALFEDGE) return;
    visit(vertex_halfedge_[v]);
    for (uint32_t p = first_extra_[v]; p != NO_EXTRA_FAN; p = extra_fans_[p].next) visit(extra_fans_[p].halfedge);
}

} // namespace dbrg
