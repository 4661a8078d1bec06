// The public header compiles as C++ and keeps its ABI promises: struct_size first, pinned enum values.
#include "dbrg/dbrg.h"

#include <cstddef>

static_assert(offsetof(dbrg_params, struct_size) == 0, "params begin with struct_size");
static_assert(offsetof(dbrg_stats, struct_size) == 0, "stats begin with struct_size");
static_assert(DBRG_OK == 0 && DBRG_ERR_INVALID_ARGUMENT == 1 && DBRG_ERR_INTERNAL == 10, "status values are pinned");
static_assert(DBRG_VERSION_NUMBER == DBRG_VERSION_MAJOR * 10000 + DBRG_VERSION_MINOR * 100 + DBRG_VERSION_PATCH,
              "version number is derived from its parts");

int main() { return dbrg_version_number() == DBRG_VERSION_NUMBER ? 0 : 1; }
