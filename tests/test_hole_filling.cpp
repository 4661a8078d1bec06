// Unit tests of hole filling: each of its rules on a small surface made by hand (the ears start at
// concave corners, a hole that cannot be filled is enlarged, short handles are cut, the boundary's edges
// vote on whether a loop is a hole), point insertion on a grown random sphere, and the undo log
// (FaceJournal), which takes any interleaving of additions and removals back exactly.
#include <doctest/doctest.h>

#include <math.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "core/params.h"
#include "core/pi.h"
#include "points/point_conditioning.h"
#include "delaunay/tetrahedralization.h"
#include "grow/boundary_causes.h"
#include "grow/region_growing.h"
#include "holes/face_journal.h"
#include "holes/hole_filling.h"
#include "holes/point_insertion.h"
#include "delaunay_test_support.h"
#include "support/counting_allocator.h"

using namespace dbrg;

namespace {


using Triangle = std::array<uint32_t, 3>;

// A torus grid of major x minor vertices, vertex (i, j) numbered i * minor + j (indices taken modulo the
// grid), two faces per grid square, oriented outward for torus_points.
uint32_t torus_vertex(uint32_t major, uint32_t minor, uint32_t i, uint32_t j) { return (i % major) * minor + j % minor; }

std::vector<Triangle> torus_faces(uint32_t major, uint32_t minor) {
    std::vector<Triangle> faces;
    for (uint32_t i = 0; i < major; ++i) {
        for (uint32_t j = 0; j < minor; ++j) {
            const uint32_t a = torus_vertex(major, minor, i, j), b = torus_vertex(major, minor, i + 1, j),
                           c = torus_vertex(major, minor, i + 1, j + 1), d = torus_vertex(major, minor, i, j + 1);
            faces.push_back({a, b, c});
            faces.push_back({a, c, d});
        }
    }
    return faces;
}

// Vertex (i, j) at angle 2 pi i / major around the z axis and 2 pi j / minor around the tube.
std::vector<double> torus_points(uint32_t major, uint32_t minor, double radius, double tube_radius) {
    std::vector<double> xyz;
    for (uint32_t i = 0; i < major; ++i) {
        for (uint32_t j = 0; j < minor; ++j) {
            const double theta = 2 * PI * i / major, phi = 2 * PI * j / minor;
            const double ring = radius + tube_radius * cos(phi);
            xyz.insert(xyz.end(), {ring * cos(theta), ring * sin(theta), tube_radius * sin(phi)});
        }
    }
    return xyz;
}

constexpr uint32_t N = 6;  // the journal's torus grid is N x N vertices

// A closed torus without points: two faces per grid square, each remembering its first corner as its
// tetrahedron.
void build_torus(Surface& surface) {
    REQUIRE(surface.reset(N * N));
    for (const Triangle& t : torus_faces(N, N)) REQUIRE(surface.add_face(t[0], t[1], t[2], t[0]) != NO_FACE);
}

uint32_t grid_vertex(uint32_t i, uint32_t j) { return torus_vertex(N, N, i, j); }

void require_valid(const Surface& surface) {
    char message[200] = "";
    const bool valid = surface.validate(message, sizeof message);
    INFO(message);
    REQUIRE(valid);
}

// The live faces, each rotated to start at its smallest corner, with its tetrahedron, its flags and for
// each edge the corners of the twin half-edge (or none): what S is, independent of face ids.
using FaceKey = std::array<uint32_t, 11>;
std::vector<FaceKey> snapshot(const Surface& surface) {
    std::vector<FaceKey> faces;
    for (uint32_t f = 0; f < surface.face_count(); ++f) {
        if (surface.face_removed(f)) continue;
        uint32_t first = 0;
        for (uint32_t i = 1; i < 3; ++i) first = surface.corner(f, i) < surface.corner(f, first) ? i : first;
        FaceKey key{};
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t h = 3 * f + (first + k) % 3;
            key[k] = surface.origin(h);
            key[3 + 2 * k] = surface.is_boundary(h) ? NO_HALFEDGE : surface.origin(surface.twin(h));
            key[4 + 2 * k] = surface.is_boundary(h) ? NO_HALFEDGE : surface.target(surface.twin(h));
        }
        key[9] = surface.face_tet(f);
        key[10] = surface.face_flags(f);
        faces.push_back(key);
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

uint32_t face_with(const Surface& surface, uint32_t a, uint32_t b) {
    const uint32_t h = surface.find_halfedge(a, b);
    REQUIRE(h != NO_HALFEDGE);
    return Surface::face_of(h);
}

void remove(Surface& surface, FaceJournal& journal, uint32_t f) {
    const uint8_t causes[3] = {0, 0, 0};
    REQUIRE(journal.record_removed(surface, f, causes));
    REQUIRE(surface.remove_face(f));
    require_valid(surface);
}

// Adds an ear, flagged as a fill's ears are.
void add(Surface& surface, FaceJournal& journal, uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t f = surface.add_face(a, b, c, NO_TET);
    REQUIRE(f != NO_FACE);
    surface.set_face_flags(f, FACE_FILLED);
    REQUIRE(journal.record_added(surface, f));
    require_valid(surface);
}

void undo(Surface& surface, FaceJournal& journal, size_t position) {
    const bool undone = journal.undo(surface, position, [&](const FaceJournal::Entry& face) {
        const uint32_t f = surface.add_face(face.corners[0], face.corners[1], face.corners[2], face.tet);
        if (f != NO_FACE) surface.set_face_flags(f, face.flags);
        return f != NO_FACE;
    });
    REQUIRE(undone);
    require_valid(surface);
}

} // namespace

TEST_CASE("an enlargement that removes faces its own fill added is undone exactly, flags included") {
    Memory memory(nullptr);
    Surface surface(memory);
    build_torus(surface);
    require_valid(surface);
    const std::vector<FaceKey> original = snapshot(surface);
    FaceJournal journal(memory);

    // A cut: the six faces around vertex (2, 2) open a hexagonal hole with corners p[0..5].
    const uint32_t centre = grid_vertex(2, 2);
    const uint32_t p[6] = {grid_vertex(3, 2), grid_vertex(3, 3), grid_vertex(2, 3),
                           grid_vertex(1, 2), grid_vertex(1, 1), grid_vertex(2, 1)};
    for (uint32_t i = 0; i < 6; ++i) remove(surface, journal, face_with(surface, centre, p[i]));
    CHECK(!surface.is_used(centre));

    // A fill adds two ears (as the fill of one loop of a cut does).
    add(surface, journal, p[0], p[1], p[2]);
    add(surface, journal, p[0], p[2], p[3]);
    const size_t before_enlargement = journal.size();
    const std::vector<FaceKey> with_ears = snapshot(surface);

    // An enlargement (of the cut's next loop, say) removes the faces along its hole: the two ears just
    // added, and a grown face.
    remove(surface, journal, face_with(surface, p[0], p[2]));
    remove(surface, journal, face_with(surface, p[0], p[1]));
    remove(surface, journal, face_with(surface, p[4], p[3]));
    const size_t before_refill = journal.size();

    // The larger hole's fill adds an ear, fails and is undone back to where it started, then adds two
    // other ears.
    add(surface, journal, p[0], p[1], p[2]);
    undo(surface, journal, before_refill);
    add(surface, journal, p[1], p[2], p[3]);
    add(surface, journal, p[0], p[1], p[3]);
    CHECK(journal.added_count() == 4);
    CHECK(journal.removed_count() == 9);

    // The enlarged attempt fails as a whole: undoing it brings the two ears back. Then the whole change is
    // refused: undoing everything brings the torus back.
    undo(surface, journal, before_enlargement);
    CHECK(snapshot(surface) == with_ears);
    CHECK(journal.added_count() == 2);
    CHECK(journal.removed_count() == 6);
    undo(surface, journal, 0);
    CHECK(journal.size() == 0);
    CHECK(surface.live_face_count() == 2 * N * N);
    CHECK(snapshot(surface) == original);
}

namespace {

// A surface made by hand over hand-placed points, ready for hole filling: the points are conditioned and
// tetrahedralized as the pipeline does (hole filling reads them through the tetrahedralization), and the
// faces, given in the points' own numbering, have no tetrahedron. Every boundary edge counts as one where
// growing found only invalid candidates until mark_open says otherwise.
struct HandMade {
    HandMade(const std::vector<double>& xyz, const std::vector<Triangle>& faces, uint32_t max_hole_edges = 64,
             const dbrg_allocator* allocator = nullptr)
        : context(params_with(max_hole_edges, allocator)),
          points(context.memory),
          delaunay(context.memory),
          surface(context.memory),
          causes(context.memory) {
        REQUIRE(condition_points(xyz.data(), xyz.size() / 3, context, points) == DBRG_OK);
        REQUIRE(points.size() == xyz.size() / 3);
        REQUIRE(delaunay.build(points.coordinates.data(), points.size(), context) == DBRG_OK);
        vertex.resize(points.size());
        for (uint32_t v = 0; v < points.size(); ++v) vertex[points.input_index[v]] = v;
        REQUIRE(surface.reset(points.size()));
        for (const Triangle& t : faces) REQUIRE(surface.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]], NO_TET) != NO_FACE);
        require_valid(surface);
    }
    static dbrg_params params_with(uint32_t max_hole_edges, const dbrg_allocator* allocator) {
        dbrg_params params;
        fill_default_params(params);
        params.max_hole_edges = max_hole_edges;
        params.allocator = allocator;
        return params;
    }

    // The half-edge from point a to point b.
    uint32_t halfedge(uint32_t a, uint32_t b) const { return surface.find_halfedge(vertex[a], vertex[b]); }
    bool has_face(uint32_t a, uint32_t b, uint32_t c) const {
        const uint32_t h = halfedge(a, b);
        return h != NO_HALFEDGE && surface.target(Surface::next(h)) == vertex[c];
    }
    // Records that growing left boundary half-edge h open because the open-surface test refused its candidate.
    void mark_open(uint32_t h) {
        REQUIRE(surface.is_boundary(h));
        REQUIRE(causes.cover_faces(surface.face_count()));
        causes.mark_open(h);
    }
    uint32_t boundary_halfedges() const {
        uint32_t count = 0;
        for (uint32_t h = 0; h < 3 * surface.face_count(); ++h) count += surface.is_boundary(h) ? 1 : 0;
        return count;
    }
    // The genus of S, a closed connected surface: V - E + F = 2 - 2 g.
    int genus() {
        REQUIRE(boundary_halfedges() == 0);
        Array<uint32_t> components(context.memory);
        REQUIRE(surface.label_components(components) == 1);
        const int64_t v = surface.used_vertex_count(), f = surface.live_face_count(), e = 3 * f / 2;
        return int((2 - (v - e + f)) / 2);
    }

    // Hole filling's own steps in the pipeline's order; the grower's Delaunay pass has no tetrahedra to
    // start from on these faces.
    void fill_holes() {
        HoleFiller filler(delaunay.points(), surface, causes, context);
        const ProgressSpan progress(context, DBRG_STAGE_FILL_HOLES);
        bool found = false;
        REQUIRE(filler.find_holes(found) == DBRG_OK);
        if (found) REQUIRE(filler.fill_with_ears(progress, progress) == DBRG_OK);
        REQUIRE(filler.remove_small_handles(progress) == DBRG_OK);
        require_valid(surface);
    }

    Context context;
    ConditionedPoints points;
    Tetrahedralization delaunay;
    Surface surface;
    BoundaryCauses causes;
    std::vector<uint32_t> vertex;  // of each point given
};

} // namespace

