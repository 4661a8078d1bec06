// The points of a file read a batch at a time, for clouds larger than memory: memory follows the batch,
// never the file. Binary and ascii PLY (the vertex element's x, y, z; everything else is read past) and
// XYZ/PTS. A file may be read again from the start, as a pass over a cloud that does not fit needs.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "io/byte_source.h"
#include "io/mesh_io.h"

namespace dbrg::io {

class PointParser;

class PointReader {
public:
    PointReader();
    ~PointReader();
    PointReader(const PointReader&) = delete;
    PointReader& operator=(const PointReader&) = delete;

    // Opens `path` (.ply, .xyz or .pts) and reads a PLY header. Messages begin with the path.
    IoStatus open(const std::string& path);
    // Stores up to `capacity` points (x, y, z each) in `xyz` and their number in `count`, 0 once the points
    // are over. A point with a non-finite coordinate is refused, naming it by its number, as is a file that
    // ends in the middle of the points (naming the place: "PLY byte offset 1234", "XYZ line 7").
    IoStatus read(double* xyz, size_t capacity, size_t& count);
    // Starts again from the first point.
    IoStatus rewind();
    // The number of points the file declares (a PLY header), if it does.
    std::optional<uint64_t> declared_count() const;

private:
    IoStatus start();
    IoStatus failure(const std::string& what) const { return IoStatus::failure(path_ + ": " + what); }

    std::string path_;
    MeshFormat format_ = MeshFormat::ply_binary;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_{nullptr, std::fclose};
    std::optional<uint64_t> size_;
    int read_error_ = 0;
    uint64_t points_read_ = 0;
    std::unique_ptr<ByteSource> source_;
    std::unique_ptr<PointParser> parser_;
};

} // namespace dbrg::io
