// Unit tests of the half-edge surface S: linking, fans, boundary bookkeeping, validation, truncation.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/counting_allocator.h"
#include "surface/surface.h"

using namespace dbrg;

namespace {

void require_valid(const Surface& surface) {
    char message[200] = "";
    const bool valid = surface.validate(message, sizeof message);
    INFO(message);
    REQUIRE(valid);
}

} // namespace

TEST_CASE("an empty surface has no faces and unused vertices") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(4));
    CHECK(surface.face_count() == 0);
    CHECK_FALSE(surface.is_used(0));
    CHECK(surface.find_halfedge(0, 1) == NO_HALFEDGE);
    require_valid(surface);
}

TEST_CASE("faces are linked through their shared edges as they are added") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(6));
    const uint32_t f0 = surface.add_face(0, 1, 2, 7);
    require_valid(surface);
    CHECK(surface.face_tet(f0) == 7);
    for (uint32_t h = 0; h < 3; ++h) CHECK(surface.is_boundary(h));
    CHECK(surface.is_boundary_vertex(0));

    // (2, 1, 3) shares edge 1-2 in the opposite direction.
    const uint32_t f1 = surface.add_face(2, 1, 3, 8);
    require_valid(surface);
    const uint32_t h12 = surface.find_halfedge(1, 2);
    const uint32_t h21 = surface.find_halfedge(2, 1);
    REQUIRE(h12 != NO_HALFEDGE);
    REQUIRE(h21 != NO_HALFEDGE);
    CHECK(Surface::face_of(h12) == f0);
    CHECK(Surface::face_of(h21) == f1);
    CHECK(surface.twin(h12) == h21);
    CHECK(surface.find_halfedge(0, 3) == NO_HALFEDGE);
    // The vertex half-edge of a boundary vertex is its outgoing boundary half-edge.
    for (uint32_t v = 0; v < 4; ++v) {
        CHECK(surface.is_boundary(surface.vertex_halfedge(v)));
        CHECK(surface.origin(surface.vertex_halfedge(v)) == v);
    }
}

TEST_CASE("a closed fan makes its centre an interior vertex") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(6));
    // Centre 0 with the ring 1..5, each face attached to the previous one.
    for (uint32_t i = 1; i <= 4; ++i) {
        surface.add_face(0, i, i + 1, 0);
        require_valid(surface);
        CHECK(surface.is_boundary_vertex(0));
    }
    surface.add_face(0, 5, 1, 0);
    require_valid(surface);
    CHECK_FALSE(surface.is_boundary_vertex(0));
    CHECK(surface.is_boundary_vertex(1));
    // The walk around the centre visits its five outgoing half-edges once each and comes back.
    std::vector<uint32_t> targets;
    CHECK(surface.walk_fan(surface.vertex_halfedge(0), [&](uint32_t h) {
        CHECK(surface.origin(h) == 0);
        targets.push_back(surface.target(h));
        return targets.size() < 10;
    }));
    std::sort(targets.begin(), targets.end());
    CHECK(targets == std::vector<uint32_t>{1, 2, 3, 4, 5});
    // A visit that returns false stops it there.
    uint32_t visits = 0;
    CHECK_FALSE(surface.walk_vertex(0, [&](uint32_t) { return ++visits < 2; }));
    CHECK(visits == 2);
}

TEST_CASE("two fans at one vertex pinch it until a face joins them") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(5));
    surface.add_face(0, 1, 2, 0);
    CHECK(surface.check_face(0, 3, 4).pinches == 1);
    surface.add_face(0, 3, 4, 0);
    require_valid(surface);
    CHECK(surface.is_pinched(0));
    CHECK(surface.pinched_vertex_count() == 1);
    CHECK(surface.first_pinched_vertex() == 0);
    uint32_t fans = 0;
    surface.for_each_fan(0, [&](uint32_t start) {
        ++fans;
        CHECK(surface.fan_size(start) == 1);
    });
    CHECK(fans == 2);
    // The walk around a pinched vertex goes through every fan.
    std::vector<uint32_t> targets;
    CHECK(surface.walk_vertex(0, [&](uint32_t h) { targets.push_back(surface.target(h)); }));
    std::sort(targets.begin(), targets.end());
    CHECK(targets == std::vector<uint32_t>{1, 3});
    // Both edges of edge-face lookups work in either fan.
    CHECK(surface.find_halfedge(0, 1) != NO_HALFEDGE);
    CHECK(surface.find_halfedge(0, 3) != NO_HALFEDGE);
    // (0, 2, 3) joins the fans through edges 0-2 and 3-0.
    const FaceCheck join = surface.check_face(0, 2, 3);
    CHECK(join.verdict == FaceCheck::valid);
    CHECK(join.pinches == 0);
    surface.add_face(0, 2, 3, 0);
    require_valid(surface);
    CHECK_FALSE(surface.is_pinched(0));
    CHECK(surface.pinched_vertex_count() == 0);
}

