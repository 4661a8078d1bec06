// Topology and quality figures of a triangle mesh: edge, vertex and component classification in O(F).
#include "measure/mesh_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <new>
#include <vector>

#include "measure/dense_index.h"
#include "measure/zero_area.h"
#include "io/json_writer.h"

namespace dbrg::measure {
namespace {

const uint32_t NO_FACE = UINT32_MAX;

struct EdgeKeyHash {
    uint64_t operator()(uint64_t key) const { return key; }
};

// The bit patterns of a position's three coordinates.
using Triple = std::array<uint64_t, 3>;

struct TripleHash {
    uint64_t operator()(const Triple& key) const { return key[0] ^ mix_bits(key[1] ^ mix_bits(key[2])); }
};

// A triangle's three vertex (or position) numbers in increasing order: 12 bytes keep the hash table small.
using CornerSet = std::array<uint32_t, 3>;

struct CornerSetHash {
    uint64_t operator()(const CornerSet& key) const { return (uint64_t(key[0]) << 32 | key[1]) ^ mix_bits(key[2]); }
};

// Disjoint sets over 0..n-1 with path halving.
class UnionFind {
public:
    explicit UnionFind(size_t n) : parent_(n) {
        for (size_t i = 0; i < n; ++i) parent_[i] = static_cast<uint32_t>(i);
    }
    uint32_t root(uint32_t i) {
        while (parent_[i] != i) {
            parent_[i] = parent_[parent_[i]];
            i = parent_[i];
        }
        return i;
    }
    void join(uint32_t a, uint32_t b) {
        a = root(a);
        b = root(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<uint32_t> parent_;
};

IoStatus check_arrays(const MeshData& mesh, const char* what) {
    if (mesh.positions.size() % 3 != 0) return IoStatus::failure(std::string(what) + ": the position array's length is not a multiple of 3");
    if (mesh.triangles.size() % 3 != 0) return IoStatus::failure(std::string(what) + ": the triangle array's length is not a multiple of 3");
    if (mesh.vertex_count() >= UINT32_MAX || mesh.triangle_count() >= UINT32_MAX / 3) {
        return IoStatus::failure(std::string(what) + ": too large for 32-bit indices");
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (mesh.triangles[i] >= mesh.vertex_count()) {
            return IoStatus::failure(std::string(what) + ": triangle " + std::to_string(i / 3) + " refers to vertex " +
                                     std::to_string(mesh.triangles[i]) + ", but there are " + std::to_string(mesh.vertex_count()));
        }
    }
    return IoStatus::success();
}

// The exact bit pattern of a position, with -0 made +0 so that equal coordinates give equal keys.
Triple position_key(const std::vector<double>& positions, size_t vertex) {
    Triple key;
    for (size_t k = 0; k < 3; ++k) {
        const double value = positions[3 * vertex + k] == 0.0 ? 0.0 : positions[3 * vertex + k];
        std::memcpy(&key[k], &value, sizeof value);
    }
    return key;
}

CornerSet sorted_corners(uint32_t a, uint32_t b, uint32_t c) {
    CornerSet key = {a, b, c};
    std::sort(key.begin(), key.end());
    return key;
}


// For each vertex, the first vertex of the array at exactly its position (itself when there is none
// earlier). Coordinates compare as numbers: -0 equals 0, and a vertex with a NaN coordinate equals no other.
std::vector<uint32_t> first_at_same_position(const MeshData& mesh) {
    DenseIndex<Triple, TripleHash> positions(mesh.vertex_count());
    std::vector<uint32_t> first_of_position;
    std::vector<uint32_t> first(mesh.vertex_count());
    for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
        const double* p = &mesh.positions[3 * size_t(v)];
        if (std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2])) {
            first[v] = v;
            continue;
        }
        bool new_position = false;
        const uint32_t id = positions.insert(position_key(mesh.positions, v), &new_position);
        if (new_position) first_of_position.push_back(v);
        first[v] = first_of_position[id];
    }
    return first;
}

// `mesh` with every vertex replaced by the first vertex at its position (`first`, as first_at_same_position
// gives it) and the others dropped; the vertices kept stay in their order.
MeshData welded(const MeshData& mesh, const std::vector<uint32_t>& first) {
    MeshData out;
    out.has_faces = mesh.has_faces;
    std::vector<uint32_t> new_index(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        if (first[v] != v) {
            new_index[v] = new_index[first[v]];  // first[v] < v: already numbered
            continue;
        }
        new_index[v] = static_cast<uint32_t>(out.vertex_count());
        out.positions.insert(out.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v] + 3);
    }
    out.triangles.reserve(mesh.triangles.size());
    for (uint32_t index : mesh.triangles) out.triangles.push_back(new_index[index]);
    return out;
}

