// TetGen backend, absent: builds configured without -Dtetgen=enabled answer DBRG_ERR_UNSUPPORTED.
#include "delaunay/tetgen_backend.h"

namespace dbrg {

bool tetgen_available() { return false; }

dbrg_status check_tetgen(Context& context) {
    return context.fail(DBRG_ERR_UNSUPPORTED, "this build of dbrg has no TetGen backend (configure with -Dtetgen=enabled)");
}

dbrg_status build_with_tetgen(const double*, uint32_t, Context& context, Tetrahedralization& out) {
    out.clear();
    return check_tetgen(context);
}

} // namespace dbrg