TEST_CASE("check_face names what a face would break") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(8));
    // A closed fan around 0 (ring 1..4) and a separate face (5, 6, 7).
    for (uint32_t i = 1; i <= 3; ++i) surface.add_face(0, i, i + 1, 0);
    surface.add_face(0, 4, 1, 0);
    surface.add_face(5, 6, 7, 0);
    require_valid(surface);
    CHECK(surface.check_face(1, 2, 5).verdict == FaceCheck::orientation);       // 1->2 is used already
    CHECK(surface.check_face(2, 1, 5).verdict == FaceCheck::valid);             // across the boundary edge 1-2
    CHECK(surface.check_face(2, 1, 5).pinches == 1);                            // and touching 5 at a vertex
    CHECK(surface.check_face(0, 5, 6).verdict == FaceCheck::orientation);       // 5->6 again
    CHECK(surface.check_face(0, 6, 5).verdict == FaceCheck::bowtie);            // 0 is interior
    CHECK(surface.check_face(1, 0, 5).verdict == FaceCheck::edge_nonmanifold);  // 0-1 has two faces
}

TEST_CASE("removing faces opens closed fans and splits open ones") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(6));
    for (uint32_t i = 1; i <= 4; ++i) surface.add_face(0, i, i + 1, 0);
    surface.add_face(0, 5, 1, 0);
    CHECK_FALSE(surface.is_boundary_vertex(0));
    REQUIRE(surface.remove_face(2));  // (0, 3, 4)
    require_valid(surface);
    CHECK(surface.face_removed(2));
    CHECK(surface.live_face_count() == 4);
    CHECK(surface.is_boundary_vertex(0));
    CHECK_FALSE(surface.is_pinched(0));
    REQUIRE(surface.remove_face(0));  // (0, 1, 2) joined (0, 2, 3) to the rest: now they are apart at 0
    require_valid(surface);
    CHECK(surface.is_pinched(0));
    REQUIRE(surface.remove_face(4));  // (0, 5, 1): (0, 2, 3) and (0, 4, 5) are still apart
    require_valid(surface);
    CHECK(surface.is_pinched(0));
    REQUIRE(surface.remove_face(1));
    REQUIRE(surface.remove_face(3));
    require_valid(surface);
    CHECK_FALSE(surface.is_used(0));
    CHECK(surface.pinched_vertex_count() == 0);
}

TEST_CASE("the edit count changes with every face added or removed, and with nothing else") {
    // Growing reuses a candidate's examination while the count is what it was then.
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(6));
    std::vector<uint32_t> counts = {surface.edit_count()};
    for (uint32_t i = 1; i <= 4; ++i) {
        surface.add_face(0, i, i + 1, 0);
        counts.push_back(surface.edit_count());
    }
    const uint32_t before_queries = surface.edit_count();
    surface.check_face(0, 5, 1);
    surface.find_halfedge(0, 1);
    CHECK(surface.edit_count() == before_queries);
    for (uint32_t f : {1u, 2u}) {
        REQUIRE(surface.remove_face(f));
        counts.push_back(surface.edit_count());
    }
    surface.add_face(0, 2, 3, 0);
    counts.push_back(surface.edit_count());
    std::vector<uint32_t> sorted = counts;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::unique(sorted.begin(), sorted.end()) == sorted.end());
}

TEST_CASE("validate reports an edge used twice in the same direction") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(4));
    surface.add_face(0, 1, 2, 0);
    surface.add_face(0, 1, 3, 0);
    char message[200];
    CHECK_FALSE(surface.validate(message, sizeof message));
}

TEST_CASE("a tetrahedron's four faces close up") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(4));
    surface.add_face(0, 2, 1, 0);
    surface.add_face(0, 1, 3, 0);
    surface.add_face(1, 2, 3, 0);
    surface.add_face(2, 0, 3, 0);
    require_valid(surface);
    for (uint32_t h = 0; h < 12; ++h) CHECK_FALSE(surface.is_boundary(h));
}

TEST_CASE("remove_small_components keeps the largest component and the large enough ones") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(12));
    // A closed tetrahedron (4 faces), a strip of 2 faces, and a single face, all apart.
    surface.add_face(0, 2, 1, 0);
    surface.add_face(0, 1, 3, 0);
    surface.add_face(1, 2, 3, 0);
    surface.add_face(2, 0, 3, 0);
    surface.add_face(4, 5, 6, 0);
    surface.add_face(6, 5, 7, 0);
    surface.add_face(8, 9, 10, 0);
    Array<uint32_t> removed(memory);
    REQUIRE(surface.remove_small_components(2, removed));
    CHECK(removed.size() == 1);  // the single face; the strip has 2, the tetrahedron is the largest
    CHECK(surface.face_removed(6));
    CHECK_FALSE(surface.is_used(8));
    CHECK(surface.is_used(5));
    require_valid(surface);
    REQUIRE(surface.remove_small_components(5, removed));
    CHECK(removed.size() == 3);
    CHECK(surface.live_face_count() == 4);
    require_valid(surface);
}

