// Progress span: one pass's share of a stage's progress, and passes over many items done in steps that
// report it, so that the caller hears from the library (and can cancel) every few milliseconds.
#pragma once

#include <stddef.h>

#include "core/context.h"
#include "core/parallel.h"
#include "core/status.h"

namespace dbrg {

// The share [begin, end] of stage `stage`'s progress that one pass of its work covers.
class ProgressSpan {
public:
    ProgressSpan(Context& context, dbrg_stage stage, double begin = 0.0, double end = 1.0)
        : context_(&context), stage_(stage), begin_(begin), end_(end) {}

    // The share [from, to] of this span, from and to in [0, 1].
    ProgressSpan part(double from, double to) const { return ProgressSpan(*context_, stage_, at(from), at(to)); }

    // Reports that `done` of the pass's `total` items are done. Returns DBRG_ERR_CANCELLED (with its message)
    // when the caller cancels.
    dbrg_status report(size_t done, size_t total) const {
        return context_->report(stage_, at(total == 0 ? 1.0 : double(done) / double(total)));
    }

    // report(i, total) at every `every`-th item i of a sequential loop (fewer than STEP_ITEMS where an item
    // takes more than a few nanoseconds).
    dbrg_status report_at(size_t i, size_t total, size_t every = STEP_ITEMS) const {
        return i % every == 0 ? report(i, total) : DBRG_OK;
    }

    // Calls work(begin, end) on slices of 0 .. items - 1: steps of at most step_items(parts) items, each split
    // into `parts` slices run at once, with a report before each step. Returns DBRG_OK or DBRG_ERR_CANCELLED.
    template <class Work>
    dbrg_status for_each_step(size_t items, uint32_t parts, const Work& work) const {
        const size_t step = step_items(parts);
        for (size_t begin = 0; begin < items; begin += step) {
            DBRG_PROPAGATE(report(begin, items));
            const size_t end = items - begin < step ? items : begin + step;
            for_each_slice(end - begin, parts, [&](size_t from, size_t to) { work(begin + from, begin + to); });
        }
        return report(items, items);
    }

    // parallel_sort, reporting between its steps. Returns DBRG_OK or DBRG_ERR_CANCELLED.
    template <class T, class Less>
    dbrg_status sort(T* items, size_t count, T* scratch, uint32_t parts, const Less& less) const {
        const bool sorted = parallel_sort(items, count, scratch, parts, less,
                                          [this](size_t done, size_t total) { return report(done, total) == DBRG_OK; });
        return sorted ? DBRG_OK : DBRG_ERR_CANCELLED;
    }

    Context& context() const { return *context_; }

private:
    // The stage's fraction at `share` of this span; the end exactly at share 1, so spans that meet agree.
    double at(double share) const { return share >= 1.0 ? end_ : begin_ + (end_ - begin_) * share; }

    Context* context_;
    dbrg_stage stage_;
    double begin_, end_;
};

} // namespace dbrg
