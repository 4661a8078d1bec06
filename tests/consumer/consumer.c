/* A program that uses an installed dbrg the way a user's program would: it reconstructs points spread
 * over a sphere and checks the result is a closed surface through every point. With
 * DBRG_CONSUMER_WRITE_MESH it also writes the mesh, with its vertex normals, through libdbrg_io.
 * Usage: consumer [OUTPUT.ply]. Exit status 0 when every check holds. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include <dbrg/dbrg.h>
#ifdef DBRG_CONSUMER_WRITE_MESH
#include <dbrg/dbrg_io.h>
#endif

enum { POINT_COUNT = 200 };

/* Points on the unit sphere along a Fibonacci spiral: evenly spread, none coincident. */
static void sphere_points(double* xyz, uint32_t count) {
    const double golden_angle = 3.14159265358979323846 * (3.0 - sqrt(5.0));
    uint32_t i;
    for (i = 0; i < count; ++i) {
        double z = 1.0 - (2.0 * i + 1.0) / count;
        double r = sqrt(1.0 - z * z);
        xyz[3 * i + 0] = r * cos(golden_angle * i);
        xyz[3 * i + 1] = r * sin(golden_angle * i);
        xyz[3 * i + 2] = z;
    }
}

#ifdef DBRG_CONSUMER_WRITE_MESH
static int write_mesh(const char* path, const double* xyz, const dbrg_mesh* mesh) {
    float normals[3 * POINT_COUNT];
    char message[256];
    const uint32_t* triangles = dbrg_mesh_triangles(mesh);
    uint32_t triangle_count = dbrg_mesh_triangle_count(mesh);
    if (dbrg_io_vertex_normals(xyz, POINT_COUNT, triangles, triangle_count, normals) != DBRG_IO_OK) {
        fprintf(stderr, "consumer: dbrg_io_vertex_normals failed\n");
        return 0;
    }
    if (dbrg_io_write_mesh(path, xyz, POINT_COUNT, triangles, triangle_count, normals, message, sizeof message)
        != DBRG_IO_OK) {
        fprintf(stderr, "consumer: %s\n", message);
        return 0;
    }
    return 1;
}
#endif

int main(int argc, char** argv) {
    double xyz[3 * POINT_COUNT];
    dbrg_points points;
    dbrg_mesh* mesh = NULL;
    dbrg_status status;
    int ok = 1;

    /* A header from one install and a library from another would show here first. */
    if (dbrg_version_number() != DBRG_VERSION_NUMBER) {
        fprintf(stderr, "consumer: header %s, library %s\n", DBRG_VERSION_STRING, dbrg_version_string());
        return 1;
    }

    sphere_points(xyz, POINT_COUNT);
    points.data = xyz;
    points.count = POINT_COUNT;
    points.stride_bytes = 3 * sizeof(double);
    points.type = DBRG_FLOAT64;
    status = dbrg_reconstruct(&points, NULL, &mesh);
    if (status != DBRG_OK) {
        fprintf(stderr, "consumer: %s: %s\n", dbrg_status_string(status), dbrg_mesh_message(mesh));
        dbrg_mesh_destroy(mesh);
        return 1;
    }
    /* A closed surface of genus 0 through all V points has 2V - 4 triangles (Euler: V - E + F = 2). */
    if (dbrg_mesh_boundary_loop_count(mesh) != 0 || dbrg_mesh_triangle_count(mesh) != 2 * POINT_COUNT - 4) {
        fprintf(stderr, "consumer: %u triangles and %u boundary loops; a closed sphere has %u and 0\n",
                dbrg_mesh_triangle_count(mesh), dbrg_mesh_boundary_loop_count(mesh), 2u * POINT_COUNT - 4u);
        ok = 0;
    }
#ifdef DBRG_CONSUMER_WRITE_MESH
    if (ok && argc > 1) ok = write_mesh(argv[1], xyz, mesh);
#else
    (void)argc;
    (void)argv;
#endif
    if (ok) printf("dbrg %s: %u triangles\n", dbrg_version_string(), dbrg_mesh_triangle_count(mesh));
    dbrg_mesh_destroy(mesh);
    return ok ? 0 : 1;
}
