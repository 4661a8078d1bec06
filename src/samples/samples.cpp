// Sample point sets on known surfaces: random points spread by area, thinned to a Poisson-disk set so the
// spacing is even, or clustered on a graded grid as a decimated mesh's vertices are, with the spacing tuned
// until the count is close to what was asked.
#include "samples/samples.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/pi.h"
#include "core/splitmix64.h"

namespace dbrg::samples {
namespace {

class Random {
public:
    explicit Random(uint64_t seed) : generator_(seed) {}
    uint64_t next() { return generator_.next(); }
    // Uniform in [lo, hi).
    double uniform(double lo = 0, double hi = 1) { return lo + (hi - lo) * generator_.uniform(); }

private:
    SplitMix64 generator_;
};

struct Point {
    double x, y, z;
};

// A grid cell's 21-bit coordinates packed into 63 bits.
uint64_t cell_key(int64_t i, int64_t j, int64_t k) {
    return (uint64_t(i) & 0x1fffff) << 42 | (uint64_t(j) & 0x1fffff) << 21 | (uint64_t(k) & 0x1fffff);
}

// Cell key -> a point's index, by open addressing: std::unordered_map's node per entry made thinning a
// million-point sample take half a minute, nearly all of it in its lookups.
class CellMap {
public:
    static constexpr uint32_t NONE = UINT32_MAX;

    explicit CellMap(size_t expected) { rehash(expected); }

    uint32_t find(uint64_t key) const {
        for (size_t i = home(key);; i = (i + 1) & mask_) {
            if (keys_[i] == key) return values_[i];
            if (keys_[i] == EMPTY) return NONE;
        }
    }

    // The value of `key`, which is entered with NONE if it is not there yet.
    uint32_t& operator[](uint64_t key) {
        if (2 * (count_ + 1) > keys_.size()) rehash(keys_.size());
        size_t i = home(key);
        for (; keys_[i] != key; i = (i + 1) & mask_) {
            if (keys_[i] == EMPTY) {
                keys_[i] = key;
                ++count_;
                break;
            }
        }
        return values_[i];
    }

private:
    static constexpr uint64_t EMPTY = ~uint64_t(0);  // no cell key: they use 63 bits

    size_t home(uint64_t key) const { return size_t((key * 0x9e3779b97f4a7c15ull) >> shift_); }

    // Room for twice `entries`, every entry moved over.
    void rehash(size_t entries) {
        std::vector<uint64_t> keys(std::move(keys_));
        std::vector<uint32_t> values(std::move(values_));
        int bits = 4;
        while ((size_t(1) << bits) < 2 * entries) ++bits;
        keys_.assign(size_t(1) << bits, EMPTY);
        values_.assign(keys_.size(), NONE);
        mask_ = keys_.size() - 1;
        shift_ = 64 - bits;
        count_ = 0;
        for (size_t i = 0; i < keys.size(); ++i) {
            if (keys[i] != EMPTY) (*this)[keys[i]] = values[i];
        }
    }

