// Small handles: removes topological noise from the components of S after hole filling. Where a
// surface comes closer to itself than the sample spacing, growing can bridge the two sheets with a
// few triangles: a handle whose shortest non-separating cycle is only a few edges long. Each such handle
// is cut along that cycle and both sides are filled; real handles, whose non-separating cycles are long
// in units of the local edges, stay.
//
// Based on: I. Guskov and Z. J. Wood, "Topological noise removal", Graphics Interface 2001 (find a short
// non-separating cycle by growing a small region, cut along it, fill both sides); the test of whether a
// cycle separates uses the tree-cotree homology basis of J. Erickson and K. Whittlesey, "Greedy optimal
// homotopy and homology generators", SODA 2005.
#include <algorithm>
#include <math.h>

#include "core/intrinsics.h"
#include "core/progress_span.h"
#include "core/status.h"
#include "holes/hole_filling.h"

namespace dbrg {
namespace {

constexpr uint32_t NO_VERTEX = UINT32_MAX;

// The criterion, scale-free because it counts edges: a handle is noise when a non-separating cycle of at
// most MAX_CYCLE_EDGES edges goes around it. Such a handle's cross-section is sampled by at most that many
// points, fewer than a sampling that resolves it as a tube would give: where growing bridges a gap
// narrower than the spacing, the bridge is a triangle or two wide and cycles of 3 to 5 edges go around it,
// while a tube sampled well enough to be reconstructed (a torus, the rocker arm's hole, a double torus
// from 1000 points on) has none shorter than 7 edges.
constexpr uint32_t MAX_CYCLE_EDGES = 6;
// And it must be short in length, not only in edges: at most this many times the mean length of the
// edges around its vertices. A bridge across a gap narrower than the spacing is crossed by cycles of
// 1.3 to 2.9 local edge lengths (the cheburashka's neck, the cow's mouth), while a coarsely sampled tube
// whose cross-section has only 4 to 6 edges (a torus of 100 to 150 points) goes around in more than 4.
constexpr double MAX_CYCLE_LENGTH = 3.5;
// A cycle of at most MAX_CYCLE_EDGES edges through a seed lies within this many edges of it.
constexpr uint32_t BALL_RADIUS = MAX_CYCLE_EDGES / 2;
// Homology classes are bit vectors over the 2g generators of the tree-cotree decomposition; at most this
// many 64-bit words of them are kept. A cycle found non-zero on a subset of the generators is
// non-separating all the same; handles missed that way are found in the next round.
constexpr uint32_t MAX_WORDS = 4;
// The breadth-first passes over the whole surface report every this many vertices or faces: a millisecond
// or two.
constexpr size_t REPORT_STEP = 1 << 14;

struct CycleCandidate {
    uint32_t first;   // into the cycle vertex list
    uint32_t length;  // edges (= vertices) of the cycle
    double measure;   // for ordering: the shortest first
};

} // namespace

// Euler characteristic bookkeeping for every component.
struct SurfaceTopology {
    explicit SurfaceTopology(Memory& memory) : face_component(memory), genus(memory) {}
    Array<uint32_t> face_component;
    Array<int32_t> genus;  // per component; -1 for a component with a pinched vertex
    uint32_t components = 0;
    uint64_t boundary_halfedges = 0;
    uint32_t total_genus = 0;  // over the components
};

namespace {

// Labels the components (the long part, reported to `progress`) and counts each one's genus.
dbrg_status measure_topology(const Surface& surface, const ProgressSpan& progress, SurfaceTopology& topology) {
    Context& context = progress.context();
    topology.face_component.clear();  // label_components fills only what it adds
    dbrg_status status = DBRG_OK;
    const auto between = [&](size_t done, size_t total) { return (status = progress.report(done, total)) == DBRG_OK; };
    const uint32_t components = surface.label_components(topology.face_component, between);
    if (components == NO_FACE) return status != DBRG_OK ? status : context.fail_out_of_memory();
    Array<int64_t> chi(context.memory);
    Array<uint64_t> boundary(context.memory);
    if (!chi.resize(components, 0) || !boundary.resize(components, 0) || !topology.genus.resize(components, 0)) {
        return context.fail_out_of_memory();
    }
    topology.components = components;
    topology.boundary_halfedges = 0;
    topology.total_genus = 0;
    for (uint32_t f = 0; f < surface.face_count(); ++f) {
        const uint32_t k = topology.face_component[f];
        if (k == NO_FACE) continue;
        uint32_t open = 0;
        for (uint32_t i = 0; i < 3; ++i) open += surface.is_boundary(3 * f + i) ? 1 : 0;
        boundary[k] += open;
        // F - E: a face counts 1, each interior edge -1/2 from each side, each boundary edge -1.
        chi[k] += 2 - 3 - int64_t(open);  // doubled: 2F - 2E = 2 - (3 + open)
    }
    Array<uint8_t> pinched(context.memory);
    Array<uint32_t> loops(context.memory);
    if (!pinched.resize(components, 0) || !loops.resize(components, 0)) return context.fail_out_of_memory();
    for (uint32_t v = 0; v < surface.vertex_count(); ++v) {
        if (!surface.is_used(v)) continue;
        const uint32_t k = topology.face_component[Surface::face_of(surface.vertex_halfedge(v))];
        chi[k] += 2;
        if (surface.is_pinched(v)) pinched[k] = 1;  // not a manifold component: left alone
    }
    Array<uint8_t> walked(context.memory);
    if (!walked.resize(3 * size_t(surface.face_count()), 0)) return context.fail_out_of_memory();
    for (uint32_t h = 0; h < 3 * surface.face_count(); ++h) {
        if (!surface.is_boundary(h) || walked[h] || surface.face_removed(Surface::face_of(h))) continue;
        surface.walk_loop(h, [&](uint32_t g) { walked[g] = 1; });
        ++loops[topology.face_component[Surface::face_of(h)]];
    }
    for (uint32_t k = 0; k < components; ++k) {
        topology.boundary_halfedges += boundary[k];
        // chi[k] is 2 (V - E + F); an orientable surface with b boundary loops has V - E + F = 2 - 2 g - b.
        topology.genus[k] = pinched[k] ? -1 : int32_t((4 - chi[k] - 2 * int64_t(loops[k])) / 4);
        if (topology.genus[k] > 0) topology.total_genus += uint32_t(topology.genus[k]);
    }
    return DBRG_OK;
}

} // namespace

dbrg_status HoleFiller::remove_small_handles(const ProgressSpan& progress) {
    Memory& memory = context_.memory;
    if (added_base_ == 0) {
        added_base_ = surface_.face_count();
        restored_open_.clear();
    }
    SurfaceTopology topology(memory);
    // Rounds of finding and cutting, each on the surface the last one left, while the genus drops (so at
    // most as many rounds as handles; there is usually one, or two where cut handles were close together).
    for (double round_begin = 0, round_end = 0.5;; round_begin = round_end, round_end = (1 + round_end) / 2) {
        const ProgressSpan round = progress.part(round_begin, round_end);
        const ProgressSpan tree_progress = round.part(HANDLES_PROGRESS_TREE, HANDLES_PROGRESS_COTREE);
        const ProgressSpan cotree_progress = round.part(HANDLES_PROGRESS_COTREE, HANDLES_PROGRESS_CYCLES);
        const ProgressSpan seeds_progress = round.part(HANDLES_PROGRESS_CYCLES, HANDLES_PROGRESS_CUTS);
        const ProgressSpan cuts_progress = round.part(HANDLES_PROGRESS_CUTS, 1);
        DBRG_PROPAGATE(measure_topology(surface_, round.part(0, HANDLES_PROGRESS_TREE), topology));
        if (topology.total_genus == 0) break;
        const uint32_t vertices = surface_.vertex_count();
        const uint32_t faces = surface_.face_count();
        auto target_face = [&](uint32_t f) {
            const uint32_t k = topology.face_component[f];
            return k != NO_FACE && topology.genus[k] > 0;
        };
        auto target_vertex = [&](uint32_t v) {
            return surface_.is_used(v) && target_face(Surface::face_of(surface_.vertex_halfedge(v)));
        };

        // A spanning tree T of the vertices of each closed component with handles (breadth first).
        enum : uint8_t { OTHER_EDGE = 0, TREE_EDGE = 1, COTREE_EDGE = 2 };
        Array<uint8_t> kind(memory);  // per half-edge
        Array<uint32_t> tree_parent(memory), queue(memory);
        if (!kind.resize(3 * size_t(faces), OTHER_EDGE) || !tree_parent.resize(vertices, NO_VERTEX) ||
            !queue.reserve(vertices)) {
            return context_.fail_out_of_memory();
        }
        size_t tree_vertices = 0;
        for (uint32_t root = 0; root < vertices; ++root) {
            if (tree_parent[root] != NO_VERTEX || !target_vertex(root)) continue;
            tree_parent[root] = root;
            queue.clear();
            queue.push_back(root);
            for (size_t q = 0; q < queue.size(); ++q) {
                DBRG_PROPAGATE(tree_progress.report_at(tree_vertices++, vertices, REPORT_STEP));
                const uint32_t u = queue[q];
                surface_.walk_fan(surface_.vertex_halfedge(u), [&](uint32_t h) {
                    const uint32_t x = surface_.target(h);
                    if (tree_parent[x] == NO_VERTEX) {
                        tree_parent[x] = u;
                        kind[h] = TREE_EDGE;
                        if (!surface_.is_boundary(h)) kind[surface_.twin(h)] = TREE_EDGE;
                        queue.push_back(x);
                    }
                });
            }
        }

        // Each boundary loop is capped with a virtual face (node faces + its number), so that the
        // components are closed surfaces of the same genus: a cycle around a border is separating then,
        // and only handles are left to find.
        Array<uint32_t> cap_of(memory);  // per boundary half-edge of a target face: its cap's node
        Array<uint32_t> cap_start(memory), cap_edges(memory);  // the caps' half-edges, cap by cap
        if (!cap_of.resize(3 * size_t(faces), NO_FACE) || !cap_start.push_back(0)) return context_.fail_out_of_memory();
        for (uint32_t h = 0; h < 3 * faces; ++h) {
            if (!surface_.is_boundary(h) || cap_of[h] != NO_FACE || !target_face(Surface::face_of(h))) continue;
            const uint32_t cap = faces + static_cast<uint32_t>(cap_start.size() - 1);
            const bool walked = surface_.walk_loop(h, [&](uint32_t g) {
                cap_of[g] = cap;
                return cap_edges.push_back(g);
            });
            if (!walked || !cap_start.push_back(static_cast<uint32_t>(cap_edges.size()))) return context_.fail_out_of_memory();
        }
        const uint32_t nodes = faces + static_cast<uint32_t>(cap_start.size() - 1);
        // The face (or cap) across half-edge h from its own face.
        auto across = [&](uint32_t h) { return surface_.is_boundary(h) ? cap_of[h] : Surface::face_of(surface_.twin(h)); };

        // A spanning tree C of the faces and caps through the edges not in T (the cotree); the edges in
        // neither are the leftover edges, 2 g of them per component, and each closes one generator of the
        // homology. node_parent_edge[n]: the half-edge of n on its parent edge (for a cap, its face's).
        Array<uint32_t> node_parent(memory), node_parent_edge(memory), node_order(memory);
        Array<uint8_t> node_seen(memory);
        Array<uint32_t> generator(memory);  // the leftover edges by their smaller half-edge
        if (!node_parent.resize(nodes, NO_FACE) || !node_parent_edge.resize(nodes, NO_HALFEDGE) ||
            !node_seen.resize(nodes, 0) || !node_order.reserve(nodes)) {
            return context_.fail_out_of_memory();
        }
        for (uint32_t root = 0; root < faces; ++root) {
            if (node_seen[root] || !target_face(root)) continue;
            node_seen[root] = 1;
            node_order.push_back(root);
            for (size_t q = node_order.size() - 1; q < node_order.size(); ++q) {
                DBRG_PROPAGATE(cotree_progress.report_at(q, nodes, REPORT_STEP));
                const uint32_t n = node_order[q];
                const uint32_t* edges = n < faces ? nullptr : &cap_edges[cap_start[n - faces]];
                const uint32_t degree = n < faces ? 3 : cap_start[n - faces + 1] - cap_start[n - faces];
                for (uint32_t i = 0; i < degree; ++i) {
                    const uint32_t h = n < faces ? 3 * n + i : edges[i];  // a half-edge of the edge crossed
                    if (kind[h] != OTHER_EDGE) continue;
                    const uint32_t other = n < faces ? across(h) : Surface::face_of(h);
                    if (node_seen[other]) {
                        // Seen from both sides, so kept once: from the side of its smaller half-edge, or
                        // for a border edge, from its face.
                        const bool keep = surface_.is_boundary(h) ? n < faces : h < surface_.twin(h);
                        if (keep && !generator.push_back(h)) return context_.fail_out_of_memory();
                        continue;
                    }
                    node_seen[other] = 1;
                    node_parent[other] = n;
                    node_parent_edge[other] = surface_.is_boundary(h) ? h : surface_.twin(h);
                    kind[h] = COTREE_EDGE;
                    if (!surface_.is_boundary(h)) kind[surface_.twin(h)] = COTREE_EDGE;
                    node_order.push_back(other);
                }
            }
        }
        // Generator i belongs to the i-th leftover edge in the order of their smaller half-edges.
        std::sort(generator.begin(), generator.end());
        const uint32_t words = std::min<uint32_t>(MAX_WORDS, uint32_t((generator.size() + 63) / 64));
        if (words == 0) break;
        // label[n]: the generators whose dual cycle (the leftover edge's dual plus the cotree path between its
        // faces) crosses the cotree edge from node n to its parent: the leftover edges with exactly one side
        // in n's subtree.
        Array<uint64_t> label(memory);
        if (!label.resize(size_t(nodes) * words, 0)) return context_.fail_out_of_memory();
        for (uint32_t i = 0; i < generator.size() && i < 64 * words; ++i) {
            const uint32_t h = generator[i];
            label[size_t(Surface::face_of(h)) * words + i / 64] ^= uint64_t(1) << (i % 64);
            label[size_t(across(h)) * words + i / 64] ^= uint64_t(1) << (i % 64);
        }
        for (size_t q = node_order.size(); q-- > 0;) {
            const uint32_t n = node_order[q];
            if (node_parent[n] == NO_FACE) continue;
            for (uint32_t w = 0; w < words; ++w) label[size_t(node_parent[n]) * words + w] ^= label[size_t(n) * words + w];
        }
        // The class of edge h: the generators whose dual cycles cross it. A cycle is non-separating exactly
        // when the sum of its edges' classes is not zero (it crosses some dual cycle an odd number of times).
        auto edge_class_word = [&](uint32_t h, uint32_t w) -> uint64_t {
            if (kind[h] == TREE_EDGE) return 0;
            const uint32_t t = surface_.is_boundary(h) ? h : surface_.twin(h);
            if (kind[h] == COTREE_EDGE) {
                // The child is the side whose parent edge this is.
                const uint32_t f = Surface::face_of(h);
                const uint32_t child = node_parent_edge[f] == h || node_parent_edge[f] == t ? f : across(h);
                return label[size_t(child) * words + w];
            }
            const uint32_t key = h < t ? h : t;
            const uint32_t* at = std::lower_bound(generator.begin(), generator.end(), key);
            const size_t i = size_t(at - generator.begin());
            if (i == generator.size() || generator[i] != key) return 0;
            return i / 64 == w ? uint64_t(1) << (i % 64) : 0;
        };

        // Short non-separating cycles: from each seed, a breadth-first ball; an edge between two
        // ball vertices that is not in the ball's tree closes a cycle (through their common ancestor) whose
        // class is the sum of the classes along the two tree paths and the edge.
        Array<uint32_t> stamp(memory), depth(memory), parent(memory), ball(memory), cycles(memory), path(memory);
        Array<uint64_t> cls(memory), candidate_class(memory);
        Array<uint8_t> is_seed(memory);
        Array<CycleCandidate> candidates(memory);
        if (!stamp.resize(vertices, 0) || !depth.resize(vertices, 0) || !parent.resize(vertices, NO_VERTEX) ||
            !cls.resize(size_t(vertices) * words, 0) || !is_seed.resize(vertices, 0)) {
            return context_.fail_out_of_memory();
        }
        // A non-separating cycle has an edge of non-zero class, so it passes through an end of one: those
        // ends are the seeds, and the shortest non-separating cycle through a seed closes within its ball
        // (Erickson and Har-Peled: it is one tree path, an edge and another tree path of a shortest-path
        // tree from the seed). The edges of non-zero class are the ones the dual cycles cross, so the
        // seeds lie along 2 g dual cycles as long as the surface is wide: far fewer than the vertices.
        for (uint32_t n : node_order) {
            uint64_t any = 0;
            for (uint32_t w = 0; w < words; ++w) any |= label[size_t(n) * words + w];
            const uint32_t h = node_parent_edge[n];
            if (any != 0 && h != NO_HALFEDGE) is_seed[surface_.origin(h)] = is_seed[surface_.target(h)] = 1;
        }
        for (uint32_t i = 0; i < generator.size() && i < 64 * words; ++i) {
            is_seed[surface_.origin(generator[i])] = is_seed[surface_.target(generator[i])] = 1;
        }
        uint32_t seeds = 0;
        for (uint32_t seed = 0; seed < vertices; ++seed) {
            if (!is_seed[seed]) continue;
            DBRG_PROPAGATE(seeds_progress.report(seed, vertices));
            ++seeds;
            ball.clear();
            ball.push_back(seed);
            stamp[seed] = seeds;
            depth[seed] = 0;
            parent[seed] = NO_VERTEX;
            for (uint32_t w = 0; w < words; ++w) cls[size_t(seed) * words + w] = 0;
            uint32_t best_length = MAX_CYCLE_EDGES + 1, best_u = NO_VERTEX, best_x = NO_VERTEX;
            double best_measure = HUGE_VAL;
            for (size_t q = 0; q < ball.size(); ++q) {
                const uint32_t u = ball[q];
                const bool walked = surface_.walk_fan(surface_.vertex_halfedge(u), [&](uint32_t h) {
                    const uint32_t x = surface_.target(h);
                    if (stamp[x] != seeds) {
                        if (depth[u] < BALL_RADIUS) {
                            stamp[x] = seeds;
                            depth[x] = depth[u] + 1;
                            parent[x] = u;
                            for (uint32_t w = 0; w < words; ++w) {
                                cls[size_t(x) * words + w] = cls[size_t(u) * words + w] ^ edge_class_word(h, w);
                            }
                            if (!ball.push_back(x)) return false;
                        }
                    } else if (parent[x] != u && parent[u] != x && u < x) {
                        uint64_t any = 0;
                        for (uint32_t w = 0; w < words; ++w) {
                            any |= cls[size_t(x) * words + w] ^ cls[size_t(u) * words + w] ^ edge_class_word(h, w);
                        }
                        if (any != 0) {
                            // The cycle through the common ancestor of u and x.
                            uint32_t a = u, b = x, length = 1;
                            while (a != b) {
                                if (depth[a] >= depth[b]) a = parent[a];
                                else b = parent[b];
                                ++length;
                            }
                            if (length <= MAX_CYCLE_EDGES && length <= best_length) {
                                // Among cycles of as many edges, the shortest in space.
                                double m = 0;
                                for (uint32_t c = u; c != a; c = parent[c]) {
                                    m += length_between(c, parent[c]);
                                }
                                for (uint32_t c = x; c != a; c = parent[c]) m += length_between(c, parent[c]);
                                m += length_between(u, x);
                                if (length < best_length || m < best_measure) {
                                    best_length = length;
                                    best_measure = m;
                                    best_u = u;
                                    best_x = x;
                                }
                            }
                        }
                    }
                    return true;
                });
                if (!walked) return context_.fail_out_of_memory();
            }
            if (best_u == NO_VERTEX) continue;
            // Record the cycle: u up to the ancestor, then down to x.
            path.clear();
            uint32_t a = best_u, b = best_x;
            CycleCandidate candidate{static_cast<uint32_t>(cycles.size()), 0, 0};
            Array<uint32_t>& down = path;
            while (a != b) {
                if (depth[a] >= depth[b]) {
                    if (!cycles.push_back(a)) return context_.fail_out_of_memory();
                    a = parent[a];
                } else {
                    if (!down.push_back(b)) return context_.fail_out_of_memory();
                    b = parent[b];
                }
            }
            if (!cycles.push_back(a)) return context_.fail_out_of_memory();
            for (size_t i = down.size(); i-- > 0;) {
                if (!cycles.push_back(down[i])) return context_.fail_out_of_memory();
            }
            candidate.length = static_cast<uint32_t>(cycles.size()) - candidate.first;
            // Relative to the mean edge length around the cycle's vertices.
            double edge_sum = 0;
            uint32_t edge_count = 0;
            for (uint32_t i = candidate.first; i < cycles.size(); ++i) {
                const uint32_t v = cycles[i];
                surface_.walk_fan(surface_.vertex_halfedge(v), [&](uint32_t h) {
                    edge_sum += length_between(v, surface_.target(h));
                    ++edge_count;
                });
            }
            candidate.measure = best_measure / (edge_sum / edge_count);
            if (candidate.measure > MAX_CYCLE_LENGTH) {
                cycles.shrink(candidate.first);
                continue;
            }
            if (!candidates.push_back(candidate)) return context_.fail_out_of_memory();
            for (uint32_t w = 0; w < words; ++w) {
                uint64_t c = cls[size_t(best_u) * words + w] ^ cls[size_t(best_x) * words + w];
                const uint32_t e = surface_.find_halfedge(best_u, best_x);
                c ^= edge_class_word(e, w);
                if (!candidate_class.push_back(c)) return context_.fail_out_of_memory();
            }
        }

        // Cut the shortest first; a candidate whose class the cut ones already span goes around a handle
        // that is gone (or is a sum of cut ones) and is skipped.
        Array<uint32_t> order(memory);
        if (!order.resize(candidates.size())) return context_.fail_out_of_memory();
        for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
            if (candidates[a].length != candidates[b].length) return candidates[a].length < candidates[b].length;
            if (candidates[a].measure != candidates[b].measure) return candidates[a].measure < candidates[b].measure;
            return a < b;
        });
        Array<uint64_t> basis(memory);  // reduced classes of the cut cycles, each with a distinct leading bit
        Array<uint64_t> reduced(memory);
        if (!reduced.resize(words)) return context_.fail_out_of_memory();
        uint32_t removed_this_round = 0;
        for (size_t k = 0; k < order.size(); ++k) {
            const uint32_t i = order[k];
            for (uint32_t w = 0; w < words; ++w) reduced[w] = candidate_class[size_t(i) * words + w];
            auto leading = [&](const uint64_t* c) -> int {
                for (uint32_t w = words; w-- > 0;) {
                    if (c[w] != 0) return int(64 * w + 63 - count_leading_zeros(c[w]));
                }
                return -1;
            };
            for (size_t b = 0; b < basis.size(); b += words) {
                const int bit = leading(&basis[b]);
                if ((reduced[bit / 64] >> (bit % 64)) & 1) {
                    for (uint32_t w = 0; w < words; ++w) reduced[w] ^= basis[b + w];
                }
            }
            if (leading(reduced.data()) < 0) continue;
            bool removed = false;
            // Each cut measures the whole surface again: its share of the cuts' progress.
            const ProgressSpan cut_progress = cuts_progress.part(double(k) / order.size(), double(k + 1) / order.size());
            DBRG_PROPAGATE(cut_handle(&cycles[candidates[i].first], candidates[i].length, cut_progress, topology, removed));
            if (!removed) continue;
            ++removed_this_round;
            // Insert keeping the basis sorted by decreasing leading bit, so reduction above is one pass.
            for (uint32_t w = 0; w < words; ++w) {
                if (!basis.push_back(reduced[w])) return context_.fail_out_of_memory();
            }
            for (size_t b = basis.size() - words; b >= words && leading(&basis[b - words]) < leading(&basis[b]); b -= words) {
                for (uint32_t w = 0; w < words; ++w) std::swap(basis[b + w], basis[b - words + w]);
            }
        }
        handles_removed_ += removed_this_round;
        if (removed_this_round == 0) break;
    }
    if (memory.failed()) return context_.fail_out_of_memory();
    dbrg_stats& stats = context_.stats;
    stats.handles_removed = handles_removed_;
    stats.hole_triangles_added += handle_triangles_added_;
    stats.hole_triangles_removed += handle_triangles_removed_;
    return DBRG_OK;
}

