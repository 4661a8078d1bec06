// Point input: checks the caller's strided float/double array and copies it into x, y, z doubles.
#include "points/point_input.h"

#include <math.h>
#include <string.h>

#include "core/c_enum.h"
#include "core/progress_span.h"
#include "core/status.h"

namespace dbrg {
namespace {

template <class Scalar>
dbrg_status copy_points(const unsigned char* bytes, size_t count, size_t stride, Context& context, Array<double>& xyz) {
    const ProgressSpan progress(context, DBRG_STAGE_VALIDATE, 0.0, VALIDATE_READ_SHARE);
    double* out = xyz.data();
    for (size_t i = 0; i < count; ++i) {
        DBRG_PROPAGATE(progress.report_at(i, count));
        Scalar p[3];
        memcpy(p, bytes + i * stride, sizeof p);  // the caller's stride need not keep scalars aligned
        for (int k = 0; k < 3; ++k) {
            if (!isfinite(p[k])) {
                return context.fail(DBRG_ERR_NON_FINITE_INPUT, "point %zu has %s %c coordinate", i,
                                    isnan(p[k]) ? "a NaN" : "an infinite", "xyz"[k]);
            }
            out[3 * i + k] = static_cast<double>(p[k]);
        }
    }
    return progress.report(count, count);
}

} // namespace

dbrg_status check_not_too_many_points(size_t count, Context& context) {
    if (count <= DBRG_MAX_POINTS) return DBRG_OK;
    return context.fail(DBRG_ERR_TOO_MANY_POINTS, "%zu points given; at most %zu are supported", count,
                        static_cast<size_t>(DBRG_MAX_POINTS));
}

dbrg_status check_enough_points(size_t count, Context& context) {
    if (count >= 4) return DBRG_OK;
    return context.fail(DBRG_ERR_TOO_FEW_POINTS, "%zu point%s given; at least 4 distinct points are needed", count,
                        count == 1 ? "" : "s");
}

dbrg_status check_point_count(size_t count, Context& context) {
    DBRG_PROPAGATE(check_enough_points(count, context));
    return check_not_too_many_points(count, context);
}

dbrg_status copy_caller_points(const dbrg_points* points, Context& context, Array<double>& xyz) {
    if (!points) return context.fail(DBRG_ERR_INVALID_ARGUMENT, "points is NULL");
    const int type = c_enum_value(points->type);
    if (type != DBRG_FLOAT32 && type != DBRG_FLOAT64) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "points->type is %d; expected DBRG_FLOAT32 or DBRG_FLOAT64", type);
    }
    const size_t scalar_size = points->type == DBRG_FLOAT32 ? sizeof(float) : sizeof(double);
    if (points->stride_bytes < 3 * scalar_size) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "points->stride_bytes is %zu; a point needs at least %zu bytes",
                            points->stride_bytes, 3 * scalar_size);
    }
    DBRG_PROPAGATE(check_not_too_many_points(points->count, context));
    if (points->count > (SIZE_MAX - 3 * scalar_size) / points->stride_bytes) {
        return context.fail(DBRG_ERR_TOO_MANY_POINTS, "%zu point%s at a stride of %zu bytes overflow%s the address space",
                            points->count, points->count == 1 ? "" : "s", points->stride_bytes,
                            points->count == 1 ? "s" : "");
    }
    if (points->count > 0 && !points->data) {
        return context.fail(DBRG_ERR_INVALID_ARGUMENT, "points->data is NULL but points->count is %zu", points->count);
    }
    if (!xyz.resize(3 * points->count)) return context.fail_out_of_memory();
    const unsigned char* bytes = static_cast<const unsigned char*>(points->data);
    DBRG_PROPAGATE(points->type == DBRG_FLOAT32
                       ? copy_points<float>(bytes, points->count, points->stride_bytes, context, xyz)
                       : copy_points<double>(bytes, points->count, points->stride_bytes, context, xyz));
    // After the copy: a NaN among three points is the problem to name first.
    return check_enough_points(points->count, context);
}

} // namespace dbrg
