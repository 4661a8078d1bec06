// Parallel insertion: the last BRIO round, inserted by several threads at once, each claiming the
// tetrahedra it reads and taking slots from chunks of a store sized beforehand.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "core/parallel.h"
#include "core/status.h"
#include "delaunay/delaunay_builder.h"

namespace dbrg {
namespace {

// Each thread has room for a cavity of this many tetrahedra and faces (a thousand times the usual), for
// this many claims at once, takes slots this many at a time, and remembers up to one in DEFERRED_SHARE of
// its points as given up.
constexpr size_t MAX_SHARED_CAVITY = 1024;
constexpr size_t MAX_SHARED_FACES = 2048;
constexpr size_t MAX_SHARED_HELD = 8192;
constexpr uint32_t CHUNK_SLOTS = 1024;
constexpr uint32_t DEFERRED_SHARE = 8;
// Each thread adds its count of points inserted to round_inserted_ this many at a time (the counter's cache
// line is shared); the calling thread looks at the others this often while it waits for them.
constexpr uint32_t COUNT_STEP = 64;
constexpr std::chrono::milliseconds WATCH_INTERVAL(1);

// Whether a part of the round is still to run, running or done.
enum : uint8_t { PART_WAITING, PART_RUNNING, PART_DONE };

} // namespace

// The last BRIO round, split into consecutive stretches of the order (so into separate regions of
// space), one per thread, inserted at once. Each thread claims a tetrahedron (an atomic mark per slot)
// before it reads it, and keeps its claims until its point is in; a cavity's tetrahedra and all their
// neighbours are claimed before anything changes, so no thread ever reads a tetrahedron another is
// rewriting. Where another thread has one, the point is given up, and the calling thread inserts it
// afterwards. The tetrahedralization of a point set does not depend on the insertion order, so the
// tetrahedra are the same as with one thread (their slots differ). Threads take new slots in chunks
// from a store sized beforehand and never allocate: what needs more room than their fixed scratch space
// is given up too. A thread that finds the store full stops; the store grows and they go on. The calling
// thread reports progress for all of them, and once its own stretch is in, goes on reporting while it
// waits for theirs.
dbrg_status DelaunayBuilder::insert_last_round(uint32_t parts) {
    std::optional<Inserter> others[MAX_INSERTION_THREADS];
    Inserter* inserters[MAX_INSERTION_THREADS] = {&main_};
    BrioOrder::Slice slices[MAX_INSERTION_THREADS];
    dbrg_status statuses[MAX_INSERTION_THREADS];
    // Whether a part's hint is a tetrahedron of the tetrahedralization as it is now: the calling thread's
    // is, from its last insertion; after a phase, those of the parts that ran (each held its own). A part
    // that sat a phase out while others inserted finds a start again: its tetrahedron may be gone.
    bool hint_live[MAX_INSERTION_THREADS] = {true};
    for (uint32_t part = 0; part < parts; ++part) {
        if (part > 0) inserters[part] = &others[part].emplace(memory_);
        slices[part] = order_->last_round_slice(part, parts);
        DBRG_PROPAGATE(prepare_inserter(*inserters[part], part, slices[part].span() / DEFERRED_SHARE + 64));
        inserters[part]->random ^= part;  // other walks, the same result
    }
    uint32_t anchor = main_.hint;  // a live tetrahedron
    bool store_full = true;
    while (store_full) {
        // Every reserved slot is the threads' to take. Those not written yet the calling thread maps
        // while the others start inserting (a thread writes a slot before it uses it).
        const size_t slots = std::max(projected_slots(), size_t(slot_end_) + size_t(CHUNK_SLOTS) * parts);
        if (4 * slots > out_.vertices_.size()) DBRG_PROPAGATE(reserve_store(std::min<size_t>(slots, MAX_TET_SLOTS)));
        const size_t written = out_.vertices_.size() / 4;
        out_.vertices_.resize_unwritten(out_.vertices_.capacity());
        out_.adjacency_.resize_unwritten(out_.vertices_.capacity());
        const uint32_t capacity = static_cast<uint32_t>(out_.vertices_.size() / 4);
        claims_.clear();
        if (!claims_.resize(capacity, 0)) return context_.fail_out_of_memory();
        next_chunk_.store(slot_end_, std::memory_order_relaxed);
        stop_.store(false, std::memory_order_relaxed);
        bool active[MAX_INSERTION_THREADS] = {};
        for (uint32_t part = 0; part < parts; ++part) {
            Inserter& in = *inserters[part];
            statuses[part] = DBRG_OK;
            in.out_of_slots = false;
            in.held.clear();
            BrioOrder::Slice rest = slices[part];
            uint32_t first;
            if (!rest.next(first) || in.deferred.size() == in.deferred.capacity()) continue;
            if (!hint_live[part]) {
                // Found by the calling thread, walking from a live tetrahedron to the part's next point.
                DBRG_PROPAGATE(locate<false>(main_, anchor, point(first), in.hint));
                hint_live[part] = true;
            }
            if (claims_[in.hint] != 0) continue;  // the same start as another part's: this one waits
            claims_[in.hint] = in.mark;
            in.held.push_back(in.hint);  // within the capacity prepare_inserter reserved
            active[part] = true;
        }
        round_inserted_.store(0, std::memory_order_relaxed);
        std::atomic<uint8_t> state[MAX_INSERTION_THREADS];
        for (uint32_t part = 0; part < parts; ++part) state[part].store(active[part] ? PART_WAITING : PART_DONE);
        // Each part runs once: on its thread, or on the calling thread (which reports) when that is done
        // with its own part before the part's thread has started it (a thread the system refused to start
        // never does: its part would wait until part 0 returns).
        const auto run_once = [&](uint32_t part, bool calling_thread) {
            uint8_t waiting = PART_WAITING;
            if (!state[part].compare_exchange_strong(waiting, PART_RUNNING, std::memory_order_acquire)) return;
            insert_slice(*inserters[part], slices[part], calling_thread, statuses[part]);
            state[part].store(PART_DONE, std::memory_order_release);
        };
        // The calling thread maps the store, inserts its own part, takes over the parts no thread has
        // started, and reports the others' points as they come in until the last part is done. It stops
        // every part when the caller cancels.
        const auto report_or_stop = [&]() {
            statuses[0] = report_round();
            if (statuses[0] != DBRG_OK) stop_.store(true, std::memory_order_relaxed);
            return statuses[0] == DBRG_OK;
        };
        run_parts(parts, [&](uint32_t part) {
            if (part != 0) return run_once(part, false);
            bool going = true;
            for (size_t from = written; going && from < capacity; from += WRITE_STEP_SLOTS) {
                going = report_or_stop();
                if (going) map_store(from, std::min<size_t>(from + WRITE_STEP_SLOTS, capacity));
            }
            if (going) run_once(0, true);
            for (uint32_t other = 1; other < parts; ++other) run_once(other, true);
            for (;;) {
                bool running = false;
                for (uint32_t other = 1; other < parts; ++other) {
                    running = running || state[other].load(std::memory_order_acquire) != PART_DONE;
                }
                if (!running) break;
                if (statuses[0] == DBRG_OK) report_or_stop();
                std::this_thread::sleep_for(WATCH_INTERVAL);
            }
        });
        // The calling thread alone again.
        slot_end_ = std::min(next_chunk_.load(std::memory_order_relaxed), capacity);
        store_full = false;
        uint32_t inserted = 0;
        for (uint32_t part = 0; part < parts; ++part) {
            Inserter& in = *inserters[part];
            if (statuses[part] != DBRG_OK) {
                return in.failure ? context_.fail(statuses[part], "%s", in.failure) : statuses[part];
            }
            hand_back_chunk(in);
            inserted += in.inserted;
            in.inserted = 0;
            store_full = store_full || in.out_of_slots;
        }
        inserted_ += inserted;
        for (uint32_t part = 0; part < parts; ++part) {
            hint_live[part] = active[part] || (hint_live[part] && inserted == 0);
            if (hint_live[part]) anchor = inserters[part]->hint;
        }
        store_full = store_full && inserted > 0;
    }
    claims_.release();
    if (!hint_live[0]) main_.hint = anchor;
    for (uint32_t part = 1; part < parts; ++part) {
        Inserter& in = *inserters[part];
        while (in.free_head != NO_TET) {
            const uint32_t s = in.free_head;
            in.free_head = adjacency_[4 * size_t(s)];
            free_slot(main_, s);
        }
        main_.finite_change += in.finite_change;
        main_.counters += in.counters;
    }
    // What the threads left: the points they set aside, and the rest of a stretch they stopped in, part by
    // part. Each insertion is told the point after it, as in sequential insertion, so that the next walk
    // starts from the new tetrahedron nearest to that point: on surface samples an arbitrary one of them
    // may be a needle across the shape (on a cylinder, such walks cost ten times the predicate calls).
    uint32_t part = 0;
    size_t deferred_next = 0;
    const auto next_left = [&](uint32_t& v) {
        for (; part < parts; ++part, deferred_next = 0) {
            const Array<uint32_t>& deferred = inserters[part]->deferred;
            if (deferred_next < deferred.size()) {
                v = deferred[deferred_next++];
                return true;
            }
            if (slices[part].next(v)) return true;
        }
        return false;
    };
    uint32_t next;
    for (bool more = next_left(next); more;) {
        const uint32_t v = next;
        more = next_left(next);
        if (inserted_ % PROGRESS_INTERVAL == 0) DBRG_PROPAGATE(context_.report(DBRG_STAGE_DELAUNAY, double(inserted_) / count_));
        ++inserted_;
        DBRG_PROPAGATE(insert<false>(main_, v, more ? point(next) : nullptr));
    }
    return DBRG_OK;
}

dbrg_status DelaunayBuilder::prepare_inserter(Inserter& in, uint32_t part, uint32_t deferred_room) {
    in.mark = static_cast<uint8_t>(part + 1);
    in.held.clear();
    in.deferred.clear();
    const bool room = in.cavity.reserve(MAX_SHARED_CAVITY) && in.outside.reserve(MAX_SHARED_CAVITY) &&
                      in.boundary.reserve(MAX_SHARED_FACES) && in.new_tets.reserve(MAX_SHARED_FACES) &&
                      in.new_slots.reserve(MAX_SHARED_FACES) && in.filed.reserve(3 * MAX_SHARED_FACES) &&
                      in.held.reserve(MAX_SHARED_HELD) && in.deferred.reserve(deferred_room);
    if (!room) return context_.fail_out_of_memory();
    return size_edge_table(in, MAX_SHARED_FACES);
}

// One thread's stretch. Points it sets aside are listed for the calling thread; once that list is full,
// or the store is, the thread stops and leaves the rest of its stretch in `slice`. On the calling thread
// (`reporting`) it also reports progress and stops every part when the caller cancels.
void DelaunayBuilder::insert_slice(Inserter& in, BrioOrder::Slice& slice, bool reporting, dbrg_status& status) {
    uint32_t next_at = slice.position(), next, steps = 0;
    bool more = slice.next(next);
    while (more && !stop_.load(std::memory_order_relaxed)) {
        const uint32_t v = next, v_at = next_at;
        next_at = slice.position();
        more = slice.next(next);
        status = insert<true>(in, v, more ? point(next) : nullptr);
        if (status != DBRG_OK) {
            stop_.store(true, std::memory_order_relaxed);
            return;
        }
        if (!in.left_out) {
            if (++in.inserted % COUNT_STEP == 0) round_inserted_.fetch_add(COUNT_STEP, std::memory_order_relaxed);
        } else if (!in.out_of_slots && in.deferred.size() < in.deferred.capacity()) {
            in.deferred.push_back(v);
        } else {
            slice.rewind(v_at);
            return;
        }
        if (reporting && ++steps % PROGRESS_INTERVAL == 0) {
            status = report_round();
            if (status != DBRG_OK) {
                stop_.store(true, std::memory_order_relaxed);
                return;
            }
        }
    }
    if (more) slice.rewind(next_at);
}

// The points inserted before the round and, about, those its threads have inserted so far.
dbrg_status DelaunayBuilder::report_round() {
    return context_.report(DBRG_STAGE_DELAUNAY, double(inserted_ + round_inserted_.load(std::memory_order_relaxed)) / count_);
}

// Lets go of every claim but the hint's, which the next walk starts from.
void DelaunayBuilder::release_claims(Inserter& in) {
    for (uint32_t t : in.held) {
        if (t != in.hint) __atomic_store_n(claims_.data() + t, uint8_t(0), __ATOMIC_RELEASE);
    }
    in.held.clear();
    in.held.push_back(in.hint);
}

// Whether a shared insertion that replaces `cavity_size` tetrahedra by `faces` new ones fits in the
// thread's scratch space and slots; takes another chunk of the store if it needs one.
bool DelaunayBuilder::room_for(Inserter& in, size_t faces, size_t cavity_size) {
    if (faces > in.new_tets.capacity() || faces > in.new_slots.capacity() || 3 * faces > in.filed.capacity() ||
        edge_table_size(faces) > in.edges.size()) {
        return false;
    }
    const size_t needed = faces > cavity_size ? faces - cavity_size : 0;
    if (in.held.size() + needed > in.held.capacity()) return false;
    const uint32_t capacity = static_cast<uint32_t>(claims_.size());
    while (in.free_count + (in.chunk_end - in.chunk_next) < needed) {
        // Checked before adding, so that threads out of room cannot wrap the counter around.
        in.out_of_slots = next_chunk_.load(std::memory_order_relaxed) >= capacity;
        if (in.out_of_slots) return false;
        const uint32_t begin = next_chunk_.fetch_add(CHUNK_SLOTS, std::memory_order_relaxed);
        in.out_of_slots = begin >= capacity;
        if (in.out_of_slots) return false;
        hand_back_chunk(in);
        in.chunk_next = begin;
        in.chunk_end = std::min(begin + CHUNK_SLOTS, capacity);
    }
    return true;
}

} // namespace dbrg
