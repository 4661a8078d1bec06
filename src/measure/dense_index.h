// An open-addressing hash index that numbers distinct keys 0, 1, 2, ... in order of first insertion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dbrg::measure {

inline uint64_t mix_bits(uint64_t h) {
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebull;
    return h ^ (h >> 31);
}

// Key needs operator== and a default constructor; Hash maps a Key to uint64_t (it is mixed again here, so
// a plain combination does). Linear probing over a power-of-two table kept at most half full, keys stored
// in the slots: one or two cache misses per lookup, which is what lets the mesh report handle millions
// of edges in a fraction of a second.
template <class Key, class Hash>
class DenseIndex {
public:
    static constexpr uint32_t NOT_FOUND = UINT32_MAX;

    explicit DenseIndex(size_t expected_keys) { grow_table(expected_keys); }

    // The id of `key`, which is given the next id if it is new (then *inserted is true).
    uint32_t insert(const Key& key, bool* inserted = nullptr) {
        if (2 * (size_ + 1) > slots_.size()) grow_table(2 * size_ + 1);
        size_t at = mix_bits(hash_(key)) & mask_;
        while (slots_[at].id != NOT_FOUND) {
            if (slots_[at].key == key) {
                if (inserted) *inserted = false;
                return slots_[at].id;
            }
            at = (at + 1) & mask_;
        }
        slots_[at] = {key, static_cast<uint32_t>(size_)};
        if (inserted) *inserted = true;
        return static_cast<uint32_t>(size_++);
    }

    // The id of `key`, or NOT_FOUND.
    uint32_t find(const Key& key) const {
        size_t at = mix_bits(hash_(key)) & mask_;
        while (slots_[at].id != NOT_FOUND) {
            if (slots_[at].key == key) return slots_[at].id;
            at = (at + 1) & mask_;
        }
        return NOT_FOUND;
    }

    size_t size() const { return size_; }

private:
    struct Slot {
        Key key;
        uint32_t id;
    };

    void grow_table(size_t keys) {
        size_t capacity = 16;
        while (capacity < 2 * keys) capacity *= 2;
        if (capacity <= slots_.size()) return;
        std::vector<Slot> old(capacity, Slot{Key(), NOT_FOUND});
        old.swap(slots_);
        mask_ = capacity - 1;
        for (const Slot& slot : old) {
            if (slot.id == NOT_FOUND) continue;
            size_t at = mix_bits(hash_(slot.key)) & mask_;
            while (slots_[at].id != NOT_FOUND) at = (at + 1) & mask_;
            slots_[at] = slot;
        }
    }

    std::vector<Slot> slots_;
    size_t size_ = 0;
    size_t mask_ = 0;
    Hash hash_;
};

} // namespace dbrg::measure
