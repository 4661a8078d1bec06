// Memory: the caller's allocator behind a small interface that counts bytes and remembers failure.
#pragma once

#include <stddef.h>

#include "dbrg/dbrg.h"

namespace dbrg {

// Bytes held through several Memory objects together (a call's working memory and its result's), and
// their joint peak.
struct MemoryMeter {
    size_t in_use = 0;
    size_t peak = 0;
};

// Wraps a dbrg_allocator. Counts the bytes held and their peak, and keeps a sticky flag once any
// allocation has failed, so that a long computation can check once instead of after every push.
class Memory {
public:
    // allocator may be NULL: the C library's malloc/realloc/free.
    explicit Memory(const dbrg_allocator* allocator);
    Memory(const Memory&) = delete;
    Memory& operator=(const Memory&) = delete;

    // NULL on failure (and failed() becomes true). A zero size gives NULL without failing.
    void* allocate(size_t size);
    // NULL on failure; the old block then stays valid.
    void* reallocate(void* block, size_t old_size, size_t new_size);
    void release(void* block, size_t size);
    // Asks the kernel to map the whole pages inside [data, data + bytes) now, in one call, instead of one
    // page fault at a time as they are first written: on a virtual machine each fault is expensive. For
    // memory about to be written in full. Advice only, and only for malloc's memory (a caller's allocator
    // may hand out memory the library must not give advice about); errno is left as it was.
    void populate(void* data, size_t bytes) const;

    bool failed() const { return failed_; }
    // True when the blocks come from the C library's malloc, not from a caller's allocator: only then may
    // the library give the kernel advice about their pages.
    bool uses_system_allocator() const { return system_; }
    size_t bytes_in_use() const { return in_use_; }
    size_t peak_bytes() const { return peak_; }

    // Also counts this object's bytes in `meter` from now on (bytes already held included), or stops
    // counting them with NULL. The meter must outlive the counting.
    void count_in(MemoryMeter* meter);
    // The meter this object counts in, or NULL.
    MemoryMeter* meter() const { return meter_; }

private:
    void add(size_t added, size_t removed);

    dbrg_allocator allocator_;
    size_t in_use_ = 0;
    size_t peak_ = 0;
    MemoryMeter* meter_ = nullptr;
    bool failed_ = false;
    bool system_ = false;
};

} // namespace dbrg