    std::vector<uint64_t> keys_;
    std::vector<uint32_t> values_;
    size_t mask_ = 0, count_ = 0;
    int shift_ = 0;
};

Point on_unit_sphere(Random& random) {
    const double z = random.uniform(-1, 1), a = random.uniform(0, 2 * PI), r = std::sqrt(1 - z * z);
    return {r * std::cos(a), r * std::sin(a), z};
}

// A tube around Bernoulli's lemniscate; the two lobes meet in the middle, which makes two handles.
double double_torus_field(double x, double y, double z) {
    const double lemniscate = (x * x + y * y) * (x * x + y * y) - x * x + y * y;
    return lemniscate * lemniscate + z * z - 0.01;
}

// Newton steps onto the zero set of the double torus field; false when the point does not converge.
bool project_to_double_torus(Point& p) {
    for (int step = 0; step < 30; ++step) {
        const double h = 1e-7;
        const double f = double_torus_field(p.x, p.y, p.z);
        const double gx = (double_torus_field(p.x + h, p.y, p.z) - double_torus_field(p.x - h, p.y, p.z)) / (2 * h);
        const double gy = (double_torus_field(p.x, p.y + h, p.z) - double_torus_field(p.x, p.y - h, p.z)) / (2 * h);
        const double gz = (double_torus_field(p.x, p.y, p.z + h) - double_torus_field(p.x, p.y, p.z - h)) / (2 * h);
        const double g2 = gx * gx + gy * gy + gz * gz;
        if (g2 < 1e-20) return false;
        p = {p.x - f * gx / g2, p.y - f * gy / g2, p.z - f * gz / g2};
        if (std::fabs(f) < 1e-13) return true;
    }
    return false;
}

// A point on the surface of the box [-hx, hx] x [-hy, hy] x [-hz, hz], uniform by area.
Point on_box(Random& random, double hx, double hy, double hz) {
    const double areas[3] = {hy * hz, hx * hz, hx * hy};  // of the faces normal to x, y, z
    double pick = random.uniform(0, areas[0] + areas[1] + areas[2]);
    const double side = random.next() % 2 ? 1.0 : -1.0, s = random.uniform(-1, 1), t = random.uniform(-1, 1);
    if (pick < areas[0]) return {side * hx, s * hy, t * hz};
    pick -= areas[0];
    if (pick < areas[1]) return {s * hx, side * hy, t * hz};
    return {s * hx, t * hy, side * hz};
}

// The relative spacing of the samples at p: 1 everywhere but on the graded sphere, where it grows by
// sqrt(10) from the top pole to the bottom one, so the density falls tenfold.
double relative_spacing(Shape shape, const Point& p) {
    return shape == Shape::graded_sphere ? std::pow(10.0, 0.25 * (1 - p.z)) : 1.0;
}

// One random point on the shape, roughly uniform by area (thinning evens out what is left).
bool raw_point(Shape shape, Random& random, Point& p) {
    switch (shape) {
    case Shape::sphere:
        p = on_unit_sphere(random);
        return true;
    case Shape::bumpy_sphere: {
        const Point d = on_unit_sphere(random);
        const double r = 1 + 0.12 * std::sin(5 * d.x) * std::sin(5 * d.y) * std::sin(5 * d.z);
        p = {r * d.x, r * d.y, r * d.z};
        return true;
    }
    case Shape::hemisphere:
        p = on_unit_sphere(random);
        p.z = std::fabs(p.z);
        return true;
    case Shape::torus: {
        const double major = 1, minor = 0.35;
        const double u = random.uniform(0, 2 * PI), v = random.uniform(0, 2 * PI);
        // Keep the point with probability proportional to the area element.
        if (random.uniform(0, major + minor) > major + minor * std::cos(v)) return false;
        const double ring = major + minor * std::cos(v);
        p = {ring * std::cos(u), ring * std::sin(u), minor * std::sin(v)};
        return true;
    }
    case Shape::double_torus:
        p = {random.uniform(-1.2, 1.2), random.uniform(-0.6, 0.6), random.uniform(-0.15, 0.15)};
        return project_to_double_torus(p);
    case Shape::open_cylinder: {
        const double a = random.uniform(0, 2 * PI);
        p = {0.5 * std::cos(a), 0.5 * std::sin(a), random.uniform(-1, 1)};
        return true;
    }
    case Shape::saddle: {
        const double x = random.uniform(-1, 1), y = random.uniform(-1, 1);
        if (random.uniform() * 9 > 1 + 4 * x * x + 4 * y * y) return false;  // area element of the graph
        p = {x, y, x * x - y * y};
        return true;
    }
    case Shape::cube:
        p = on_box(random, 1, 1, 1);
        return true;
    case Shape::thin_plate:
        p = on_box(random, 1, 1, 0.04);
        return true;
    case Shape::capped_cylinder: {
        // Side area 2 pi r h = 2 pi (0.5)(2), each cap pi r^2: pick by area.
        const double a = random.uniform(0, 2 * PI), pick = random.uniform(0, 2.5);
        if (pick < 2) {
            p = {0.5 * std::cos(a), 0.5 * std::sin(a), random.uniform(-1, 1)};
        } else {
            const double r = 0.5 * std::sqrt(random.uniform());
            p = {r * std::cos(a), r * std::sin(a), pick < 2.25 ? -1.0 : 1.0};
        }
        return true;
    }
    case Shape::graded_sphere:
        p = on_unit_sphere(random);
        return true;
    }
    return false;
}

// Keeps, in order, each point at least `spacing` times its relative spacing away from every point kept
// before it.
std::vector<Point> thin(Shape shape, const std::vector<Point>& raw, double base_spacing) {
    double largest = 1;
    for (const Point& p : raw) largest = std::max(largest, relative_spacing(shape, p));
    const double spacing = base_spacing * largest;  // the grid cell: no conflict reaches past a neighbour cell
    CellMap first_in_cell(raw.size() / 4);
    std::vector<uint32_t> next_in_cell;
    std::vector<Point> kept;
    for (const Point& p : raw) {
        const int64_t ci = int64_t(std::floor(p.x / spacing)), cj = int64_t(std::floor(p.y / spacing)),
                      ck = int64_t(std::floor(p.z / spacing));
        const double needed = base_spacing * relative_spacing(shape, p);
        const auto near_one_in = [&](int64_t i, int64_t j, int64_t k) {
            for (uint32_t q = first_in_cell.find(cell_key(i, j, k)); q != CellMap::NONE; q = next_in_cell[q]) {
                const Point& o = kept[q];
                const double dx = o.x - p.x, dy = o.y - p.y, dz = o.z - p.z;
                if (dx * dx + dy * dy + dz * dz < needed * needed) return true;
            }
            return false;
        };
        // The point's own cell first: most points are turned away, and mostly by a point there.
        bool too_close = near_one_in(ci, cj, ck);
        for (int64_t i = ci - 1; i <= ci + 1 && !too_close; ++i) {
            for (int64_t j = cj - 1; j <= cj + 1 && !too_close; ++j) {
                for (int64_t k = ck - 1; k <= ck + 1 && !too_close; ++k) {
                    too_close = (i != ci || j != cj || k != ck) && near_one_in(i, j, k);
                }
            }
        }
        if (too_close) continue;
        uint32_t& head = first_in_cell[cell_key(ci, cj, ck)];
        next_in_cell.push_back(head);
        head = uint32_t(kept.size());
        kept.push_back(p);
    }
    return kept;
}

// `count` random points on the shape, roughly uniform by area.
std::vector<Point> raw_points(Shape shape, size_t count, Random& random) {
    std::vector<Point> raw;
    raw.reserve(count);
    while (raw.size() < count) {
        Point p;
        if (raw_point(shape, random, p)) raw.push_back(p);
    }
    return raw;
}

// Keeps, in order, the first point in each cell of a grid whose cells are `base` long in z at the bottom
// and grow geometrically up to sqrt(density_ratio) times that at the top (so the density of kept points
// falls density_ratio times), `stretch` times as long in x as in y.
std::vector<Point> cluster(const std::vector<Point>& raw, double base, double density_ratio, double stretch) {
    double bottom = HUGE_VAL, top = -HUGE_VAL;
    for (const Point& p : raw) {
        bottom = std::min(bottom, p.z);
        top = std::max(top, p.z);
    }
    const double height = top - bottom, half_log = 0.5 * std::log(density_ratio);
    CellMap taken(raw.size() / 4);
    std::vector<Point> kept;
    for (const Point& p : raw) {
        const double t = (p.z - bottom) / height, growth = std::exp(half_log * t);
        // z measured in cells: the integral of 1 / (base * growth) from the bottom.
        const double z_cells = half_log > 0 ? height * (1 - 1 / growth) / (half_log * base) : (p.z - bottom) / base;
        const int64_t i = int64_t(std::floor(p.x / (base * growth * stretch))), j = int64_t(std::floor(p.y / (base * growth))),
                      k = int64_t(std::floor(z_cells));
        uint32_t& first = taken[cell_key(i, j, k)];
        if (first != CellMap::NONE) continue;
        first = uint32_t(kept.size());
        kept.push_back(p);
    }
    return kept;
}

std::vector<double> coordinates(const std::vector<Point>& points) {
    std::vector<double> xyz;
    xyz.reserve(3 * points.size());
    for (const Point& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    return xyz;
}

} // namespace

ShapeFacts facts(Shape shape) {
    switch (shape) {
    case Shape::sphere: return {"sphere", 0, 0};
    case Shape::torus: return {"torus", 1, 0};
    case Shape::double_torus: return {"double_torus", 2, 0};
    case Shape::bumpy_sphere: return {"bumpy_sphere", 0, 0};
    case Shape::hemisphere: return {"hemisphere", 0, 1};
    case Shape::open_cylinder: return {"open_cylinder", 0, 2};
    case Shape::saddle: return {"saddle", 0, 1};
    case Shape::cube: return {"cube", 0, 0};
    case Shape::capped_cylinder: return {"capped_cylinder", 0, 0};
    case Shape::graded_sphere: return {"graded_sphere", 0, 0};
    case Shape::thin_plate: return {"thin_plate", 0, 0};
    }
    return {"unknown", 0, 0};
}

bool shape_from_name(std::string_view name, Shape& shape) {
    for (Shape s : {Shape::sphere, Shape::torus, Shape::double_torus, Shape::bumpy_sphere, Shape::hemisphere,
                    Shape::open_cylinder, Shape::saddle, Shape::cube, Shape::capped_cylinder, Shape::graded_sphere,
                    Shape::thin_plate}) {
        if (name == facts(s).name) {
            shape = s;
            return true;
        }
    }
    return false;
}

std::vector<double> sample_clustered(Shape shape, size_t count, double density_ratio, double stretch, uint64_t seed) {
    Random random(seed);
    const std::vector<Point> raw = raw_points(shape, 30 * count, random);
    // The number of cells hit falls as the square of the cell size: a few corrections home in on `count`.
    double base = 2.0 / std::sqrt(double(count));
    std::vector<Point> kept = cluster(raw, base, density_ratio, stretch);
    for (int round = 0; round < 8 && !kept.empty(); ++round) {
        const double ratio = double(kept.size()) / double(count);
        if (std::fabs(ratio - 1) < 0.03) break;
        base *= std::sqrt(ratio);
        kept = cluster(raw, base, density_ratio, stretch);
    }
    return coordinates(kept);
}

std::vector<double> sample(Shape shape, size_t count, uint64_t seed) {
    Random random(seed);
    const std::vector<Point> raw = raw_points(shape, 6 * count, random);
    // The number of points kept falls as the square of the spacing: a few corrections home in on `count`.
    double spacing = 2.0 / std::sqrt(double(count));
    std::vector<Point> kept = thin(shape, raw, spacing);
    for (int round = 0; round < 4 && !kept.empty(); ++round) {
        const double ratio = double(kept.size()) / double(count);
        if (std::fabs(ratio - 1) < 0.02) break;
        spacing *= std::sqrt(ratio);
        kept = thin(shape, raw, spacing);
    }
    return coordinates(kept);
}

} // namespace dbrg::samples
