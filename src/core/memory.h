// Memory: the caller's allocator behind a small interface that counts bytes and remembers failure.
#pragma once

#include <stddef.h>

#include "dbrg/dbrg.h"

namespace dbrg {

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

    bool failed() const { return failed_; }
    size_t bytes_in_use() const { return in_use_; }
    size_t peak_bytes() const { return peak_; }

private:
    dbrg_allocator allocator_;
    size_t in_use_ = 0;
    size_t peak_ = 0;
    bool failed_ = false;
};

} // namespace dbrg
