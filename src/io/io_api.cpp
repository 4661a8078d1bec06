// The C interface of the I/O library (include/dbrg/dbrg_io.h): checks the caller's arrays, then hands
// them to the writers and the normals as MeshData, and hands read points out as a MeshData behind an
// opaque handle; no exception crosses it.
#include "dbrg/dbrg_io.h"

#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string>

#include "io/mesh_io.h"
#include "io/vertex_normals.h"

// The points a read gave; the C handle's type.
struct dbrg_io_points {
    dbrg::io::MeshData mesh;
};

namespace {

using dbrg::io::IoStatus;
using dbrg::io::MeshData;

void put_message(char* message, size_t capacity, const std::string& text) {
    if (!message || capacity == 0) return;
    const size_t length = text.size() < capacity - 1 ? text.size() : capacity - 1;
    std::memcpy(message, text.data(), length);
    message[length] = '\0';
}

// Copies the caller's arrays into `mesh`; returns an empty string, or what is wrong with them.
std::string copy_mesh(const double* positions, uint32_t vertex_count, const uint32_t* triangles, uint32_t triangle_count,
                      const float* normals, MeshData& mesh) {
    if (!positions && vertex_count > 0) return "positions is NULL with a non-zero vertex count";
    if (!triangles && triangle_count > 0) return "triangles is NULL with a non-zero triangle count";
    mesh.positions.assign(positions, positions + 3 * size_t(vertex_count));
    mesh.triangles.assign(triangles, triangles + 3 * size_t(triangle_count));
    if (normals) mesh.normals.assign(normals, normals + 3 * size_t(vertex_count));
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (mesh.triangles[i] >= vertex_count) {
            return "triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(mesh.triangles[i]) +
                   ", but there are " + std::to_string(vertex_count);
        }
    }
    return {};
}

} // namespace

