// Resource figures of this process for the --stats-json reports.
#pragma once

#include <cstdint>

namespace dbrg::cli {

// The most resident memory this process has held so far, in bytes (0 where the system cannot tell).
uint64_t peak_rss_bytes();

// Seconds on a monotonic clock.
double seconds_now();

} // namespace dbrg::cli
