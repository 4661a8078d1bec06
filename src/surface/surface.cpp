// Surface: the growing triangulated surface S (paper §2.2) as an array-based half-edge structure, with the
// topological examination (§3.2.1) of a face before it is added.
#include "surface/surface.h"

#include <stdio.h>

#include <algorithm>

namespace dbrg {

Surface::Surface(Memory& memory)
    : corners_(memory), twins_(memory), tets_(memory), flags_(memory), vertex_halfedge_(memory), extra_fans_(memory), first_extra_(memory) {}

bool Surface::reset(uint32_t vertex_count) {
    corners_.clear();
    twins_.clear();
    tets_.clear();
    flags_.clear();
    extra_fans_.clear();
    pinched_vertices_ = 0;
    used_vertices_ = 0;
    removed_faces_ = 0;
    vertex_halfedge_.clear();
    first_extra_.clear();
    return vertex_halfedge_.resize(vertex_count, NO_HALFEDGE) && first_extra_.resize(vertex_count, NO_EXTRA_FAN);
}

uint32_t Surface::find_halfedge(uint32_t a, uint32_t b) const {
    uint32_t found = NO_HALFEDGE;
    walk_vertex(a, [&](uint32_t h) {
        if (target(h) == b) found = h;
        return found == NO_HALFEDGE;
    });
    return found;
}

void Surface::find_edges(uint32_t x, uint32_t y, uint32_t z, uint32_t& xy, uint32_t& yx, uint32_t& xz,
                         uint32_t& zx) const {
    xy = yx = xz = zx = NO_HALFEDGE;
    walk_vertex(x, [&](uint32_t h) {
        const uint32_t w = target(h), into = prev(h), from = origin(into);
        if (w == y) xy = h;
        if (w == z) xz = h;
        if (from == y) yx = into;
        if (from == z) zx = into;
        return xy == NO_HALFEDGE || yx == NO_HALFEDGE || xz == NO_HALFEDGE || zx == NO_HALFEDGE;
    });
}

uint32_t Surface::fan_exit(uint32_t incoming_boundary) const {
    uint32_t h = next(incoming_boundary);
    while (twins_[h] != NO_HALFEDGE) h = next(twins_[h]);
    return h;
}

FaceCheck Surface::check_face(uint32_t a, uint32_t b, uint32_t c) const {
    FaceCheck check;
    const uint32_t corners[3] = {a, b, c};
    // The half-edges from each corner to the next (edge i in the face's direction) and to the previous one
    // (the reverse of edge i + 2): a turn around a finds those between a and the others, a turn around c
    // those between c and b (none when c has no face yet, as when growing reaches a new point).
    uint32_t to_next[3], to_previous[3], unused[2];
    find_edges(a, b, c, to_next[0], to_previous[1], to_previous[0], to_next[2]);
    find_edges(c, b, a, to_previous[2], to_next[1], unused[0], unused[1]);
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t same = to_next[i];
        if (same != NO_HALFEDGE) {
            check.verdict = is_boundary(same) ? FaceCheck::orientation : FaceCheck::edge_nonmanifold;
            return check;
        }
        const uint32_t reverse = to_previous[(i + 1) % 3];
        if (reverse != NO_HALFEDGE && !is_boundary(reverse)) {
            check.verdict = FaceCheck::edge_nonmanifold;
            return check;
        }
        check.shared[i] = reverse;
    }
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t p = corners[i];
        if (!is_used(p)) continue;
        // At p the face leaves along edge i and arrives along edge i + 2; their reverses in S, if any, are
        // the boundary half-edges entering the fan X it joins and leaving the fan Y it joins.
        const uint32_t entering_x = check.shared[i];
        const uint32_t leaving_y = check.shared[(i + 2) % 3];
        if (entering_x == NO_HALFEDGE && leaving_y == NO_HALFEDGE) {
            if (!is_boundary_vertex(p)) {
                check.verdict = FaceCheck::bowtie;  // p's only fan is closed
                return check;
            }
            ++check.pinches;
        } else if (entering_x != NO_HALFEDGE && leaving_y != NO_HALFEDGE && fan_exit(entering_x) == leaving_y &&
                   is_pinched(p)) {
            check.verdict = FaceCheck::bowtie;  // it would close one fan of a pinched vertex
            return check;
        }
    }
    return check;
}

