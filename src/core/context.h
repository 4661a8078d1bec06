// Context: what every stage of one call shares — memory, progress/cancel, the error message, statistics.
#pragma once

#include <stdint.h>

#include "core/memory.h"
#include "dbrg/dbrg.h"

namespace dbrg {

// Reports progress to the caller's callback, at most about a thousand times per stage, and
// remembers a cancellation so that every later check sees it.
class Progress {
public:
    Progress(dbrg_progress_fn callback, void* user) : callback_(callback), user_(user) {}

    // Returns false when the caller has asked to cancel (now or earlier).
    bool report(dbrg_stage stage, double fraction);

private:
    dbrg_progress_fn callback_;
    void* user_;
    int last_stage_ = -1;
    double last_fraction_ = 0;
    bool cancelled_ = false;
};

class Context {
public:
    explicit Context(const dbrg_params& params);
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Records `status` with a printf-style message for the caller and returns it.
    dbrg_status fail(dbrg_status status, const char* format, ...)
#if defined(__GNUC__)
        __attribute__((format(printf, 3, 4)))
#endif
        ;
    // OUT_OF_MEMORY or CANCELLED with their standard messages, after memory failed or progress cancelled.
    dbrg_status fail_out_of_memory();
    dbrg_status fail_cancelled();

    // Reports progress; returns DBRG_ERR_CANCELLED (with its message) when the caller cancels.
    dbrg_status report(dbrg_stage stage, double fraction);

    const char* message() const { return message_; }

    dbrg_params params;
    Memory memory;
    Progress progress;
    dbrg_stats stats;

private:
    char message_[256];
};

// Seconds on a monotonic clock, for the per-stage times.
double seconds_now();

} // namespace dbrg
