// Array: a growable array of trivially copyable values whose memory comes from a Memory.
#pragma once

#include <stddef.h>
#include <string.h>

#include <type_traits>
#include <utility>

#include "core/memory.h"

namespace dbrg {

// The core's only container. Growth returns false on allocation failure and leaves the array as it
// was, so callers can turn failure into DBRG_ERR_OUT_OF_MEMORY; nothing here throws or aborts.
template <class T>
class Array {
    static_assert(std::is_trivially_copyable<T>::value, "Array holds trivially copyable values only");

public:
    explicit Array(Memory& memory) : memory_(&memory) {}
    ~Array() { release(); }
    Array(const Array&) = delete;
    Array& operator=(const Array&) = delete;
    Array(Array&& other) noexcept : memory_(other.memory_), data_(other.data_), size_(other.size_), capacity_(other.capacity_) {
        other.data_ = nullptr;
        other.size_ = other.capacity_ = 0;
    }
    Array& operator=(Array&& other) noexcept {
        if (this != &other) {
            release();
            memory_ = other.memory_;
            data_ = other.data_;
            size_ = other.size_;
            capacity_ = other.capacity_;
            other.data_ = nullptr;
            other.size_ = other.capacity_ = 0;
        }
        return *this;
    }

    bool reserve(size_t capacity) {
        if (capacity <= capacity_) return true;
        if (capacity > SIZE_MAX / sizeof(T)) return false;
        void* grown = memory_->reallocate(data_, capacity_ * sizeof(T), capacity * sizeof(T));
        if (!grown) return false;
        data_ = static_cast<T*>(grown);
        capacity_ = capacity;
        return true;
    }

    // Room for `extra` more elements. Grows as push_back does, so that adding a few at a time costs
    // amortized constant time whatever the allocator (an exact reserve would copy the whole array each time).
    bool reserve_more(size_t extra) {
        if (extra <= capacity_ - size_) return true;
        if (extra > SIZE_MAX / sizeof(T) - size_) return false;
        const size_t grown = grown_capacity();
        return reserve(size_ + extra > grown ? size_ + extra : grown);
    }

    // New elements are copies of `fill`.
    bool resize(size_t size, const T& fill = T()) {
        const size_t old_size = size_;
        if (!resize_for_overwrite(size)) return false;
        for (size_t i = old_size; i < size; ++i) data_[i] = fill;
        return true;
    }

    // New elements are left unwritten (their pages mapped, as resize maps them): for a caller that writes
    // every one of them next.
    bool resize_for_overwrite(size_t size) {
        if (!reserve(size)) return false;
        const size_t added_bytes = size > size_ ? (size - size_) * sizeof(T) : 0;
        if (added_bytes >= POPULATE_BYTES) memory_->populate(data_ + size_, added_bytes);
        size_ = size;
        return true;
    }

    // Sets the size, at most the capacity, without writing the new elements: for a caller that writes
    // them itself (in parallel slices, say).
    void resize_unwritten(size_t size) { size_ = size <= capacity_ ? size : capacity_; }

    bool push_back(const T& value) {
        if (size_ == capacity_ && !reserve(grown_capacity())) return false;
        data_[size_++] = value;
        return true;
    }

    void pop_back() { --size_; }
    void clear() { size_ = 0; }
    // Drops the elements from `size` on; the capacity stays (release() gives memory back).
    void shrink(size_t size) { if (size < size_) size_ = size; }

    // Gives the memory back to the allocator.
    void release() {
        memory_->release(data_, capacity_ * sizeof(T));
        data_ = nullptr;
        size_ = capacity_ = 0;
    }

    T& operator[](size_t i) { return data_[i]; }
    const T& operator[](size_t i) const { return data_[i]; }
    T& back() { return data_[size_ - 1]; }
    const T& back() const { return data_[size_ - 1]; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    T* begin() { return data_; }
    T* end() { return data_ + size_; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }
    size_t size() const { return size_; }
    size_t capacity() const { return capacity_; }
    bool empty() const { return size_ == 0; }
    Memory& memory() const { return *memory_; }

    void swap(Array& other) {
        std::swap(memory_, other.memory_);
        std::swap(data_, other.data_);
        std::swap(size_, other.size_);
        std::swap(capacity_, other.capacity_);
    }

private:
    // Fills of at least this many bytes (a few hundred pages) have their pages mapped in one call first
    // (Memory::populate).
    static constexpr size_t POPULATE_BYTES = size_t(1) << 20;

    size_t grown_capacity() const { return capacity_ < 8 ? 8 : capacity_ + capacity_ / 2; }

    Memory* memory_;
    T* data_ = nullptr;
    size_t size_ = 0;
    size_t capacity_ = 0;
};

} // namespace dbrg
