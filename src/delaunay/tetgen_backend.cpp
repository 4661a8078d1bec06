// TetGen backend: runs TetGen on the points and converts its tetrahedra and neighbours into the
// Tetrahedralization store, adding the infinite tetrahedra behind the hull. The only file of the
// library built with C++ exceptions, because TetGen reports errors by throwing; none escapes it.
#include "delaunay/tetgen_backend.h"

#include <tetgen.h>

#include <algorithm>
#include <new>

#include "core/status.h"
#include "points/point_input.h"

namespace dbrg {
namespace {

struct HullEdge {
    uint32_t a, b;   // a < b
    uint32_t tet;    // an infinite tetrahedron
    uint32_t face;   // its local face through the edge and the infinite vertex
};

// TetGen frees the point list it is given; this keeps it away from ours.
struct BorrowedPoints {
    tetgenio& io;
    ~BorrowedPoints() { io.pointlist = nullptr; }
};

} // namespace

class TetgenImporter {
public:
    static dbrg_status import(const tetgenio& result, const double* points, uint32_t count, Context& context,
                              Tetrahedralization& out);
};

dbrg_status TetgenImporter::import(const tetgenio& result, const double* points, uint32_t count, Context& context,
                                   Tetrahedralization& out) {
    if (result.numberofpoints != static_cast<int>(count) || result.numberofcorners != 4 || !result.neighborlist ||
        result.numberoftetrahedra <= 0) {
        return context.fail(DBRG_ERR_INTERNAL, "TetGen returned %d points and %d tetrahedra for %u points",
                            result.numberofpoints, result.numberoftetrahedra, count);
    }
    out.points_ = points;
    out.vertex_count_ = count;
    const uint32_t finite = static_cast<uint32_t>(result.numberoftetrahedra);
    const int* tl = result.tetrahedronlist;
    const int* nl = result.neighborlist;

    // Finite tetrahedra first, positively oriented (TetGen's orientation convention is the opposite
    // of ours; checked per tetrahedron rather than assumed).
    uint32_t hull_faces = 0;
    for (uint32_t t = 0; t < finite; ++t) {
        for (int k = 0; k < 4; ++k) hull_faces += nl[4 * size_t(t) + k] < 0;
    }
    const size_t slots = size_t(finite) + hull_faces;
    if (slots >= MAX_TET_SLOTS) {
        return context.fail(DBRG_ERR_TOO_MANY_POINTS, "the tetrahedralization needs more than 2^30 tetrahedra");
    }
    Array<uint32_t>& vertices = out.vertices_;
    Array<uint32_t>& adjacency = out.adjacency_;
    if (!vertices.resize(4 * slots) || !adjacency.resize(4 * slots, NO_TET)) return context.fail_out_of_memory();
    for (uint32_t t = 0; t < finite; ++t) {
        uint32_t* tv = &vertices[4 * size_t(t)];
        for (int k = 0; k < 4; ++k) tv[k] = static_cast<uint32_t>(tl[4 * size_t(t) + k]);
        if (orient3d(out.point(tv[0]), out.point(tv[1]), out.point(tv[2]), out.point(tv[3]), out.counters) < 0) {
            std::swap(tv[0], tv[1]);
        }
    }
    // Neighbours, matched by vertex sets so that TetGen's face numbering does not matter; the faces of
    // t left without a neighbour are on the hull and get an infinite tetrahedron each.
    uint32_t next_infinite = finite;
    Array<HullEdge> hull_edges(context.memory);
    if (!hull_edges.reserve(3 * size_t(hull_faces))) return context.fail_out_of_memory();
    for (uint32_t t = 0; t < finite; ++t) {
        const uint32_t* tv = &vertices[4 * size_t(t)];
        for (int k = 0; k < 4; ++k) {
            const int neighbour = nl[4 * size_t(t) + k];
            if (neighbour < 0) continue;
            const uint32_t n = static_cast<uint32_t>(neighbour);
            uint32_t lf = NO_LOCAL_INDEX, g = NO_LOCAL_INDEX;
            for (uint32_t lv = 0; lv < 4; ++lv) {
                if (out.tet_local_index(n, tv[lv]) == NO_LOCAL_INDEX) lf = lv;
                if (out.tet_local_index(t, vertices[4 * size_t(n) + lv]) == NO_LOCAL_INDEX) g = lv;
            }
            if (lf == NO_LOCAL_INDEX || g == NO_LOCAL_INDEX) {
                return context.fail(DBRG_ERR_INTERNAL, "TetGen neighbours %u and %u share no face", t, n);
            }
            adjacency[4 * size_t(t) + lf] = n << 2 | g;
        }
        for (uint32_t lf = 0; lf < 4; ++lf) {
            if (adjacency[4 * size_t(t) + lf] != NO_TET) continue;
            const uint32_t s = next_infinite++;
            uint32_t* iv = &vertices[4 * size_t(s)];
            infinite_tet_behind(tv, lf, iv);
            adjacency[4 * size_t(t) + lf] = s << 2 | 3;
            adjacency[4 * size_t(s) + 3] = t << 2 | lf;
            for (uint32_t f = 0; f < 3; ++f) {
                const uint32_t a = iv[(f + 1) % 3], b = iv[(f + 2) % 3];
                hull_edges.push_back(HullEdge{a < b ? a : b, a < b ? b : a, s, f});
            }
        }
    }
    if (next_infinite != slots) return context.fail(DBRG_ERR_INTERNAL, "TetGen's neighbour lists are inconsistent");
    // Infinite tetrahedra meet across the hull edges: sorted by edge, they come in pairs.
    std::sort(hull_edges.begin(), hull_edges.end(), [](const HullEdge& x, const HullEdge& y) {
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    for (size_t i = 0; i < hull_edges.size(); i += 2) {
        const HullEdge& x = hull_edges[i];
        if (i + 1 >= hull_edges.size() || hull_edges[i + 1].a != x.a || hull_edges[i + 1].b != x.b ||
            (i + 2 < hull_edges.size() && hull_edges[i + 2].a == x.a && hull_edges[i + 2].b == x.b)) {
            return context.fail(DBRG_ERR_INTERNAL, "TetGen's hull is not a closed manifold at edge %u %u", x.a, x.b);
        }
        const HullEdge& y = hull_edges[i + 1];
        adjacency[4 * size_t(x.tet) + x.face] = y.tet << 2 | y.face;
        adjacency[4 * size_t(y.tet) + y.face] = x.tet << 2 | x.face;
    }
    out.finite_tets_ = finite;
    if (!out.index_vertex_tets()) return context.fail_out_of_memory();
    for (uint32_t v = 0; v < count; ++v) {
        if (out.vertex_tet_[v] == NO_TET) {
            return context.fail(DBRG_ERR_INTERNAL, "TetGen left point %u out of the tetrahedralization", v);
        }
    }
    return DBRG_OK;
}

bool tetgen_available() { return true; }

dbrg_status check_tetgen(Context&) { return DBRG_OK; }

dbrg_status build_with_tetgen(const double* points, uint32_t count, Context& context, Tetrahedralization& out) {
    out.clear();
    DBRG_PROPAGATE(check_point_count(count, context));
    if (count > static_cast<uint32_t>(INT32_MAX / 3)) {
        return context.fail(DBRG_ERR_TOO_MANY_POINTS, "%u points given; the TetGen backend takes at most %d",
                            count, INT32_MAX / 3);
    }
    out.counters = PredicateCounters();
    const double start = seconds_now();
    dbrg_status status = DBRG_OK;
    try {
        tetgenio input, result;
        BorrowedPoints borrowed{input};
        input.firstnumber = 0;
        input.numberofpoints = static_cast<int>(count);
        input.pointlist = const_cast<double*>(points);  // TetGen only reads it
        char switches[] = "Qnz";                         // quiet, neighbours, zero-based indices
        tetrahedralize(switches, &input, &result);
        status = context.report(DBRG_STAGE_DELAUNAY, 0.5);
        if (status == DBRG_OK) status = TetgenImporter::import(result, points, count, context, out);
    } catch (const std::bad_alloc&) {
        status = context.fail(DBRG_ERR_OUT_OF_MEMORY, "TetGen ran out of memory");
    } catch (int code) {
        status = context.fail(code == 1 ? DBRG_ERR_OUT_OF_MEMORY : DBRG_ERR_INTERNAL, "TetGen stopped with error code %d",
                              code);
    } catch (...) {
        status = context.fail(DBRG_ERR_INTERNAL, "TetGen failed with an exception");
    }
    if (status == DBRG_OK) status = context.report(DBRG_STAGE_DELAUNAY, 1.0);
    context.stats.seconds_delaunay += seconds_now() - start;
    if (status != DBRG_OK) {
        out.clear();
        return status;
    }
    context.stats.tetrahedra = out.finite_tet_count();
    return DBRG_OK;
}

} // namespace dbrg
