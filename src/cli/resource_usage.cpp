// Resource figures of this process for the --stats-json reports.
#include "cli/resource_usage.h"

#include <sys/resource.h>

#include <chrono>

namespace dbrg::cli {

uint64_t peak_rss_bytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

double seconds_now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace dbrg::cli
