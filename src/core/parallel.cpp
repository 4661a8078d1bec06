// Parallel parts: how many threads a stage uses, and starting them. POSIX threads rather than std::thread:
// the library is built without exceptions, and pthread_create reports a refusal as a value.
#include "core/parallel.h"

#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif
#if __has_include(<pthread.h>)
#include <pthread.h>
#define DBRG_HAVE_PTHREADS 1
#endif

namespace dbrg {
namespace {

struct PartCall {
    void (*task)(const void* work, uint32_t part);
    const void* work;
    uint32_t part;
};

[[maybe_unused]] void* run_part(void* argument) {
    const PartCall* call = static_cast<const PartCall*>(argument);
    call->task(call->work, call->part);
    return nullptr;
}

// The processors this process may run on: on Linux those of its affinity mask (a container or `taskset`
// may allow fewer than the machine has), elsewhere the hardware's count; at least 1.
uint32_t available_processors() {
#if defined(__linux__)
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return static_cast<uint32_t>(CPU_COUNT(&set));
#endif
    const unsigned hardware = std::thread::hardware_concurrency();  // 0 when it cannot be told
    return hardware == 0 ? 1 : static_cast<uint32_t>(hardware);
}

} // namespace

uint32_t part_count(uint32_t requested_threads, size_t items, size_t min_items_per_part) {
    uint32_t threads = requested_threads == 0 ? available_processors() : requested_threads;
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    const size_t by_size = min_items_per_part == 0 ? items : items / min_items_per_part;
    return by_size < threads ? (by_size < 1 ? 1 : static_cast<uint32_t>(by_size)) : threads;
}

void run_parts_on_threads(uint32_t parts, void (*task)(const void* work, uint32_t part), const void* work) {
#if DBRG_HAVE_PTHREADS
    // Parts beyond MAX_THREADS, and those whose thread did not start, run on the calling thread.
    const uint32_t threaded = parts < MAX_THREADS ? parts : MAX_THREADS;
    PartCall calls[MAX_THREADS];
    pthread_t threads[MAX_THREADS];
    bool started[MAX_THREADS] = {};
    for (uint32_t part = 1; part < threaded; ++part) {
        calls[part] = PartCall{task, work, part};
        started[part] = pthread_create(&threads[part], nullptr, run_part, &calls[part]) == 0;
    }
    task(work, 0);
    for (uint32_t part = threaded; part < parts; ++part) task(work, part);
    for (uint32_t part = 1; part < threaded; ++part) {
        if (started[part]) {
            pthread_join(threads[part], nullptr);
        } else {
            task(work, part);
        }
    }
#else
    for (uint32_t part = 0; part < parts; ++part) task(work, part);
#endif
}

} // namespace dbrg
