// Parameters: the defaults of dbrg_params (the paper's values where it gives one) and their range checks.
#pragma once

#include "dbrg/dbrg.h"

namespace dbrg {

// Fills every field of `params` with its default and sets struct_size.
void fill_default_params(dbrg_params& params);

// Returns a sentence naming the first field out of range, or nullptr when all are valid.
const char* find_parameter_problem(const dbrg_params& params);

} // namespace dbrg