extern "C" DBRG_IO_API dbrg_io_status dbrg_io_vertex_normals(const double* positions, uint32_t vertex_count,
                                                             const uint32_t* triangles, uint32_t triangle_count,
                                                             float* out_normals) {
    try {
        if (!out_normals && vertex_count > 0) return DBRG_IO_ERR_INVALID_ARGUMENT;
        MeshData mesh;
        if (!copy_mesh(positions, vertex_count, triangles, triangle_count, nullptr, mesh).empty()) {
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        const std::vector<float> normals = dbrg::io::vertex_normals(mesh.positions, mesh.triangles);
        if (!normals.empty()) std::memcpy(out_normals, normals.data(), normals.size() * sizeof(float));
        return DBRG_IO_OK;
    } catch (const std::bad_alloc&) {
        return DBRG_IO_ERR_OUT_OF_MEMORY;
    } catch (...) {
        return DBRG_IO_ERR_OUT_OF_MEMORY;  // the only other throw: a vector too long for memory (length_error)
    }
}

extern "C" DBRG_IO_API dbrg_io_status dbrg_io_write_mesh(const char* path, const double* positions, uint32_t vertex_count,
                                                         const uint32_t* triangles, uint32_t triangle_count,
                                                         const float* normals, char* message, size_t message_capacity) {
    put_message(message, message_capacity, "");
    try {
        if (!path) {
            put_message(message, message_capacity, "path is NULL");
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        const std::optional<dbrg::io::MeshFormat> format = dbrg::io::format_from_path(path);
        if (!format || *format == dbrg::io::MeshFormat::las) {
            put_message(message, message_capacity,
                        std::string(path) + ": unknown file type for writing (expected .ply, .obj, .off, .xyz, .pts or .stl)");
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        MeshData mesh;
        const std::string wrong = copy_mesh(positions, vertex_count, triangles, triangle_count, normals, mesh);
        if (!wrong.empty()) {
            put_message(message, message_capacity, wrong);
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        mesh.has_faces = true;
        const IoStatus status = dbrg::io::write_mesh(path, mesh);
        if (status) return DBRG_IO_OK;
        put_message(message, message_capacity, status.message);
        // write_mesh turns an allocation failure into this message; every other failure is the file's.
        return status.message.find("out of memory") != std::string::npos ? DBRG_IO_ERR_OUT_OF_MEMORY : DBRG_IO_ERR_FILE;
    } catch (const std::bad_alloc&) {
        put_message(message, message_capacity, "out of memory");
        return DBRG_IO_ERR_OUT_OF_MEMORY;
    } catch (const std::exception& error) {  // a vector too long for memory (length_error)
        put_message(message, message_capacity, std::string("out of memory: ") + error.what());
        return DBRG_IO_ERR_OUT_OF_MEMORY;
    }
}

extern "C" DBRG_IO_API dbrg_io_status dbrg_io_read_points(const char* path, dbrg_io_points** out_points, char* message,
                                                          size_t message_capacity) {
    put_message(message, message_capacity, "");
    if (out_points) *out_points = nullptr;
    try {
        if (!path || !out_points) {
            put_message(message, message_capacity, !path ? "path is NULL" : "out_points is NULL");
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        const std::string name(path);
        if (!dbrg::io::format_from_path(name)) {
            MeshData none;
            // read_mesh words the refusal (an unknown type, or LAZ to decompress) as the program does.
            put_message(message, message_capacity, dbrg::io::read_mesh(name, none).message);
            return DBRG_IO_ERR_INVALID_ARGUMENT;
        }
        auto points = std::make_unique<dbrg_io_points>();
        const IoStatus status = dbrg::io::read_mesh(name, points->mesh);
        if (!status) {
            put_message(message, message_capacity, status.message);
            return status.message.find("out of memory") != std::string::npos ? DBRG_IO_ERR_OUT_OF_MEMORY : DBRG_IO_ERR_FILE;
        }
        points->mesh.triangles.clear();
        *out_points = points.release();
        return DBRG_IO_OK;
    } catch (const std::bad_alloc&) {
        put_message(message, message_capacity, "out of memory");
        return DBRG_IO_ERR_OUT_OF_MEMORY;
    } catch (const std::exception& error) {  // a string too long for memory (length_error)
        put_message(message, message_capacity, std::string("out of memory: ") + error.what());
        return DBRG_IO_ERR_OUT_OF_MEMORY;
    }
}

extern "C" DBRG_IO_API void dbrg_io_points_destroy(dbrg_io_points* points) { delete points; }

extern "C" DBRG_IO_API uint32_t dbrg_io_points_count(const dbrg_io_points* points) {
    return points ? static_cast<uint32_t>(points->mesh.vertex_count()) : 0;
}

extern "C" DBRG_IO_API const double* dbrg_io_points_positions(const dbrg_io_points* points) {
    return points && !points->mesh.positions.empty() ? points->mesh.positions.data() : nullptr;
}

extern "C" DBRG_IO_API const float* dbrg_io_points_normals(const dbrg_io_points* points) {
    return points && !points->mesh.normals.empty() ? points->mesh.normals.data() : nullptr;
}

extern "C" DBRG_IO_API uint32_t dbrg_io_points_attribute_count(const dbrg_io_points* points) {
    return points ? static_cast<uint32_t>(points->mesh.properties.size()) : 0;
}

namespace {

const dbrg::io::VertexProperty* attribute(const dbrg_io_points* points, uint32_t index) {
    return points && index < points->mesh.properties.size() ? &points->mesh.properties[index] : nullptr;
}

} // namespace

extern "C" DBRG_IO_API const char* dbrg_io_points_attribute_name(const dbrg_io_points* points, uint32_t index) {
    const dbrg::io::VertexProperty* property = attribute(points, index);
    return property ? property->name.c_str() : nullptr;
}

static_assert(static_cast<int>(dbrg::io::ValueType::int8) == DBRG_IO_INT8 &&
                  static_cast<int>(dbrg::io::ValueType::uint16) == DBRG_IO_UINT16 &&
                  static_cast<int>(dbrg::io::ValueType::float64) == DBRG_IO_FLOAT64,
              "ValueType lists the types in the order of dbrg_io_value_type's values");

extern "C" DBRG_IO_API dbrg_io_value_type dbrg_io_points_attribute_type(const dbrg_io_points* points, uint32_t index) {
    const dbrg::io::VertexProperty* property = attribute(points, index);
    return property ? static_cast<dbrg_io_value_type>(property->type) : DBRG_IO_FLOAT64;
}

extern "C" DBRG_IO_API const void* dbrg_io_points_attribute_values(const dbrg_io_points* points, uint32_t index) {
    const dbrg::io::VertexProperty* property = attribute(points, index);
    return property && !property->bytes.empty() ? property->bytes.data() : nullptr;
}
