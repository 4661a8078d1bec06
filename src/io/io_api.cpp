// The C interface of the I/O library (include/dbrg/dbrg_io.h): checks the caller's arrays, then hands
// them to the writers and the normals as MeshData; no exception crosses it.
#include "dbrg/dbrg_io.h"

#include <cstring>
#include <exception>
#include <new>
#include <optional>
#include <string>

#include "io/mesh_io.h"
#include "io/vertex_normals.h"

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
