// Passes over a cloud file too large for memory: summary, spacing, bucket files (see cloud_files.h).
#include "tiles/cloud_files.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <queue>
#include <unordered_map>

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <ctime>

#include "tiles/point_spacing.h"

namespace dbrg::out_of_core {
namespace {

// Points read per batch: large enough to cost little per call, small beside any budget (1.5 MiB).
const size_t BATCH_POINTS = 1 << 16;

// Calls `visit(p, id)` for every point of `reader`, from the start, with its position in the file.
template <class Visit>
io::IoStatus for_each_point(io::PointReader& reader, const Visit& visit) {
    io::IoStatus status = reader.rewind();
    if (!status) return status;
    std::vector<double> xyz(3 * BATCH_POINTS);
    uint64_t id = 0;
    for (;;) {
        size_t count = 0;
        status = reader.read(xyz.data(), BATCH_POINTS, count);
        if (!status || count == 0) return status;
        for (size_t i = 0; i < count; ++i) visit(&xyz[3 * i], id++);
    }
}

struct Sampled {
    uint64_t hash;
    std::array<double, 3> xyz;
    bool operator<(const Sampled& other) const { return hash != other.hash ? hash < other.hash : xyz < other.xyz; }
};

// Cells of a grid from the box's low corner, keyed by their coordinates (each below 2^21 and at least -1).
struct Grid {
    double low[3];
    double cell;

    int64_t coordinate(const double* p, int axis) const { return static_cast<int64_t>((p[axis] - low[axis]) / cell); }
    static uint64_t key(int64_t x, int64_t y, int64_t z) {
        const int64_t offset = 1;
        return uint64_t(x + offset) << 42 | uint64_t(y + offset) << 21 | uint64_t(z + offset);
    }
};

// One pass over the file finding, for each of `queries` (indices into `xyz`), the nearest other point in
// its cell of `grid` and the 26 around it; lowers best[q]. The cells around the queries are listed once,
// so a point costs one look-up.
io::IoStatus search_pass(io::PointReader& reader, const Grid& grid, const std::vector<std::array<double, 3>>& xyz,
                         const std::vector<uint32_t>& queries, std::vector<double>& best) {
    std::vector<std::pair<uint64_t, uint32_t>> around;  // (cell, query), sorted
    around.reserve(27 * queries.size());
    for (uint32_t q : queries) {
        const double* p = xyz[q].data();
        const int64_t c[3] = {grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2)};
        for (int64_t x = c[0] - 1; x <= c[0] + 1; ++x) {
            for (int64_t y = c[1] - 1; y <= c[1] + 1; ++y) {
                for (int64_t z = c[2] - 1; z <= c[2] + 1; ++z) around.emplace_back(Grid::key(x, y, z), q);
            }
        }
    }
    std::sort(around.begin(), around.end());
    std::unordered_map<uint64_t, uint32_t> first;  // cell -> its first entry in `around`
    first.reserve(around.size());
    for (size_t i = around.size(); i-- > 0;) first[around[i].first] = uint32_t(i);
    return for_each_point(reader, [&](const double* p, uint64_t) {
        const uint64_t key = Grid::key(grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2));
        const auto found = first.find(key);
        if (found == first.end()) return;
        for (size_t i = found->second; i < around.size() && around[i].first == key; ++i) {
            const std::array<double, 3>& q = xyz[around[i].second];
            const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            double& nearest = best[around[i].second];
            if (d > 0 && d < nearest) nearest = d;
        }
    });
}

} // namespace

io::IoStatus summarize(io::PointReader& reader, CloudSummary& summary) {
    summary = CloudSummary();
    summary.low.fill(HUGE_VAL);
    summary.high.fill(-HUGE_VAL);
    std::priority_queue<Sampled> sample;  // the smallest hashes seen, the largest of them on top
    const io::IoStatus status = for_each_point(reader, [&](const double* p, uint64_t) {
        ++summary.count;
        for (int a = 0; a < 3; ++a) {
            summary.low[a] = std::min(summary.low[a], p[a]);
            summary.high[a] = std::max(summary.high[a], p[a]);
            summary.float_exact = summary.float_exact && double(float(p[a])) == p[a];
        }
        const Sampled candidate{coordinate_hash(p), {p[0], p[1], p[2]}};
        if (sample.size() < SAMPLE_POINTS) {
            sample.push(candidate);
        } else if (candidate < sample.top()) {
            sample.pop();
            sample.push(candidate);
        }
    });
    if (!status) return status;
    for (int a = 1; a < 3; ++a) {
        if (summary.high[a] - summary.low[a] > summary.high[summary.axis] - summary.low[summary.axis]) summary.axis = a;
    }
    for (; !sample.empty(); sample.pop()) summary.axis_sample.push_back(sample.top().xyz[summary.axis]);
    std::sort(summary.axis_sample.begin(), summary.axis_sample.end());
    return status;
}

