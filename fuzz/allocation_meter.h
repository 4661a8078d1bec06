// Measures the most heap bytes a harness holds at once, so that a reader's promise to allocate no more
// than a small multiple of its input can be checked. Works through the sanitizer allocator's hooks, so
// only in builds with AddressSanitizer (the fuzz builds); elsewhere it measures nothing.
#pragma once

#include <stddef.h>

namespace dbrg::fuzz {

// True when this build can measure.
bool allocation_meter_available();
// Starts a measurement.
void reset_peak_bytes();
// The most bytes held at once since the measurement started, beyond those held when it started; 0
// without a meter.
size_t peak_bytes();

} // namespace dbrg::fuzz
