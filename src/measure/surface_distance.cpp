// Sampled surface-to-surface distance: a bounding volume hierarchy over the target's triangles, searched
// branch and bound for each sample point, in a frame scaled to the unit box so that no square overflows.
#include "measure/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dbrg::measure {
namespace {

struct Point {
    double x, y, z;
    double operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }
};

Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point operator*(Point a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Point a, Point b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point cross(Point a, Point b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double squared(Point a) { return dot(a, a); }

struct Triangle {
    Point a, b, c;
};

struct Box {
    Point lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    void add(Point p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    double squared_distance(Point p) const {
        const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
        const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
        const double dz = std::max({lo.z - p.z, 0.0, p.z - hi.z});
        return dx * dx + dy * dy + dz * dz;
    }
};

double squared_distance_to_segment(Point p, Point a, Point b) {
    const Point ab = b - a;
    const double length = squared(ab);
    const double t = length > 0 ? std::clamp(dot(p - a, ab) / length, 0.0, 1.0) : 0.0;
    return squared(p - (a + ab * t));
}

// The squared distance from p to the nearest point of triangle abc: p's projection onto the plane when
// that falls inside (each side, crossed with p's offset from it, points along the normal), otherwise the
// nearest of the three sides. Cross products keep their accuracy on slivers, where the barycentric
// weights of a projection cancel away.
double squared_distance_to_triangle(Point p, const Triangle& t) {
    const Point normal = cross(t.b - t.a, t.c - t.a);
    const double area = std::sqrt(squared(normal));
    if (area > 0 && dot(cross(t.b - t.a, p - t.a), normal) >= 0 && dot(cross(t.c - t.b, p - t.b), normal) >= 0 &&
        dot(cross(t.a - t.c, p - t.c), normal) >= 0) {
        const double height = dot(p - t.a, normal) / area;
        return height * height;
    }
    return std::min({squared_distance_to_segment(p, t.a, t.b), squared_distance_to_segment(p, t.b, t.c),
                     squared_distance_to_segment(p, t.c, t.a)});
}

// Maps coordinates into [-1, 1]^3 around the centre of a box, dividing rather than multiplying so that
// a box of 1e308 or of 1e-320 maps without overflow.
struct Frame {
    Point centre{0, 0, 0};
    double half = 1;
    Point map(Point p) const { return {(p.x - centre.x) / half, (p.y - centre.y) / half, (p.z - centre.z) / half}; }
};

bool usable(const MeshData& mesh, size_t t) {
    const uint32_t* c = &mesh.triangles[3 * t];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) return false;
    for (int k = 0; k < 3; ++k) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!std::isfinite(mesh.positions[3 * size_t(c[k]) + axis])) return false;
        }
    }
    return true;
}

Point corner(const MeshData& mesh, size_t t, int k) {
    const double* p = &mesh.positions[3 * size_t(mesh.triangles[3 * t + k])];
    return {p[0], p[1], p[2]};
}

std::vector<Triangle> usable_triangles(const MeshData& mesh, const Frame& frame) {
    std::vector<Triangle> out;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (!usable(mesh, t)) continue;
        out.push_back({frame.map(corner(mesh, t, 0)), frame.map(corner(mesh, t, 1)), frame.map(corner(mesh, t, 2))});
    }
    return out;
}

class TriangleTree {
public:
    explicit TriangleTree(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
        order_.resize(triangles_.size());
        for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
        nodes_.push_back({});
        struct Pending {
            uint32_t node, start, end;
        };
        std::vector<Pending> pending{{0, 0, static_cast<uint32_t>(order_.size())}};
        while (!pending.empty()) {
            const Pending p = pending.back();
            pending.pop_back();
            Box bounds, centres;
            for (uint32_t i = p.start; i < p.end; ++i) {
                const Triangle& t = triangles_[order_[i]];
                bounds.add(t.a);
                bounds.add(t.b);
                bounds.add(t.c);
                centres.add(centroid(t));
            }
            nodes_[p.node].bounds = bounds;
            if (p.end - p.start <= LEAF_SIZE) {
                nodes_[p.node].start = p.start;
                nodes_[p.node].count = p.end - p.start;
                continue;
            }
            // Halve at the median centroid along the widest spread; ties go by triangle number.
            const Point spread = centres.hi - centres.lo;
            const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
            const uint32_t middle = p.start + (p.end - p.start) / 2;
            std::nth_element(order_.begin() + p.start, order_.begin() + middle, order_.begin() + p.end,
                             [&](uint32_t i, uint32_t j) {
                                 const double ci = centroid(triangles_[i])[axis], cj = centroid(triangles_[j])[axis];
                                 return ci != cj ? ci < cj : i < j;
                             });
            const uint32_t left = static_cast<uint32_t>(nodes_.size());
            nodes_[p.node].left = left;
            nodes_.resize(nodes_.size() + 2);
            pending.push_back({left, p.start, middle});
            pending.push_back({left + 1, middle, p.end});
        }
    }