io::IoStatus stream_spacing(io::PointReader& reader, const CloudSummary& summary, double& spacing) {
    spacing = 0;
    if (summary.count < 2) return io::IoStatus::success();
    const double extent = std::max({summary.high[0] - summary.low[0], summary.high[1] - summary.low[1],
                                    summary.high[2] - summary.low[2]});
    if (!(extent > 0)) return io::IoStatus::success();
    const double cell = spacing_grid_cell(extent, summary.count);
    const uint64_t stride = spacing_sample_stride(summary.count);
    std::vector<std::array<double, 3>> xyz;
    io::IoStatus status = for_each_point(reader, [&](const double* p, uint64_t) {
        if (coordinate_hash(p) % stride == 0) xyz.push_back({p[0], p[1], p[2]});
    });
    if (!status) return status;
    std::vector<double> best(xyz.size(), HUGE_VAL);
    std::vector<uint32_t> queries(xyz.size());
    for (uint32_t q = 0; q < queries.size(); ++q) queries[q] = q;
    // Cells of 4 of the whole-cloud grid's cells settle nearly every sample point; cells of 16 the rest,
    // as far as the whole-cloud search looks. A neighbour found no further than a cell's side is the
    // nearest: every point outside the 27 cells searched is further away.
    for (double scale : {4.0, 16.0}) {
        const Grid grid{{summary.low[0], summary.low[1], summary.low[2]}, scale * cell};
        status = search_pass(reader, grid, xyz, queries, best);
        if (!status) return status;
        std::vector<uint32_t> unresolved;
        for (uint32_t q : queries) {
            if (!(best[q] <= grid.cell)) unresolved.push_back(q);
        }
        queries.swap(unresolved);
        if (queries.empty()) break;
    }
    std::vector<double> distances;
    for (double d : best) {
        if (d != HUGE_VAL) distances.push_back(d);
    }
    if (distances.empty()) {
        spacing = cell;
        return status;
    }
    const auto percentile = distances.begin() + distances.size() * 9 / 10;
    std::nth_element(distances.begin(), percentile, distances.end());
    spacing = *percentile;
    return status;
}

std::vector<double> sample_walls(const CloudSummary& summary, uint32_t tile_count, double min_width) {
    std::vector<double> walls;
    const std::vector<double>& values = summary.axis_sample;
    if (values.empty()) return walls;
    const double first = summary.low[summary.axis], last = summary.high[summary.axis];
    for (uint32_t k = 1; k < tile_count; ++k) {
        const double wall = values[values.size() * k / tile_count];
        const double previous = walls.empty() ? first : walls.back();
        if (!(wall - previous >= min_width && last - wall >= min_width)) continue;
        walls.push_back(wall);
    }
    return walls;
}

namespace {

// A folder of temporary files younger than this is never taken for abandoned: it may be one another run
// has just made and not yet locked.
constexpr time_t ABANDONED_AFTER_SECONDS = 60;

void remove_folder(const std::string& path) {
    if (DIR* folder = opendir(path.c_str())) {
        while (const dirent* entry = readdir(folder)) {
            const std::string name = entry->d_name;
            if (name != "." && name != "..") unlink((path + "/" + name).c_str());
        }
        closedir(folder);
    }
    rmdir(path.c_str());
}

// Removes the folders named `prefix`... in `parent` that a killed run left: no process holds their lock
// (the kernel lets go of a dead process's locks) and they are not new. Where the file system has no
// locks, nothing is removed.
void remove_abandoned(const std::string& parent, const std::string& prefix) {
    DIR* folder = opendir(parent.c_str());
    if (!folder) return;
    while (const dirent* entry = readdir(folder)) {
        const std::string name = entry->d_name;
        if (name.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string path = parent + "/" + name;
        const int descriptor = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (descriptor < 0) continue;
        struct stat status;
        if (fstat(descriptor, &status) == 0 && time(nullptr) - status.st_mtime >= ABANDONED_AFTER_SECONDS &&
            flock(descriptor, LOCK_EX | LOCK_NB) == 0) {
            remove_folder(path);
        }
        close(descriptor);
    }
    closedir(folder);
}

} // namespace

TempFolder::~TempFolder() {
    if (path_.empty()) return;
    remove_folder(path_);
    if (lock_ >= 0) close(lock_);
}

io::IoStatus TempFolder::create(const std::string& parent, const std::string& stem) {
    const std::string prefix = "." + stem + ".dbrg-tiles-";
    remove_abandoned(parent, prefix);
    std::string name = parent + "/" + prefix + "XXXXXX";
    if (!mkdtemp(name.data())) {
        return io::IoStatus::failure(parent + ": cannot create a folder for the tiles: " + std::strerror(errno));
    }
    path_ = name;
    // Held until the folder goes, so that later runs can tell it from one a killed run left behind.
    lock_ = open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (lock_ >= 0) flock(lock_, LOCK_EX);
    return io::IoStatus::success();
}

io::IoStatus write_buckets(io::PointReader& reader, int axis, const std::vector<double>& walls, double halo,
                           const std::vector<std::string>& paths) {
    std::vector<std::unique_ptr<std::FILE, int (*)(std::FILE*)>> files;
    for (const std::string& path : paths) {
        files.emplace_back(std::fopen(path.c_str(), "wb"), std::fclose);
        if (!files.back()) return io::IoStatus::failure(path + ": cannot create: " + std::strerror(errno));
    }
    bool written = true;
    io::IoStatus status = for_each_point(reader, [&](const double* p, uint64_t id) {
        const double x = p[axis];
        const PointRecord record{id, {p[0], p[1], p[2]}};
        // The slab whose core holds the point, then its neighbours while their halo reaches it.
        const size_t core = size_t(std::upper_bound(walls.begin(), walls.end(), x) - walls.begin());
        size_t first = core, last = core;
        while (first > 0 && x < walls[first - 1] + halo) --first;
        while (last < walls.size() && x >= walls[last] - halo) ++last;
        for (size_t k = first; k <= last; ++k) written = written && std::fwrite(&record, sizeof record, 1, files[k].get()) == 1;
    });
    for (size_t k = 0; k < files.size(); ++k) {
        written = std::fclose(files[k].release()) == 0 && written;
        if (!written && status) status = io::IoStatus::failure(paths[k] + ": cannot write: " + std::strerror(errno));
    }
    return status;
}

} // namespace dbrg::out_of_core