uint32_t Surface::add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet) {
    FaceCheck check;
    const uint32_t corners[3] = {a, b, c};
    for (uint32_t i = 0; i < 3; ++i) check.shared[i] = find_halfedge(corners[(i + 1) % 3], corners[i]);
    return add_face(a, b, c, tet, check);
}

uint32_t Surface::add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet, const FaceCheck& check) {
    const uint32_t f = face_count();
    if (!corners_.reserve_more(3) || !twins_.reserve_more(3) || !tets_.reserve_more(1) || !flags_.reserve_more(1)) {
        return NO_FACE;
    }
    const uint32_t corners[3] = {a, b, c};
    const uint32_t* shared = check.shared;
    uint32_t closes[3];
    for (uint32_t i = 0; i < 3; ++i) {
        // Whether the fan entered through shared[i] is the one left through shared[i + 2]: the face closes it.
        closes[i] = shared[i] != NO_HALFEDGE && shared[(i + 2) % 3] != NO_HALFEDGE &&
                    fan_exit(shared[i]) == shared[(i + 2) % 3];
    }
    for (uint32_t i = 0; i < 3; ++i) {
        corners_.push_back(corners[i]);
        twins_.push_back(shared[i]);
        if (shared[i] != NO_HALFEDGE) twins_[shared[i]] = 3 * f + i;
    }
    tets_.push_back(tet);
    flags_.push_back(0);
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t p = corners[i], leaving = 3 * f + i;
        const uint32_t entering_x = shared[i], leaving_y = shared[(i + 2) % 3];
        if (entering_x == NO_HALFEDGE && leaving_y == NO_HALFEDGE) {
            if (!add_fan(p, leaving)) return NO_FACE;
        } else if (entering_x == NO_HALFEDGE) {
            replace_fan(p, leaving_y, leaving);  // Y now ends at the new face
        } else if (leaving_y != NO_HALFEDGE) {
            if (closes[i]) {
                replace_fan(p, leaving_y, leaving);  // any outgoing half-edge stands for a closed fan
            } else {
                drop_fan(p, leaving_y);  // X and Y are one fan now, ending where X ended
            }
        }
    }
    return f;
}

bool Surface::remove_face(uint32_t f) {
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t p = corner(f, i), leaving = 3 * f + i, arriving = prev(leaving);
        const uint32_t after = twins_[leaving];    // the neighbour's half-edge into p across `leaving`
        const uint32_t before = twins_[arriving];  // the neighbour's half-edge out of p across `arriving`
        if (after == NO_HALFEDGE && before == NO_HALFEDGE) {
            drop_fan(p, leaving);  // the face was a fan of its own
        } else if (after == NO_HALFEDGE) {
            replace_fan(p, leaving, before);  // the fan now ends one face earlier
        } else if (before != NO_HALFEDGE) {
            if (!is_boundary(vertex_halfedge_[p])) {
                vertex_halfedge_[p] = before;  // the closed fan opens here
            } else if (!add_fan(p, before)) {
                return false;  // the open fan splits in two
            }
        }
    }
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t h = 3 * f + i;
        if (twins_[h] != NO_HALFEDGE) twins_[twins_[h]] = NO_HALFEDGE;
        twins_[h] = REMOVED;
    }
    ++removed_faces_;
    return true;
}

