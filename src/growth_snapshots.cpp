// Growth snapshots: the surface at evenly spaced stages of growth for the caller's snapshot callback.
#include "growth_snapshots.h"

#include "core/status.h"

namespace dbrg {

GrowthSnapshots::GrowthSnapshots(const ConditionedPoints& points, Context& context)
    : points_(points), context_(context), triangles_(context.memory) {}

void GrowthSnapshots::attach(RegionGrower& grower) {
    if (wanted()) grower.observe_steps(on_step, this);
}

dbrg_status GrowthSnapshots::on_step(void* self, const Surface& surface, double points_reached) {
    GrowthSnapshots& snapshots = *static_cast<GrowthSnapshots*>(self);
    if (snapshots.finished_) return DBRG_OK;  // hole filling's regrow_holes grows S through the same grower
    const uint32_t asked = snapshots.context_.params.snapshot_count;
    const uint32_t count = asked < DBRG_MAX_SNAPSHOTS ? asked : DBRG_MAX_SNAPSHOTS;
    // Thresholds 1/K .. (K - 1)/K while growing; finish() takes the K-th. A step that passes several
    // (a small input, a large K) takes one snapshot for all of them, so there are never more calls than
    // steps, whatever K is.
    const uint32_t passed = snapshots.taken_;
    while (snapshots.taken_ + 1 < count && points_reached * count >= snapshots.taken_ + 1) ++snapshots.taken_;
    return snapshots.taken_ > passed ? snapshots.take(surface, points_reached) : DBRG_OK;
}

dbrg_status GrowthSnapshots::finish(const Surface& surface) {
    if (!wanted()) return DBRG_OK;
    finished_ = true;
    const dbrg_status status = take(surface, double(surface.used_vertex_count()) / surface.vertex_count());
    triangles_.release();  // hole filling follows: its memory is worth more
    return status;
}

dbrg_status GrowthSnapshots::take(const Surface& surface, double points_reached) {
    triangles_.clear();
    if (!triangles_.reserve(3 * size_t(surface.live_face_count()))) return context_.fail_out_of_memory();
    for (uint32_t f = 0; f < surface.face_count(); ++f) {
        if (surface.face_removed(f)) continue;
        for (uint32_t i = 0; i < 3; ++i) triangles_.push_back(points_.input_index[surface.corner(f, i)]);
    }
    const uint32_t triangles = static_cast<uint32_t>(triangles_.size() / 3);
    if (context_.params.snapshot(context_.params.snapshot_user, triangles_.data(), triangles, points_reached) != 0) {
        return context_.fail(DBRG_ERR_CANCELLED, "cancelled by the snapshot callback");
    }
    return DBRG_OK;
}

} // namespace dbrg
