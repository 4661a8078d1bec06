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

// The most items a pass over the points works through between two returns to the calling thread, where
// progress is reported and a cancel seen: about a millisecond to a few tens of milliseconds of work. With
// many threads a step grows so that each still gets MIN_POINTS_PER_THREAD items.
constexpr size_t STEP_ITEMS = size_t(1) << 18;

inline size_t step_items(uint32_t parts) {
    return parts > STEP_ITEMS / MIN_POINTS_PER_THREAD ? size_t(parts) * MIN_POINTS_PER_THREAD : STEP_ITEMS;
}

// The length of the runs parallel_sort sorts before merging them: one step's share for each part.
inline size_t sort_run_items(size_t count, uint32_t parts) {
    const size_t step = std::min(count, step_items(parts));
    return parts <= 1 ? step : (step + parts - 1) / parts;
}

// Whether parallel_sort needs its scratch array (more than one run).
inline bool sort_needs_scratch(size_t count, uint32_t parts) { return count > sort_run_items(count, parts); }

// Writes items [from, to) of one merge round's output: source holds sorted runs of `width` items, and the
// round merges runs 2k and 2k + 1 into target. Each merge is cut along its merge path, so any range of the
// output can be written on its own.
template <class T, class Less>
void merge_round_range(const T* source, T* target, size_t count, size_t width, size_t from, size_t to, const Less& less) {
    for (size_t lo = from / (2 * width) * (2 * width); lo < to; lo += 2 * width) {
        const size_t mid = std::min(lo + width, count), hi = std::min(mid + width, count);
        const size_t first = std::max(lo, from) - lo, last = std::min(hi, to) - lo;  // of this pair's output
        const T* a = source + lo;
        const T* b = source + mid;
        const size_t m = mid - lo, n = hi - mid;
        const size_t i0 = merge_split(a, m, b, n, first, less), i1 = merge_split(a, m, b, n, last, less);
        std::merge(a + i0, a + i1, b + (first - i0), b + (last - i1), target + lo + first, less);
    }
}

// Sorts items[0 .. count) by `less` on `parts` threads, as a merge sort in steps of about
// step_items(parts) items: runs sorted by std::sort, one per part at a time, then rounds of pairwise merges,
// each step's output shared equally among the parts. Before each step, on the calling thread, calls
// between(done, total) with the work done so far, and stops when it returns false: parallel_sort then
// returns false and the items are left in some order. `less` must be a strict total order on the items (no
// two equal), so the result is the one a sequential sort gives. `scratch` holds `count` items when
// sort_needs_scratch(count, parts) (its content is overwritten).
template <class T, class Less, class Between>
bool parallel_sort(T* items, size_t count, T* scratch, uint32_t parts, const Less& less, const Between& between) {
    if (count < 2) return true;
    parts = parts < 1 ? 1 : parts;
    const size_t run = sort_run_items(count, parts), runs = (count + run - 1) / run, step = run * parts;
    // Work in item moves: a run's sort costs about log2(run) per item, a merge round or the copy back one.
    size_t run_cost = 1, rounds = 0;
    while (run_cost < 64 && run >> run_cost) ++run_cost;
    for (size_t width = run; width < count; width *= 2) ++rounds;
    const size_t total = count * (run_cost + rounds + rounds % 2);
    size_t done = 0;
    for (size_t first = 0; first < runs; first += parts) {
        if (!between(done, total)) return false;
        run_parts(parts, [&](uint32_t part) {
            const size_t begin = (first + part) * run;
            if (first + part < runs) std::sort(items + begin, items + std::min(count, begin + run), less);
        });
        done += (std::min(count, (first + parts) * run) - first * run) * run_cost;
    }
    T* source = items;
    T* target = scratch;
    for (size_t width = run; width < count; width *= 2) {
        for (size_t begin = 0; begin < count; begin += step) {
            if (!between(done, total)) return false;
            const size_t end = std::min(count, begin + step);
            for_each_slice(end - begin, parts, [&](size_t from, size_t to) {
                merge_round_range(source, target, count, width, begin + from, begin + to, less);
            });
            done += end - begin;
        }
        std::swap(source, target);
    }
    for (size_t begin = 0; source != items && begin < count; begin += step) {
        if (!between(done, total)) return false;
        const size_t end = std::min(count, begin + step);
        for_each_slice(end - begin, parts, [&](size_t from, size_t to) {
            std::copy(source + begin + from, source + begin + to, items + begin + from);
        });
        done += end - begin;
    }
    return between(total, total);
}

} // namespace dbrg
