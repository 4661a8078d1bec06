// Parallel parts: the stages that split into independent slices (transforming, sorting and scanning the
// points, filling the tetrahedron store) run them on several threads. Each part writes only its own slice
// of memory that the calling thread allocated; parts never allocate, report progress or touch the context,
// so the caller's allocator and callbacks are only ever used from the calling thread, and the result is
// the same for any number of threads.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include <algorithm>

namespace dbrg {

// At most this many threads, whatever the machine or the caller asks for.
constexpr uint32_t MAX_THREADS = 64;

// The fewest points a thread gets in the per-point stages: starting a thread costs tens of microseconds,
// sorting or scanning this many points about a millisecond.
constexpr size_t MIN_POINTS_PER_THREAD = 16384;

// How many parts to split `items` items into: the caller's thread count (0: every processor the process
// may use), at most MAX_THREADS, and at most one part per `min_items_per_part` items, so that small inputs
// never pay for starting a thread.
uint32_t part_count(uint32_t requested_threads, size_t items, size_t min_items_per_part);

// The first item of part `part` when `items` items are split into `parts` nearly equal slices.
inline size_t part_begin(size_t items, uint32_t parts, uint32_t part) {
    return items / parts * part + items % parts * part / parts;  // items * part / parts without overflow
}

// Calls task(work, part) for part 1 .. parts - 1 each on a thread of its own (up to MAX_THREADS) and for
// part 0 on the calling thread, and returns when all are done. A thread the system refuses to start, or
// a part beyond MAX_THREADS, costs only time: that part runs on the calling thread.
void run_parts_on_threads(uint32_t parts, void (*task)(const void* work, uint32_t part), const void* work);

// Calls work(part) for every part in 0 .. parts - 1 at once (see run_parts_on_threads).
template <class Work>
void run_parts(uint32_t parts, const Work& work) {
    if (parts <= 1) {
        work(0);
        return;
    }
    run_parts_on_threads(parts, [](const void* w, uint32_t part) { (*static_cast<const Work*>(w))(part); }, &work);
}

// Calls work(begin, end) on `parts` nearly equal slices of 0 .. items - 1 at once.
template <class Work>
void for_each_slice(size_t items, uint32_t parts, const Work& work) {
    run_parts(parts, [&](uint32_t part) { work(part_begin(items, parts, part), part_begin(items, parts, part + 1)); });
}

// How many items of `a` (length m) come among the first k items of the merge of sorted runs a and b
// (length n), ties going to a as in std::merge: the smallest i whose next item of a does not precede the
// last taken item of b (binary search along the merge path).
template <class T, class Less>
size_t merge_split(const T* a, size_t m, const T* b, size_t n, size_t k, const Less& less) {
    size_t low = k > n ? k - n : 0, high = k < m ? k : m;
    while (low < high) {
        const size_t i = low + (high - low) / 2;
        const size_t j = k - i;
        if (j > 0 && !less(b[j - 1], a[i])) {
            low = i + 1;  // a[i] comes before b[j - 1]: more of a belongs in the first k
        } else {
            high = i;
        }
    }
    return low;
}

// Sorts items[0 .. count) by `less` on `parts` threads: each sorts a slice, then rounds of pairwise merges,
// each merge cut along its merge path so that every thread writes an equal share of the output. `less`
// must be a strict total order on the items (no two equal), so the result is the one a sequential sort
// gives. With more than one part, `scratch` holds `count` items (its content is overwritten).
template <class T, class Less>
void parallel_sort(T* items, size_t count, T* scratch, uint32_t parts, const Less& less) {
    if (parts <= 1 || count < 2) {
        std::sort(items, items + count, less);
        return;
    }
    // Run r is [run_begin(r), run_begin(r + 1)); there are `runs` of them.
    uint32_t runs = parts;
    uint32_t run_step = 1;  // slices per run
    auto run_begin = [&](uint32_t r) { return part_begin(count, parts, r * run_step > parts ? parts : r * run_step); };
    run_parts(parts, [&](uint32_t part) {
        std::sort(items + part_begin(count, parts, part), items + part_begin(count, parts, part + 1), less);
    });
    T* source = items;
    T* target = scratch;
    while (runs > 1) {
        // Output slice `part` of the whole array: merge the pieces of each pair of runs that fall inside it.
        run_parts(parts, [&](uint32_t part) {
            const size_t out_begin = part_begin(count, parts, part), out_end = part_begin(count, parts, part + 1);
            for (uint32_t pair = 0; 2 * pair < runs; ++pair) {
                const size_t lo = run_begin(2 * pair), mid = run_begin(2 * pair + 1 < runs ? 2 * pair + 1 : runs);
                const size_t hi = run_begin(2 * pair + 2 < runs ? 2 * pair + 2 : runs);
                const size_t from = std::max(lo, out_begin), to = std::min(hi, out_end);
                if (from >= to) continue;
                const T* a = source + lo;
                const T* b = source + mid;
                const size_t m = mid - lo, n = hi - mid;
                const size_t i0 = merge_split(a, m, b, n, from - lo, less), i1 = merge_split(a, m, b, n, to - lo, less);
                std::merge(a + i0, a + i1, b + (from - lo - i0), b + (to - lo - i1), target + from, less);
            }
        });
        runs = (runs + 1) / 2;
        run_step *= 2;
        std::swap(source, target);
    }
    if (source != items) {
        for_each_slice(count, parts, [&](size_t begin, size_t end) { std::copy(source + begin, source + end, items + begin); });
    }
}

} // namespace dbrg
