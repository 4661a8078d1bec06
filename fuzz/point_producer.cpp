// The fuzzers' point producer: fuzz bytes -> a grid-snapped point set in a caller layout (see the header).
#include "point_producer.h"

#include <math.h>

#include <cfloat>
#include <limits>

namespace dbrg::fuzz {
namespace {

const int GRID_SIZES[8] = {2, 3, 4, 5, 7, 16, 64, 256};
const uint8_t ESCAPE_SPECIAL = 255;
const uint8_t ESCAPE_RAW = 254;

const double SPECIAL_VALUES[] = {
    std::numeric_limits<double>::quiet_NaN(),
    -std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),
    DBL_MAX,
    -DBL_MAX,
    0x1p1000,
    -0x1p600,
    1e300,
    FLT_MAX,
    0x1p127,
    DBL_MIN,
    std::numeric_limits<double>::denorm_min(),
    -0x1p-1060,
    1e-300,
    0x1p-149,
    0x1p-500,
    -0.0,
    0.1,
    1.0 / 3.0,
    1.0 + 0x1p-52,
    1.0 - 0x1p-53,
    0x1p53 + 2,
};

} // namespace

PointSet produce_points(FuzzInput& input, size_t max_points) {
    test::PointLayout layout;
    const uint8_t shape = input.byte();
    layout.type = (shape & 1) ? DBRG_FLOAT32 : DBRG_FLOAT64;
    layout.padding = (shape >> 1) & 15;
    layout.offset = shape >> 5;
    const uint8_t grid_choice = input.byte();
    const int grid_size = GRID_SIZES[grid_choice & 7];
    const bool escapes = (grid_choice & 8) != 0;
    const int exponent = input.byte() % 128 - 64;

    std::vector<double> xyz;
    std::vector<int32_t> grid;
    bool on_grid = true;
    while (input.remaining() >= 3 && xyz.size() < 3 * max_points) {
        for (int k = 0; k < 3; ++k) {
            const uint8_t code = input.byte();
            double value;
            if (escapes && code == ESCAPE_SPECIAL) {
                value = input.pick(SPECIAL_VALUES);
                on_grid = false;
            } else if (escapes && code == ESCAPE_RAW) {
                value = input.raw_double();
                on_grid = false;
            } else {
                const int32_t steps = code % grid_size - grid_size / 2;
                grid.push_back(steps);
                value = ldexp(static_cast<double>(steps), exponent);
            }
            // What the library will read: a float32 caller's values are floats.
            if (layout.type == DBRG_FLOAT32) value = static_cast<float>(value);
            xyz.push_back(value);
        }
    }
    bool finite = true;
    for (double x : xyz) finite = finite && isfinite(x);
    test::StoredPoints stored(xyz, layout);
    return PointSet{std::move(xyz), on_grid, on_grid ? std::move(grid) : std::vector<int32_t>(), exponent, finite,
                    std::move(stored)};
}

} // namespace dbrg::fuzz
