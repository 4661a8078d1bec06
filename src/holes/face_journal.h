// Face journal: the undo log of a tentative change to S (a hole fill, a handle cut), so that a change
// that fails is put back exactly as it was.
#pragma once

#include <assert.h>
#include <stdint.h>

#include "core/array.h"
#include "surface/surface.h"

namespace dbrg {

// One ordered log of face additions and removals, taken back last first. Undoing in reverse passes back
// through the states the changes went through, so any interleaving undoes exactly, also where a change
// removed faces the same journal had added (an enlargement inside a fill). Faces are found by their
// corners, not their ids: a removed face that an undo puts back gets a new id, and an earlier entry for
// it must still find it. A directed edge belongs to at most one face of S, so two corners are enough.
class FaceJournal {
public:
    struct Entry {
        uint32_t corners[3];
        uint32_t tet;
        uint8_t causes[3];  // the caller's per-edge marks of a removed face, handed back when it is restored
        uint8_t flags;      // the face's FACE_* bits, handed back with it
        bool removed;       // a removal; otherwise an addition
    };

    explicit FaceJournal(Memory& memory) : entries_(memory) {}

    // The position after the last entry, to undo back to.
    size_t size() const { return entries_.size(); }
    uint32_t added_count() const { return added_; }
    uint32_t removed_count() const { return removed_; }
    // Forgets every entry: the changes so far are kept.
    void clear() {
        entries_.clear();
        added_ = removed_ = 0;
    }

    // Records that face f was just added. Returns false on allocation failure.
    bool record_added(const Surface& surface, uint32_t f) {
        const uint8_t no_causes[3] = {0, 0, 0};
        return record(surface, f, no_causes, false);
    }
    // Records that face f is being or was just removed (a removed face's corners stay readable), with
    // `causes` to hand back when it is restored. Returns false on allocation failure.
    bool record_removed(const Surface& surface, uint32_t f, const uint8_t causes[3]) {
        return record(surface, f, causes, true);
    }

    // Takes back the entries from `position` on, last first: removes each face added, and has
    // restore(entry) add back each face removed (the caller adds it, so it can attach its own data to the
    // new id). Returns false when a removal or restore(entry) failed for lack of memory, or (a bug) a face
    // to remove is not there.
    template <class Restore>
    bool undo(Surface& surface, size_t position, Restore&& restore) {
        while (entries_.size() > position) {
            const Entry entry = entries_.back();
            entries_.pop_back();
            if (entry.removed) {
                --removed_;
                if (!restore(entry)) return false;
                continue;
            }
            --added_;
            // Undoing exactly leaves S as it was right after the addition, so the face is there; if it
            // ever is not, stop rather than remove some other face.
            const uint32_t h = surface.find_halfedge(entry.corners[0], entry.corners[1]);
            assert(h != NO_HALFEDGE && surface.target(Surface::next(h)) == entry.corners[2]);
            if (h == NO_HALFEDGE || surface.target(Surface::next(h)) != entry.corners[2]) return false;
            if (!surface.remove_face(Surface::face_of(h))) return false;
        }
        return true;
    }

private:
    bool record(const Surface& surface, uint32_t f, const uint8_t causes[3], bool removed) {
        Entry entry;
        for (uint32_t i = 0; i < 3; ++i) {
            entry.corners[i] = surface.corner(f, i);
            entry.causes[i] = causes[i];
        }
        entry.tet = surface.face_tet(f);
        entry.flags = surface.face_flags(f);
        entry.removed = removed;
        if (!entries_.push_back(entry)) return false;
        ++(removed ? removed_ : added_);
        return true;
    }

    Array<Entry> entries_;
    uint32_t added_ = 0;
    uint32_t removed_ = 0;
};

} // namespace dbrg
