/* The whole public API exercised from C99: versions, statuses, parameters, input checks, reconstruction,
 * the tetrahedralization, tiles, the caller's allocator (counted, and failing on purpose) and cancellation. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dbrg/dbrg.h"

static int checks_passed = 0;
static int checks_failed = 0;

#define CHECK(condition)                                                  \
    do {                                                                  \
        if (condition) {                                                  \
            ++checks_passed;                                              \
        } else {                                                          \
            ++checks_failed;                                              \
            fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #condition); \
        }                                                                 \
    } while (0)

/* An allocator that counts live blocks and bytes and can refuse the k-th request. */
typedef struct counting_allocator {
    long live_blocks;
    size_t live_bytes;
    long requests;
    long fail_at; /* 0: never */
} counting_allocator;

static int refuse(counting_allocator* a) {
    ++a->requests;
    return a->fail_at != 0 && a->requests == a->fail_at;
}

static void* counting_allocate(void* user, size_t size) {
    counting_allocator* a = (counting_allocator*)user;
    void* block;
    if (refuse(a)) return NULL;
    block = malloc(size);
    if (block) {
        ++a->live_blocks;
        a->live_bytes += size;
    }
    return block;
}

static void* counting_reallocate(void* user, void* block, size_t old_size, size_t new_size) {
    counting_allocator* a = (counting_allocator*)user;
    void* moved;
    if (refuse(a)) return NULL;
    moved = realloc(block, new_size);
    if (moved) a->live_bytes = a->live_bytes - old_size + new_size;
    return moved;
}

static void counting_deallocate(void* user, void* block, size_t size) {
    counting_allocator* a = (counting_allocator*)user;
    if (!block) return;
    --a->live_blocks;
    a->live_bytes -= size;
    free(block);
}

/* n points spread evenly over the unit sphere (a Fibonacci spiral). */
static double* sphere_points(size_t n) {
    double* xyz = (double*)malloc(3 * n * sizeof(double));
    const double golden = 3.14159265358979323846 * (3.0 - sqrt(5.0));
    size_t i;
    for (i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * (double)i + 1.0) / (double)n;
        const double r = sqrt(1.0 - z * z);
        xyz[3 * i + 0] = r * cos(golden * (double)i);
        xyz[3 * i + 1] = r * sin(golden * (double)i);
        xyz[3 * i + 2] = z;
    }
    return xyz;
}

static dbrg_points as_points(const void* data, size_t count, size_t stride, dbrg_scalar_type type) {
    dbrg_points p;
    p.data = data;
    p.count = count;
    p.stride_bytes = stride;
    p.type = type;
    return p;
}

static void test_versions_and_statuses(void) {
    int s;
    CHECK(dbrg_version_number() == DBRG_VERSION_NUMBER);
    CHECK(strcmp(dbrg_version_string(), DBRG_VERSION_STRING) == 0);
    CHECK(strcmp(dbrg_status_string(DBRG_OK), "DBRG_OK") == 0);
    CHECK(strcmp(dbrg_status_string(DBRG_ERR_NON_FINITE_INPUT), "DBRG_ERR_NON_FINITE_INPUT") == 0);
    for (s = DBRG_OK; s <= DBRG_ERR_INTERNAL; ++s) CHECK(strncmp(dbrg_status_string((dbrg_status)s), "DBRG_", 5) == 0);
    CHECK(strcmp(dbrg_status_string((dbrg_status)999), "DBRG_STATUS_UNKNOWN") == 0);
}