    double squared_distance(Point p, uint32_t triangle) const {
        return squared_distance_to_triangle(p, triangles_[triangle]);
    }

    // Lowers `best` to the squared distance from p to the nearest triangle, if that is less, and sets
    // `index` to that triangle. Each node and triangle looked at counts one visit.
    void nearest(Point p, double& best, uint32_t& index, uint64_t& visits) const {
        uint32_t stack[128];  // a median-split tree over fewer than 2^32 triangles is less than 32 deep
        uint32_t size = 0;
        stack[size++] = 0;
        while (size > 0) {
            const Node& node = nodes_[stack[--size]];
            ++visits;
            if (node.bounds.squared_distance(p) >= best) continue;
            if (node.count > 0) {
                for (uint32_t i = node.start; i < node.start + node.count; ++i) {
                    const double d = squared_distance_to_triangle(p, triangles_[order_[i]]);
                    if (d < best) {
                        best = d;
                        index = order_[i];
                    }
                }
                visits += node.count;
                continue;
            }
            // The nearer child is searched first, so that its triangles tighten the bound for the other.
            const bool left_first =
                nodes_[node.left].bounds.squared_distance(p) <= nodes_[node.left + 1].bounds.squared_distance(p);
            stack[size++] = left_first ? node.left + 1 : node.left;
            stack[size++] = left_first ? node.left : node.left + 1;
        }
    }

private:
    static constexpr uint32_t LEAF_SIZE = 4;
    struct Node {
        Box bounds;
        uint32_t left = 0;   // internal nodes: the children are left and left + 1
        uint32_t start = 0;  // leaves: order_[start, start + count)
        uint32_t count = 0;
    };
    static Point centroid(const Triangle& t) { return (t.a + t.b + t.c) * (1.0 / 3.0); }

    std::vector<Triangle> triangles_;
    std::vector<uint32_t> order_;
    std::vector<Node> nodes_;
};

Frame frame_around(const MeshData& a, const MeshData& b) {
    Box box;
    for (const MeshData* mesh : {&a, &b}) {
        for (size_t t = 0; t < mesh->triangle_count(); ++t) {
            if (!usable(*mesh, t)) continue;
            for (int k = 0; k < 3; ++k) box.add(corner(*mesh, t, k));
        }
    }
    Frame frame;
    if (!(box.lo.x <= box.hi.x)) return frame;  // no usable triangle
    frame.centre = {box.lo.x / 2 + box.hi.x / 2, box.lo.y / 2 + box.hi.y / 2, box.lo.z / 2 + box.hi.z / 2};
    frame.half = std::max({box.hi.x / 2 - box.lo.x / 2, box.hi.y / 2 - box.lo.y / 2, box.hi.z / 2 - box.lo.z / 2});
    if (!(frame.half > 0)) frame.half = 1;
    return frame;
}

} // namespace

std::optional<SurfaceDistance> surface_distance(const MeshData& from, const MeshData& to) {
    const Frame frame = frame_around(from, to);
    const std::vector<Triangle> samplers = usable_triangles(from, frame);
    std::vector<Triangle> targets = usable_triangles(to, frame);
    if (samplers.empty() || targets.empty()) return std::nullopt;
    const TriangleTree tree(std::move(targets));

    // A search looks at 25-45 boxes and triangles where the surfaces run close together, up to about 1,200
    // where they are hundreds of sides apart; thousands on average mean triangles piled onto each other,
    // and the measure is given up as soon as the whole allowance is spent rather than after minutes.
    const uint64_t VISITS_PER_SAMPLE = 2048, VISITS_AT_START = 1 << 20;
    const uint64_t sample_count = 7 * uint64_t(samplers.size());
    const uint64_t allowance = VISITS_AT_START + VISITS_PER_SAMPLE * sample_count;
    uint64_t visits = 0;
    double largest = 0, total = 0;
    // Neighbouring samples have nearby nearest triangles: the last one found bounds the search for the next.
    uint32_t warm_start = 0;
    for (const Triangle& t : samplers) {
        const Point samples[7] = {t.a, t.b, t.c, (t.a + t.b) * 0.5, (t.b + t.c) * 0.5, (t.a + t.c) * 0.5,
                                  (t.a + t.b + t.c) * (1.0 / 3.0)};
        for (const Point& p : samples) {
            double best = tree.squared_distance(p, warm_start);
            tree.nearest(p, best, warm_start, visits);
            const double d = std::sqrt(best);
            largest = std::max(largest, d);
            total += d;
        }
        if (visits > allowance) return std::nullopt;
    }
    SurfaceDistance out;
    out.max = largest * frame.half;
    // Equal distances can average a rounding above the largest.
    out.mean = std::min(total / double(sample_count) * frame.half, out.max);
    out.samples = sample_count;
    if (!std::isfinite(out.max) || !std::isfinite(out.mean)) return std::nullopt;
    return out;
}

} // namespace dbrg::measure