// Per-edge record: how many proper faces use it and the first two of them with their directions.
struct EdgeUse {
    uint32_t count = 0;
    uint32_t face[2] = {NO_FACE, NO_FACE};
    bool ascending[2] = {false, false};  // the face runs from the smaller vertex index to the larger
};

uint32_t corner_of(const std::vector<uint32_t>& triangles, uint32_t face, uint32_t vertex) {
    for (uint32_t k = 0; k < 3; ++k) {
        if (triangles[3 * size_t(face) + k] == vertex) return 3 * face + k;
    }
    return 3 * face;  // unreachable: callers pass a corner vertex of the face
}

IoStatus compute(const MeshData& mesh, MeshReport& report) {
    const std::vector<uint32_t>& triangles = mesh.triangles;
    const size_t face_count = mesh.triangle_count();
    const size_t vertex_count = mesh.vertex_count();
    report = MeshReport();
    report.faces = face_count;

    // Flags as bytes rather than std::vector<bool>: cheaper random access on millions of entries.
    std::vector<uint8_t> proper(face_count, 0);
    DenseIndex<CornerSet, CornerSetHash> vertex_sets(face_count);
    DenseIndex<uint64_t, EdgeKeyHash> edge_index(3 * face_count / 2 + 1);
    std::vector<EdgeUse> edges;
    edges.reserve(3 * face_count / 2 + 1);
    std::vector<uint32_t> corner_edge(3 * face_count, UINT32_MAX);
    std::vector<uint8_t> vertex_used(vertex_count, 0);
    uint64_t proper_faces = 0;

    for (size_t f = 0; f < face_count; ++f) {
        const uint32_t* corner = &triangles[3 * f];
        bool new_set = false;
        vertex_sets.insert(sorted_corners(corner[0], corner[1], corner[2]), &new_set);
        if (!new_set) ++report.duplicate_faces;
        const bool repeated = corner[0] == corner[1] || corner[1] == corner[2] || corner[0] == corner[2];
        if (repeated || has_zero_area(mesh.positions, corner)) ++report.degenerate_faces;
        if (repeated) continue;
        proper[f] = 1;
        ++proper_faces;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t from = corner[k], to = corner[(k + 1) % 3];
            vertex_used[from] = 1;
            const uint64_t key = uint64_t(std::min(from, to)) << 32 | std::max(from, to);
            const uint32_t id = edge_index.insert(key);
            if (id == edges.size()) edges.emplace_back();
            EdgeUse& use = edges[id];
            if (use.count < 2) {
                use.face[use.count] = static_cast<uint32_t>(f);
                use.ascending[use.count] = from < to;
            }
            ++use.count;
            corner_edge[3 * f + k] = id;
        }
    }

    // Faces joined through any shared edge (one set per component); corners joined across manifold
    // edges (one set per fan).
    UnionFind components(face_count);
    UnionFind fans(3 * face_count);
    std::vector<uint32_t> boundary_corners;  // the two corners of each boundary edge, in its face
    std::vector<uint8_t> nonmanifold_vertex(vertex_count, 0);
    for (size_t f = 0; f < face_count; ++f) {
        if (!proper[f]) continue;
        for (uint32_t k = 0; k < 3; ++k) {
            const EdgeUse& use = edges[corner_edge[3 * f + k]];
            components.join(static_cast<uint32_t>(f), use.face[0]);
            // The rest looks at each edge once, from its first face.
            if (use.face[0] != f) continue;
            const uint32_t from = triangles[3 * f + k], to = triangles[3 * f + (k + 1) % 3];
            if (use.count == 1) {
                ++report.edges_boundary;
                boundary_corners.push_back(static_cast<uint32_t>(3 * f + k));
                boundary_corners.push_back(static_cast<uint32_t>(3 * f + (k + 1) % 3));
            } else if (use.count == 2) {
                ++report.edges_manifold;
                if (use.ascending[0] == use.ascending[1]) report.oriented = false;
                for (uint32_t vertex : {from, to}) {
                    fans.join(corner_of(triangles, use.face[0], vertex), corner_of(triangles, use.face[1], vertex));
                }
            } else {
                ++report.edges_nonmanifold;
                nonmanifold_vertex[from] = nonmanifold_vertex[to] = 1;
            }
        }
    }

    // Each fan is one set of corners with one root; a vertex with two roots among its corners is a bow-tie.
    std::vector<uint8_t> has_fan(vertex_count, 0);
    for (size_t f = 0; f < face_count; ++f) {
        if (!proper[f]) continue;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t corner = static_cast<uint32_t>(3 * f + k);
            if (fans.root(corner) != corner) continue;
            const uint32_t vertex = triangles[corner];
            if (has_fan[vertex]) nonmanifold_vertex[vertex] = 1;
            has_fan[vertex] = 1;
        }
    }
    // Boundary loops join boundary edges at their ends, each end being a fan rather than a vertex, so
    // that the two loops of a bow-tie vertex stay apart.
    UnionFind loops(3 * face_count);
    std::vector<uint8_t> on_loop(3 * face_count, 0);
    for (size_t i = 0; i < boundary_corners.size(); i += 2) {
        const uint32_t a = fans.root(boundary_corners[i]), b = fans.root(boundary_corners[i + 1]);
        loops.join(a, b);
        on_loop[a] = on_loop[b] = 1;
    }
    for (uint32_t node = 0; node < on_loop.size(); ++node) {
        if (on_loop[node] && loops.root(node) == node) ++report.boundary_loops;
    }
    for (size_t v = 0; v < vertex_count; ++v) {
        if (vertex_used[v]) ++report.vertices;
        if (nonmanifold_vertex[v]) ++report.vertices_nonmanifold;
    }
    for (size_t f = 0; f < face_count; ++f) {
        if (proper[f] && components.root(static_cast<uint32_t>(f)) == f) ++report.components;
    }
    report.vertices_isolated = vertex_count - report.vertices;
    const uint64_t edge_count = edges.size();
    report.euler_characteristic = int64_t(report.vertices) - int64_t(edge_count) + int64_t(proper_faces);
    const bool closed_manifold = report.edges_boundary == 0 && report.edges_nonmanifold == 0 && report.vertices_nonmanifold == 0;
    if (closed_manifold && report.oriented && report.components > 0) {
        // chi is additive over components, and each closed oriented component has chi_c = 2 - 2 g_c.
        report.genus = (2 * int64_t(report.components) - report.euler_characteristic) / 2;
    }
    return IoStatus::success();
}

