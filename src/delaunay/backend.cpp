// Delaunay backend choice: hands the points to the built-in engine or to the TetGen adapter.
#include "delaunay/backend.h"

#include "delaunay/tetgen_backend.h"

namespace dbrg {

dbrg_status build_tetrahedralization(dbrg_backend backend, const double* points, uint32_t count, PointOrder order,
                                     Context& context, Tetrahedralization& out) {
    if (backend == DBRG_BACKEND_TETGEN) return build_with_tetgen(points, count, context, out);
    return out.build(points, count, context, order);
}

dbrg_status check_backend(dbrg_backend backend, Context& context) {
    return backend == DBRG_BACKEND_TETGEN ? check_tetgen(context) : DBRG_OK;
}

} // namespace dbrg
