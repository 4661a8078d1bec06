// Test support: points stored the way a caller may hand them over — float32 or float64, any stride, a
// misaligned start — as dbrg_points over a buffer the object owns. Header-only and free of doctest, so
// that the fuzz harnesses use it too.
#pragma once

#include <stddef.h>
#include <string.h>

#include <vector>

#include "dbrg/dbrg.h"

namespace dbrg::test {

struct PointLayout {
    dbrg_scalar_type type = DBRG_FLOAT64;
    size_t padding = 0;  // bytes after each point's three scalars
    size_t offset = 0;   // bytes before the first point
};

class StoredPoints {
public:
    // Stores x, y, z triples; with DBRG_FLOAT32 each value is converted to float (exact when it is one).
    StoredPoints(const std::vector<double>& xyz, const PointLayout& layout) : layout_(layout) {
        const size_t scalar = layout.type == DBRG_FLOAT32 ? sizeof(float) : sizeof(double);
        const size_t stride = 3 * scalar + layout.padding;
        const size_t count = xyz.size() / 3;
        // Padding holds a recognisable pattern; the library must never read it as coordinates.
        bytes_.assign(layout.offset + count * stride, 0xA5);
        for (size_t i = 0; i < count; ++i) {
            unsigned char* point = bytes_.data() + layout.offset + i * stride;
            for (size_t k = 0; k < 3; ++k) {
                if (layout.type == DBRG_FLOAT32) {
                    const float value = static_cast<float>(xyz[3 * i + k]);
                    memcpy(point + k * sizeof value, &value, sizeof value);
                } else {
                    memcpy(point + k * sizeof(double), &xyz[3 * i + k], sizeof(double));
                }
            }
        }
        points_.data = count > 0 ? bytes_.data() + layout.offset : nullptr;
        points_.count = count;
        points_.stride_bytes = stride;
        points_.type = layout.type;
    }
    StoredPoints(const StoredPoints&) = delete;             // points_ refers into bytes_
    StoredPoints& operator=(const StoredPoints&) = delete;
    StoredPoints(StoredPoints&&) = default;                 // moving a vector keeps its buffer

    const dbrg_points& points() const { return points_; }
    const PointLayout& layout() const { return layout_; }

private:
    PointLayout layout_;
    std::vector<unsigned char> bytes_;
    dbrg_points points_{};
};

} // namespace dbrg::test