double HoleFiller::length_between(uint32_t a, uint32_t b) const {
    return length(load_vec3(points_.point(a)) - load_vec3(points_.point(b)));
}

// Removes the faces around the cycle's vertices, which leaves two loops where the cycle went around a
// handle, and fills them. Kept only when the genus dropped and the surface is as closed and as connected
// as before; otherwise everything is put back.
dbrg_status HoleFiller::cut_handle(const uint32_t* cycle, size_t length, const ProgressSpan& progress,
                                   SurfaceTopology& before, bool& removed) {
    removed = false;
    for (size_t i = 0; i < length; ++i) {
        const uint32_t a = cycle[i], b = cycle[(i + 1) % length];
        if (!surface_.is_used(a) || surface_.is_pinched(a)) return DBRG_OK;
        if (surface_.find_halfedge(a, b) == NO_HALFEDGE && surface_.find_halfedge(b, a) == NO_HALFEDGE) return DBRG_OK;
    }
    Memory& memory = context_.memory;
    FaceJournal journal(memory);
    Array<uint32_t> doomed(memory), starts(memory);
    const uint32_t pinched_before = surface_.pinched_vertex_count();
    for (size_t i = 0; i < length; ++i) {
        if (!surface_.walk_vertex(cycle[i], [&](uint32_t h) { return doomed.push_back(Surface::face_of(h)); })) {
            return context_.fail_out_of_memory();
        }
    }
    std::sort(doomed.begin(), doomed.end());
    uint32_t* last = std::unique(doomed.begin(), doomed.end());
    doomed.shrink(size_t(last - doomed.begin()));
    for (uint32_t f : doomed) {
        for (uint32_t g = 3 * f; g < 3 * f + 3; ++g) {
            if (!surface_.is_boundary(g) && !starts.push_back(surface_.twin(g))) return context_.fail_out_of_memory();
        }
        DBRG_PROPAGATE(remove_and_record(f, journal));
    }
    // A cut that leaves a vertex with two sheets is not a clean cut along the cycle: put it back.
    if (surface_.pinched_vertex_count() > pinched_before) return undo(journal, 0);

    // Fill every loop the removal opened over its own vertices: on the data sets, enlarging fills no cut
    // loop that ears alone leave open.
    filling_cut_ = true;
    bool all_filled = true;
    dbrg_status status = DBRG_OK;
    for (uint32_t s : starts) {
        if (surface_.face_removed(Surface::face_of(s)) || !surface_.is_boundary(s)) continue;  // closed with another
        status = fill_within_fold_limits(surface_.origin(s), surface_.target(s), 0, journal, all_filled);
        if (status != DBRG_OK || !all_filled) break;
    }
    filling_cut_ = false;
    DBRG_PROPAGATE(status);
    // A loop left open fails the test below whatever the topology: spare the pass over the whole surface.
    if (!all_filled) return undo(journal, 0);

    SurfaceTopology after(memory);
    DBRG_PROPAGATE(measure_topology(surface_, progress, after));
    if (after.components == before.components && after.boundary_halfedges == before.boundary_halfedges &&
        after.total_genus < before.total_genus) {
        removed = true;
        handle_triangles_added_ += journal.added_count();
        handle_triangles_removed_ += journal.removed_count();
        before.components = after.components;
        before.boundary_halfedges = after.boundary_halfedges;
        before.total_genus = after.total_genus;
        return DBRG_OK;
    }
    return undo(journal, 0);
}

} // namespace dbrg