template <class Action>
IoStatus guarded(Action&& action) {
    try {
        return action();
    } catch (const std::bad_alloc&) {
        return IoStatus::failure("out of memory");
    }
}

} // namespace

IoStatus make_mesh_report(const MeshData& mesh, MeshReport& report, VertexIdentity identity) {
    IoStatus status = check_arrays(mesh, "mesh");
    if (!status) return status;
    return guarded([&] {
        const std::vector<uint32_t> first = first_at_same_position(mesh);
        uint64_t duplicates = 0;
        for (size_t v = 0; v < first.size(); ++v) duplicates += first[v] != v;
        const bool weld = identity == VertexIdentity::position;
        const IoStatus computed = weld && duplicates > 0 ? compute(welded(mesh, first), report) : compute(mesh, report);
        report.vertices_welded = weld;
        report.duplicate_positions = duplicates;
        return computed;
    });
}

IoStatus add_face_recall(const MeshData& mesh, const MeshData& reference, MeshReport& report) {
    IoStatus status = check_arrays(mesh, "mesh");
    if (status) status = check_arrays(reference, "reference");
    if (!status) return status;
    return guarded([&] {
        // Number the mesh's distinct positions, then describe each triangle by its set of position numbers.
        DenseIndex<Triple, TripleHash> positions(mesh.vertex_count());
        std::vector<uint32_t> position_of(mesh.vertex_count());
        for (size_t v = 0; v < mesh.vertex_count(); ++v) position_of[v] = positions.insert(position_key(mesh.positions, v));
        DenseIndex<CornerSet, CornerSetHash> triangles(mesh.triangle_count());
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            const uint32_t* c = &mesh.triangles[3 * t];
            triangles.insert(sorted_corners(position_of[c[0]], position_of[c[1]], position_of[c[2]]));
        }
        uint64_t found = 0;
        for (size_t t = 0; t < reference.triangle_count(); ++t) {
            uint32_t ids[3];
            bool all_present = true;
            for (size_t k = 0; k < 3; ++k) {
                ids[k] = positions.find(position_key(reference.positions, reference.triangles[3 * t + k]));
                all_present = all_present && ids[k] != positions.NOT_FOUND;
            }
            if (all_present && triangles.find(sorted_corners(ids[0], ids[1], ids[2])) != triangles.NOT_FOUND) ++found;
        }
        report.reference_faces = reference.triangle_count();
        report.face_recall.reset();
        if (reference.triangle_count() > 0) report.face_recall = double(found) / double(reference.triangle_count());
        return IoStatus::success();
    });
}