TEST_CASE("ears start at concave corners: the tip of a cone waits though its ear is the smallest valid one") {
    // A steep cone (tip p, ring q0 .. q7) with a wedge cut out between q7 and q0, a strip of faces around
    // the ring and a corner c outside the ring, level with the tip, so that the hole is the loop p, q0, c,
    // q7. Across the cone's tip, the faces average to a normal that points away from the wedge: p's ear
    // (p, q7, q0) faces against it, so p is no concave corner (paper §5), though that ear is valid and of
    // all valid ears the one with the smallest circumradius. The concave corners q0 and q7 have valid ears
    // too, so the hole is closed from them, along the diagonal p-c rather than q0-q7.
    const uint32_t ring = 8, p = 0, c = 1;  // q_k is 2 + k, and the strip's outer corner of ring corner x is x + ring + 1
    const auto q = [](uint32_t k) { return 2 + k; };
    const auto outer = [&](uint32_t x) { return x + ring + 1; };
    const double alpha = PI / 4;
    std::vector<double> xyz = {0, 0, 2, 1.6, 0, 2};
    for (uint32_t k = 0; k < ring; ++k) {
        const double phi = alpha + (2 * PI - 2 * alpha) * k / (ring - 1);
        xyz.insert(xyz.end(), {cos(phi), sin(phi), 0});
    }
    // The ring goes round c, q0, ..., q7 (counter-clockwise from above); the strip's outer corners lie
    // further out and lower.
    std::vector<uint32_t> around = {c};
    for (uint32_t k = 0; k < ring; ++k) around.push_back(q(k));
    for (uint32_t x : around) {
        const double* point = &xyz[3 * x];
        const double angle = atan2(point[1], point[0]), z = point[2] - 0.6;
        xyz.insert(xyz.end(), {1.6 * cos(angle), 1.6 * sin(angle), z});
    }
    std::vector<Triangle> faces;
    for (uint32_t k = 0; k + 1 < ring; ++k) faces.push_back({p, q(k), q(k + 1)});
    for (size_t i = 0; i < around.size(); ++i) {
        const uint32_t x = around[i], y = around[(i + 1) % around.size()];
        faces.push_back({x, outer(x), outer(y)});
        faces.push_back({x, outer(y), y});
    }
    HandMade made(xyz, faces, 8);
    // The outer rim is the surface's border; its 9 edges are more than max_hole_edges, so it stays open.
    const uint32_t rim = made.halfedge(outer(c), outer(q(0)));
    REQUIRE(rim != NO_HALFEDGE);
    made.surface.walk_loop(rim, [&](uint32_t h) { made.mark_open(h); });
    REQUIRE(made.surface.is_boundary(made.halfedge(p, q(0))));

    made.fill_holes();
    CHECK(made.context.stats.holes_filled == 1);
    CHECK(made.boundary_halfedges() == around.size());  // the border
    CHECK_FALSE(made.has_face(p, q(ring - 1), q(0)));
    CHECK(made.has_face(q(0), p, c));
    CHECK(made.has_face(p, q(ring - 1), c));
}

