// Points of a file a batch at a time (see point_reader.h).
#include "io/point_reader.h"

#include <cerrno>
#include <cmath>
#include <cstring>

#include <sys/stat.h>

#include "io/formats.h"

namespace dbrg::io {

PointReader::PointReader() = default;
PointReader::~PointReader() = default;

IoStatus PointReader::open(const std::string& path) {
    path_ = path;
    parser_.reset();
    source_.reset();
    const std::optional<MeshFormat> format = format_from_path(path);
    if (!format || (*format != MeshFormat::ply_binary && *format != MeshFormat::xyz)) {
        return failure("points are streamed from .ply, .xyz and .pts files only");
    }
    format_ = *format;
    file_.reset(std::fopen(path.c_str(), "rb"));
    if (!file_) return failure(std::strerror(errno));
    struct stat info;
    if (fstat(fileno(file_.get()), &info) != 0) return failure(std::strerror(errno));
    if (!S_ISREG(info.st_mode)) return failure("not a regular file (the points are read more than once)");
    size_ = static_cast<uint64_t>(info.st_size);
    return start();
}

IoStatus PointReader::start() {
    read_error_ = 0;
    points_read_ = 0;
    source_ = std::make_unique<ByteSource>(
        [this](char* destination, size_t capacity) {
            const size_t got = std::fread(destination, 1, capacity, file_.get());
            if (got < capacity && std::ferror(file_.get())) read_error_ = errno;
            return got;
        },
        size_);
    if (format_ == MeshFormat::xyz) {
        parser_ = xyz_points(*source_);
        return IoStatus::success();
    }
    const IoStatus status = ply_points(*source_, parser_);
    if (read_error_ != 0) return failure(std::strerror(read_error_));
    return status ? status : failure(status.message);
}

IoStatus PointReader::rewind() {
    if (!file_) return failure("not open");
    if (std::fseek(file_.get(), 0, SEEK_SET) != 0) return failure(std::strerror(errno));
    parser_.reset();
    return start();
}

IoStatus PointReader::read(double* xyz, size_t capacity, size_t& count) {
    count = 0;
    if (!parser_) return failure("not open");
    const IoStatus status = parser_->read(xyz, capacity, count);
    // The parser took a failed read for the end of the file; the failure itself is the news.
    if (read_error_ != 0) return failure(std::strerror(read_error_));
    if (!status) return failure(status.message);
    for (size_t i = 0; i < 3 * count; ++i) {
        if (!std::isfinite(xyz[i])) {
            return failure("point " + std::to_string(points_read_ + i / 3) + " (counting from 0) has a non-finite coordinate");
        }
    }
    points_read_ += count;
    return status;
}

std::optional<uint64_t> PointReader::declared_count() const { return parser_ ? parser_->declared_count() : std::nullopt; }

} // namespace dbrg::io