bool Surface::remove_pinches(Array<uint32_t>& removed, const uint8_t* spared) {
    for (;;) {
        uint32_t v = NO_HALFEDGE;
        for (const ExtraFan& fan : extra_fans_) {
            if (!spared || !spared[fan.vertex]) {
                v = fan.vertex;
                break;
            }
        }
        if (v == NO_HALFEDGE) break;
        uint32_t largest = NO_HALFEDGE, largest_size = 0;
        for_each_fan(v, [&](uint32_t start) {
            const uint32_t size = fan_size(start);
            if (size > largest_size || (size == largest_size && start < largest)) {
                largest = start;
                largest_size = size;
            }
        });
        const size_t first = removed.size();
        bool grown = true;
        for_each_fan(v, [&](uint32_t start) {
            if (start != largest) walk_fan(start, [&](uint32_t h) { grown = grown && removed.push_back(face_of(h)); });
        });
        if (!grown) return false;
        for (size_t i = first; i < removed.size(); ++i) {
            if (!remove_face(removed[i])) return false;
        }
    }
    return true;
}

bool Surface::add_fan(uint32_t v, uint32_t h) {
    if (vertex_halfedge_[v] == NO_HALFEDGE) {
        vertex_halfedge_[v] = h;
        ++used_vertices_;
        return true;
    }
    if (!extra_fans_.push_back(ExtraFan{v, h, NO_EXTRA_FAN})) return false;
    pinched_vertices_ += is_pinched(v) ? 0 : 1;
    link_extra_fan(uint32_t(extra_fans_.size() - 1));
    return true;
}

void Surface::replace_fan(uint32_t v, uint32_t old_h, uint32_t new_h) {
    if (vertex_halfedge_[v] == old_h) {
        vertex_halfedge_[v] = new_h;
        return;
    }
    for (uint32_t p = first_extra_[v]; p != NO_EXTRA_FAN; p = extra_fans_[p].next) {
        if (extra_fans_[p].halfedge == old_h) extra_fans_[p].halfedge = new_h;
    }
}

void Surface::drop_fan(uint32_t v, uint32_t h) {
    uint32_t found = NO_EXTRA_FAN;
    if (vertex_halfedge_[v] == h) {
        // Promote another fan, if any, to be the vertex's first.
        found = first_extra_[v];
        vertex_halfedge_[v] = found != NO_EXTRA_FAN ? extra_fans_[found].halfedge : NO_HALFEDGE;
        used_vertices_ -= vertex_halfedge_[v] == NO_HALFEDGE ? 1 : 0;
    } else {
        for (uint32_t p = first_extra_[v]; p != NO_EXTRA_FAN && found == NO_EXTRA_FAN; p = extra_fans_[p].next) {
            if (extra_fans_[p].halfedge == h) found = p;
        }
    }
    if (found == NO_EXTRA_FAN) return;
    remove_extra_fan(found);
    pinched_vertices_ -= is_pinched(v) ? 0 : 1;
}

void Surface::link_extra_fan(uint32_t position) {
    uint32_t* slot = &first_extra_[extra_fans_[position].vertex];
    while (*slot != NO_EXTRA_FAN && *slot < position) slot = &extra_fans_[*slot].next;
    extra_fans_[position].next = *slot;
    *slot = position;
}

void Surface::unlink_extra_fan(uint32_t position) {
    uint32_t* slot = &first_extra_[extra_fans_[position].vertex];
    while (*slot != position) slot = &extra_fans_[*slot].next;
    *slot = extra_fans_[position].next;
}

void Surface::remove_extra_fan(uint32_t position) {
    unlink_extra_fan(position);
    const uint32_t last = uint32_t(extra_fans_.size() - 1);
    if (position != last) {
        unlink_extra_fan(last);
        extra_fans_[position] = extra_fans_[last];
        link_extra_fan(position);
    }
    extra_fans_.pop_back();
}

