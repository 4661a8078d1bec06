// The cloud of a file too large for memory, handled in passes over the file: a summary (count, box, a
// bounded sample), the point spacing, and the points sorted into per-tile bucket files on disk, each point
// with its 64-bit id (its position in the file). Part of the out-of-core loop (out_of_core.h).
#pragma once

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "io/point_reader.h"

namespace dbrg::out_of_core {

// What one pass over the file learns.
struct CloudSummary {
    uint64_t count = 0;
    std::array<double, 3> low{}, high{};
    bool float_exact = true;  // every coordinate is a float: the output can store floats
    // The axis along which the box is longest, and a sample of the points' coordinates on it: those of
    // the SAMPLE_POINTS points of smallest coordinate hash (the same sample whatever the points' order),
    // sorted, for the walls' quantiles.
    int axis = 0;
    std::vector<double> axis_sample;
};

// Points kept for the walls' quantiles: the quantile of a fraction q is off by about
// sqrt(q (1 - q) / SAMPLE_POINTS) of the points, 0.2 % at the median.
constexpr size_t SAMPLE_POINTS = 1 << 16;

// Streams `reader` once (from the start) for its summary.
io::IoStatus summarize(io::PointReader& reader, CloudSummary& summary);

// The point spacing estimate_spacing (point_spacing.h) gives for the whole cloud, from two passes: one
// picking its hash-chosen sample, one searching the cells around each sample point for its nearest
// neighbour (in one more pass, further out, for the few not found close by). The figures differ only
// where a sample point's nearest neighbour is more than 16 of the whole-cloud search's cells away (an
// outlier), which the two searches treat differently.
io::IoStatus stream_spacing(io::PointReader& reader, const CloudSummary& summary, double& spacing);

// The inner walls of `tile_count` slabs along summary.axis at quantiles of the sample, dropping walls
// closer than `min_width` to the previous one or to either end of the box, as slab_walls does.
std::vector<double> sample_walls(const CloudSummary& summary, uint32_t tile_count, double min_width);

// A folder of temporary files, removed with everything in it when the object goes (success or failure).
// It is locked while it exists; a run killed before it could remove its folder leaves it unlocked, and the
// next run that makes one in the same place removes it (once it is a minute old).
class TempFolder {
public:
    TempFolder() = default;
    ~TempFolder();
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    // Creates a new folder named after `stem` inside `parent`, first removing the abandoned ones of that name.
    io::IoStatus create(const std::string& parent, const std::string& stem);
    std::string file(const std::string& name) const { return path_ + "/" + name; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    int lock_ = -1;  // the folder, opened to hold its lock
};

// A point as it lies in a bucket file: its 64-bit id and coordinates.
struct PointRecord {
    uint64_t id;
    double xyz[3];
};

// Sorts the points of `reader` into the bucket files `paths` (one per slab): slab k's file gets every
// point whose coordinate on `axis` lies in [walls[k-1] - halo, walls[k] + halo) (unbounded outward at
// the ends), so each holds its core and its halo. A pass over the file.
io::IoStatus write_buckets(io::PointReader& reader, int axis, const std::vector<double>& walls, double halo,
                           const std::vector<std::string>& paths);

// Reads a whole file of fixed-size records (the machine's own layout: the files never leave the run).
template <class Record>
io::IoStatus read_records(const std::string& path, std::vector<Record>& records) {
    records.clear();
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) return io::IoStatus::failure(path + ": cannot open: " + std::strerror(errno));
    std::fseek(file, 0, SEEK_END);
    const long bytes = std::ftell(file);
    std::fseek(file, 0, SEEK_SET);
    records.resize(bytes > 0 ? size_t(bytes) / sizeof(Record) : 0);
    const bool ok = bytes >= 0 && std::fread(records.data(), sizeof(Record), records.size(), file) == records.size();
    std::fclose(file);
    return ok ? io::IoStatus::success() : io::IoStatus::failure(path + ": cannot read");
}

// Writes `records` as a whole file, replacing it.
template <class Record>
io::IoStatus write_records(const std::string& path, const std::vector<Record>& records) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) return io::IoStatus::failure(path + ": cannot create: " + std::strerror(errno));
    const bool written = std::fwrite(records.data(), sizeof(Record), records.size(), file) == records.size();
    const int saved_errno = errno;
    if (std::fclose(file) != 0 || !written) {
        return io::IoStatus::failure(path + ": cannot write: " + std::strerror(written ? errno : saved_errno));
    }
    return io::IoStatus::success();
}

} // namespace dbrg::out_of_core
