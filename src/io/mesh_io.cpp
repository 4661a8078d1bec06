// The entry points of the I/O library: format choice, reading and writing files and buffers, error boundary.
#include "io/mesh_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <unordered_set>

#include <sys/stat.h>

#include "io/file_output.h"
#include "io/formats.h"

namespace dbrg::io {
namespace {

std::string lower_extension(std::string_view path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of("/\\");
    if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
    std::string extension(path.substr(dot + 1));
    for (char& c : extension) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return extension;
}

// Reads or writes may throw std::bad_alloc (a genuinely huge file) or length_error; both become statuses.
template <class Action>
IoStatus without_exceptions(Action&& action) {
    try {
        return action();
    } catch (const std::bad_alloc&) {
        return IoStatus::failure("out of memory");
    } catch (const std::exception& error) {
        return IoStatus::failure(std::string("unexpected error: ") + error.what());
    }
}

// Each property of an element (vertex or face) has a value per item and a name a PLY header can hold,
// used once and by none of the values the writer writes itself (`reserved`).
IoStatus check_properties(const std::vector<VertexProperty>& properties, const char* element, size_t count,
                          std::unordered_set<std::string> names) {
    for (const VertexProperty& property : properties) {
        const std::string quoted = std::string(element) + " property '" + property.name + "'";
        if (property.name.empty()) return IoStatus::failure(std::string("a ") + element + " property has no name");
        for (char c : property.name) {
            if (static_cast<unsigned char>(c) <= ' ' || c == '\x7f') return IoStatus::failure(quoted + ": a name holds no blank or control character");
        }
        if (!names.insert(property.name).second) return IoStatus::failure(quoted + ": the name is taken");
        if (property.bytes.size() != count * value_size(property.type)) {
            return IoStatus::failure(quoted + " has " + std::to_string(property.bytes.size() / value_size(property.type)) +
                                     " values for " + std::to_string(count) + " " + (element[0] == 'v' ? "vertices" : "triangles"));
        }
    }
    return IoStatus::success();
}

IoStatus check_mesh(const MeshData& mesh) {
    if (mesh.positions.size() % 3 != 0) return IoStatus::failure("the position array's length is not a multiple of 3");
    if (mesh.triangles.size() % 3 != 0) return IoStatus::failure("the triangle array's length is not a multiple of 3");
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
        return IoStatus::failure("the normal array's length differs from the position array's");
    }
    IoStatus status = check_properties(mesh.properties, "vertex", mesh.vertex_count(), {"x", "y", "z", "nx", "ny", "nz"});
    if (!status) return status;
    status = check_properties(mesh.face_properties, "face", mesh.triangle_count(), {"vertex_indices", "vertex_index"});
    if (!status) return status;
    if (mesh.triangle_count() > std::numeric_limits<uint32_t>::max()) return IoStatus::failure("too many triangles to write");
    const size_t vertex_count = mesh.vertex_count();
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (mesh.triangles[i] >= vertex_count) {
            return IoStatus::failure("triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(mesh.triangles[i]) +
                                     ", but there are " + std::to_string(vertex_count));
        }
    }
    return IoStatus::success();
}

} // namespace

std::optional<MeshFormat> format_from_path(std::string_view path) {
    const std::string extension = lower_extension(path);
    if (extension == "ply") return MeshFormat::ply_binary;
    if (extension == "obj") return MeshFormat::obj;
    if (extension == "off") return MeshFormat::off;
    if (extension == "xyz" || extension == "pts") return MeshFormat::xyz;
    if (extension == "stl") return MeshFormat::stl;
    if (extension == "las") return MeshFormat::las;
    return std::nullopt;
}

const char* format_name(MeshFormat format) {
    switch (format) {
    case MeshFormat::ply_binary: return "ply_binary";
    case MeshFormat::ply_ascii: return "ply_ascii";
    case MeshFormat::obj: return "obj";
    case MeshFormat::off: return "off";
    case MeshFormat::xyz: return "xyz";
    case MeshFormat::stl: return "stl";
    case MeshFormat::las: return "las";
    }
    return "unknown";
}