bool Surface::validate(char* message, size_t capacity) const {
    const uint32_t faces = face_count();
    const uint32_t halfedges = 3 * faces;
    uint32_t removed = 0;
    for (uint32_t f = 0; f < faces; ++f) {
        if (face_removed(f)) {
            ++removed;
            continue;
        }
        const uint32_t a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
        if (a == b || b == c || c == a || a >= vertex_count() || b >= vertex_count() || c >= vertex_count()) {
            snprintf(message, capacity, "face %u has corners %u %u %u", f, a, b, c);
            return false;
        }
        for (uint32_t h = 3 * f; h < 3 * f + 3; ++h) {
            const uint32_t t = twins_[h];
            if (t == NO_HALFEDGE) continue;
            if (t >= halfedges || face_removed(face_of(t)) || twins_[t] != h || origin(t) != target(h) ||
                target(t) != origin(h)) {
                snprintf(message, capacity, "half-edge %u and its twin %u do not match", h, t);
                return false;
            }
        }
    }
    if (removed != removed_faces_) {
        snprintf(message, capacity, "%u faces are marked removed, %u counted", removed, removed_faces_);
        return false;
    }
    uint32_t used = 0;
    for (uint32_t v = 0; v < vertex_count(); ++v) used += is_used(v) ? 1 : 0;
    if (used != used_vertices_) {
        snprintf(message, capacity, "%u vertices have faces, %u counted", used, used_vertices_);
        return false;
    }
    // No directed edge twice (an orientation clash or a third face on an edge), and a boundary half-edge
    // must not have a reverse partner anywhere.
    Array<uint64_t> directed(corners_.memory());
    Array<uint32_t> faces_at_vertex(corners_.memory());
    if (!directed.reserve(halfedges) || !faces_at_vertex.resize(vertex_count(), 0)) {
        snprintf(message, capacity, "out of memory while validating");
        return false;
    }
    for (uint32_t h = 0; h < halfedges; ++h) {
        if (face_removed(face_of(h))) continue;
        directed.push_back(uint64_t(origin(h)) << 32 | target(h));
        ++faces_at_vertex[origin(h)];
    }
    std::sort(directed.begin(), directed.end());
    for (size_t i = 1; i < directed.size(); ++i) {
        if (directed[i] == directed[i - 1]) {
            snprintf(message, capacity, "edge %u->%u is used twice in the same direction",
                     uint32_t(directed[i] >> 32), uint32_t(directed[i]));
            return false;
        }
    }
    for (uint32_t h = 0; h < halfedges; ++h) {
        if (face_removed(face_of(h)) || !is_boundary(h)) continue;
        if (std::binary_search(directed.begin(), directed.end(), uint64_t(target(h)) << 32 | origin(h))) {
            snprintf(message, capacity, "half-edge %u is not linked to its reverse", h);
            return false;
        }
    }
    // The recorded fans of each vertex hold all its faces: open fans start at their outgoing boundary
    // half-edge, and a closed fan is the vertex's only fan.
    uint32_t pinched = 0;
    for (uint32_t v = 0; v < vertex_count(); ++v) {
        uint32_t reached = 0, fans = 0;
        bool well_formed = true;
        for_each_fan(v, [&](uint32_t start) {
            ++fans;
            if (start >= halfedges || face_removed(face_of(start)) || origin(start) != v) {
                well_formed = false;
                return;
            }
            bool open = false;
            walk_fan(start, [&](uint32_t h) {
                ++reached;
                open = rotate(h) == NO_HALFEDGE;
                return reached <= faces_at_vertex[v];  // a corrupt fan may circle without coming back
            });
            if (open ? !is_boundary(start) : fans > 1) well_formed = false;
        });
        pinched += fans > 1 ? 1 : 0;
        if (!well_formed || reached != faces_at_vertex[v] || (fans > 1) != is_pinched(v)) {
            snprintf(message, capacity, "vertex %u: %u recorded fans hold %u of its %u faces%s", v, fans, reached,
                     faces_at_vertex[v], well_formed ? "" : ", and one does not start at a boundary half-edge");
            return false;
        }
    }
    if (pinched != pinched_vertices_) {
        snprintf(message, capacity, "%u vertices are pinched, %u counted", pinched, pinched_vertices_);
        return false;
    }
    return true;
}

} // namespace dbrg
