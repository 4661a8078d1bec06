// Heap metering through the sanitizer allocator's malloc and free hooks (see allocation_meter.h). They see
// every allocation of the process, libFuzzer's own included; measurements start from what is held then.
#include "allocation_meter.h"

#include <stddef.h>

#include <atomic>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DBRG_ALLOCATION_METER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define DBRG_ALLOCATION_METER 1
#endif

#ifdef DBRG_ALLOCATION_METER
// From the sanitizer runtime (declared here: GCC ships no sanitizer/allocator_interface.h).
extern "C" {
int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*, size_t),
                                              void (*free_hook)(const volatile void*));
size_t __sanitizer_get_allocated_size(const volatile void* block);
}
#endif

namespace dbrg::fuzz {
namespace {

// Signed: blocks allocated before the hooks were installed may be freed after.
std::atomic<long long> held{0};
std::atomic<long long> peak{0};
long long baseline = 0;

#ifdef DBRG_ALLOCATION_METER
void on_allocate(const volatile void*, size_t size) {
    const long long now = held.fetch_add(static_cast<long long>(size), std::memory_order_relaxed) + static_cast<long long>(size);
    long long high = peak.load(std::memory_order_relaxed);
    while (now > high && !peak.compare_exchange_weak(high, now, std::memory_order_relaxed)) {
    }
}

void on_release(const volatile void* block) {
    held.fetch_sub(static_cast<long long>(__sanitizer_get_allocated_size(block)), std::memory_order_relaxed);
}

// Installed before main, so that `held` counts every block that can later be freed.
const int installed = __sanitizer_install_malloc_and_free_hooks(on_allocate, on_release);
#endif

} // namespace

bool allocation_meter_available() {
#ifdef DBRG_ALLOCATION_METER
    return installed != 0;
#else
    return false;
#endif
}

void reset_peak_bytes() {
    baseline = held.load();
    peak.store(baseline);
}

size_t peak_bytes() { return allocation_meter_available() ? static_cast<size_t>(peak.load() - baseline) : 0; }

} // namespace dbrg::fuzz
