// Status plumbing: errors travel as dbrg_status return values with a message on the context.
#pragma once

#include "dbrg/dbrg.h"

// Evaluates an expression yielding dbrg_status and returns it from the enclosing function unless OK.
#define DBRG_PROPAGATE(expression)                     \
    do {                                               \
        const dbrg_status dbrg_status_ = (expression); \
        if (dbrg_status_ != DBRG_OK) return dbrg_status_; \
    } while (0)
