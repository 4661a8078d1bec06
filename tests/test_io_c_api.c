/* The I/O library's C interface (include/dbrg/dbrg_io.h) compiled as C99 and driven through libdbrg_io:
 * normals of a tetrahedron point away from it, a written OBJ holds what was given, points read back with
 * their attributes, errors are statuses. */
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

/* A PLY of three points with colour and confidence is read back with them; the OBJ written by main
 * reads back as its points; refusals are statuses with a message. */
static void check_read_points(const char* folder) {
    char path[4096];
    char message[256];
    dbrg_io_points* points = (dbrg_io_points*)&message; /* set to NULL by a failed read */
    FILE* file;
    uint32_t i;

    sprintf(path, "%s/coloured.ply", folder);
    file = fopen(path, "w");
    CHECK(file != NULL);
    if (!file) return;
    fputs("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
          "property uchar red\nproperty float confidence\nproperty float nx\nproperty float ny\nproperty float nz\n"
          "end_header\n0.5 1 2 255 0.25 0 0 1\n3 4 5 0 0.5 0 1 0\n6 7 8.125 17 1 1 0 0\n", file);
    fclose(file);
    CHECK(dbrg_io_read_points(path, &points, message, sizeof message) == DBRG_IO_OK);
    CHECK(message[0] == '\0');
    CHECK(dbrg_io_points_count(points) == 3);
    CHECK(dbrg_io_points_positions(points)[0] == 0.5 && dbrg_io_points_positions(points)[8] == 8.125);
    CHECK(dbrg_io_points_normals(points) != NULL && dbrg_io_points_normals(points)[3 * 2] == 1.0f);
    CHECK(dbrg_io_points_attribute_count(points) == 2);
    CHECK(strcmp(dbrg_io_points_attribute_name(points, 0), "red") == 0);
    CHECK(dbrg_io_points_attribute_type(points, 0) == DBRG_IO_UINT8);
    CHECK(strcmp(dbrg_io_points_attribute_name(points, 1), "confidence") == 0);
    CHECK(dbrg_io_points_attribute_type(points, 1) == DBRG_IO_FLOAT32);
    for (i = 0; i < 3; ++i) {
        static const uint8_t red[3] = {255, 0, 17};
        static const float confidence[3] = {0.25f, 0.5f, 1.0f};
        CHECK(((const uint8_t*)dbrg_io_points_attribute_values(points, 0))[i] == red[i]);
        CHECK(((const float*)dbrg_io_points_attribute_values(points, 1))[i] == confidence[i]);
    }
    CHECK(dbrg_io_points_attribute_name(points, 2) == NULL);
    CHECK(dbrg_io_points_attribute_values(points, 2) == NULL);
    dbrg_io_points_destroy(points);

    sprintf(path, "%s/tetrahedron.obj", folder);
    CHECK(dbrg_io_read_points(path, &points, message, sizeof message) == DBRG_IO_OK);
    CHECK(dbrg_io_points_count(points) == 5);
    CHECK(dbrg_io_points_attribute_count(points) == 0);
    CHECK(dbrg_io_points_positions(points)[12] == 5.0);
    dbrg_io_points_destroy(points);

    sprintf(path, "%s/scan.laz", folder);
    CHECK(dbrg_io_read_points(path, &points, message, sizeof message) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(points == NULL);
    CHECK(strstr(message, "decompress") != NULL);
    sprintf(path, "%s/missing.ply", folder);
    CHECK(dbrg_io_read_points(path, &points, message, sizeof message) == DBRG_IO_ERR_FILE);
    CHECK(strstr(message, "No such file") != NULL);
    sprintf(path, "%s/tetrahedron.obj", folder);
    file = fopen(path, "w");
    if (file) {
        fputs("v 0 0 zero\n", file);
        fclose(file);
    }
    CHECK(dbrg_io_read_points(path, &points, message, sizeof message) == DBRG_IO_ERR_FILE);
    CHECK(strstr(message, "line 1") != NULL);
    CHECK(dbrg_io_read_points(path, NULL, message, sizeof message) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_io_read_points(NULL, &points, NULL, 0) == DBRG_IO_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_io_points_count(NULL) == 0 && dbrg_io_points_attribute_count(NULL) == 0);
    CHECK(dbrg_io_points_positions(NULL) == NULL && dbrg_io_points_normals(NULL) == NULL);
    dbrg_io_points_destroy(NULL);
}

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
    sprintf(path, "%s/tetrahedron.las", argv[1]);
    CHECK(dbrg_io_write_mesh(path, positions, 5, triangles, 4, NULL, message, sizeof message) == DBRG_IO_ERR_INVALID_ARGUMENT);

    check_read_points(argv[1]);
    return failures == 0 ? 0 : 1;
}
