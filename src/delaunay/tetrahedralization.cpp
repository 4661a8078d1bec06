// Tetrahedralization: the tetrahedron store's queries — local indices, the tetrahedron of each vertex
// and the star of a vertex.
#include "delaunay/tetrahedralization.h"

namespace dbrg {
namespace {

// A set of tetrahedron ids for the star of one vertex: a linear scan while the star is small (the
// usual case, a few dozen tetrahedra), an open-addressing table once it is large.
class TetSet {
public:
    explicit TetSet(Memory& memory) : table_(memory) {}

    // Returns 1 when t was added, 0 when it was there, -1 on allocation failure.
    int insert(uint32_t t, const Array<uint32_t>& members) {
        if (table_.empty()) {
            for (uint32_t m : members) {
                if (m == t) return 0;
            }
            if (members.size() < LINEAR_LIMIT) return 1;
            if (!rehash(members, 4 * LINEAR_LIMIT)) return -1;
        }
        if (4 * (members.size() + 1) > 3 * table_.size() && !rehash(members, 2 * table_.size())) return -1;
        const uint32_t mask = static_cast<uint32_t>(table_.size() - 1);
        for (uint32_t k = hash(t) & mask;; k = (k + 1) & mask) {
            if (table_[k] == t) return 0;
            if (table_[k] == NO_TET) {
                table_[k] = t;
                return 1;
            }
        }
    }

private:
    static constexpr size_t LINEAR_LIMIT = 64;  // 4 * LINEAR_LIMIT must be a power of two
    static uint32_t hash(uint32_t t) { return (t * 0x9e3779b1u) >> 7; }

    bool rehash(const Array<uint32_t>& members, size_t capacity) {
        if (!table_.resize(capacity)) return false;
        for (uint32_t& slot : table_) slot = NO_TET;
        const uint32_t mask = static_cast<uint32_t>(capacity - 1);
        for (uint32_t m : members) {
            uint32_t k = hash(m) & mask;
            while (table_[k] != NO_TET) k = (k + 1) & mask;
            table_[k] = m;
        }
        return true;
    }

    Array<uint32_t> table_;
};

} // namespace

Tetrahedralization::Tetrahedralization(Memory& memory) : vertices_(memory), adjacency_(memory), vertex_tet_(memory) {}

void Tetrahedralization::clear() {
    vertices_.release();
    adjacency_.release();
    vertex_tet_.release();
    points_ = nullptr;
    vertex_count_ = 0;
    finite_tets_ = 0;
}

bool Tetrahedralization::index_vertex_tets() {
    if (!vertex_tet_.resize(vertex_count_, NO_TET)) return false;
    for (uint32_t t = tet_slots(); t-- > 0;) {
        if (tet_is_free(t)) continue;
        for (uint32_t lv = 0; lv < 4; ++lv) {
            const uint32_t w = vertices_[4 * size_t(t) + lv];
            if (w != INFINITE_VERTEX) vertex_tet_[w] = t;
        }
    }
    return true;
}

uint32_t Tetrahedralization::tet_local_index(uint32_t t, uint32_t v) const {
    const uint32_t* tv = vertices_.data() + 4 * size_t(t);
    for (uint32_t lv = 0; lv < 4; ++lv) {
        if (tv[lv] == v) return lv;
    }
    return NO_LOCAL_INDEX;
}

void Tetrahedralization::canonical_corners(uint32_t t, uint32_t local[4]) const {
    // The double transposition that brings corner m to the front, then a 3-cycle of the other three.
    static constexpr uint32_t TO_FRONT[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
    const uint32_t* v = vertices_.data() + 4 * size_t(t);
    uint32_t m = 0;
    for (uint32_t i = 1; i < 4; ++i) m = v[i] < v[m] ? i : m;
    const uint32_t* p = TO_FRONT[m];
    uint32_t k = 1;
    for (uint32_t i = 2; i < 4; ++i) k = v[p[i]] < v[p[k]] ? i : k;
    local[0] = p[0];
    local[1] = p[k];
    local[2] = p[1 + k % 3];
    local[3] = p[1 + (k + 1) % 3];
}

bool Tetrahedralization::tets_around_vertex(uint32_t v, Array<uint32_t>& tets) const {
    // Breadth-first over the tetrahedra containing v: the neighbours across the three faces through v.
    tets.clear();
    TetSet seen(tets.memory());
    if (!tets.push_back(vertex_tet_[v])) return false;
    for (size_t i = 0; i < tets.size(); ++i) {
        const uint32_t t = tets[i];
        for (uint32_t lf = 0; lf < 4; ++lf) {
            if (tet_vertex(t, lf) == v) continue;
            const uint32_t n = tet_adjacent(t, lf);
            const int added = seen.insert(n, tets);
            if (added < 0 || (added > 0 && !tets.push_back(n))) return false;
        }
    }
    return true;
}

} // namespace dbrg
