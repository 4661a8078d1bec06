// Local fit: a point's neighbourhood approximated by a height function over its tangent plane, for the
// cleaning stage's noise estimate and smoothing.
//
// Based on: F. Cazals, M. Pouget, "Estimating differential quantities using polynomial fitting of
// osculating jets" (SGP 2003), at degree 2.
#pragma once

#include <stdint.h>

#include "core/vec3.h"

namespace dbrg {

struct LocalFit {
    Vec3 normal;    // unit normal of the tangent plane (principal component of least variance), either sign
    double height;  // the fitted surface's height above the point along `normal`: the point projected is
                    // point + height * normal
    double rms;     // root mean square of the fit's residuals over the points fitted
};

// Fits z = c0 + c1 x + c2 y + c3 x^2 + c4 x y + c5 y^2 over `count` points given by their offsets from the
// point fitted around (its own offset, zero, among them), in the frame of their principal components, by
// least squares. Offsets, not positions: moving the cloud changes nothing in the fit. Falls back to the
// plane of the principal components when the points are too few or too degenerate for the quadric (fewer
// than 6, or all on a curve). `count` is at least 1.
LocalFit fit_local_quadric(const Vec3* offsets, uint32_t count);

} // namespace dbrg
