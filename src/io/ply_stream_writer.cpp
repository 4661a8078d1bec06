// Streaming binary PLY output (see ply_stream_writer.h).
#include "io/ply_stream_writer.h"

#include <cstring>
#include <limits>

#include "io/formats.h"

namespace dbrg::io {
namespace {

template <class Value>
void append_little_endian(std::string& out, Value value) {
    static_assert(sizeof(Value) <= sizeof(uint64_t), "a scalar");
    uint64_t bits = 0;
    if constexpr (sizeof(Value) == 8) {
        std::memcpy(&bits, &value, 8);
    } else {
        uint32_t narrow;
        std::memcpy(&narrow, &value, 4);
        bits = narrow;
    }
    for (size_t i = 0; i < sizeof(Value); ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

} // namespace

IoStatus PlyStreamWriter::refuse(const std::string& what) {
    status_ = IoStatus::failure(path_ + ": " + what);
    file_.abandon();
    return status_;
}

IoStatus PlyStreamWriter::open(const std::string& path, const Layout& layout) {
    path_ = path;
    layout_ = layout;
    if (layout_.vertex_count > uint64_t(std::numeric_limits<uint32_t>::max()) + 1) layout_.wide_indices = true;
    vertices_written_ = triangles_written_ = 0;
    status_ = file_.open(path);
    if (!status_) return status_;
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by dbrg\nelement vertex ";
    append_unsigned(header, layout_.vertex_count);
    for (const char* axis : {"x", "y", "z"}) {
        header += std::string("\nproperty ") + (layout_.double_coordinates ? "double " : "float ") + axis;
    }
    header += "\nelement face ";
    append_unsigned(header, layout_.triangle_count);
    header += layout_.wide_indices ? "\nproperty list uchar uint64 vertex_indices" : "\nproperty list uchar uint vertex_indices";
    header += "\nend_header\n";
    return status_ = file_.write(header);
}

IoStatus PlyStreamWriter::add_vertices(const double* xyz, size_t count) {
    if (!status_) return status_;
    if (count > layout_.vertex_count - vertices_written_) {
        return refuse("more vertices than the " + std::to_string(layout_.vertex_count) + " declared");
    }
    chunk_.clear();
    for (size_t i = 0; i < 3 * count; ++i) {
        if (layout_.double_coordinates) append_little_endian(chunk_, xyz[i]);
        else append_little_endian(chunk_, static_cast<float>(xyz[i]));
    }
    vertices_written_ += count;
    return status_ = file_.write(chunk_);
}

IoStatus PlyStreamWriter::add_triangles(const uint64_t* corners, size_t count) {
    if (!status_) return status_;
    if (vertices_written_ != layout_.vertex_count) return refuse("a triangle before the last vertex");
    if (count > layout_.triangle_count - triangles_written_) {
        return refuse("more triangles than the " + std::to_string(layout_.triangle_count) + " declared");
    }
    chunk_.clear();
    for (size_t t = 0; t < count; ++t) {
        chunk_.push_back(3);
        for (size_t k = 0; k < 3; ++k) {
            const uint64_t index = corners[3 * t + k];
            if (index >= layout_.vertex_count) {
                return refuse("triangle " + std::to_string(triangles_written_ + t) + " uses vertex " +
                              std::to_string(index) + " of " + std::to_string(layout_.vertex_count));
            }
            if (layout_.wide_indices) append_little_endian(chunk_, index);
            else append_little_endian(chunk_, static_cast<uint32_t>(index));
        }
    }
    triangles_written_ += count;
    return status_ = file_.write(chunk_);
}

IoStatus PlyStreamWriter::finish() {
    if (!status_) return status_;
    if (vertices_written_ != layout_.vertex_count || triangles_written_ != layout_.triangle_count) {
        return refuse(std::to_string(vertices_written_) + " vertices and " + std::to_string(triangles_written_) +
                      " triangles written of the " + std::to_string(layout_.vertex_count) + " and " +
                      std::to_string(layout_.triangle_count) + " declared");
    }
    return status_ = file_.finish();
}

} // namespace dbrg::io