namespace {

// The surface of the cube [0, 4]^3, a grid of squares of side 2 split along a diagonal, with a crack: in
// one square, the face on one side of the diagonal a-b is split at the diagonal's midpoint m, so a hole
// a, m, b has three corners on a line. With `open_face`, the face (m, b, d) of the split is missing too.
struct CrackedCube {
    explicit CrackedCube(bool open_face);
    uint32_t a, b, m, d;  // points
    std::vector<double> xyz;
    std::vector<Triangle> faces;
};

CrackedCube::CrackedCube(bool open_face) {
    std::map<std::array<int, 3>, uint32_t> index;
    const auto point = [&](std::array<int, 3> at) {
        const auto found = index.find(at);
        if (found != index.end()) return found->second;
        xyz.insert(xyz.end(), {double(at[0]), double(at[1]), double(at[2])});
        return index[at] = uint32_t(index.size());
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (int side : {0, 4}) {
            // u x v points out of the cube.
            const int u = side ? (axis + 1) % 3 : (axis + 2) % 3, v = side ? (axis + 2) % 3 : (axis + 1) % 3;
            const auto corner = [&](int i, int j) {
                std::array<int, 3> at{};
                at[axis] = side;
                at[u] = 2 * i;
                at[v] = 2 * j;
                return point(at);
            };
            for (int i = 0; i < 2; ++i) {
                for (int j = 0; j < 2; ++j) {
                    faces.push_back({corner(i, j), corner(i + 1, j), corner(i + 1, j + 1)});
                    faces.push_back({corner(i, j), corner(i + 1, j + 1), corner(i, j + 1)});
                }
            }
        }
    }
    // The square from a = (0, 0, 0) to b = (2, 2, 0) on the bottom, whose second face is (a, b, d).
    a = point({0, 0, 0});
    b = point({2, 2, 0});
    m = point({1, 1, 0});
    const auto second = std::find_if(faces.begin(), faces.end(), [&](const Triangle& t) { return t[0] == a && t[1] == b; });
    REQUIRE(second != faces.end());
    d = (*second)[2];
    faces.erase(second);
    faces.push_back({a, m, d});
    if (!open_face) faces.push_back({m, b, d});
}

} // namespace

