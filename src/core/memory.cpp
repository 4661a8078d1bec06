// Memory: the caller's allocator behind a small interface that counts bytes and remembers failure.
#include "core/memory.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace dbrg {
namespace {

void* system_allocate(void*, size_t size) { return malloc(size); }
void* system_reallocate(void*, void* block, size_t, size_t new_size) { return realloc(block, new_size); }
void system_deallocate(void*, void* block, size_t) { free(block); }

void add_to(MemoryMeter& meter, size_t added, size_t removed) {
    meter.in_use = meter.in_use + added - removed;
    if (meter.in_use > meter.peak) meter.peak = meter.in_use;
}

} // namespace

Memory::Memory(const dbrg_allocator* allocator) {
    if (allocator && allocator->allocate && allocator->reallocate && allocator->deallocate) {
        allocator_ = *allocator;
    } else {
        allocator_ = dbrg_allocator{system_allocate, system_reallocate, system_deallocate, nullptr};
        system_ = true;
    }
}

void* Memory::allocate(size_t size) {
    if (size == 0) return nullptr;
    void* block = allocator_.allocate(allocator_.user, size);
    if (!block) {
        failed_ = true;
        return nullptr;
    }
    add(size, 0);
    return block;
}

void* Memory::reallocate(void* block, size_t old_size, size_t new_size) {
    if (!block) return allocate(new_size);
    void* moved = allocator_.reallocate(allocator_.user, block, old_size, new_size);
    if (!moved) {
        failed_ = true;
        return nullptr;
    }
    add(new_size, old_size);
    return moved;
}

void Memory::release(void* block, size_t size) {
    if (!block) return;
    allocator_.deallocate(allocator_.user, block, size);
    add(0, size);
}

void Memory::populate(void* data, size_t bytes) const {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    if (!system_) return;
    const long page_size = sysconf(_SC_PAGESIZE);
    if (page_size <= 0) return;
    const uintptr_t page = static_cast<uintptr_t>(page_size);
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + page - 1) & ~(page - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(page - 1);
    const int saved_errno = errno;
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
    errno = saved_errno;
#else
    (void)data;
    (void)bytes;
#endif
}

void Memory::count_in(MemoryMeter* meter) {
    if (meter_) meter_->in_use -= in_use_;
    meter_ = meter;
    if (meter_) add_to(*meter_, in_use_, 0);
}

void Memory::add(size_t added, size_t removed) {
    in_use_ = in_use_ + added - removed;
    if (in_use_ > peak_) peak_ = in_use_;
    if (meter_) add_to(*meter_, added, removed);
}

} // namespace dbrg
