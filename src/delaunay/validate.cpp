// Tetrahedralization validation: adjacency, orientation, the empty-sphere property with the same
// perturbed predicates as construction, hull convexity and the Euler characteristic.
#include <stdarg.h>
#include <stdio.h>

#include <algorithm>

#include "delaunay/tetrahedralization.h"

namespace dbrg {
namespace {

bool report(char* message, size_t capacity, const char* format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

bool report(char* message, size_t capacity, const char* format, ...) {
    if (message && capacity > 0) {
        va_list args;
        va_start(args, format);
        vsnprintf(message, capacity, format, args);
        va_end(args);
    }
    return false;
}

} // namespace

bool Tetrahedralization::validate(char* message, size_t message_capacity) const {
    if (message && message_capacity > 0) message[0] = '\0';
    const uint32_t slots = tet_slots();
    if (adjacency_.size() != vertices_.size()) {
        return report(message, message_capacity, "the vertex and adjacency arrays differ in size");
    }
    if (vertex_count_ < 4 || slots == 0) return report(message, message_capacity, "the tetrahedralization is empty");
    PredicateCounters local;
    uint64_t finite = 0, finite_faces = 0;

    for (uint32_t t = 0; t < slots; ++t) {
        if (tet_is_free(t)) continue;
        // Vertices: valid, distinct, the infinite one only in slot 3.
        for (uint32_t lv = 0; lv < 4; ++lv) {
            const uint32_t w = tet_vertex(t, lv);
            if (w == INFINITE_VERTEX ? lv != 3 : w >= vertex_count_) {
                return report(message, message_capacity, "tet %u has an invalid vertex %u in slot %u", t, w, lv);
            }
            for (uint32_t lu = 0; lu < lv; ++lu) {
                if (tet_vertex(t, lu) == w) return report(message, message_capacity, "tet %u repeats vertex %u", t, w);
            }
        }
        const bool is_finite = tet_is_finite(t);
        finite += is_finite;
        const double* p[4];
        for (uint32_t lv = 0; lv < 4; ++lv) p[lv] = tet_vertex(t, lv) == INFINITE_VERTEX ? nullptr : point(tet_vertex(t, lv));
        if (is_finite && orient3d(p[0], p[1], p[2], p[3], local) <= 0) {
            return report(message, message_capacity, "finite tet %u (%u %u %u %u) is not positively oriented", t,
                          tet_vertex(t, 0), tet_vertex(t, 1), tet_vertex(t, 2), tet_vertex(t, 3));
        }

        for (uint32_t lf = 0; lf < 4; ++lf) {
            const uint32_t n = tet_adjacent(t, lf);
            const uint32_t g = tet_adjacent_face(t, lf);
            if (n >= slots || tet_is_free(n) || n == t) {
                return report(message, message_capacity, "tet %u face %u has no valid neighbour (%u)", t, lf, n);
            }
            if (tet_adjacent(n, g) != t || tet_adjacent_face(n, g) != lf) {
                return report(message, message_capacity, "adjacency of tet %u face %u and tet %u face %u is not mutual",
                              t, lf, n, g);
            }
            // The shared face: the same three vertices on both sides.
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t w = tet_vertex(t, FACE_VERTEX[lf][k]);
                if (tet_local_index(n, w) == NO_LOCAL_INDEX || tet_local_index(n, w) == g) {
                    return report(message, message_capacity, "tet %u face %u and tet %u face %u are different triangles",
                                  t, lf, n, g);
                }
            }
            const uint32_t w = tet_vertex(n, g);  // the vertex across face lf
            if ((is_finite || lf == 3) && t < n) ++finite_faces;  // a face without the infinite vertex, once
            if (w == INFINITE_VERTEX) continue;  // nothing to check against a point at infinity
            const double* q = point(w);
            if (is_finite) {
                if (insphere_sos(p[0], p[1], p[2], p[3], q, local) > 0) {
                    return report(message, message_capacity,
                                  "face %u of tet %u is not locally Delaunay: vertex %u of tet %u is inside its circumsphere",
                                  lf, t, w, n);
                }
            } else {
                // Convexity at a hull edge: the neighbour's apex must not see the hull face of t.
                const int side = orient3d(p[0], p[1], p[2], q, local);
                if (side > 0 || (side == 0 && incircle3d_sos(p[0], p[1], p[2], q, local) > 0)) {
                    return report(message, message_capacity,
                                  "the hull is not convex (or not Delaunay) at hull face %u %u %u: vertex %u sees it",
                                  tet_vertex(t, 0), tet_vertex(t, 1), tet_vertex(t, 2), w);
                }
            }
        }
    }
    if (finite != finite_tets_) {
        return report(message, message_capacity, "%llu finite tets found but %u counted",
                      static_cast<unsigned long long>(finite), finite_tets_);
    }
    if (vertex_tet_.size() != vertex_count_) return report(message, message_capacity, "vertex_tet has the wrong size");
    for (uint32_t v = 0; v < vertex_count_; ++v) {
        const uint32_t t = vertex_tet_[v];
        if (t >= slots || tet_is_free(t) || tet_local_index(t, v) == NO_LOCAL_INDEX) {
            return report(message, message_capacity, "vertex %u is in no tetrahedron (vertex_tet %u)", v, t);
        }
    }

    // Euler characteristic of the finite complex (a triangulated ball): V - E + F - T = 1. Edges are
    // counted by sorting the six edges of every finite tetrahedron.
    Array<uint64_t> edges(vertices_.memory());
    if (!edges.reserve(6 * finite)) return report(message, message_capacity, "out of memory while validating");
    for (uint32_t t = 0; t < slots; ++t) {
        if (tet_is_free(t) || !tet_is_finite(t)) continue;
        for (uint32_t i = 0; i < 4; ++i) {
            for (uint32_t j = i + 1; j < 4; ++j) {
                uint64_t a = tet_vertex(t, i), b = tet_vertex(t, j);
                if (a > b) std::swap(a, b);
                edges.push_back(a << 32 | b);
            }
        }
    }
    std::sort(edges.begin(), edges.end());
    const uint64_t edge_count = static_cast<uint64_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
    const int64_t euler = int64_t(vertex_count_) - int64_t(edge_count) + int64_t(finite_faces) - int64_t(finite);
    if (euler != 1) {
        return report(message, message_capacity, "Euler characteristic V - E + F - T = %u - %llu + %llu - %llu = %lld, not 1",
                      vertex_count_, static_cast<unsigned long long>(edge_count),
                      static_cast<unsigned long long>(finite_faces), static_cast<unsigned long long>(finite),
                      static_cast<long long>(euler));
    }
    return true;
}

} // namespace dbrg