TEST_CASE("a hole that cannot be filled over its own corners is enlarged by its rim's faces and filled") {
    // The crack a, m, b has one ear, of no area: no ear over its own corners is valid (paper §5). Removing
    // the three faces around it leaves the square, which two ears close.
    CrackedCube crack(false);
    HandMade made(crack.xyz, crack.faces);
    REQUIRE(made.boundary_halfedges() == 3);
    made.fill_holes();
    CHECK(made.context.stats.holes_filled == 1);
    CHECK(made.context.stats.hole_triangles_removed == 3);
    CHECK(made.context.stats.hole_triangles_added == 2);
    CHECK(made.boundary_halfedges() == 0);
    CHECK_FALSE(made.surface.is_used(made.vertex[crack.m]));
    CHECK(made.genus() == 0);
}

TEST_CASE("the ears of a failed attempt are taken back before the hole is enlarged") {
    // The hole b, a, m, d takes the ear (d, m, b), and then only (b, a, m), of no area, is left: the
    // attempt fails, its ear is taken back, and the larger hole is filled instead, without m. The rim is
    // the three faces on the hole's four edges ((a, m, d) has two), and the larger hole has five corners.
    CrackedCube crack(true);
    HandMade made(crack.xyz, crack.faces);
    REQUIRE(made.boundary_halfedges() == 4);
    made.fill_holes();
    CHECK(made.context.stats.holes_filled == 1);
    CHECK(made.context.stats.hole_triangles_removed == 3);
    CHECK(made.context.stats.hole_triangles_added == 3);
    CHECK(made.boundary_halfedges() == 0);
    CHECK_FALSE(made.has_face(crack.d, crack.m, crack.b));
    CHECK_FALSE(made.surface.is_used(made.vertex[crack.m]));
    CHECK(made.genus() == 0);
}

