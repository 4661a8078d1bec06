/* The I/O library's C interface (include/dbrg/dbrg_io.h) compiled as C99 and driven through libdbrg_io:
 * normals of a tetrahedron point away from it, a written OBJ holds what was given, errors are statuses. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dbrg/dbrg_io.h"

static int failures = 0;

#define CHECK(condition)                                                    \
    do {                                                                    \
        if (!(condition)) {                                                 \
            fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #condition); \
            ++failures;                                                     \
        }                                                                   \
    } while (0)

int main(int argc, char** argv) {
    /* A tetrahedron, each face counter-clockwise seen from outside, and a point no face uses. */
    static const double positions[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5};
    static const uint32_t triangles[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    static const double centroid[3] = {0.25, 0.25, 0.25};
    static const uint32_t out_of_range[3] = {0, 1, 5};
    float normals[15];
    char message[256];
    char path[4096];
    uint32_t v;
    FILE* file;
    int vn_lines = 0, face_lines = 0;

    if (argc != 2 || strlen(argv[1]) > sizeof path - 32) {
        fprintf(stderr, "usage: test_io_c_api SCRATCH_FOLDER\n");
        return 2;
    }
    CHECK(dbrg_io_vertex_normals(positions, 5, triangles, 4, normals) == DBRG_IO_OK);
    for (v = 0; v < 4; ++v) {
        const float* n = &normals[3 * v];
        const double outward = (positions[3 * v] - centroid[0]) * n[0] + (positions[3 * v + 1] - centroid[1]) * n[1] +
                               (positions[3 * v + 2] - centroid[2]) * n[2];
        CHECK(fabs(sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]) - 1.0) < 1e-6);
        CHECK(outward > 0.0);
    }
    CHECK(normals[12] == 0.0f && normals[13] == 0.0f && normals[14] == 0.0f);
    CHECK(dbrg_io_vertex_normals(positions, 5, out_of_range, 1, normals) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_io_vertex_normals(NULL, 5, triangles, 4, normals) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_io_vertex_normals(NULL, 0, NULL, 0, NULL) == DBRG_IO_OK);

    sprintf(path, "%s/tetrahedron.obj", argv[1]);
    CHECK(dbrg_io_write_mesh(path, positions, 5, triangles, 4, normals, message, sizeof message) == DBRG_IO_OK);
    CHECK(message[0] == '\0');
    file = fopen(path, "r");
    CHECK(file != NULL);
    if (file) {
        char line[256];
        while (fgets(line, sizeof line, file)) {
            vn_lines += strncmp(line, "vn ", 3) == 0;
            face_lines += strncmp(line, "f ", 2) == 0;
        }
        fclose(file);
    }
    CHECK(vn_lines == 5);
    CHECK(face_lines == 4);

    CHECK(dbrg_io_write_mesh(path, positions, 5, out_of_range, 1, NULL, message, sizeof message) ==
          DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(strstr(message, "refers to vertex 5") != NULL);
    sprintf(path, "%s/tetrahedron.docx", argv[1]);
    CHECK(dbrg_io_write_mesh(path, positions, 5, triangles, 4, NULL, message, sizeof message) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(strstr(message, "unknown file type") != NULL);
    sprintf(path, "%s/no-such-folder/tetrahedron.ply", argv[1]);
    CHECK(dbrg_io_write_mesh(path, positions, 5, triangles, 4, NULL, message, 8) == DBRG_IO_ERR_FILE);
    CHECK(strlen(message) == 7); /* cut short to the room given */
    CHECK(dbrg_io_write_mesh(NULL, positions, 5, triangles, 4, NULL, NULL, 0) == DBRG_IO_ERR_INVALID_ARGUMENT);
    return failures == 0 ? 0 : 1;
}
