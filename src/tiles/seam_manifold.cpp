// The out-of-core loop's manifold check at a seam (see seam_manifold.h).
#include "tiles/seam_manifold.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace dbrg::out_of_core {
namespace {

using Corners = std::array<uint64_t, 3>;
using Edge = std::pair<uint64_t, uint64_t>;

Edge edge_of(uint64_t a, uint64_t b) { return {std::min(a, b), std::max(a, b)}; }

// Union-find over the few faces around one vertex.
size_t root_of(std::vector<size_t>& parent, size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

} // namespace

Corners sorted_corners(const uint64_t* face) {
    Corners corners{face[0], face[1], face[2]};
    std::sort(corners.begin(), corners.end());
    return corners;
}

std::vector<size_t> faces_breaking_manifold(const uint64_t* faces, size_t count,
                                            const std::unordered_set<uint64_t>& checked) {
    std::vector<Corners> key(count);
    for (size_t f = 0; f < count; ++f) key[f] = sorted_corners(faces + 3 * f);
    std::vector<size_t> order(count);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
    std::vector<uint8_t> left_out(count, 0);
    std::map<Edge, uint32_t> uses;  // the edges with an end checked, by the faces taken
    const auto is_checked = [&](uint64_t v) { return checked.count(v) != 0; };
    const Corners* last_taken = nullptr;  // repeats of a face come right after it in `order`
    for (size_t f : order) {
        const uint64_t* t = faces + 3 * f;
        bool fits = last_taken == nullptr || *last_taken != key[f];
        for (int i = 0; fits && i < 3; ++i) {
            const uint64_t a = t[i], b = t[(i + 1) % 3];
            const auto found = uses.find(edge_of(a, b));
            fits = found == uses.end() || found->second < 2;
        }
        if (!fits) {
            left_out[f] = 1;
            continue;
        }
        last_taken = &key[f];
        for (int i = 0; i < 3; ++i) {
            const uint64_t a = t[i], b = t[(i + 1) % 3];
            if (is_checked(a) || is_checked(b)) ++uses[edge_of(a, b)];
        }
    }
    // The faces taken around each checked vertex, in the order above; then its fans, until no vertex has two.
    std::map<uint64_t, std::vector<size_t>> around;
    for (size_t f : order) {
        if (left_out[f]) continue;
        for (int i = 0; i < 3; ++i) {
            if (is_checked(faces[3 * f + i])) around[faces[3 * f + i]].push_back(f);
        }
    }
    for (bool changed = true; changed;) {
        changed = false;
        for (auto& [v, fan] : around) {
            fan.erase(std::remove_if(fan.begin(), fan.end(), [&](size_t f) { return left_out[f] != 0; }), fan.end());
            // Two faces around v are in one fan when they share an edge from v (two faces at most, above).
            std::vector<size_t> parent(fan.size());
            std::iota(parent.begin(), parent.end(), size_t(0));
            std::map<uint64_t, size_t> first_across;  // the other end of an edge from v -> the first face on it
            for (size_t i = 0; i < fan.size(); ++i) {
                for (int k = 0; k < 3; ++k) {
                    const uint64_t u = faces[3 * fan[i] + k];
                    if (u == v) continue;
                    const auto [at, fresh] = first_across.emplace(u, i);
                    if (!fresh) parent[root_of(parent, at->second)] = root_of(parent, i);
                }
            }
            std::vector<size_t> size(fan.size(), 0);
            for (size_t i = 0; i < fan.size(); ++i) ++size[root_of(parent, i)];
            size_t kept = fan.empty() ? 0 : root_of(parent, 0);
            for (size_t i = 0; i < fan.size(); ++i) {
                if (size[root_of(parent, i)] > size[kept]) kept = root_of(parent, i);
            }
            for (size_t i = 0; i < fan.size(); ++i) {
                if (root_of(parent, i) == kept) continue;
                left_out[fan[i]] = 1;
                changed = true;
            }
        }
    }
    std::vector<size_t> out;
    for (size_t f = 0; f < count; ++f) {
        if (left_out[f]) out.push_back(f);
    }
    return out;
}

} // namespace dbrg::out_of_core
