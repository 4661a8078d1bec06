/* dbrg_io: dbrg's own readers, mesh writers and vertex normals behind a small C interface, for bindings
 * and programs that want to read the files the dbrg program reads and write the files it writes. A library of its own (libdbrg_io), so that
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
    DBRG_IO_ERR_FILE = 2,             /* the file could not be read or written, or is not valid in its format
                                         (the message gives the system's reason, or the problem and where) */
    DBRG_IO_ERR_OUT_OF_MEMORY = 3
} dbrg_io_status;

/* The type of a per-point attribute's values, as PLY has them; values are pinned and only grow. */
typedef enum dbrg_io_value_type {
    DBRG_IO_INT8 = 0,
    DBRG_IO_UINT8 = 1,
    DBRG_IO_INT16 = 2,
    DBRG_IO_UINT16 = 3,
    DBRG_IO_INT32 = 4,
    DBRG_IO_UINT32 = 5,
    DBRG_IO_FLOAT32 = 6,
    DBRG_IO_FLOAT64 = 7
} dbrg_io_value_type;

/* Points read from a file, with their per-point attributes; opaque, owned by the caller, freed with
 * dbrg_io_points_destroy. Every pointer the accessors return lives as long as the object. */
typedef struct dbrg_io_points dbrg_io_points;

/* Reads the points (the vertices) of the file at `path`, with their attributes, as the dbrg program
 * reads its input: .ply .obj .off .stl .xyz .pts .las by extension (faces are not read). Attributes are
 * a PLY's vertex properties besides x y z nx ny nz (colours, intensity, ...) with their names and types,
 * and a LAS file's uint16 intensity and red, green, blue; normals are a PLY's nx ny nz.
 * Returns DBRG_IO_OK, DBRG_IO_ERR_INVALID_ARGUMENT (NULL path or out_points, unknown extension, .laz),
 * DBRG_IO_ERR_FILE (cannot be read, or malformed: the message names the problem and where) or
 * DBRG_IO_ERR_OUT_OF_MEMORY, with a one-line message in `message`.
 * path: a NUL-terminated file name.
 * out_points: receives the points on success, NULL otherwise; free them with dbrg_io_points_destroy.
 * message, message_capacity: as for dbrg_io_write_mesh. */
DBRG_IO_API dbrg_io_status dbrg_io_read_points(const char* path, dbrg_io_points** out_points, char* message,
                                               size_t message_capacity);

/* Frees points read by dbrg_io_read_points; NULL is a no-op. */
DBRG_IO_API void dbrg_io_points_destroy(dbrg_io_points* points);

/* The number of points; 0 for NULL. */
DBRG_IO_API uint32_t dbrg_io_points_count(const dbrg_io_points* points);

/* x, y, z of point 0, then point 1, ... (3 * count doubles); NULL when there are no points. */
DBRG_IO_API const double* dbrg_io_points_positions(const dbrg_io_points* points);

/* nx, ny, nz per point (3 * count floats) as the file gave them, or NULL when it gave none. */
DBRG_IO_API const float* dbrg_io_points_normals(const dbrg_io_points* points);

/* The number of per-point attributes; 0 for NULL. */
DBRG_IO_API uint32_t dbrg_io_points_attribute_count(const dbrg_io_points* points);

/* The name of attribute `index` (NUL-terminated), or NULL when index >= the attribute count. */
DBRG_IO_API const char* dbrg_io_points_attribute_name(const dbrg_io_points* points, uint32_t index);

/* The type of attribute `index`'s values; DBRG_IO_FLOAT64 when index is out of range. */
DBRG_IO_API dbrg_io_value_type dbrg_io_points_attribute_type(const dbrg_io_points* points, uint32_t index);

/* Attribute `index`'s values, one per point in point order, each of its type in the machine's byte order;
 * NULL when index is out of range or there are no points. */
DBRG_IO_API const void* dbrg_io_points_attribute_values(const dbrg_io_points* points, uint32_t index);

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
