// An open-addressing hash index that numbers distinct keys 0, 1, 2, ... in order of first insertion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dbrg::io {

inline uint64_t mix_bits(uint64_t h) {
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebull;
    return h ^ (h >> 31);
}

// Key needs operator==; Hash maps a Key to uint64_t (it is mixed again here, so a plain combination does).
// Linear probing over a power-of-two table kept at most half full: one or two probes per lookup, which is
// what lets the mesh report handle millions of edges in a fraction of a second.
template <class Key, class Hash>
class DenseIndex {
public:
    static constexpr uint32_t NOT_FOUND = UINT32_MAX;

    explicit DenseIndex(size_t expected_keys) {
        keys_.reserve(expected_keys);
        resize_table(expected_keys);
    }

    // The id of `key`, which is given the next id if it is new (then *inserted is true).
    uint32_t insert(const Key& key, bool* inserted = nullptr) {
        if (2 * (keys_.size() + 1) > slots_.size()) resize_table(2 * keys_.size() + 1);
        size_t slot = mix_bits(hash_(key)) & mask_;
        while (slots_[slot] != NOT_FOUND) {
            if (keys_[slots_[slot]] == key) {
                if (inserted) *inserted = false;
                return slots_[slot];
            }
            slot = (slot + 1) & mask_;
        }
        const uint32_t id = static_cast<uint32_t>(keys_.size());
        slots_[slot] = id;
        keys_.push_back(key);
        if (inserted) *inserted = true;
        return id;
    }

    // The id of `key`, or NOT_FOUND.
    uint32_t find(const Key& key) const {
        size_t slot = mix_bits(hash_(key)) & mask_;
        while (slots_[slot] != NOT_FOUND) {
            if (keys_[slots_[slot]] == key) return slots_[slot];
            slot = (slot + 1) & mask_;
        }
        return NOT_FOUND;
    }

    size_t size() const { return keys_.size(); }

private:
    void resize_table(size_t keys) {
        size_t capacity = 16;
        while (capacity < 2 * keys) capacity *= 2;
        if (capacity <= slots_.size()) return;
        slots_.assign(capacity, NOT_FOUND);
        mask_ = capacity - 1;
        for (uint32_t id = 0; id < keys_.size(); ++id) {
            size_t slot = mix_bits(hash_(keys_[id])) & mask_;
            while (slots_[slot] != NOT_FOUND) slot = (slot + 1) & mask_;
            slots_[slot] = id;
        }
    }

    std::vector<uint32_t> slots_;
    std::vector<Key> keys_;
    size_t mask_ = 0;
    Hash hash_;
};

} // namespace dbrg::io