static void test_params(void) {
    dbrg_params params;
    char message[256];
    CHECK(dbrg_params_init(NULL) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_params_init_sized(&params, 8) == DBRG_ERR_INVALID_ARGUMENT);
    {
        /* A caller whose header has a larger struct gets this library's part filled, and is told its size. */
        struct {
            dbrg_params params;
            unsigned char newer_fields[32];
        } newer;
        memset(&newer, 0xab, sizeof newer);
        CHECK(dbrg_params_init_sized(&newer.params, sizeof newer) == DBRG_OK);
        CHECK(newer.params.struct_size == sizeof(dbrg_params));
        CHECK(newer.newer_fields[0] == 0xab);
    }
    CHECK(dbrg_params_init(&params) == DBRG_OK);
    CHECK(params.struct_size == sizeof params);
    CHECK(fabs(params.sliver_angle - 5.0 * 3.14159265358979323846 / 6.0) < 1e-12);
    CHECK(params.fill_holes == 1);
    CHECK(params.threads == 0);
    CHECK(params.snapshot == NULL && params.snapshot_user == NULL && params.snapshot_count == 0);
    {
        /* A caller compiled against 0.1.0, whose struct ends before the snapshot fields, is still served. */
        dbrg_params older;
        memset(&older, 0xab, sizeof older);
        CHECK(dbrg_params_init_sized(&older, offsetof(dbrg_params, snapshot)) == DBRG_OK);
        CHECK(older.struct_size == offsetof(dbrg_params, snapshot));
        CHECK(dbrg_params_validate(&older, message, sizeof message) == DBRG_OK);
        CHECK(dbrg_params_init_sized(&older, offsetof(dbrg_params, snapshot) - 1) == DBRG_ERR_INVALID_ARGUMENT);
        /* A size no header ever had (half a pointer of the snapshot fields) is refused. */
        CHECK(dbrg_params_init_sized(&older, offsetof(dbrg_params, snapshot) + 4) == DBRG_ERR_INVALID_ARGUMENT);
        older.struct_size = offsetof(dbrg_params, snapshot) + 4;
        CHECK(dbrg_params_validate(&older, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    }
    params.reserved = 1;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    CHECK(strstr(message, "reserved") != NULL);
    params.reserved = 0;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_OK);
    CHECK(message[0] == '\0');
    CHECK(dbrg_params_validate(NULL, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);

    params.sliver_angle = 4.0;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    CHECK(strstr(message, "sliver_angle") != NULL);
    dbrg_params_init(&params);
    params.boundary_factor = 0.5;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    CHECK(strstr(message, "boundary_factor") != NULL);
    params.boundary_factor = NAN;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    dbrg_params_init(&params);
    params.max_hole_edges = 2;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    CHECK(strstr(message, "max_hole_edges") != NULL);
    dbrg_params_init(&params);
    params.backend = (dbrg_backend)7;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
    dbrg_params_init(&params);
    {
        dbrg_allocator incomplete = {NULL, NULL, NULL, NULL};
        params.allocator = &incomplete;
        CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_PARAMETER);
        CHECK(strstr(message, "allocator") != NULL);
    }
    dbrg_params_init(&params);
    params.struct_size = 8;
    CHECK(dbrg_params_validate(&params, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(strstr(message, "struct_size") != NULL);
    /* A message buffer too small is truncated, never overrun. */
    CHECK(dbrg_params_validate(&params, message, 4) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(strlen(message) == 3);
}

static void test_point_checks(void) {
    char message[256];
    double xyz[5 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    float xyz_f[4 * 4] = {0, 0, 0, 9, 1, 0, 0, 9, 0, 1, 0, 9, 0, 0, 1, 9};
    double coplanar[5 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 3, 0};
    double collinear[5 * 3] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 5, 5, 5};
    double duplicates[5 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0};
    dbrg_points p;

    CHECK(dbrg_points_validate(NULL, NULL, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    p = as_points(xyz, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_OK);
    p = as_points(xyz_f, 4, 4 * sizeof(float), DBRG_FLOAT32);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_OK);
    p = as_points(xyz, 5, 2 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(strstr(message, "stride") != NULL);
    p = as_points(NULL, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    p = as_points(xyz, 5, 3 * sizeof(double), (dbrg_scalar_type)5);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
    p = as_points(xyz, (size_t)DBRG_MAX_POINTS + 1, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_TOO_MANY_POINTS);
    p = as_points(xyz, 1000, (size_t)-1 / 100, DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_TOO_MANY_POINTS);
    p = as_points(xyz, 3, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_TOO_FEW_POINTS);

    xyz[3 * 3 + 1] = NAN;
    p = as_points(xyz, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_NON_FINITE_INPUT);
    CHECK(strstr(message, "point 3") != NULL);
    CHECK(strstr(message, "has a NaN y coordinate") != NULL);
    xyz[3 * 3 + 1] = INFINITY;
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_NON_FINITE_INPUT);
    CHECK(strstr(message, "has an infinite y coordinate") != NULL);

    p = as_points(coplanar, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_OK); /* a flat set is a surface */
    p = as_points(collinear, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_DEGENERATE_INPUT);
    CHECK(strstr(message, "collinear") != NULL);
    p = as_points(duplicates, 5, 3 * sizeof(double), DBRG_FLOAT64);
    CHECK(dbrg_points_validate(&p, NULL, message, sizeof message) == DBRG_ERR_TOO_FEW_POINTS);
    CHECK(strstr(message, "3 distinct") != NULL);
}

/* Every directed edge at most once (orientation consistent, at most two faces an edge), indices in range. */
static int is_oriented_manifold(const uint32_t* triangles, uint32_t count, uint32_t points) {
    uint64_t* directed = (uint64_t*)malloc(3 * (size_t)count * sizeof(uint64_t) + 1);
    uint32_t t, i, j;
    int ok = 1;
    for (t = 0; t < count; ++t) {
        for (i = 0; i < 3; ++i) {
            const uint32_t a = triangles[3 * t + i], b = triangles[3 * t + (i + 1) % 3];
            if (a >= points || b >= points || a == b) ok = 0;
            directed[3 * t + i] = (uint64_t)a << 32 | b;
        }
    }
    for (i = 0; ok && i < 3 * count; ++i) {
        for (j = i + 1; j < 3 * count; ++j) {
            if (directed[i] == directed[j]) ok = 0;
        }
    }
    free(directed);
    return ok;
}

static int count_progress_calls;
static int cancel_after;

static int progress(void* user, dbrg_stage stage, double fraction) {
    (void)user;
    (void)stage;
    if (fraction < 0 || fraction > 1) return 1;
    ++count_progress_calls;
    return cancel_after > 0 && count_progress_calls >= cancel_after;
}

static void test_reconstruction(void) {
    const size_t n = 400;
    double* xyz = sphere_points(n);
    dbrg_points p = as_points(xyz, n, 3 * sizeof(double), DBRG_FLOAT64);
    dbrg_params params;
    dbrg_mesh* mesh = NULL;
    dbrg_stats stats;
    uint32_t loop_length = 7;
    double saved;

    CHECK(dbrg_reconstruct(&p, NULL, NULL) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_reconstruct(&p, NULL, &mesh) == DBRG_OK);
    CHECK(dbrg_mesh_status(mesh) == DBRG_OK);
    CHECK(strcmp(dbrg_mesh_message(mesh), "") == 0);
    CHECK(dbrg_mesh_point_count(mesh) == n);
    CHECK(dbrg_mesh_triangle_count(mesh) == 2 * n - 4); /* a closed sphere: Euler's formula */
    CHECK(is_oriented_manifold(dbrg_mesh_triangles(mesh), dbrg_mesh_triangle_count(mesh), (uint32_t)n));
    CHECK(dbrg_mesh_face_flags(mesh) != NULL);
    CHECK(dbrg_mesh_face_flags(NULL) == NULL);
    CHECK(dbrg_mesh_boundary_loop_count(mesh) == 0);
    CHECK(dbrg_mesh_boundary_loop(mesh, 0, &loop_length) == NULL);
    CHECK(loop_length == 0);
    memset(&stats, 0, sizeof stats);
    CHECK(dbrg_mesh_stats(mesh, &stats) == DBRG_ERR_INVALID_ARGUMENT);
    stats.struct_size = sizeof stats;
    CHECK(dbrg_mesh_stats(mesh, &stats) == DBRG_OK);
    CHECK(stats.struct_size == sizeof stats);
    CHECK(stats.input_points == n);
    CHECK(stats.unique_points == n);
    CHECK(stats.triangles == dbrg_mesh_triangle_count(mesh));
    CHECK(stats.tetrahedra > 0);
    CHECK(stats.seconds_total >= stats.seconds_delaunay);
    CHECK(stats.peak_bytes > 0);
    {
        /* A caller compiled against 0.4.0, whose struct ends before points_inserted, gets its fields only. */
        dbrg_stats older;
        memset(&older, 0xab, sizeof older);
        older.struct_size = offsetof(dbrg_stats, points_inserted);
        CHECK(dbrg_mesh_stats(mesh, &older) == DBRG_OK);
        CHECK(older.struct_size == offsetof(dbrg_stats, points_inserted));
        CHECK(older.triangles == stats.triangles);
        CHECK(older.points_inserted == 0xabababab);
    }
    dbrg_mesh_destroy(mesh);
    dbrg_mesh_destroy(NULL);

    /* A failed call still gives a result object with the status and a message. */
    saved = xyz[5];
    xyz[5] = NAN;
    CHECK(dbrg_reconstruct(&p, NULL, &mesh) == DBRG_ERR_NON_FINITE_INPUT);
    CHECK(dbrg_mesh_status(mesh) == DBRG_ERR_NON_FINITE_INPUT);
    CHECK(strstr(dbrg_mesh_message(mesh), "point 1") != NULL);
    CHECK(dbrg_mesh_triangle_count(mesh) == 0);
    CHECK(dbrg_mesh_triangles(mesh) == NULL);
    CHECK(dbrg_mesh_face_flags(mesh) == NULL);
    dbrg_mesh_destroy(mesh);
    xyz[5] = saved;

    dbrg_params_init(&params);
    params.sliver_angle = 1.0;
    CHECK(dbrg_reconstruct(&p, &params, &mesh) == DBRG_ERR_INVALID_PARAMETER);
    CHECK(strstr(dbrg_mesh_message(mesh), "sliver_angle") != NULL);
    dbrg_mesh_destroy(mesh);

    dbrg_params_init(&params);
    params.progress = progress;
    count_progress_calls = 0;
    cancel_after = 0;
    CHECK(dbrg_reconstruct(&p, &params, &mesh) == DBRG_OK);
    CHECK(count_progress_calls > 3);
    dbrg_mesh_destroy(mesh);
    cancel_after = 2;
    count_progress_calls = 0;
    CHECK(dbrg_reconstruct(&p, &params, &mesh) == DBRG_ERR_CANCELLED);
    CHECK(dbrg_mesh_triangle_count(mesh) == 0);
    dbrg_mesh_destroy(mesh);
    free(xyz);
}

static void test_allocator(void) {
    const size_t n = 80;
    double* xyz = sphere_points(n);
    dbrg_points p = as_points(xyz, n, 3 * sizeof(double), DBRG_FLOAT64);
    counting_allocator counter = {0, 0, 0, 0};
    dbrg_allocator allocator;
    dbrg_params params;
    dbrg_mesh* mesh = NULL;
    long total_requests, k, tried = 0, out_of_memory = 0;

    allocator.allocate = counting_allocate;
    allocator.reallocate = counting_reallocate;
    allocator.deallocate = counting_deallocate;
    allocator.user = &counter;
    dbrg_params_init(&params);
    params.allocator = &allocator;
    CHECK(dbrg_reconstruct(&p, &params, &mesh) == DBRG_OK);
    CHECK(counter.live_blocks > 0);
    dbrg_mesh_destroy(mesh);
    CHECK(counter.live_blocks == 0);
    CHECK(counter.live_bytes == 0);
    total_requests = counter.requests;
    CHECK(total_requests > 10);

    /* Refusing any one request gives DBRG_ERR_OUT_OF_MEMORY and leaks nothing (every request up to 100,
     * then a sample; tests/test_allocation_failure.cpp tries them all). */
    for (k = 1; k <= total_requests; k += k < 100 ? 1 : 1 + total_requests / 200) {
        dbrg_status status;
        counter.requests = 0;
        counter.fail_at = k;
        status = dbrg_reconstruct(&p, &params, &mesh);
        ++tried;
        if (status == DBRG_ERR_OUT_OF_MEMORY) ++out_of_memory;
        CHECK(status == DBRG_ERR_OUT_OF_MEMORY);
        dbrg_mesh_destroy(mesh);
        CHECK(counter.live_blocks == 0);
        CHECK(counter.live_bytes == 0);
    }
    CHECK(out_of_memory == tried);
    CHECK(tried >= (total_requests < 100 ? total_requests : 100));
    free(xyz);
}

static void test_tetrahedralization(void) {
    /* A cube's corners and its centre: cospherical corners, resolved by perturbation. */
    const float cube[9 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1, 0.5f, 0.5f, 0.5f};
    dbrg_points p = as_points(cube, 9, 3 * sizeof(float), DBRG_FLOAT32);
    dbrg_tetrahedralization* tets = NULL;
    const uint32_t* vertices;
    const uint32_t* adjacency;
    uint32_t count, t, f, hull_faces = 0;
    int symmetric = 1;

    CHECK(dbrg_tetrahedralize(&p, NULL, NULL) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_tetrahedralize(&p, NULL, &tets) == DBRG_OK);
    CHECK(dbrg_tetrahedralization_status(tets) == DBRG_OK);
    CHECK(strcmp(dbrg_tetrahedralization_message(tets), "") == 0);
    CHECK(dbrg_tetrahedralization_unique_point_count(tets) == 9);
    count = dbrg_tetrahedralization_tet_count(tets);
    vertices = dbrg_tetrahedralization_tets(tets);
    adjacency = dbrg_tetrahedralization_adjacency(tets);
    CHECK(count == 12); /* the centre sees each of the 6 faces as two triangles */
    for (t = 0; t < count; ++t) {
        for (f = 0; f < 4; ++f) {
            const uint32_t other = adjacency[4 * t + f];
            uint32_t g, back = 0;
            CHECK(vertices[4 * t + f] < 9);
            if (other == DBRG_NO_NEIGHBOR) {
                ++hull_faces;
                continue;
            }
            for (g = 0; g < 4; ++g) back += adjacency[4 * other + g] == t;
            if (back != 1) symmetric = 0;
        }
    }
    CHECK(symmetric);
    CHECK(hull_faces == 12);
    dbrg_tetrahedralization_destroy(tets);
    dbrg_tetrahedralization_destroy(NULL);

    p.count = 3;
    CHECK(dbrg_tetrahedralize(&p, NULL, &tets) == DBRG_ERR_TOO_FEW_POINTS);
    CHECK(dbrg_tetrahedralization_tet_count(tets) == 0);
    CHECK(strlen(dbrg_tetrahedralization_message(tets)) > 0);
    dbrg_tetrahedralization_destroy(tets);
}

/* A piece's figures added to a whole run's: counts add up, the noise estimate is the larger, the whole
 * mesh's figures stay the total's, the piece's peak becomes the tile peak; short or missing structs fail. */
static void test_stats_add_piece(void) {
    dbrg_stats total, piece;
    memset(&total, 0, sizeof total);
    memset(&piece, 0, sizeof piece);
    total.struct_size = piece.struct_size = sizeof(dbrg_stats);
    total.tetrahedra = 5;
    total.triangles = 7;
    total.noise_level = 0.1;
    total.tile_peak_bytes = 10;
    piece.tetrahedra = 2;
    piece.triangles = 100;
    piece.noise_level = 0.3;
    piece.smoothing_iterations = 3;
    piece.peak_bytes = 20;
    piece.seconds_grow = 0.5;
    CHECK(dbrg_stats_add_piece(&total, &piece) == DBRG_OK);
    CHECK(total.tetrahedra == 7 && total.triangles == 7 && total.noise_level == 0.3);
    CHECK(total.smoothing_iterations == 3 && total.tile_peak_bytes == 20 && total.seconds_grow == 0.5);
    CHECK(total.peak_bytes == 0);
    piece.noise_level = 0.2;
    CHECK(dbrg_stats_add_piece(&total, &piece) == DBRG_OK && total.noise_level == 0.3 && total.tetrahedra == 9);
    CHECK(dbrg_stats_add_piece(NULL, &piece) == DBRG_ERR_INVALID_ARGUMENT);
    CHECK(dbrg_stats_add_piece(&total, NULL) == DBRG_ERR_INVALID_ARGUMENT);
    /* Counts stop at their largest value. */
    piece.tetrahedra = 0xfffffffau; /* 9 + this passes 2^32 */
    CHECK(dbrg_stats_add_piece(&total, &piece) == DBRG_OK && total.tetrahedra == 0xffffffffu);
    /* A caller of 0.5.0 has every field up to points_inserted, and nothing past its size is written. */
    {
        struct {
            dbrg_stats stats;
            unsigned char after[16];
        } shorter;
        memset(&shorter, 0xab, sizeof shorter);
        memset(&shorter.stats, 0, offsetof(dbrg_stats, points_inserted) + sizeof(uint32_t));
        shorter.stats.struct_size = offsetof(dbrg_stats, points_inserted) + sizeof(uint32_t);
        piece.tetrahedra = 4;
        piece.points_inserted = 6;
        CHECK(dbrg_stats_add_piece(&shorter.stats, &piece) == DBRG_OK);
        CHECK(shorter.stats.tetrahedra == 4 && shorter.stats.points_inserted == 6);
        CHECK(((const unsigned char*)&shorter)[shorter.stats.struct_size] == 0xab && shorter.after[0] == 0xab);
    }
    piece.struct_size = offsetof(dbrg_stats, points_inserted);
    CHECK(dbrg_stats_add_piece(&total, &piece) == DBRG_ERR_INVALID_ARGUMENT && total.tetrahedra == 0xffffffffu);
}

static void test_tiles(void) {
    const size_t n = 8000; /* 3 slabs of a sphere this dense are wider than the strips around their walls */
    double* xyz = sphere_points(n);
    dbrg_points p = as_points(xyz, n, 3 * sizeof(double), DBRG_FLOAT64);
    uint64_t* ids = (uint64_t*)malloc(n * sizeof *ids);
    const double low[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, high[3] = {0.0, HUGE_VAL, HUGE_VAL};
    dbrg_tile_mesh* tile = NULL;
    dbrg_mesh* mesh = NULL;
    dbrg_stats stats;
    const uint64_t* triangles;
    uint64_t count, i;
    size_t k;
    int ids_known = 1;

    for (k = 0; k < n; ++k) ids[k] = ((uint64_t)1 << 35) + k;
    CHECK(dbrg_reconstruct_tile(&p, ids, low, high, NULL, &tile) == DBRG_OK);
    count = dbrg_tile_mesh_triangle_count(tile);
    triangles = dbrg_tile_mesh_triangles(tile);
    CHECK(count > 0 && triangles != NULL);
    for (i = 0; i < 3 * count; ++i) ids_known = ids_known && triangles[i] - ids[0] < n;
    CHECK(ids_known);
    CHECK(dbrg_tile_mesh_status(tile) == DBRG_OK);
    CHECK(strcmp(dbrg_tile_mesh_message(tile), "") == 0);
    stats.struct_size = sizeof stats;
    CHECK(dbrg_tile_mesh_stats(tile, &stats) == DBRG_OK && stats.triangles > count);
    /* The owned half of the sphere, grown back to the whole. */
    {
        dbrg_tile_mesh* grown = NULL;
        CHECK(dbrg_grow_from_surface(&p, ids, triangles, (size_t)count, NULL, NULL, &grown) == DBRG_OK);
        CHECK(dbrg_tile_mesh_triangle_count(grown) > count);
        CHECK(dbrg_tile_mesh_dropped(grown, &i) == NULL && i == 0);
        dbrg_tile_mesh_destroy(grown);
    }
    /* The plan, and a stitch of the owned half's faces at its wall, x = 0: faces are dropped and added. */
    {
        dbrg_tiling tiling;
        double walls[2];
        char message[128];
        dbrg_tile_mesh* seam = NULL;
        uint64_t dropped = 0;
        tiling.struct_size = sizeof tiling;
        CHECK(dbrg_tiling_plan(&p, 3, NULL, &tiling, walls, message, sizeof message) == DBRG_OK);
        CHECK(tiling.wall_count == 2 && tiling.axis < 3 && walls[0] < walls[1] && tiling.spacing > 0);
        CHECK(tiling.halo > tiling.seam_reach && strcmp(message, "") == 0);
        CHECK(dbrg_tiling_plan(&p, 3, NULL, NULL, walls, message, sizeof message) == DBRG_ERR_INVALID_ARGUMENT);
        CHECK(strcmp(message, "tiling is NULL") == 0);
        tiling.axis = 0;
        CHECK(dbrg_seam_stitch(&p, ids, triangles, (size_t)count, &tiling, 0.0, NULL, &seam) == DBRG_OK);
        CHECK(dbrg_tile_mesh_dropped(seam, &dropped) != NULL && dropped > 0 && dropped < count);
        CHECK(dbrg_tile_mesh_triangle_count(seam) > 0);
        dbrg_tile_mesh_destroy(seam);
    }
    dbrg_tile_mesh_destroy(tile);
    dbrg_tile_mesh_destroy(NULL);
    CHECK(dbrg_reconstruct_tile(&p, NULL, low, high, NULL, &tile) == DBRG_ERR_INVALID_ARGUMENT);
    dbrg_tile_mesh_destroy(tile);

    CHECK(dbrg_reconstruct_tiled(&p, 3, NULL, &mesh) == DBRG_OK);
    CHECK(is_oriented_manifold(dbrg_mesh_triangles(mesh), dbrg_mesh_triangle_count(mesh), (uint32_t)n));
    CHECK(dbrg_mesh_boundary_loop_count(mesh) == 0);
    stats.struct_size = sizeof stats;
    CHECK(dbrg_mesh_stats(mesh, &stats) == DBRG_OK && stats.tiles == 3);
    /* Assembling the tiled mesh's own faces gives them back. */
    {
        dbrg_mesh* again = NULL;
        CHECK(dbrg_mesh_assemble(&p, dbrg_mesh_triangles(mesh), dbrg_mesh_triangle_count(mesh), NULL, 0, NULL, &again) == DBRG_OK);
        CHECK(dbrg_mesh_triangle_count(again) == dbrg_mesh_triangle_count(mesh));
        dbrg_mesh_destroy(again);
    }
    dbrg_mesh_destroy(mesh);
    free(ids);
    free(xyz);
}

int main(void) {
    test_versions_and_statuses();
    test_params();
    test_point_checks();
    test_reconstruction();
    test_allocator();
    test_tetrahedralization();
    test_tiles();
    test_stats_add_piece();
    printf("%d passed, %d failed\n", checks_passed, checks_failed);
    return checks_failed == 0 ? 0 : 1;
}
