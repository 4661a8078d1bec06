// Triangle orientation: consistent orientation of a triangle soup across shared edges (see
// triangle_orientation.h).
#include "tiles/triangle_orientation.h"

#include <math.h>

#include <algorithm>
#include <functional>

#include "core/vec3.h"
#include "grow/triangle_geometry.h"

namespace dbrg {
namespace {

const uint32_t NO_NEIGHBOUR = UINT32_MAX;

struct Triangle {
    uint32_t v[3];
    bool operator<(const Triangle& o) const { return std::lexicographical_compare(v, v + 3, o.v, o.v + 3); }
};

// A face's use of an edge, filed under the edge's lower end: the upper end in the high half, then the face
// and, in the lowest bit, whether the face runs from the lower end to the upper one. Eight bytes, so that
// sorting a mesh's uses moves half what a record of four fields did, and ordered by one comparison. Face
// numbers fit in 31 bits: orient_triangles takes fewer than 2^32 / 3 faces, as the uses' 32-bit offsets
// need anyway.
using EdgeUse = uint64_t;

EdgeUse edge_use(uint32_t high, uint32_t face, bool forward) {
    return uint64_t(high) << 32 | uint64_t(face) << 1 | uint64_t(forward);
}
uint32_t use_high(EdgeUse use) { return uint32_t(use >> 32); }
uint32_t use_face(EdgeUse use) { return uint32_t(use) >> 1; }
bool use_forward(EdgeUse use) { return (use & 1) != 0; }

// Writes item(i) for i < count to `out`, grouped by key(i), an index below `keys` (a counting sort), each
// group sorted by `less`. The keys here are vertices and a group a vertex's fan, a few items: a third of
// the time of sorting all the items at once. first[k] is where group k starts in `out` (first[keys] =
// count).
template <class T, class Key, class Item, class Less>
bool sort_by_vertex(size_t count, size_t keys, const Key& key, const Item& item, const Less& less, Array<T>& out,
                    Array<uint32_t>& first) {
    if (!first.resize(keys + 1, 0) || !out.resize(count)) return false;
    for (size_t i = 0; i < count; ++i) ++first[size_t(key(i)) + 1];
    for (size_t k = 0; k < keys; ++k) first[k + 1] += first[k];
    // Filed with first[k] as the cursor, which ends where group k + 1 starts; then moved back.
    for (size_t i = 0; i < count; ++i) out[first[key(i)]++] = item(i);
    for (size_t k = keys; k > 0; --k) first[k] = first[k - 1];
    first[0] = 0;
    for (size_t k = 0; k < keys; ++k) {
        T* begin = out.begin() + first[k];
        T* end = out.begin() + first[k + 1];
        if (end - begin > 16) {
            std::sort(begin, end, less);
            continue;
        }
        for (T* at = begin + 1; at < end; ++at) {  // insertion sort: cheaper than std::sort's set-up
            const T value = *at;
            T* to = at;
            for (; to > begin && less(value, to[-1]); --to) *to = to[-1];
            *to = value;
        }
    }
    return true;
}

// One past the largest index of `triangles`.
size_t vertex_bound(const Array<uint32_t>& triangles) {
    uint32_t largest = 0;
    for (uint32_t v : triangles) largest = std::max(largest, v);
    return triangles.empty() ? 0 : size_t(largest) + 1;
}

// Rotates each triangle to start at its smallest index and sorts them.
bool canonical_order(const Array<uint32_t>& triangles, size_t vertices, Memory& memory, Array<Triangle>& sorted) {
    const auto smallest = [&](size_t f) {
        const uint32_t* t = triangles.data() + 3 * f;
        return t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
    };
    const auto rotated = [&](size_t f) {
        const uint32_t* t = triangles.data() + 3 * f;
        const int first = smallest(f);
        return Triangle{{t[first], t[(first + 1) % 3], t[(first + 2) % 3]}};
    };
    Array<uint32_t> first(memory);
    return sort_by_vertex(triangles.size() / 3, vertices, [&](size_t f) { return triangles[3 * f + smallest(f)]; },
                          rotated, std::less<Triangle>(), sorted, first);
}

// Every face's use of each of its edges, grouped by the edge's lower end (group v from first[v] to
// first[v + 1]), each group sorted by the upper end, then by face.
bool sorted_edge_uses(const Array<Triangle>& faces, size_t vertices, Array<EdgeUse>& uses, Array<uint32_t>& first) {
    const auto low = [&](size_t u) { return std::min(faces[u / 3].v[u % 3], faces[u / 3].v[(u + 1) % 3]); };
    const auto use = [&](size_t u) {
        const uint32_t a = faces[u / 3].v[u % 3], b = faces[u / 3].v[(u + 1) % 3];
        return edge_use(std::max(a, b), uint32_t(u / 3), a < b);
    };
    return sort_by_vertex(3 * faces.size(), vertices, low, use, std::less<EdgeUse>(), uses, first);
}

// Whether face t, turned over when `flip`, faces up by the seeding rule (+z, else +x, else +y).
bool faces_up(const Triangle& t, bool flip, const double* xyz) {
    const Vec3 a = load_vec3(xyz + 3 * size_t(t.v[0])), b = load_vec3(xyz + 3 * size_t(t.v[1]));
    const Vec3 c = load_vec3(xyz + 3 * size_t(t.v[2]));
    Vec3 n = cross(b - a, c - a);
    if (flip) n = Vec3{-n.x, -n.y, -n.z};
    return n.z != 0 ? n.z > 0 : (n.x != 0 ? n.x > 0 : n.y >= 0);
}

} // namespace

dbrg_status orient_triangles(Array<uint32_t>& triangles, const double* xyz, bool turn_up, Context& context) {
    if (triangles.size() / 3 > UINT32_MAX / 3) {
        return context.fail(DBRG_ERR_TOO_MANY_POINTS, "%zu faces to orient: at most %u fit", triangles.size() / 3,
                            UINT32_MAX / 3);
    }
    const size_t vertices = vertex_bound(triangles);
    Array<Triangle> faces(context.memory);
    if (!canonical_order(triangles, vertices, context.memory, faces)) return context.fail_out_of_memory();
    const uint32_t count = static_cast<uint32_t>(faces.size());

    // Neighbours across the edges exactly two faces share, and whether they run it the same way.
    Array<EdgeUse> uses(context.memory);
    Array<uint32_t> first(context.memory);
    Array<uint32_t> neighbour(context.memory);
    Array<uint8_t> same_way(context.memory);
    if (!sorted_edge_uses(faces, vertices, uses, first) ||
        !neighbour.resize(3 * size_t(count), NO_NEIGHBOUR) || !same_way.resize(3 * size_t(count), 0)) {
        return context.fail_out_of_memory();
    }
    const auto slot = [&](uint32_t f) {
        uint32_t s = 3 * f;
        while (neighbour[s] != NO_NEIGHBOUR) ++s;
        return s;
    };
    for (size_t v = 0; v < vertices; ++v) {
        for (size_t i = first[v], j; i < first[v + 1]; i = j) {
            for (j = i + 1; j < first[v + 1] && use_high(uses[j]) == use_high(uses[i]);) ++j;
            if (j - i != 2 || use_face(uses[i]) == use_face(uses[i + 1])) continue;
            const uint8_t same = use_forward(uses[i]) == use_forward(uses[i + 1]);
            const uint32_t s = slot(use_face(uses[i])), t = slot(use_face(uses[i + 1]));
            neighbour[s] = use_face(uses[i + 1]);
            neighbour[t] = use_face(uses[i]);
            same_way[s] = same_way[t] = same;
        }
    }
    first.release();
    uses.release();

    // Breadth-first from the first face of each component; `order` lists each component's faces together.
    Array<uint8_t> flip(context.memory), seen(context.memory);
    Array<uint32_t> order(context.memory);
    if (!flip.resize(count, 0) || !seen.resize(count, 0) || !order.reserve(count)) return context.fail_out_of_memory();
    for (uint32_t start = 0; start < count; ++start) {
        if (seen[start]) continue;
        const size_t first = order.size();
        seen[start] = 1;
        order.push_back(start);
        for (size_t k = first; k < order.size(); ++k) {
            const uint32_t f = order[k];
            for (uint32_t s = 3 * f; s < 3 * f + 3 && neighbour[s] != NO_NEIGHBOUR; ++s) {
                const uint32_t g = neighbour[s];
                if (seen[g]) continue;
                seen[g] = 1;
                flip[g] = flip[f] ^ same_way[s];
                order.push_back(g);
            }
        }
        if (!turn_up) continue;
        // The component's seed face: at its highest point, the smallest circumradius.
        uint32_t top = faces[order[first]].v[0];
        for (size_t k = first; k < order.size(); ++k) {
            for (uint32_t v : faces[order[k]].v) {
                const double z = xyz[3 * size_t(v) + 2], top_z = xyz[3 * size_t(top) + 2];
                if (z > top_z || (z == top_z && v < top)) top = v;
            }
        }
        uint32_t seed = NO_NEIGHBOUR;
        double best = HUGE_VAL;
        for (size_t k = first; k < order.size(); ++k) {
            const Triangle& t = faces[order[k]];
            if (t.v[0] != top && t.v[1] != top && t.v[2] != top) continue;
            const double r = circumradius(xyz + 3 * size_t(t.v[0]), xyz + 3 * size_t(t.v[1]), xyz + 3 * size_t(t.v[2]));
            if (r < best) {  // faces come in sorted order: a tie keeps the smaller one
                best = r;
                seed = order[k];
            }
        }
        if (seed != NO_NEIGHBOUR && !faces_up(faces[seed], flip[seed] != 0, xyz)) {
            for (size_t k = first; k < order.size(); ++k) flip[order[k]] ^= 1;
        }
    }
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t f = order[k];
        const Triangle& t = faces[f];
        triangles[3 * size_t(k)] = t.v[0];
        triangles[3 * size_t(k) + 1] = t.v[flip[f] ? 2 : 1];
        triangles[3 * size_t(k) + 2] = t.v[flip[f] ? 1 : 2];
    }
    return DBRG_OK;
}

} // namespace dbrg