TEST_CASE("a handle whose short cycles are short in space is cut and both sides are filled; a tube stays") {
    struct Tube {
        uint32_t major, minor;
        double tube_radius;
        bool noise;
    };
    // A tube with 3 edges around, thin against the edges along it, is the bridge growing builds across a
    // gap narrower than the spacing. A tube with 4 edges around, as wide as long, is a coarse but real
    // handle: its cycles are short in edges but not in space. With 8 edges around, none is short.
    for (const Tube& tube : {Tube{12, 3, 0.1, true}, Tube{24, 4, 0.35, false}, Tube{12, 8, 0.4, false}}) {
        CAPTURE(tube.minor);
        HandMade made(torus_points(tube.major, tube.minor, 1.0, tube.tube_radius), torus_faces(tube.major, tube.minor));
        REQUIRE(made.genus() == 1);
        made.fill_holes();
        CHECK(made.context.stats.handles_removed == (tube.noise ? 1 : 0));
        CHECK(made.genus() == (tube.noise ? 0 : 1));
    }
}

TEST_CASE("a small handle on a surface with a border is cut all the same, and the border stays") {
    // The thin tube above with one face missing: a border of 3 edges, left open (no hole filling), so the
    // component is not closed; the handle is found on the surface with its border capped.
    HandMade made(torus_points(12, 3, 1.0, 0.1), torus_faces(12, 3));
    REQUIRE(made.surface.remove_face(0));
    REQUIRE(made.boundary_halfedges() == 3);
    HoleFiller filler(made.delaunay.points(), made.surface, made.causes, made.context);
    REQUIRE(filler.remove_small_handles(ProgressSpan(made.context, DBRG_STAGE_FILL_HOLES)) == DBRG_OK);
    require_valid(made.surface);
    CHECK(made.context.stats.handles_removed == 1);
    CHECK(made.boundary_halfedges() == 3);
    Array<uint32_t> components(made.context.memory);
    CHECK(made.surface.label_components(components) == 1);
    // V - E + F of a disk-like surface with one border: 1.
    const int64_t v = made.surface.used_vertex_count(), f = made.surface.live_face_count(), e = (3 * f + 3) / 2;
    CHECK(v - e + f == 1);
}

namespace {

// A share of the stage's progress, with its start and without its end.
struct Window {
    double from, to;
    bool holds(double fraction) const { return fraction >= from && fraction < to; }
};

// Counts the reports inside a window, and with `cancel` cancels at the first one.
struct Reports {
    Window window;
    bool cancel;
    uint32_t inside = 0;
    double last = -1;
    static int record(void* user, dbrg_stage, double fraction) {
        Reports& self = *static_cast<Reports*>(user);
        self.last = fraction;
        self.inside += self.window.holds(fraction) ? 1 : 0;
        return self.cancel && self.window.holds(fraction) ? 1 : 0;
    }
};

} // namespace