IoStatus read_mesh_source(ByteSource& source, MeshFormat format, MeshData& out) {
    out = MeshData();
    IoStatus status = without_exceptions([&] {
        switch (format) {
        case MeshFormat::ply_binary:
        case MeshFormat::ply_ascii: return read_ply(source, out);
        case MeshFormat::obj: return read_obj(source, out);
        case MeshFormat::off: return read_off(source, out);
        case MeshFormat::xyz: return read_xyz(source, out);
        case MeshFormat::stl: return read_stl(source, out);
        case MeshFormat::las: return read_las(source, out);
        }
        return IoStatus::failure("unknown format");
    });
    if (!status) out = MeshData();
    return status;
}

IoStatus read_mesh_buffer(const void* data, size_t size, MeshFormat format, MeshData& out) {
    out = MeshData();
    if (!data && size > 0) return IoStatus::failure("no data (NULL buffer with a non-zero size)");
    ByteSource source(std::string_view(static_cast<const char*>(data), data ? size : 0));
    return read_mesh_source(source, format, out);
}

IoStatus read_mesh(const std::string& path, MeshData& out) {
    out = MeshData();
    if (lower_extension(path) == "laz") {
        return IoStatus::failure(path + ": LAZ files are compressed; decompress it to .las first, e.g. with "
                                        "'laszip -i FILE.laz -o FILE.las'");
    }
    const std::optional<MeshFormat> format = format_from_path(path);
    if (!format) return IoStatus::failure(path + ": unknown file type (expected .ply, .obj, .off, .xyz, .pts, .stl or .las)");
    IoStatus status = without_exceptions([&] {
        // Closed on every way out, a thrown bad_alloc included.
        const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
        if (!file) return IoStatus::failure(std::strerror(errno));
        struct stat info;
        if (fstat(fileno(file.get()), &info) != 0) return IoStatus::failure(std::strerror(errno));
        if (S_ISDIR(info.st_mode)) return IoStatus::failure("a directory, not a file");
        // The file is parsed as it is read, a chunk at a time: a pipe or device that never ends (or a
        // huge file of garbage) fails on its first bad bytes instead of filling memory first. Only a
        // regular file's size is known in advance.
        std::optional<uint64_t> size;
        if (S_ISREG(info.st_mode)) size = static_cast<uint64_t>(info.st_size);
        int read_error = 0;
        ByteSource source(
            [&](char* destination, size_t capacity) {
                const size_t got = std::fread(destination, 1, capacity, file.get());
                if (got < capacity && std::ferror(file.get())) read_error = errno;
                return got;
            },
            size);
        const IoStatus read = read_mesh_source(source, *format, out);
        // The reader took the failed read for the end of the file; the failure itself is the news.
        if (read_error != 0) {
            out = MeshData();
            return IoStatus::failure(std::strerror(read_error));
        }
        return read;
    });
    if (!status) status.message = path + ": " + status.message;
    return status;
}

IoStatus write_mesh_buffer(const MeshData& mesh, MeshFormat format, std::string& out) {
    IoStatus status = check_mesh(mesh);
    if (!status) return status;
    if (format == MeshFormat::las) return IoStatus::failure("LAS files are read, not written (use .ply .obj .off .stl or .xyz)");
    return without_exceptions([&] {
        switch (format) {
        case MeshFormat::ply_binary: write_ply(mesh, true, out); break;
        case MeshFormat::ply_ascii: write_ply(mesh, false, out); break;
        case MeshFormat::obj: write_obj(mesh, out); break;
        case MeshFormat::off: write_off(mesh, out); break;
        case MeshFormat::xyz: write_xyz(mesh, out); break;
        case MeshFormat::stl: write_stl(mesh, out); break;
        case MeshFormat::las: break;
        }
        return IoStatus::success();
    });
}

IoStatus write_mesh(const std::string& path, const MeshData& mesh, MeshFormat format) {
    std::string bytes;
    const IoStatus status = write_mesh_buffer(mesh, format, bytes);
    if (!status) return IoStatus::failure(path + ": " + status.message);
    return write_file(path, bytes);
}

IoStatus write_mesh(const std::string& path, const MeshData& mesh) {
    const std::optional<MeshFormat> format = format_from_path(path);
    if (!format) return IoStatus::failure(path + ": unknown file type (expected .ply, .obj, .off, .xyz, .pts or .stl)");
    return write_mesh(path, mesh, *format);
}

} // namespace dbrg::io
