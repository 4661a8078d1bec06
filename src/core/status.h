// Status plumbing: errors travel as dbrg_status return values with a message on the context.
#pragma once

#include "dbrg/dbrg.h"

// Returns `status` from the enclosing function when `condition` holds.
#define DBRG_RETURN_IF(condition, status) \
    do {                                   \
        if (condition) return (status);    \
    } while (0)

// Evaluates an expression yielding dbrg_status and returns it from the enclosing function unless OK.
#define DBRG_PROPAGATE(expression)                     \
    do {                                               \
        const dbrg_status dbrg_status_ = (expression); \
        if (dbrg_status_ != DBRG_OK) return dbrg_status_; \
    } while (0)

// Returns DBRG_ERR_OUT_OF_MEMORY from the enclosing function when a growth call reports failure.
#define DBRG_TRY_GROW(expression) DBRG_RETURN_IF(!(expression), DBRG_ERR_OUT_OF_MEMORY)