TEST_CASE("cutting a small handle reports inside the cuts' share, and a cancel there leaves nothing held") {
    // The thin tube above, with the whole stage's progress given to removing handles: its first round
    // takes the first half, and the cuts the end of that. Each cut measures the surface again, reporting
    // as it starts (the passes before report below the cuts' share).
    const Window cuts{0.5 * HANDLES_PROGRESS_CUTS, 0.5};
    for (const bool cancel : {false, true}) {
        CAPTURE(cancel);
        test::CountingAllocator allocator;
        Reports reports{cuts, cancel};
        dbrg_status status;
        {
            HandMade made(torus_points(12, 3, 1.0, 0.1), torus_faces(12, 3), 64, allocator.get());
            made.context.progress = Progress(Reports::record, &reports);
            HoleFiller filler(made.delaunay.points(), made.surface, made.causes, made.context);
            status = filler.remove_small_handles(ProgressSpan(made.context, DBRG_STAGE_FILL_HOLES));
            CHECK(made.context.stats.handles_removed == (cancel ? 0 : 1));
        }
        CHECK(allocator.live_blocks() == 0);
        CHECK(allocator.contract_violations() == 0);
        if (!cancel) {
            CHECK(status == DBRG_OK);
            CHECK(reports.inside >= 1);
        } else {
            CHECK(status == DBRG_ERR_CANCELLED);
            CHECK(reports.inside == 1);
            CHECK(cuts.holds(reports.last));  // nothing reported after the cancel
        }
    }
}

namespace {

// A torus of 48 x 24 vertices with the faces around a block of `side` x `side` vertices removed: a hole
// of 4 side + 2 edges (the quads' diagonals cut two corners), about side + 1 vertex spacings across.
struct HoledTorus : HandMade {
    HoledTorus(uint32_t side, double boundary_factor)
        : HandMade(torus_points(48, 24, 1.0, 0.4), torus_faces(48, 24), 256) {
        context.params.boundary_factor = boundary_factor;
        for (uint32_t i = 0; i < side; ++i) {
            for (uint32_t j = 0; j < side; ++j) {
                std::vector<uint32_t> fan;
                surface.walk_vertex(vertex[torus_vertex(48, 24, 10 + i, 8 + j)], [&](uint32_t h) { fan.push_back(Surface::face_of(h)); });
                for (uint32_t f : fan) REQUIRE(surface.remove_face(f));
            }
        }
        for (uint32_t h = 0; h < 3 * surface.face_count(); ++h) {
            if (surface.is_boundary(h)) loop.push_back(h);
        }
        REQUIRE(loop.size() == 4 * side + 2);
    }
    std::vector<uint32_t> loop;  // the hole's boundary half-edges
};

} // namespace

TEST_CASE("a boundary loop is a hole unless most of its edges saw growing refuse a candidate as too large") {
    // 22 edges round an opening wide next to the faces' circumradius at the default boundary_factor 3, so
    // the edges' vote decides.
    for (uint32_t open_edges = 0; open_edges <= 22; open_edges += 2) {
        CAPTURE(open_edges);
        HoledTorus torus(5, 3);
        for (uint32_t i = 0; i < open_edges; ++i) torus.mark_open(torus.loop[i]);
        torus.fill_holes();
        const bool hole = 2 * open_edges <= 22;  // a minority, or half, of the edges call it a border
        CHECK(torus.context.stats.holes_found == (hole ? 1 : 0));
        CHECK(torus.boundary_halfedges() == (hole ? 0 : 22));
    }
}

TEST_CASE("a loop every edge of which saw a candidate refused as too large is a hole when it is short or narrow") {
    SUBCASE("short: 14 edges") {
        HoledTorus torus(3, 3);
        for (uint32_t h : torus.loop) torus.mark_open(h);
        torus.fill_holes();
        CHECK(torus.context.stats.holes_filled == 1);
        CHECK(torus.genus() == 1);
    }
    SUBCASE("narrow next to the faces around it, with a larger boundary factor") {
        HoledTorus torus(5, 6);
        for (uint32_t h : torus.loop) torus.mark_open(h);
        torus.fill_holes();
        CHECK(torus.context.stats.holes_filled == 1);
        CHECK(torus.genus() == 1);
    }
    SUBCASE("wide: the same opening at the default factor is a border") {
        HoledTorus torus(5, 3);
        for (uint32_t h : torus.loop) torus.mark_open(h);
        torus.fill_holes();
        CHECK(torus.context.stats.holes_found == 0);
        CHECK(torus.boundary_halfedges() == 22);
    }
}

