// Growth snapshots: the surface at evenly spaced stages of growth, handed to the caller's snapshot callback
// in the caller's point indexing — the stages the paper's Figures 1, 7 and 8 show.
#pragma once

#include "core/array.h"
#include "core/context.h"
#include "points/point_conditioning.h"
#include "grow/region_growing.h"
#include "surface/surface.h"

namespace dbrg {

class GrowthSnapshots {
public:
    GrowthSnapshots(const ConditionedPoints& points, Context& context);

    // Makes `grower` report its steps here, when the caller asked for snapshots.
    void attach(RegionGrower& grower);

    // The last snapshot, once growing has ended.
    dbrg_status finish(const Surface& surface);

private:
    static dbrg_status on_step(void* self, const Surface& surface, double points_reached);
    dbrg_status take(const Surface& surface, double points_reached);
    bool wanted() const { return context_.params.snapshot && context_.params.snapshot_count > 0; }

    const ConditionedPoints& points_;
    Context& context_;
    bool finished_ = false;
    uint32_t taken_ = 0;         // thresholds passed: snapshot k is due when 1 + k of K are passed
    Array<uint32_t> triangles_;  // the current snapshot's triangles, caller's indices
};

} // namespace dbrg
