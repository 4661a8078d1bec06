// Canonical order of the finite tetrahedra (see canonical_order.h).
#include "delaunay/canonical_order.h"

#include <algorithm>

namespace dbrg {

dbrg_status write_canonical_tetrahedra(const Tetrahedralization& delaunay, const uint32_t* input_index,
                                       const ProgressSpan& progress, Array<uint32_t>& tets, Array<uint32_t>& adjacency) {
    // Finite tetrahedra are numbered in the order of their canonical corners (counting sort by the first,
    // then the few that share it by the other three), and written with their corners in that order: the
    // output is the same whichever slots construction left them in (threads leave them in other slots).
    const uint32_t slots = delaunay.tet_slots();
    const auto corners = [&](uint32_t t, uint32_t local[4], uint32_t vertex[4]) {
        delaunay.canonical_corners(t, local);
        for (uint32_t i = 0; i < 4; ++i) vertex[i] = delaunay.tet_vertex(t, local[i]);
    };
    Array<uint32_t> bucket_end(progress.context().memory);  // per smallest corner
    Array<uint32_t> order(progress.context().memory);
    Array<uint32_t> number(progress.context().memory);
    if (!bucket_end.resize(size_t(delaunay.vertex_count()) + 1, 0) || !number.resize(slots, DBRG_NO_NEIGHBOR)) {
        return progress.context().fail_out_of_memory();
    }
    // The first canonical corner is the smallest vertex: the counting sort needs no more than that.
    const auto smallest = [&](uint32_t t) {
        return std::min(std::min(delaunay.tet_vertex(t, 0), delaunay.tet_vertex(t, 1)),
                        std::min(delaunay.tet_vertex(t, 2), delaunay.tet_vertex(t, 3)));
    };
    // A vertex's bucket takes about a microsecond to sort, a tetrahedron's corners a few hundred nanoseconds
    // to put in canonical order: those loops report more often than every STEP_ITEMS.
    const ProgressSpan counting = progress.part(0.0, 0.1), ordering = progress.part(0.1, 0.2),
                       sorting = progress.part(0.2, 0.6), numbering = progress.part(0.6, 0.65),
                       writing = progress.part(0.65, 1.0);
    const size_t VERTICES_PER_REPORT = 1 << 14, TETS_PER_REPORT = 1 << 16;
    uint32_t local[4], vertex[4], finite = 0;
    for (uint32_t t = 0; t < slots; ++t) {
        DBRG_PROPAGATE(counting.report_at(t, slots));
        if (delaunay.tet_is_free(t) || !delaunay.tet_is_finite(t)) continue;
        ++bucket_end[smallest(t) + 1];
        ++finite;
    }
    for (size_t v = 1; v < bucket_end.size(); ++v) bucket_end[v] += bucket_end[v - 1];
    if (!order.resize(finite)) return progress.context().fail_out_of_memory();
    for (uint32_t t = 0; t < slots; ++t) {
        DBRG_PROPAGATE(ordering.report_at(t, slots));
        if (delaunay.tet_is_free(t) || !delaunay.tet_is_finite(t)) continue;
        order[bucket_end[smallest(t)]++] = t;  // bucket_end[v] ends as the end of v's bucket
    }
    // Within a bucket, by the other three corners, each tetrahedron's computed once.
    struct Keyed {
        uint32_t rest[3];
        uint32_t slot;
    };
    Array<Keyed> bucket(progress.context().memory);
    for (size_t v = 0, begin = 0; v < delaunay.vertex_count(); begin = bucket_end[v++]) {
        DBRG_PROPAGATE(sorting.report_at(v, delaunay.vertex_count(), VERTICES_PER_REPORT));
        bucket.clear();
        for (size_t i = begin; i < bucket_end[v]; ++i) {
            corners(order[i], local, vertex);
            if (!bucket.push_back(Keyed{{vertex[1], vertex[2], vertex[3]}, order[i]})) return progress.context().fail_out_of_memory();
        }
        std::sort(bucket.begin(), bucket.end(), [](const Keyed& x, const Keyed& y) {
            return std::lexicographical_compare(x.rest, x.rest + 3, y.rest, y.rest + 3);
        });
        for (size_t i = begin; i < bucket_end[v]; ++i) order[i] = bucket[i - begin].slot;
    }
    for (uint32_t i = 0; i < finite; ++i) {
        DBRG_PROPAGATE(numbering.report_at(i, finite));
        number[order[i]] = i;
    }
    // Not filled first: that would touch every page in one go, between two reports; written in order,
    // they are touched a step at a time.
    if (!tets.reserve(4 * size_t(finite)) || !adjacency.reserve(4 * size_t(finite))) {
        return progress.context().fail_out_of_memory();
    }
    tets.resize_unwritten(4 * size_t(finite));
    adjacency.resize_unwritten(4 * size_t(finite));
    for (uint32_t i = 0; i < finite; ++i) {
        DBRG_PROPAGATE(writing.report_at(i, finite, TETS_PER_REPORT));
        corners(order[i], local, vertex);
        for (uint32_t k = 0; k < 4; ++k) {
            tets[4 * size_t(i) + k] = input_index[vertex[k]];
            adjacency[4 * size_t(i) + k] = number[delaunay.tet_adjacent(order[i], local[k])];
        }
    }
    return DBRG_OK;
}

} // namespace dbrg