TEST_CASE("allocation failure is reported, not hidden") {
    dbrg_allocator refusing{[](void*, size_t) -> void* { return nullptr; },
                            [](void*, void*, size_t, size_t) -> void* { return nullptr; },
                            [](void*, void*, size_t) {}, nullptr};
    Memory memory(&refusing);
    Surface surface(memory);
    CHECK_FALSE(surface.reset(4));
    CHECK(memory.failed());
}

TEST_CASE("removing pinches spares the vertices marked, and treats the others") {
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(11));
    // Vertex 0 pinched by two single faces; vertex 5 by a fan of two faces and a single one.
    surface.add_face(0, 1, 2, 0);
    surface.add_face(0, 3, 4, 0);
    surface.add_face(5, 6, 7, 0);
    surface.add_face(5, 7, 8, 0);
    surface.add_face(5, 9, 10, 0);
    REQUIRE(surface.pinched_vertex_count() == 2);
    const uint8_t spared[11] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    Array<uint32_t> removed(memory);
    REQUIRE(surface.remove_pinches(removed, spared));
    require_valid(surface);
    CHECK(surface.is_pinched(0));
    CHECK_FALSE(surface.is_pinched(5));
    REQUIRE(removed.size() == 1);
    CHECK(removed[0] == 4);  // the smaller fan of vertex 5
}

TEST_CASE("faces added past the reservation one at a time cost amortized constant allocator calls") {
    // Hole filling and the tiles' assembly add faces beyond what growing reserved. Growing the arrays by
    // exactly one face at a time copied them on every add with an allocator that cannot extend in place:
    // quadratic time.
    test::CountingAllocator allocator;
    Memory memory(allocator.get());
    Surface surface(memory);
    const uint32_t columns = 4000;  // a strip: two rows of points, two triangles per column
    REQUIRE(surface.reset(2 * columns));
    allocator.fail_at(0);  // counts from here
    for (uint32_t i = 0; i + 1 < columns; ++i) {
        REQUIRE(surface.add_face(i, i + 1, columns + i, 0) != NO_FACE);
        REQUIRE(surface.add_face(i + 1, columns + i + 1, columns + i, 0) != NO_FACE);
    }
    CHECK(surface.face_count() == 2 * (columns - 1));
    CHECK(allocator.requests() < 200);
    require_valid(surface);
}

TEST_CASE("pinched vertices keep every fan while fans of many vertices come and go in any order") {
    // Four hubs, each with a ring of eight faces added and then removed in a shuffled order, the hubs taking
    // turns: each hub gains and loses up to four fans at a time, and the extra fans of all hubs are recorded
    // side by side, so removing one moves another hub's.
    const uint32_t hubs = 4, ring = 8;
    Memory memory(nullptr);
    Surface surface(memory);
    REQUIRE(surface.reset(hubs * (ring + 1)));
    const auto face = [&](uint32_t hub, uint32_t k, uint32_t corner[3]) {
        const uint32_t base = hub * (ring + 1);
        corner[0] = base;
        corner[1] = base + 1 + k;
        corner[2] = base + 1 + (k + 1) % ring;
    };
    uint64_t state = 12345;
    const auto random_below = [&](uint32_t n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return uint32_t((state >> 33) % n);
    };
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<std::pair<uint32_t, uint32_t>> order;  // (hub, ring position), hubs interleaved
        for (uint32_t k = 0; k < ring; ++k) {
            for (uint32_t hub = 0; hub < hubs; ++hub) order.push_back({hub, k});
        }
        for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random_below(uint32_t(i))]);
        std::vector<uint32_t> faces;
        uint32_t most_pinched = 0;
        for (const auto& [hub, k] : order) {
            uint32_t corner[3];
            face(hub, k, corner);
            faces.push_back(surface.add_face(corner[0], corner[1], corner[2], 0));
            require_valid(surface);
            most_pinched = std::max(most_pinched, surface.pinched_vertex_count());
        }
        CHECK(most_pinched > 1);
        CHECK(surface.pinched_vertex_count() == 0);  // every ring closed
        for (size_t i = faces.size(); i > 1; --i) std::swap(faces[i - 1], faces[random_below(uint32_t(i))]);
        for (uint32_t f : faces) {
            REQUIRE(surface.remove_face(f));
            require_valid(surface);
        }
        CHECK(surface.used_vertex_count() == 0);
        REQUIRE(surface.reset(hubs * (ring + 1)));
    }
}
