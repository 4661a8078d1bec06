// Fuzz target: point conditioning and the built-in Delaunay tetrahedralization on produced points. Every
// point set the conditioning accepts must tetrahedralize, pass validate() (adjacency, orientation, local
// Delaunay property, hull convexity, Euler characteristic) and use every distinct point as a vertex.
#include <math.h>

#include <string>

#include "core/array.h"
#include "core/context.h"
#include "points/point_input.h"
#include "points/point_conditioning.h"
#include "delaunay/tetrahedralization.h"
#include "fuzz_check.h"
#include "fuzz_input.h"
#include "point_producer.h"

using namespace dbrg;
using namespace dbrg::fuzz;

namespace {

const size_t MAX_POINTS = 3000;

// Distinct, sorted, and each a caller point moved by the recorded transform, which on the grid is exact and
// brings the largest extent into [0.5, 1).
void check_conditioned(const ConditionedPoints& conditioned, const PointSet& set) {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (uint32_t v = 0; v < conditioned.size(); ++v) {
        const double* p = conditioned.point(v);
        FUZZ_CHECK(conditioned.input_index[v] < set.count());
        if (v > 0) FUZZ_CHECK_WHY(compare_points(conditioned.point(v - 1), p) < 0, "conditioned points not strictly increasing");
        for (int k = 0; k < 3; ++k) {
            FUZZ_CHECK(p[k] > -2.0 && p[k] < 2.0);
            lo[k] = v == 0 || p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = v == 0 || p[k] > hi[k] ? p[k] : hi[k];
        }
        // Grid coordinates cannot round: steps are at least 2^-64 and extents below 2^71.
        if (!set.on_grid) continue;
        const double* original = &set.xyz[3 * conditioned.input_index[v]];
        for (int k = 0; k < 3; ++k) {
            FUZZ_CHECK_WHY(ldexp(original[k] - conditioned.origin[k], conditioned.scale_exponent) == p[k],
                           "a conditioned point is not its caller point under the recorded transform");
        }
    }
    if (!set.on_grid) return;
    double extent = 0;
    for (int k = 0; k < 3; ++k) extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
    FUZZ_CHECK(extent >= 0.5 && extent < 1.0);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzInput input(data, size);
    const PointSet set = produce_points(input, MAX_POINTS);

    // No allocator and no progress callback; the stages below read nothing else of the parameters.
    dbrg_params params{};
    params.struct_size = sizeof params;
    Context context(params);
    Array<double> xyz(context.memory);
    // Statuses of rejected input are fuzz_reconstruct's business; here only accepted sets matter.
    if (copy_caller_points(&set.points(), context, xyz) != DBRG_OK) return 0;
    ConditionedPoints conditioned(context.memory);
    const dbrg_status status = condition_points(xyz.data(), set.count(), context, conditioned);
    if (status != DBRG_OK) {
        FUZZ_CHECK_WHY(status == DBRG_ERR_TOO_FEW_POINTS || status == DBRG_ERR_DEGENERATE_INPUT, context.message());
        FUZZ_CHECK(conditioned.size() == 0);
        return 0;
    }
    FUZZ_CHECK(conditioned.size() >= 4 && conditioned.size() + conditioned.duplicates_merged == set.count());
    check_conditioned(conditioned, set);
    if (conditioned.flat) {  // no tetrahedra: the flat path of reconstruction is fuzz_reconstruct's
        FUZZ_CHECK(refuse_flat(conditioned, set.count(), context) == DBRG_ERR_DEGENERATE_INPUT);
        return 0;
    }

    Tetrahedralization delaunay(context.memory);
    const dbrg_status built = delaunay.build(conditioned.coordinates.data(), conditioned.size(), context);
    FUZZ_CHECK_WHY(built == DBRG_OK, (std::to_string(built) + ": " + context.message()).c_str());
    char message[256] = "";
    FUZZ_CHECK_WHY(delaunay.validate(message, sizeof message), message);
    FUZZ_CHECK(delaunay.vertex_count() == conditioned.size());
    FUZZ_CHECK(delaunay.finite_tet_count() > 0);
    for (uint32_t v = 0; v < delaunay.vertex_count(); ++v) {
        FUZZ_CHECK_WHY(delaunay.tet_local_index(delaunay.vertex_tet(v), v) < 4, "a point is not a vertex of its tetrahedron");
    }
    return 0;
}
