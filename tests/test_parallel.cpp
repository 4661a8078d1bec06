// Parallel parts: the slicing, the merge-path split and the parallel sort agree with their sequential
// meaning for any number of parts, including more parts than items; the sort works in steps and stops
// between two when asked. Run under ThreadSanitizer in CI.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "core/splitmix64.h"

using namespace dbrg;

namespace {

struct Keyed {
    uint32_t key;
    uint32_t index;
};

bool by_key_then_index(const Keyed& a, const Keyed& b) { return a.key != b.key ? a.key < b.key : a.index < b.index; }

// Keys drawn from a small range, so many items share a key and only the index orders them.
std::vector<Keyed> random_items(size_t count, uint32_t key_range, uint64_t seed) {
    SplitMix64 random(seed);
    std::vector<Keyed> items(count);
    for (size_t i = 0; i < count; ++i) items[i] = Keyed{static_cast<uint32_t>(random.next() % key_range), static_cast<uint32_t>(i)};
    return items;
}

} // namespace

TEST_CASE("slices cover every item once, in order") {
    for (size_t items : {0u, 1u, 7u, 64u, 1000u}) {
        for (uint32_t parts = 1; parts <= 9; ++parts) {
            CHECK(part_begin(items, parts, 0) == 0);
            CHECK(part_begin(items, parts, parts) == items);
            for (uint32_t part = 0; part < parts; ++part) {
                CHECK(part_begin(items, parts, part) <= part_begin(items, parts, part + 1));
                CHECK(part_begin(items, parts, part + 1) - part_begin(items, parts, part) <= items / parts + 1);
            }
        }
    }
}

TEST_CASE("run_parts runs each part exactly once, also beyond MAX_THREADS") {
    for (uint32_t parts : {1u, 2u, 3u, 8u, MAX_THREADS, MAX_THREADS + 7}) {
        std::vector<std::atomic<int>> runs(parts);
        run_parts(parts, [&](uint32_t part) { ++runs[part]; });
        for (uint32_t part = 0; part < parts; ++part) CHECK(runs[part].load() == 1);
    }
}

TEST_CASE("part_count: the caller's threads, at most one per minimum share, at least one") {
    CHECK(part_count(1, 1000000, 1000) == 1);
    CHECK(part_count(4, 1000000, 1000) == 4);
    CHECK(part_count(4, 2500, 1000) == 2);
    CHECK(part_count(4, 10, 1000) == 1);
    CHECK(part_count(1000, 1u << 30, 1) == MAX_THREADS);
    CHECK(part_count(0, 1u << 30, 1) >= 1);
}

TEST_CASE("merge_split finds where the first k items of a merge come from") {
    const std::vector<int> a = {1, 3, 3, 5, 9}, b = {2, 3, 4, 10};
    std::vector<int> merged(a.size() + b.size());
    std::merge(a.begin(), a.end(), b.begin(), b.end(), merged.begin());
    const auto less = [](int x, int y) { return x < y; };
    for (size_t k = 0; k <= merged.size(); ++k) {
        const size_t i = merge_split(a.data(), a.size(), b.data(), b.size(), k, less);
        // The first k of the merge are a[0, i) and b[0, k - i), in merged order.
        std::vector<int> head(a.begin(), a.begin() + long(i));
        head.insert(head.end(), b.begin(), b.begin() + long(k - i));
        std::sort(head.begin(), head.end());
        CHECK(head == std::vector<int>(merged.begin(), merged.begin() + long(k)));
    }
}

TEST_CASE("parallel_sort gives std::sort's order for any number of parts") {
    for (size_t count : {0u, 1u, 2u, 5u, 100u, 4097u, 50000u}) {
        const std::vector<Keyed> original = random_items(count, count < 50 ? 3 : 1000, count);
        std::vector<Keyed> expected = original;
        std::sort(expected.begin(), expected.end(), by_key_then_index);
        for (uint32_t parts : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 33u, MAX_THREADS, MAX_THREADS + 1}) {
            CAPTURE(count);
            CAPTURE(parts);
            std::vector<Keyed> items = original, scratch(count);
            CHECK(parallel_sort(items.data(), count, scratch.data(), parts, by_key_then_index, [](size_t, size_t) { return true; }));
            bool same = true;
            for (size_t i = 0; i < count; ++i) same = same && items[i].key == expected[i].key && items[i].index == expected[i].index;
            CHECK(same);
        }
    }
}

TEST_CASE("parallel_sort works in steps, reports the work done between them, and stops when asked") {
    // Several steps of runs and of each merge round, whatever the number of parts.
    const size_t count = 3 * STEP_ITEMS + 12345;
    const std::vector<Keyed> original = random_items(count, 1000, 5);
    std::vector<Keyed> expected = original;
    std::sort(expected.begin(), expected.end(), by_key_then_index);
    for (uint32_t parts : {1u, 2u, 3u, 7u}) {
        CAPTURE(parts);
        REQUIRE(sort_needs_scratch(count, parts));
        std::vector<Keyed> items = original, scratch(count);
        std::vector<std::pair<size_t, size_t>> calls;  // (done, total)
        const auto record = [&](size_t done, size_t total) {
            calls.emplace_back(done, total);
            return true;
        };
        REQUIRE(parallel_sort(items.data(), count, scratch.data(), parts, by_key_then_index, record));
        bool same = true;
        for (size_t i = 0; i < count; ++i) same = same && items[i].key == expected[i].key && items[i].index == expected[i].index;
        CHECK(same);
        // A call before every step: the runs and at least one merge round take four steps each.
        CHECK(calls.size() >= 8);
        bool in_order = true;
        for (size_t i = 0; i < calls.size(); ++i) {
            in_order = in_order && calls[i].second == calls[0].second && (i == 0 || calls[i].first > calls[i - 1].first);
        }
        CHECK(in_order);
        CHECK(calls.front().first == 0);
        CHECK(calls.back().first == calls.back().second);
        // Stopped at the first call, one in the middle, the last: no call after that one, and false.
        for (size_t stop_at : {size_t(0), calls.size() / 2, calls.size() - 1}) {
            CAPTURE(stop_at);
            items = original;
            size_t seen = 0;
            const auto stop = [&](size_t, size_t) { return seen++ != stop_at; };
            CHECK_FALSE(parallel_sort(items.data(), count, scratch.data(), parts, by_key_then_index, stop));
            CHECK(seen == stop_at + 1);
        }
    }
}
