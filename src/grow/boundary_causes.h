// Boundary causes: why each boundary half-edge of S is still open when growing stops, the record region
// growing hands to hole filling. A hole (paper §5) is where every candidate was invalid; a real border
// of an open surface (§4) is where the open-surface test refused the candidate.
#pragma once

#include <stdint.h>

#include "core/array.h"

namespace dbrg {

enum BoundaryCause : uint8_t {
    BOUNDARY_UNRESOLVED = 0,  // every candidate was invalid (§3.2.1): a hole, for hole filling (§5)
    BOUNDARY_OPEN = 1,        // the open-surface test (§4) refused its candidate: a real border
};

// A bit per half-edge of the faces recorded so far; a half-edge past them (a face added later) is
// unresolved.
class BoundaryCauses {
public:
    explicit BoundaryCauses(Memory& memory) : open_(memory) {}

    BoundaryCause of(uint32_t halfedge) const {
        return halfedge < halfedges_ && (open_[halfedge / 8] >> halfedge % 8 & 1) ? BOUNDARY_OPEN : BOUNDARY_UNRESOLVED;
    }

    // Makes room for the half-edges of `faces` faces in one allocation. Returns false on allocation failure.
    bool reserve_faces(size_t faces) { return open_.reserve((3 * faces + 7) / 8); }
    // Records the half-edges of faces 0 .. faces - 1, those not recorded yet unresolved. Returns false on
    // allocation failure.
    bool cover_faces(uint32_t faces) {
        halfedges_ = 3 * faces;
        return open_.resize((size_t(halfedges_) + 7) / 8, 0);
    }
    // `halfedge`, a recorded one, stays open because the open-surface test refused its candidate.
    void mark_open(uint32_t halfedge) { open_[halfedge / 8] |= uint8_t(1u << halfedge % 8); }

private:
    Array<uint8_t> open_;     // the bits
    uint32_t halfedges_ = 0;  // how many half-edges have a bit
};

} // namespace dbrg
