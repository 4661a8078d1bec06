// Parameters: the defaults of dbrg_params (the paper's values where it gives one) and their range checks.
#include "core/params.h"

#include <math.h>
#include <string.h>

#include "core/c_enum.h"
#include "core/pi.h"

namespace dbrg {

void fill_default_params(dbrg_params& params) {
    memset(&params, 0, sizeof params);
    params.struct_size = sizeof params;
    params.sliver_angle = 5.0 * PI / 6.0;  // paper §3.1.2
    params.boundary_factor = 3.0;
    params.boundary_mean = DBRG_BOUNDARY_MEAN_GLOBAL;  // paper §4; measured better on the bunny (README)
    params.fill_holes = 1;
    params.max_hole_edges = 256;
    params.max_components = 64;
    params.backend = DBRG_BACKEND_BUILTIN;
    params.threads = 0;
}

const char* find_parameter_problem(const dbrg_params& params) {
    if (!(params.sliver_angle > PI / 2 && params.sliver_angle < PI)) {
        return "sliver_angle must lie strictly between pi/2 and pi radians";
    }
    if (!(params.boundary_factor == 0 || (params.boundary_factor > 1 && isfinite(params.boundary_factor)))) {
        return "boundary_factor must be 0 (off) or a finite number greater than 1";
    }
    const int mean = c_enum_value(params.boundary_mean);
    if (mean != DBRG_BOUNDARY_MEAN_LOCAL && mean != DBRG_BOUNDARY_MEAN_GLOBAL) {
        return "boundary_mean must be DBRG_BOUNDARY_MEAN_LOCAL or DBRG_BOUNDARY_MEAN_GLOBAL";
    }
    if (params.max_hole_edges < 3) return "max_hole_edges must be at least 3";
    if (params.max_components < 1) return "max_components must be at least 1";
    const int backend = c_enum_value(params.backend);
    if (backend != DBRG_BACKEND_BUILTIN && backend != DBRG_BACKEND_TETGEN) {
        return "backend must be DBRG_BACKEND_BUILTIN or DBRG_BACKEND_TETGEN";
    }
    const bool allocator_complete = !params.allocator || (params.allocator->allocate && params.allocator->reallocate &&
                                                          params.allocator->deallocate);
    if (!allocator_complete) return "allocator must provide allocate, reallocate and deallocate (or be NULL)";
    if (params.reserved != 0) return "reserved must be 0";
    const int cleaning = c_enum_value(params.cleaning);
    if (cleaning != DBRG_CLEANING_AUTO && cleaning != DBRG_CLEANING_OFF && cleaning != DBRG_CLEANING_ON) {
        return "cleaning must be DBRG_CLEANING_AUTO, DBRG_CLEANING_OFF or DBRG_CLEANING_ON";
    }
    return nullptr;
}

} // namespace dbrg
