// The fuzzers' point producer: fuzz bytes -> a point set in the caller layout dbrg accepts (float32 or
// float64, odd strides, misaligned start), with coordinates snapped to a small integer grid so that
// duplicate, collinear, coplanar and cospherical points are common, and occasional raw doubles (NaN,
// infinities, huge, tiny, subnormal).
//
// Byte layout (fuzz/make_seeds.py writes seeds in it):
//   byte 0  bit 0: float32 (else float64); bits 1-4: padding bytes after each point; bits 5-7: bytes
//           between the start of the buffer and the first point
//   byte 1  bits 0-2: grid size, one of 2 3 4 5 7 16 64 256; bit 3: bytes 254 and 255 are escapes
//   byte 2  the grid step is 2^(byte 2 % 128 - 64)
//   then one byte per coordinate, three per point, until the input ends: (byte % grid - grid / 2) steps;
//   with escapes on, 255 takes the next byte as an index into a table of special values and 254 takes
//   the next eight bytes as the bits of a double.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include <vector>

#include "fuzz_input.h"
#include "support/point_layout.h"

namespace dbrg::fuzz {

struct PointSet {
    // Coordinates as the library reads them (float32 values widened to double).
    std::vector<double> xyz;
    // When on_grid: xyz[i] == grid[i] * 2^exponent exactly, |grid[i]| <= 128, so exact integer
    // geometry (coplanarity, collinearity) can judge the library's answers.
    bool on_grid = true;
    std::vector<int32_t> grid;
    int exponent = 0;
    bool finite = true;
    // The same coordinates in the caller's layout.
    test::StoredPoints stored;

    size_t count() const { return xyz.size() / 3; }
    const dbrg_points& points() const { return stored.points(); }
    const test::PointLayout& layout() const { return stored.layout(); }
};

// Reads a point set from the input (at most max_points points).
PointSet produce_points(FuzzInput& input, size_t max_points);

} // namespace dbrg::fuzz