IoStatus add_reference_distance(const MeshData& mesh, const MeshData& reference, MeshReport& report) {
    IoStatus status = check_arrays(mesh, "mesh");
    if (status) status = check_arrays(reference, "reference");
    if (!status) return status;
    return guarded([&] {
        double sides = 0;
        uint64_t count = 0;
        for (size_t t = 0; t < reference.triangle_count(); ++t) {
            for (size_t k = 0; k < 3; ++k) {
                const double* a = &reference.positions[3 * size_t(reference.triangles[3 * t + k])];
                const double* b = &reference.positions[3 * size_t(reference.triangles[3 * t + (k + 1) % 3])];
                const double length = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
                if (std::isfinite(length) && length > 0) {
                    sides += length;
                    ++count;
                }
            }
        }
        ReferenceDistance distance;
        if (count > 0 && std::isfinite(sides)) distance.side_mean = sides / double(count);
        distance.to_reference = surface_distance(mesh, reference);
        distance.from_reference = surface_distance(reference, mesh);
        report.reference_distance = distance;
        return IoStatus::success();
    });
}

IoStatus add_points_used(const MeshData& mesh, const MeshData& points, MeshReport& report) {
    IoStatus status = check_arrays(mesh, "mesh");
    if (!status) return status;
    if (points.positions.size() % 3 != 0) return IoStatus::failure("points: the position array's length is not a multiple of 3");
    return guarded([&] {
        DenseIndex<Triple, TripleHash> used(mesh.vertex_count());
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            const uint32_t* c = &mesh.triangles[3 * t];
            if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
            for (size_t k = 0; k < 3; ++k) used.insert(position_key(mesh.positions, c[k]));
        }
        uint64_t count = 0;
        for (size_t p = 0; p < points.vertex_count(); ++p) {
            if (used.find(position_key(points.positions, p)) != used.NOT_FOUND) ++count;
        }
        report.points_input = points.vertex_count();
        report.points_used = count;
        return IoStatus::success();
    });
}

std::string to_json(const MeshReport& report) {
    io::JsonObject json;
    json.add_unsigned("faces", report.faces)
        .add_unsigned("vertices", report.vertices)
        .add_unsigned("vertices_isolated", report.vertices_isolated)
        .add_bool("vertices_welded", report.vertices_welded)
        .add_unsigned(report.vertices_welded ? "vertices_merged" : "duplicate_positions", report.duplicate_positions)
        .add_unsigned("edges_manifold", report.edges_manifold)
        .add_unsigned("edges_boundary", report.edges_boundary)
        .add_unsigned("edges_nonmanifold", report.edges_nonmanifold)
        .add_unsigned("vertices_nonmanifold", report.vertices_nonmanifold)
        .add_unsigned("boundary_loops", report.boundary_loops)
        .add_unsigned("components", report.components)
        .add_bool("oriented", report.oriented)
        .add_integer("euler_characteristic", report.euler_characteristic);
    if (report.genus) json.add_integer("genus", *report.genus);
    else json.add_null("genus");
    json.add_unsigned("degenerate_faces", report.degenerate_faces).add_unsigned("duplicate_faces", report.duplicate_faces);
    if (report.reference_faces) {
        json.add_unsigned("reference_faces", *report.reference_faces);
        if (report.face_recall) json.add_number("face_recall", *report.face_recall);
        else json.add_null("face_recall");
    }
    if (const std::optional<ReferenceDistance>& distance = report.reference_distance) {
        const auto add_distance = [&](const char* max_key, const char* mean_key, const std::optional<SurfaceDistance>& d) {
            if (d) json.add_number(max_key, d->max).add_number(mean_key, d->mean);
            else json.add_null(max_key).add_null(mean_key);
        };
        if (distance->side_mean) json.add_number("reference_side_mean", *distance->side_mean);
        else json.add_null("reference_side_mean");
        add_distance("distance_to_reference_max", "distance_to_reference_mean", distance->to_reference);
        add_distance("distance_from_reference_max", "distance_from_reference_mean", distance->from_reference);
    }
    if (report.points_input) json.add_unsigned("points_input", *report.points_input).add_unsigned("points_used", *report.points_used);
    return json.str() + "\n";
}

} // namespace dbrg::measure