namespace {

// S as growing leaves it on 3000 uniformly random points on the unit sphere: random points cluster, and a
// point closer to another than the spacing is often left under a face of a flat Delaunay tetrahedron.
struct GrownRandomSphere : HandMade {
    GrownRandomSphere() : HandMade(dbrg_test::random_sphere(3000, 11), {}) {
        RegionGrower grower(delaunay, surface, context);
        REQUIRE(grower.grow() == DBRG_OK);
        require_valid(surface);
    }
    // V - E + F of S; with the boundary, the components and the faces' flags, what must not change but for
    // the fans' two extra faces each.
    int64_t euler_characteristic() const {
        const int64_t f = surface.live_face_count(), edges = (3 * f + boundary_halfedges()) / 2;
        return int64_t(surface.used_vertex_count()) - edges + f;
    }
    uint32_t components() {
        Array<uint32_t> labels(context.memory);
        return surface.label_components(labels);
    }
    dbrg_status insert_points(const uint8_t* fixed = nullptr) {
        PointInsertion insertion(delaunay, surface, context);
        insertion.keep_fixed(fixed);
        const dbrg_status status = insertion.insert_left_out(ProgressSpan(context, DBRG_STAGE_FILL_HOLES));
        require_valid(surface);
        return status;
    }
};

} // namespace

TEST_CASE("points growing left under S are put in with fans of Delaunay triangles; the topology stays") {
    GrownRandomSphere sphere;
    const uint32_t used_before = sphere.surface.used_vertex_count(), faces_before = sphere.surface.live_face_count();
    const uint32_t boundary_before = sphere.boundary_halfedges();
    const int64_t euler_before = sphere.euler_characteristic();
    const uint32_t components_before = sphere.components();
    REQUIRE(used_before < sphere.points.size());
    MESSAGE("grown: " << sphere.points.size() - used_before << " of " << sphere.points.size() << " points left out");

    REQUIRE(sphere.insert_points() == DBRG_OK);
    const uint32_t inserted = sphere.context.stats.points_inserted;
    CHECK(inserted > 0);
    CHECK(sphere.surface.used_vertex_count() == used_before + inserted);
    // Each fan has two faces more than the disk it replaces (all the disk's vertices are on its rim).
    CHECK(sphere.surface.live_face_count() == faces_before + 2 * inserted);
    CHECK(sphere.boundary_halfedges() == boundary_before);
    CHECK(sphere.euler_characteristic() == euler_before);
    CHECK(sphere.components() == components_before);
    // Every face is still one of its tetrahedron's: a fan face spans the tetrahedron of its patch face and q.
    for (uint32_t f = 0; f < sphere.surface.face_count(); ++f) {
        if (sphere.surface.face_removed(f)) continue;
        const uint32_t t = sphere.surface.face_tet(f);
        REQUIRE(t != NO_TET);
        uint32_t shared = 0;
        for (uint32_t i = 0; i < 3; ++i) shared += sphere.delaunay.tet_local_index(t, sphere.surface.corner(f, i)) < 4 ? 1 : 0;
        CHECK(shared == 3);
    }
}

TEST_CASE("no face with a fixed corner is replaced; the points elsewhere are put in") {
    GrownRandomSphere sphere;
    // The vertices S uses on the upper half are fixed.
    std::vector<uint8_t> fixed(sphere.points.size(), 0);
    double middle = 0;
    for (uint32_t v = 0; v < fixed.size(); ++v) middle += sphere.delaunay.point(v)[2] / fixed.size();
    for (uint32_t v = 0; v < fixed.size(); ++v) {
        fixed[v] = sphere.surface.is_used(v) && sphere.delaunay.point(v)[2] > middle ? 1 : 0;
    }
    const auto faces_with_a_fixed_corner = [&] {
        std::vector<FaceKey> kept;
        for (const FaceKey& key : snapshot(sphere.surface)) {
            if (fixed[key[0]] || fixed[key[1]] || fixed[key[2]]) kept.push_back(key);
        }
        return kept;
    };
    const std::vector<FaceKey> before = faces_with_a_fixed_corner();
    REQUIRE(sphere.insert_points(fixed.data()) == DBRG_OK);
    CHECK(sphere.context.stats.points_inserted > 0);
    CHECK(faces_with_a_fixed_corner() == before);
}
