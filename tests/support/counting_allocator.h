// Test support: a dbrg_allocator that counts requests and live blocks, checks that the sizes the library
// hands back match the blocks it was given and that every call comes from the thread that made it (the
// library's own threads must never allocate), and refuses a chosen request on purpose. Header-only and
// free of doctest, so that the fuzz harnesses use it too.
#pragma once

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <atomic>
#include <thread>

#include "dbrg/dbrg.h"

namespace dbrg::test {

class CountingAllocator {
public:
    CountingAllocator() : allocator_{allocate, reallocate, deallocate, this} {}
    CountingAllocator(const CountingAllocator&) = delete;
    CountingAllocator& operator=(const CountingAllocator&) = delete;

    const dbrg_allocator* get() const { return &allocator_; }

    // Refuses request number `k` (1-based, counted from now), and with `persistent` every later one too;
    // 0 refuses nothing. Resets the request counts.
    void fail_at(uint64_t k, bool persistent = false) {
        fail_at_ = k;
        persistent_ = persistent;
        requests_ = 0;
        refused_ = 0;
        largest_request_ = 0;
    }

    uint64_t requests() const { return requests_; }      // allocate + reallocate calls, refused ones included
    uint64_t refused() const { return refused_; }
    uint64_t live_blocks() const { return live_blocks_; }
    size_t live_bytes() const { return live_bytes_; }
    size_t largest_request() const { return largest_request_; }
    // Calls whose size or block did not match what was allocated: always 0 in a correct library.
    uint64_t contract_violations() const { return violations_; }
    // Calls from another thread than the one that made the allocator: always 0 in a correct library.
    uint64_t foreign_thread_calls() const { return foreign_calls_.load(); }

private:
    // Each block carries its size in a header, so that sizes given back can be checked; the header keeps
    // the caller's part aligned for any scalar.
    static constexpr size_t HEADER = alignof(max_align_t) > sizeof(size_t) ? alignof(max_align_t) : sizeof(size_t);

    void note_thread() {
        if (std::this_thread::get_id() != owner_) ++foreign_calls_;
    }

    bool refuse(size_t size) {
        ++requests_;
        if (size > largest_request_) largest_request_ = size;
        const bool no = fail_at_ != 0 && (requests_ == fail_at_ || (persistent_ && requests_ > fail_at_));
        if (no) ++refused_;
        return no;
    }

    static size_t stored_size(void* block) { return *reinterpret_cast<size_t*>(static_cast<char*>(block) - HEADER); }

    static void* allocate(void* user, size_t size) {
        CountingAllocator& self = *static_cast<CountingAllocator*>(user);
        self.note_thread();
        if (self.refuse(size) || size > SIZE_MAX - HEADER) return nullptr;
        char* base = static_cast<char*>(malloc(HEADER + size));
        if (!base) return nullptr;
        *reinterpret_cast<size_t*>(base) = size;
        ++self.live_blocks_;
        self.live_bytes_ += size;
        return base + HEADER;
    }

    static void* reallocate(void* user, void* block, size_t old_size, size_t new_size) {
        CountingAllocator& self = *static_cast<CountingAllocator*>(user);
        self.note_thread();
        if (!block) {
            ++self.violations_;  // the contract gives reallocate only blocks from allocate
            return nullptr;
        }
        if (stored_size(block) != old_size) ++self.violations_;
        if (self.refuse(new_size) || new_size > SIZE_MAX - HEADER) return nullptr;
        char* base = static_cast<char*>(realloc(static_cast<char*>(block) - HEADER, HEADER + new_size));
        if (!base) return nullptr;
        *reinterpret_cast<size_t*>(base) = new_size;
        self.live_bytes_ = self.live_bytes_ - old_size + new_size;
        return base + HEADER;
    }

    static void deallocate(void* user, void* block, size_t size) {
        CountingAllocator& self = *static_cast<CountingAllocator*>(user);
        self.note_thread();
        if (!block) return;
        if (stored_size(block) != size) ++self.violations_;
        --self.live_blocks_;
        self.live_bytes_ -= size;
        free(static_cast<char*>(block) - HEADER);
    }

    dbrg_allocator allocator_;
    uint64_t fail_at_ = 0;
    bool persistent_ = false;
    uint64_t requests_ = 0;
    uint64_t refused_ = 0;
    uint64_t live_blocks_ = 0;
    size_t live_bytes_ = 0;
    size_t largest_request_ = 0;
    uint64_t violations_ = 0;
    std::thread::id owner_ = std::this_thread::get_id();
    std::atomic<uint64_t> foreign_calls_{0};
};

} // namespace dbrg::test
