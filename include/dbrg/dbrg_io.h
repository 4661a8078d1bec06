/* dbrg_io: dbrg's own mesh writers and vertex normals behind a small C interface, for bindings and
 * programs that want the files the dbrg program writes. A library of its own (libdbrg_io), so that
 * libdbrg stays free of file I/O. Valid C99 and C++; only <stddef.h> and <stdint.h>.
 *
 * Meshes are given as arrays: positions holds x, y, z of vertex 0, then vertex 1, ... (3 * vertex_count
 * doubles); triangles holds three vertex indices per triangle (3 * triangle_count), counter-clockwise
 * seen from the side the surface faces; normals, where taken, holds nx, ny, nz per vertex (floats). */
#ifndef DBRG_DBRG_IO_H
#define DBRG_DBRG_IO_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(DBRG_IO_SHARED_BUILD)
#define DBRG_IO_API __declspec(dllexport)
#elif defined(_WIN32) && defined(DBRG_IO_SHARED)
#define DBRG_IO_API __declspec(dllimport)
#elif defined(__GNUC__)
#define DBRG_IO_API __attribute__((visibility("default")))
#else
#define DBRG_IO_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Outcomes; values are pinned and only grow. */
typedef enum dbrg_io_status {
    DBRG_IO_OK = 0,
    DBRG_IO_ERR_INVALID_ARGUMENT = 1, /* a NULL array with a non-zero count, an index out of range, ... */
    DBRG_IO_ERR_FILE = 2,             /* the file could not be written (the message gives the system's reason) */
    DBRG_IO_ERR_OUT_OF_MEMORY = 3
} dbrg_io_status;

/* Unit vertex normals: for each vertex, the normals of its triangles weighted by their angle at the
 * vertex, summed and normalized; (0, 0, 0) for a vertex no triangle uses.
 * Returns DBRG_IO_OK, or DBRG_IO_ERR_INVALID_ARGUMENT for a NULL array or an index out of range.
 * positions: 3 * vertex_count doubles; may be NULL when vertex_count is 0.
 * triangles: 3 * triangle_count indices below vertex_count; may be NULL when triangle_count is 0.
 * out_normals: room for 3 * vertex_count floats, written only on success. */
DBRG_IO_API dbrg_io_status dbrg_io_vertex_normals(const double* positions, uint32_t vertex_count,
                                                  const uint32_t* triangles, uint32_t triangle_count,
                                                  float* out_normals);

/* Writes the mesh to `path` in the format its extension names (.ply binary, .obj, .off, .stl, .xyz),
 * as the dbrg program does: the file is replaced only once completely written.
 * Returns DBRG_IO_OK, DBRG_IO_ERR_INVALID_ARGUMENT (unknown extension, NULL array, index out of range),
 * DBRG_IO_ERR_FILE or DBRG_IO_ERR_OUT_OF_MEMORY, with a one-line message in `message`.
 * path: a NUL-terminated file name; "-" is standard output.
 * positions, triangles: as above; triangle_count 0 writes the points (with an empty face list).
 * normals: NULL, or 3 * vertex_count floats written to .ply (nx ny nz) and .obj (vn).
 * message: NULL, or room for message_capacity bytes; always NUL-terminated when message_capacity > 0,
 * empty on success, cut short when the room is too small. */
DBRG_IO_API dbrg_io_status dbrg_io_write_mesh(const char* path, const double* positions, uint32_t vertex_count,
                                              const uint32_t* triangles, uint32_t triangle_count,
                                              const float* normals, char* message, size_t message_capacity);

#ifdef __cplusplus
}
#endif

#endif /* DBRG_DBRG_IO_H */
