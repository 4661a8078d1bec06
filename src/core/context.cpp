// Context: what every stage of one call shares — memory, progress/cancel, the error message, statistics.
#include "core/context.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

namespace dbrg {

bool Progress::report(dbrg_stage stage, double fraction) {
    if (cancelled_) return false;
    if (!callback_) return true;
    // Throttle: a new stage, the end of a stage, or a step of at least 0.1%.
    const bool new_stage = static_cast<int>(stage) != last_stage_;
    if (!new_stage && fraction < 1.0 && fraction - last_fraction_ < 1e-3) return true;
    last_stage_ = static_cast<int>(stage);
    last_fraction_ = fraction;
    if (callback_(user_, stage, fraction) != 0) cancelled_ = true;
    return !cancelled_;
}

Context::Context(const dbrg_params& p)
    : params(p), memory(p.allocator), progress(p.progress, p.progress_user) {
    memset(&stats, 0, sizeof stats);
    stats.struct_size = sizeof stats;
    message_[0] = '\0';
}

dbrg_status Context::fail(dbrg_status status, const char* format, ...) {
    va_list args;
    va_start(args, format);
    vsnprintf(message_, sizeof message_, format, args);
    va_end(args);
    return status;
}

dbrg_status Context::fail_out_of_memory() {
    return fail(DBRG_ERR_OUT_OF_MEMORY, "out of memory: the allocator refused a request (%zu bytes were in use)",
                memory.bytes_in_use());
}

dbrg_status Context::fail_cancelled() { return fail(DBRG_ERR_CANCELLED, "cancelled by the progress callback"); }

dbrg_status Context::report(dbrg_stage stage, double fraction) {
    return progress.report(stage, fraction) ? DBRG_OK : fail_cancelled();
}

double seconds_now() {
    timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

} // namespace dbrg
