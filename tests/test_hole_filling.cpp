// Unit tests of hole filling's undo log (FaceJournal): any interleaving of additions and removals is
// taken back exactly.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "delaunay/tetrahedralization.h"
#include "holes/face_journal.h"

using namespace dbrg;

namespace {

constexpr uint32_t N = 6;  // the torus grid is N x N vertices

uint32_t grid_vertex(uint32_t i, uint32_t j) { return (i % N) * N + j % N; }

// A closed torus: two faces per grid square, each remembering its square as its tetrahedron.
void build_torus(Surface& surface) {
    REQUIRE(surface.reset(N * N));
    for (uint32_t i = 0; i < N; ++i) {
        for (uint32_t j = 0; j < N; ++j) {
            const uint32_t a = grid_vertex(i, j), b = grid_vertex(i + 1, j), c = grid_vertex(i + 1, j + 1),
                           d = grid_vertex(i, j + 1);
            REQUIRE(surface.add_face(a, b, c, a) != NO_FACE);
            REQUIRE(surface.add_face(a, c, d, a) != NO_FACE);
        }
    }
}

void require_valid(const Surface& surface) {
    char message[200] = "";
    const bool valid = surface.validate(message, sizeof message);
    INFO(message);
    REQUIRE(valid);
}

// The live faces, each rotated to start at its smallest corner, with its tetrahedron and for each edge
// the corners of the twin half-edge (or none): what S is, independent of face ids.
using FaceKey = std::array<uint32_t, 10>;
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

void add(Surface& surface, FaceJournal& journal, uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t f = surface.add_face(a, b, c, NO_TET);
    REQUIRE(f != NO_FACE);
    REQUIRE(journal.record_added(surface, f));
    require_valid(surface);
}

void undo(Surface& surface, FaceJournal& journal, size_t position) {
    const bool undone = journal.undo(surface, position, [&](const FaceJournal::Entry& face) {
        return surface.add_face(face.corners[0], face.corners[1], face.corners[2], face.tet) != NO_FACE;
    });
    REQUIRE(undone);
    require_valid(surface);
}

} // namespace

TEST_CASE("an enlargement that removes faces its own fill added is undone exactly") {
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
