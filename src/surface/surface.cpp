// Surface: the growing triangulated surface S (paper §2.2) as an array-based half-edge structure.
#include "surface/surface.h"

#include <stdio.h>

#include <algorithm>

namespace dbrg {

Surface::Surface(Memory& memory) : corners_(memory), twins_(memory), tets_(memory), vertex_halfedge_(memory) {}

bool Surface::reset(uint32_t vertex_count) {
    corners_.clear();
    twins_.clear();
    tets_.clear();
    vertex_halfedge_.clear();
    return vertex_halfedge_.resize(vertex_count, NO_HALFEDGE);
}

uint32_t Surface::find_halfedge(uint32_t a, uint32_t b) const {
    const uint32_t start = vertex_halfedge_[a];
    if (start == NO_HALFEDGE) return NO_HALFEDGE;
    uint32_t h = start;
    do {
        if (target(h) == b) return h;
        h = rotate(h);
    } while (h != NO_HALFEDGE && h != start);
    return NO_HALFEDGE;
}

uint32_t Surface::add_face(uint32_t a, uint32_t b, uint32_t c, uint32_t tet) {
    const uint32_t f = face_count();
    if (!corners_.reserve(corners_.size() + 3) || !twins_.reserve(twins_.size() + 3) || !tets_.reserve(tets_.size() + 1)) {
        return NO_FACE;
    }
    corners_.push_back(a);
    corners_.push_back(b);
    corners_.push_back(c);
    for (int i = 0; i < 3; ++i) twins_.push_back(NO_HALFEDGE);
    tets_.push_back(tet);
    for (uint32_t i = 0; i < 3; ++i) link_twins(3 * f + i);
    for (uint32_t i = 0; i < 3; ++i) update_vertex_halfedge(3 * f + i);
    return f;
}

void Surface::link_twins(uint32_t h) {
    const uint32_t opposite = find_halfedge(target(h), origin(h));
    if (opposite == NO_HALFEDGE) return;
    twins_[h] = opposite;
    twins_[opposite] = h;
}

// h is the new face's half-edge leaving v. With one fan per vertex, v's outgoing boundary half-edge
// changes only when h itself is boundary (it becomes the new one) or when both of the new face's
// half-edges at v are linked (the fan closed, and any outgoing half-edge will do).
void Surface::update_vertex_halfedge(uint32_t h) {
    const uint32_t v = origin(h);
    if (vertex_halfedge_[v] == NO_HALFEDGE || is_boundary(h) || !is_boundary(prev(h))) vertex_halfedge_[v] = h;
}

uint32_t Surface::truncate(uint32_t first_face) {
    uint32_t freed = 0;
    for (size_t h = 3 * size_t(first_face); h < corners_.size(); ++h) {
        uint32_t& start = vertex_halfedge_[corners_[h]];
        if (start != NO_HALFEDGE) ++freed;
        start = NO_HALFEDGE;
    }
    corners_.shrink(3 * size_t(first_face));
    twins_.shrink(3 * size_t(first_face));
    tets_.shrink(first_face);
    return freed;
}

bool Surface::validate(char* message, size_t capacity) const {
    const uint32_t faces = face_count();
    const uint32_t halfedges = 3 * faces;
    for (uint32_t f = 0; f < faces; ++f) {
        const uint32_t a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
        if (a == b || b == c || c == a || a >= vertex_count() || b >= vertex_count() || c >= vertex_count()) {
            snprintf(message, capacity, "face %u has corners %u %u %u", f, a, b, c);
            return false;
        }
    }
    for (uint32_t h = 0; h < halfedges; ++h) {
        const uint32_t t = twins_[h];
        if (t == NO_HALFEDGE) continue;
        if (t >= halfedges || twins_[t] != h || origin(t) != target(h) || target(t) != origin(h)) {
            snprintf(message, capacity, "half-edge %u and its twin %u do not match", h, t);
            return false;
        }
    }
    // No directed edge twice (that would be an orientation clash or a third face on an edge), and an
    // unlinked half-edge must not have a reverse partner anywhere.
    Array<uint64_t> directed(corners_.memory());
    if (!directed.reserve(halfedges)) {
        snprintf(message, capacity, "out of memory while validating");
        return false;
    }
    for (uint32_t h = 0; h < halfedges; ++h) directed.push_back(uint64_t(origin(h)) << 32 | target(h));
    std::sort(directed.begin(), directed.end());
    for (uint32_t i = 1; i < halfedges; ++i) {
        if (directed[i] == directed[i - 1]) {
            snprintf(message, capacity, "edge %u->%u is used twice in the same direction",
                     uint32_t(directed[i] >> 32), uint32_t(directed[i]));
            return false;
        }
    }
    for (uint32_t h = 0; h < halfedges; ++h) {
        if (!is_boundary(h)) continue;
        const uint64_t reverse = uint64_t(target(h)) << 32 | origin(h);
        if (std::binary_search(directed.begin(), directed.end(), reverse)) {
            snprintf(message, capacity, "half-edge %u is not linked to its reverse", h);
            return false;
        }
    }
    // One fan per vertex: rotating from vertex_halfedge reaches every face at the vertex.
    Array<uint32_t> faces_at_vertex(corners_.memory());
    if (!faces_at_vertex.resize(vertex_count(), 0)) {
        snprintf(message, capacity, "out of memory while validating");
        return false;
    }
    for (uint32_t h = 0; h < halfedges; ++h) ++faces_at_vertex[origin(h)];
    for (uint32_t v = 0; v < vertex_count(); ++v) {
        const uint32_t start = vertex_halfedge_[v];
        if (start == NO_HALFEDGE) {
            if (faces_at_vertex[v] != 0) {
                snprintf(message, capacity, "vertex %u has faces but no half-edge", v);
                return false;
            }
            continue;
        }
        if (start >= halfedges || origin(start) != v) {
            snprintf(message, capacity, "vertex %u has a half-edge that does not leave it", v);
            return false;
        }
        uint32_t reached = 0;
        bool boundary_seen = false;
        uint32_t h = start;
        do {
            ++reached;
            boundary_seen = boundary_seen || is_boundary(h);
            h = rotate(h);
        } while (h != NO_HALFEDGE && h != start && reached <= faces_at_vertex[v]);
        if (h == NO_HALFEDGE && !is_boundary(start)) {
            snprintf(message, capacity, "boundary vertex %u does not start at its outgoing boundary half-edge", v);
            return false;
        }
        if (reached != faces_at_vertex[v]) {
            snprintf(message, capacity, "vertex %u is non-manifold: one fan holds %u of its %u faces", v, reached,
                     faces_at_vertex[v]);
            return false;
        }
        if (boundary_seen && !is_boundary(start)) {
            snprintf(message, capacity, "vertex %u has a boundary half-edge but does not point to it", v);
            return false;
        }
    }
    return true;
}

} // namespace dbrg
