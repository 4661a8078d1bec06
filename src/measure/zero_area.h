// Whether a triangle has zero area, decided exactly for finite coordinates of any size: the mesh report's
// degenerate faces, where a file's coordinates carry none of the promises the core's predicates rely on.
#pragma once

#include <stdint.h>

#include <vector>

namespace dbrg::measure {

// True when the corners of the triangle `corner` (three indices into the x, y, z triples `positions`) are
// collinear. A corner with a NaN or infinite coordinate has no area to speak of: false.
bool has_zero_area(const std::vector<double>& positions, const uint32_t* corner);

} // namespace dbrg::measure
