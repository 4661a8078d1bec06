// Affine checks: exact tests for collinear triples, built on orient3d, for the degeneracy checks of
// point conditioning and the choice of the first tetrahedron.
#pragma once

#include "predicates/predicates.h"

namespace dbrg {

// True when a, b, c lie on one line (exact). Three points span a plane unless they are collinear, and
// no plane holds all four corners of the unit frame, so a, b, c are collinear exactly when every one
// of those corners is coplanar with them.
inline bool points_collinear(const double* a, const double* b, const double* c, PredicateCounters& counters) {
    static const double frame[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const double* q : frame) {
        if (orient3d(a, b, c, q, counters) != 0) return false;
    }
    return true;
}

} // namespace dbrg
