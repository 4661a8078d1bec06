/*
 * dbrg — surface reconstruction from unorganized 3D points by Delaunay-based region growing.
 *
 * The only public header of the library. Valid C99 and C++; depends on <stddef.h> and <stdint.h> only.
 *
 * Based on: C.-C. Kuo and H.-T. Yau, "A Delaunay-based region-growing approach to surface
 * reconstruction from unorganized points", Computer-Aided Design 37 (2005).
 *
 * Thread safety: the library has no global mutable state. Any number of calls may run at the same
 * time on different inputs; a result object (dbrg_mesh, dbrg_tetrahedralization) may be read from
 * several threads at once, but must not be read while another thread destroys it. Callbacks
 * (allocator, progress) run on the calling thread.
 *
 * ABI stability: within one major version, functions are only added, never removed or changed;
 * enum values are pinned and only grow (a status value is never reused); handles are opaque;
 * option and statistics structs begin with `size_t struct_size`, only grow at their end, and the
 * library reads or writes no byte past the size the caller says it has. Everything marked
 * EXPERIMENTAL may change in a minor version.
 */
#ifndef DBRG_DBRG_H
#define DBRG_DBRG_H

#include <stddef.h>
#include <stdint.h>

#define DBRG_VERSION_MAJOR 0
#define DBRG_VERSION_MINOR 5
#define DBRG_VERSION_PATCH 0
#define DBRG_VERSION_NUMBER (DBRG_VERSION_MAJOR * 10000 + DBRG_VERSION_MINOR * 100 + DBRG_VERSION_PATCH)
#define DBRG_VERSION_STRING "0.5.0"

#if defined(_WIN32) && defined(DBRG_SHARED_BUILD)
#define DBRG_API __declspec(dllexport)
#elif defined(_WIN32) && defined(DBRG_SHARED)
#define DBRG_API __declspec(dllimport)
#elif defined(__GNUC__)
#define DBRG_API __attribute__((visibility("default")))
#else
#define DBRG_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------
 * Version
 * ---------------------------------------------------------------------------------------------- */

/* Returns DBRG_VERSION_NUMBER of the library that is linked, so that a caller can detect a
 * mismatch between the header it was compiled with and the library it runs with. */
DBRG_API uint32_t dbrg_version_number(void);

/* Returns DBRG_VERSION_STRING of the linked library ("MAJOR.MINOR.PATCH"); never NULL. */
DBRG_API const char* dbrg_version_string(void);

/* ------------------------------------------------------------------------------------------------
 * Status codes. Values are pinned and never reused.
 * ---------------------------------------------------------------------------------------------- */

typedef enum dbrg_status {
    DBRG_OK = 0,
    DBRG_ERR_INVALID_ARGUMENT = 1,  /* a NULL pointer, a zero or too small stride, an unknown enum value */
    DBRG_ERR_INVALID_PARAMETER = 2, /* a dbrg_params field is out of range (message names it) */
    DBRG_ERR_NON_FINITE_INPUT = 3,  /* a coordinate is NaN or infinite (message names the point index) */
    DBRG_ERR_TOO_FEW_POINTS = 4,    /* fewer than 4 distinct points */
    DBRG_ERR_DEGENERATE_INPUT = 5,  /* all points collinear (no surface), or coplanar for dbrg_tetrahedralize */
    DBRG_ERR_TOO_MANY_POINTS = 6,   /* more points than DBRG_MAX_POINTS, or count * stride overflows */
    DBRG_ERR_OUT_OF_MEMORY = 7,     /* an allocation failed; nothing leaked */
    DBRG_ERR_CANCELLED = 8,         /* the progress callback asked to stop */
    DBRG_ERR_UNSUPPORTED = 9,       /* the feature is not available in this build (e.g. the TetGen backend) */
    DBRG_ERR_INTERNAL = 10          /* a bug in dbrg: please report it with the input */
} dbrg_status;

/* Returns the name of a status as a static string ("DBRG_ERR_NON_FINITE_INPUT"); unknown values
 * give "DBRG_STATUS_UNKNOWN". Never NULL. */
DBRG_API const char* dbrg_status_string(dbrg_status status);

/* The largest number of input points a call accepts: indices in results are 32-bit and
 * UINT32_MAX is reserved as a sentinel. */
#define DBRG_MAX_POINTS ((size_t)0x7fffffffu)

/* The value of an adjacency entry with no neighbour (a convex-hull face). */
#define DBRG_NO_NEIGHBOR UINT32_MAX

/* EXPERIMENTAL. The most growth snapshots a call takes (dbrg_params.snapshot_count): each copies the
 * surface grown so far, so a count near the number of points would cost time quadratic in it. */
#define DBRG_MAX_SNAPSHOTS 1000u

/* ------------------------------------------------------------------------------------------------
 * Caller-supplied memory allocation. Every byte the library allocates during a call or holds in a
 * result object goes through it; no global allocator is ever set.
 * ---------------------------------------------------------------------------------------------- */

typedef struct dbrg_allocator {
    /* Returns at least `size` bytes aligned for any scalar type, or NULL on failure. */
    void* (*allocate)(void* user, size_t size);
    /* Resizes a block from `old_size` to `new_size` bytes, keeping its contents; returns NULL on
     * failure, in which case the old block stays valid and is freed later by `deallocate`. */
    void* (*reallocate)(void* user, void* block, size_t old_size, size_t new_size);
    /* Frees a block obtained from allocate/reallocate; `size` is the size it was given. */
    void (*deallocate)(void* user, void* block, size_t size);
    /* Passed back as the first argument of every callback. */
    void* user;
} dbrg_allocator;

/* ------------------------------------------------------------------------------------------------
 * Progress and cancellation
 * ---------------------------------------------------------------------------------------------- */

typedef enum dbrg_stage {
    DBRG_STAGE_VALIDATE = 0,     /* checking and conditioning the input points */
    DBRG_STAGE_SORT = 1,         /* spatial sort of the points */
    DBRG_STAGE_DELAUNAY = 2,     /* Delaunay tetrahedralization */
    DBRG_STAGE_GROW = 3,         /* region growing; the fraction follows the faces grown, then the
                                    removal of small islands and the edge flips */
    DBRG_STAGE_FILL_HOLES = 4,   /* recursive hole filling */
    DBRG_STAGE_OUTPUT = 5,       /* building the result */
    DBRG_STAGE_CLEAN = 6         /* since 0.4.0: cleaning the points (outliers, near-duplicates, noise);
                                    between DBRG_STAGE_VALIDATE and DBRG_STAGE_DELAUNAY */
} dbrg_stage;

/* Called from the computing thread with the current stage and its completed fraction in [0, 1].
 * Return 0 to continue, any other value to cancel: the call then returns DBRG_ERR_CANCELLED. */
typedef int (*dbrg_progress_fn)(void* user, dbrg_stage stage, double fraction);

/* ------------------------------------------------------------------------------------------------
 * Input points: pointer + count + byte stride, float or double. The library reads them during the
 * call only and never keeps the pointer.
 * ---------------------------------------------------------------------------------------------- */

/* EXPERIMENTAL. A stage of growth, for pictures like the paper's Figures 1, 7 and 8: `triangles` holds
 * the `triangle_count` triangles grown so far as index triples into the caller's points (valid during
 * the call only; NULL when there are none); `points_reached` is the share of the distinct points the
 * surface has now. Taken while growing, a snapshot is oriented consistently but may have pinched
 * (bow-tie) vertices where two fronts touch before they are joined, and closed parts are not yet turned
 * outward. Time spent in the callback counts as growing time. Return non-zero to cancel the call (it
 * then returns DBRG_ERR_CANCELLED). */
typedef int (*dbrg_snapshot_fn)(void* user, const uint32_t* triangles, uint32_t triangle_count, double points_reached);

typedef enum dbrg_scalar_type {
    DBRG_FLOAT32 = 0,
    DBRG_FLOAT64 = 1
} dbrg_scalar_type;

typedef struct dbrg_points {
    const void* data;         /* x, y, z of point 0, then point 1 at data + stride_bytes, ... */
    size_t count;             /* number of points */
    size_t stride_bytes;      /* distance between consecutive points; at least 3 * sizeof(scalar) */
    dbrg_scalar_type type;    /* DBRG_FLOAT32 or DBRG_FLOAT64 */
} dbrg_points;

/* ------------------------------------------------------------------------------------------------
 * Parameters
 * ---------------------------------------------------------------------------------------------- */

typedef enum dbrg_backend {
    DBRG_BACKEND_BUILTIN = 0,    /* the built-in Bowyer-Watson tetrahedralization (always available) */
    DBRG_BACKEND_TETGEN = 1      /* TetGen (AGPL); only in builds configured with -Dtetgen=enabled */
} dbrg_backend;

typedef enum dbrg_boundary_mean {
    DBRG_BOUNDARY_MEAN_LOCAL = 0,  /* r_a over the triangles around the candidate's edge */
    DBRG_BOUNDARY_MEAN_GLOBAL = 1  /* r_a over all of S, as in the paper (section 4); the default */
} dbrg_boundary_mean;

/* Whether the points are cleaned before the tetrahedralization (since 0.4.0). */
typedef enum dbrg_cleaning {
    DBRG_CLEANING_AUTO = 0,  /* the default: each rule acts only where the data call for it (outliers,
                                near-duplicates; smoothing when the points are found noisy) */
    DBRG_CLEANING_OFF = 1,   /* the points go to the tetrahedralization as given (exact duplicates merged) */
    DBRG_CLEANING_ON = 2     /* as AUTO, and the points are smoothed whatever the noise estimate says */
} dbrg_cleaning;

typedef struct dbrg_params {
    size_t struct_size;              /* sizeof(dbrg_params), set by dbrg_params_init */

    /* theta_sliver (paper 3.1.2): a Delaunay triangle whose dihedral angle with its neighbour in the
     * surface is this large or larger is never attached. Radians, in (pi/2, pi). Default 5*pi/6. */
    double sliver_angle;
    /* M (paper section 4): a candidate whose circumradius exceeds M * r_a is not attached, which
     * leaves the boundary of an open surface open. 0 turns the test off (closed surfaces only).
     * Must be 0 or > 1. */
    double boundary_factor;
    /* Over which triangles r_a is averaged. */
    dbrg_boundary_mean boundary_mean;
    /* Non-zero: fill holes left by rejected candidates (paper section 5), then cut the small handles
     * growing made where a closed surface comes closer to itself than the sample spacing. Default 1. */
    uint32_t fill_holes;
    /* Holes with more boundary edges than this stay open. At least 3; default 256. A loop most of whose
     * edges the open-surface test made is a border, not a hole, unless it is at most 16 edges long or the
     * opening it bounds is no wider than boundary_factor times the mean circumradius of the triangles
     * along it (a sparse part of a closed surface, not a border). */
    uint32_t max_hole_edges;
    /* How many surface components may be grown from separate seeds (a scan of several objects).
     * At least 1. */
    uint32_t max_components;
    /* Which tetrahedralization to use. */
    dbrg_backend backend;
    /* Threads for the stages that split into parts (sorting and scanning the points, filling the
     * tetrahedron store, inserting most points into the tetrahedralization); growing the surface is
     * sequential. 1 runs on the calling thread only; 0 (the default) uses every processor the process
     * may run on. Extra threads are started only for inputs of about 22,000 points or more. They never
     * call the allocator or the progress callback: those stay on the calling thread. The result is the
     * same for any value (only the predicate counts in dbrg_stats differ). */
    uint32_t threads;

    /* NULL: the C library's malloc/realloc/free. Copied at the start of the call. */
    const dbrg_allocator* allocator;
    /* NULL: no progress reports. */
    dbrg_progress_fn progress;
    void* progress_user;

    /* Fields from version 0.2.0 on (a 0.1.0 caller's struct_size leaves them at their defaults). */

    /* EXPERIMENTAL. NULL (the default) or 0 snapshots: none. Otherwise called on the calling thread up to
     * `snapshot_count` times while the surface grows: when the share of points reached first passes
     * 1/K, 2/K, ... (K = snapshot_count, taken as DBRG_MAX_SNAPSHOTS when larger; one call for several
     * shares passed at once) and once when growing ends, before hole filling. */
    dbrg_snapshot_fn snapshot;
    void* snapshot_user;
    uint32_t snapshot_count;
    /* Must be 0. Holds the place the compiler would pad, so that the struct's size tells its version. */
    uint32_t reserved;

    /* Fields from version 0.4.0 on (an older caller's struct_size leaves them at their defaults). */

    /* Cleaning the points before the tetrahedralization: outliers (points far sparser than the rest)
     * left out, near-duplicates (points much closer than the local spacing) merged, noisy points moved
     * onto a local surface estimate for growing. Default DBRG_CLEANING_AUTO. */
    dbrg_cleaning cleaning;
    /* Non-zero: dbrg_mesh_smoothed_points gives the positions the points were smoothed to (the surface
     * then passes through those, not through the input). 0 (the default): the mesh is meant for the input
     * positions, and dbrg_mesh_smoothed_points returns NULL. */
    uint32_t output_smoothed;
} dbrg_params;

/* Fills the first `struct_size` bytes of `params` with the defaults (the paper's values where it gives
 * one) and sets params->struct_size to the number of bytes filled, which is struct_size or, for a caller
 * with a newer header, this library's sizeof(dbrg_params). C and C++ callers use dbrg_params_init below;
 * bindings pass the size of their own copy of the struct.
 * Returns DBRG_ERR_INVALID_ARGUMENT when params is NULL or struct_size is neither the size of the struct
 * of a released version (0.1.0, 0.2.0 (also 0.3.0's size) or this one) nor larger than this one's. */
DBRG_API dbrg_status dbrg_params_init_sized(dbrg_params* params, size_t struct_size);

/* Fills `params` with the defaults; inline so that the size is the one of the header the caller was
 * compiled with, and an older program never has bytes written past its struct by a newer library. */
static inline dbrg_status dbrg_params_init(dbrg_params* params) {
    return dbrg_params_init_sized(params, sizeof(dbrg_params));
}

/* Checks every field of `params`. Returns DBRG_OK, DBRG_ERR_INVALID_ARGUMENT (NULL, or a
 * struct_size the library does not know), or DBRG_ERR_INVALID_PARAMETER. When `message` is not
 * NULL, a NUL-terminated sentence naming the offending field is written into it (at most
 * `message_capacity` bytes including the NUL). */
DBRG_API dbrg_status dbrg_params_validate(const dbrg_params* params, char* message, size_t message_capacity);

/* Checks an input point array without computing anything: NULL data with a non-zero count, a
 * stride below 3 scalars, count * stride overflow, more than DBRG_MAX_POINTS points, a NaN or
 * infinite coordinate (the message names the first such point), fewer than 4 distinct points, all
 * points collinear (DBRG_ERR_DEGENERATE_INPUT). Coplanar points pass: dbrg_reconstruct accepts them
 * (dbrg_tetrahedralize does not).
 * `allocator` may be NULL (malloc). `message` as in dbrg_params_validate. */
DBRG_API dbrg_status dbrg_points_validate(const dbrg_points* points, const dbrg_allocator* allocator,
                                          char* message, size_t message_capacity);

/* ------------------------------------------------------------------------------------------------
 * Reconstruction
 * ---------------------------------------------------------------------------------------------- */

typedef struct dbrg_mesh dbrg_mesh;

/* Reconstructs an oriented manifold triangle surface through the points. Points that all lie exactly in
 * one plane are reconstructed in it: their 2-D Delaunay triangles grown with the same border rule, each
 * triangle measured by its smallest enclosing circle, faces turned to the plane normal whose largest
 * component is positive. On that flat path the statistics tetrahedra, rejected_edge_nonmanifold,
 * rejected_orientation, rejected_bowtie, rejected_dihedral, the hole fields, handles_removed and
 * seconds_fill_holes stay 0 (nothing of those stages runs); seconds_delaunay is the 2-D triangulation's.
 * Returns DBRG_OK or the status of the first problem found.
 * points: the input; read during the call only.
 * params: NULL for the defaults; otherwise initialised with dbrg_params_init.
 * out_mesh: receives a result object on every status except DBRG_ERR_INVALID_ARGUMENT for a NULL
 *   out_mesh and DBRG_ERR_OUT_OF_MEMORY before the object exists (then *out_mesh is NULL). On failure
 *   the object has no triangles and carries the status and a message. Destroy it with
 *   dbrg_mesh_destroy in every case. */
DBRG_API dbrg_status dbrg_reconstruct(const dbrg_points* points, const dbrg_params* params, dbrg_mesh** out_mesh);

/* Frees a result and everything it holds. NULL is accepted and ignored. */
DBRG_API void dbrg_mesh_destroy(dbrg_mesh* mesh);

/* Returns the status of the call that made `mesh` (DBRG_ERR_INVALID_ARGUMENT for NULL). */
DBRG_API dbrg_status dbrg_mesh_status(const dbrg_mesh* mesh);

/* Returns a NUL-terminated sentence on what went wrong. On success it is "" or, from version 0.3.0 on, a
 * warning that begins with "warning: " (the surface leaves more than half of the distinct points out,
 * usually because a parameter is set too tight). Valid until the mesh is destroyed. mesh may be NULL
 * (returns ""). */
DBRG_API const char* dbrg_mesh_message(const dbrg_mesh* mesh);

/* Returns the number of input points the triangle indices refer to (0 for NULL). */
DBRG_API uint32_t dbrg_mesh_point_count(const dbrg_mesh* mesh);

/* Returns the number of triangles (0 for NULL or a failed call). */
DBRG_API uint32_t dbrg_mesh_triangle_count(const dbrg_mesh* mesh);

/* Returns 3 * dbrg_mesh_triangle_count indices into the caller's input points, each triangle
 * counter-clockwise seen from outside (closed components face outward). Merged duplicate points
 * are represented by the smallest input index among them (points closer than 2^-201 of the cloud's
 * extent are merged too: then by the lexicographically smallest of their coordinates first, so the
 * choice never depends on the input order). NULL when there are no triangles. */
DBRG_API const uint32_t* dbrg_mesh_triangles(const dbrg_mesh* mesh);

/* Bits of dbrg_mesh_face_flags (since 0.4.0); bits not named here are 0. */
typedef enum dbrg_face_flag {
    DBRG_FACE_FILLED = 1 /* made by hole filling over a gap in the sample (params->fill_holes), not grown
                            from it: a Delaunay triangle attached over a hole, an ear, a face closing the
                            cut of a small handle, or a face that an edge flip made from such a face */
} dbrg_face_flag;

/* Returns dbrg_mesh_triangle_count bytes (since 0.4.0), one per triangle of dbrg_mesh_triangles in the
 * same order, each a combination of dbrg_face_flag bits: which triangles were invented rather than
 * grown. All 0 with params->fill_holes = 0 and for points all in one plane.
 * NULL when mesh is NULL or there are no triangles. */
DBRG_API const uint8_t* dbrg_mesh_face_flags(const dbrg_mesh* mesh);

/* Returns the number of boundary loops (open-surface borders and holes left open). */
DBRG_API uint32_t dbrg_mesh_boundary_loop_count(const dbrg_mesh* mesh);

/* Returns the point indices of boundary loop `loop` in order along the loop (each step from one index
 * to the next is a boundary edge in the direction its triangle traverses it), and writes its length
 * to *out_count.
 * Returns NULL and writes 0 when mesh is NULL or loop is out of range. out_count may be NULL. */
DBRG_API const uint32_t* dbrg_mesh_boundary_loop(const dbrg_mesh* mesh, uint32_t loop, uint32_t* out_count);

/* Figures about one reconstruction. Times are wall-clock seconds. */
typedef struct dbrg_stats {
    size_t struct_size;              /* set by the caller to sizeof(dbrg_stats) before the call */

    uint32_t input_points;           /* points in the caller's array */
    uint32_t unique_points;          /* after merging exact duplicates */
    uint32_t duplicates_merged;      /* input_points - unique_points */
    uint32_t tetrahedra;             /* finite Delaunay tetrahedra */
    uint32_t triangles;              /* triangles in the result */
    uint32_t vertices_used;          /* distinct points the result's triangles use */
    uint32_t boundary_edges;         /* edges of the result with one triangle */
    uint32_t boundary_loops;
    uint32_t components;             /* connected components of the result (each grown from its own seed) */
    uint32_t pinch_faces_removed;    /* faces removed where two sheets still met at a vertex when growing ended,
                                        with the islands of fewer than 16 faces that this cut off */

    uint64_t candidates_evaluated;   /* candidate triangles popped from the priority queue */
    uint64_t rejected_edge_nonmanifold; /* would give an edge a third triangle */
    uint64_t rejected_orientation;   /* orientation incompatible with a neighbour */
    uint64_t rejected_bowtie;        /* would make a vertex non-manifold (a neck) */
    uint64_t rejected_dihedral;      /* dihedral angle with a neighbour >= sliver_angle */
    uint64_t rejected_boundary;      /* circumradius above M * r_a (open-surface boundary) */

    uint32_t holes_found;            /* boundary loops left by rejected candidates (not by the open-surface test) */
    uint32_t holes_filled;
    uint32_t holes_left_open;        /* too large (max_hole_edges) or impossible to fill validly */
    uint32_t hole_triangles_delaunay;/* Delaunay triangles attached by a second growing pass over the holes */
    uint32_t hole_triangles_added;   /* new (non-Delaunay) triangles over the holes' vertices, and over the
                                        sides of small handles cut */
    uint32_t hole_triangles_removed; /* by the recursive enlargement of holes, and by cutting small handles */

    uint64_t predicate_calls;        /* orient3d + insphere evaluations */
    uint64_t predicate_filter_failures; /* of those, how many the floating-point filter could not decide */
    uint64_t predicate_perturbations;   /* of those, how many were exactly degenerate (symbolic perturbation) */

    double seconds_validate;
    double seconds_sort;
    double seconds_delaunay;
    double seconds_grow;
    double seconds_fill_holes;
    double seconds_output;
    double seconds_total;

    size_t peak_bytes;               /* the most memory held through the allocator at once */

    uint32_t handles_removed;        /* small handles cut from the components after hole filling (growing
                                        bridged two sheets closer than the sample spacing) */

    /* Fields from version 0.4.0 on: the cleaning stage (all 0 when params.cleaning is DBRG_CLEANING_OFF).
     * After dbrg_reconstruct_tiled the counts are the tiles' sums (a halo point counts in each tile that
     * cleans it), noise_level and smoothing_iterations the largest of the tiles'; outliers as above. */
    uint32_t outliers;               /* distinct points left out as outliers (dbrg_mesh_outliers lists them) */
    uint32_t near_duplicates_merged; /* distinct points merged into a nearby point (much closer than the
                                        local spacing); not counted in duplicates_merged */
    uint32_t points_smoothed;        /* points moved onto a local surface estimate; 0 when not smoothed */
    uint32_t smoothing_iterations;   /* projections each point went through; 0 when not smoothed */
    double noise_level;              /* the noise estimate: median residual of a local quadric fit over the
                                        mean distance to the neighbours (about 0.8 x noise / spacing) */
    double seconds_clean;
    /* Also from version 0.4.0 on; 0 except after dbrg_reconstruct_tiled. */
    uint32_t tiles;                  /* tiles reconstructed (1 when the call ran as one piece) */
    uint32_t seam_faces_dropped;     /* stitched faces left out because they would break the manifold */
    size_t tile_peak_bytes;          /* the most one tile, or one seam stitch, held through the allocator */
    /* From version 0.5.0 on. */
    uint32_t points_inserted;        /* points growing and hole filling passed over that a fan of Delaunay
                                        triangles put back into the surface (a close pair's second point) */
} dbrg_stats;

/* Returns the indices of the input points left out as outliers, ascending, and writes their number to
 * *out_count (since 0.4.0). An outlier stands for its exact duplicates too: the index given is the one
 * that would have stood for them. No triangle uses an outlier.
 * Returns NULL and writes 0 when mesh is NULL or there are none. out_count may be NULL. */
DBRG_API const uint32_t* dbrg_mesh_outliers(const dbrg_mesh* mesh, uint32_t* out_count);

/* Returns 3 * dbrg_mesh_point_count doubles (since 0.4.0): x, y, z of each input point as the surface
 * has it: the smoothed position of each point that stands for a distinct point, the input position of the
 * others (duplicates, outliers). NULL unless params->output_smoothed was set and the points were
 * smoothed (dbrg_stats.points_smoothed > 0). mesh may be NULL (returns NULL). */
DBRG_API const double* dbrg_mesh_smoothed_points(const dbrg_mesh* mesh);

/* Copies the statistics of the call that made `mesh` into `stats`, up to stats->struct_size bytes,
 * and sets stats->struct_size to the number of bytes filled (smaller than the caller's when the
 * library is older than the caller's header: the fields past it are left as they were).
 * Returns DBRG_ERR_INVALID_ARGUMENT when mesh or stats is NULL or struct_size is too small to hold
 * the struct_size field. */
DBRG_API dbrg_status dbrg_mesh_stats(const dbrg_mesh* mesh, dbrg_stats* stats);

/* ------------------------------------------------------------------------------------------------
 * Tiles: clouds larger than one process — EXPERIMENTAL (docs/tiles.md)
 *
 * A cloud is cut into tiles, each a half-open core box plus a halo of points around it; each tile is
 * reconstructed on its own (here, or in another process) and keeps the triangles its core owns; the seam
 * strips around the core walls are then cut and regrown from the surface around them. Point ids in these
 * functions are 64-bit global ids, so a cloud may have more than 4.29 billion points; one call still
 * takes at most DBRG_MAX_POINTS points.
 * ---------------------------------------------------------------------------------------------- */

/* Reconstructs `points` as `tile_count` tiles run one after another in this process and stitches them:
 * slabs along the longest axis of the points' box holding about equal numbers of points, each with a halo
 * of 8 point spacings (the 90th percentile of nearest-neighbour distances), seam strips of 3 spacings on
 * each side of a wall regrown from the surface around them. The mesh depends on the tiling (tile_count and the
 * points), never on the order tiles run. Fills *out_mesh like dbrg_reconstruct, with the statistics
 * tiles, seam_faces_dropped and tile_peak_bytes; unique_points counts every input point (duplicates are
 * merged within tiles) and the times are summed over the tiles. tile_count 0 or 1 is dbrg_reconstruct.
 * Returns DBRG_OK or the status of the first problem, whose message names the tile.
 * points: the input, at most DBRG_MAX_POINTS points; read during the call only.
 * tile_count: the number of slabs wanted; fewer where a slab would be thinner than 12 spacings (the
 *   strips around its walls) — a small cloud runs as one piece — and where points share a coordinate.
 * params: NULL for the defaults; its progress callback hears DBRG_STAGE_GROW as the share of tiles done.
 * out_mesh: as in dbrg_reconstruct. */
DBRG_API dbrg_status dbrg_reconstruct_tiled(const dbrg_points* points, uint32_t tile_count, const dbrg_params* params,
                                            dbrg_mesh** out_mesh);

/* The triangles of one tile or of a stitch, as 64-bit global point ids. */
typedef struct dbrg_tile_mesh dbrg_tile_mesh;

/* Reconstructs one tile: the surface of `points` (the points of its core and its halo) and, of it, the
 * triangles the core owns: those whose centroid, (a + b + c) / 3 in double precision with the corners
 * summed in lexicographic order of their coordinates, lies in the half-open box [core_low, core_high).
 * Every tile computes the same centroid for a triangle and half-open cores partition space, so no
 * triangle has two owners.
 * The points of the core that cleaning leaves out as outliers are listed too (dbrg_tile_mesh_outliers):
 * every point lies in one core, so the tiles list each outlier once; a stitch is given them only as corners
 * of the faces it is given (another tile may have kept one).
 * Returns DBRG_OK or the status of the first problem, as dbrg_reconstruct.
 * points: the tile's points; read during the call only.
 * point_ids: points->count global ids, distinct; read during the call only.
 * core_low, core_high: 3 bounds each; -HUGE_VAL and HUGE_VAL for an unbounded side.
 * params: NULL for the defaults; otherwise initialised with dbrg_params_init.
 * out: receives a result object as dbrg_reconstruct's out_mesh does; destroy it with
 *   dbrg_tile_mesh_destroy. */
DBRG_API dbrg_status dbrg_reconstruct_tile(const dbrg_points* points, const uint64_t* point_ids, const double* core_low,
                                           const double* core_high, const dbrg_params* params, dbrg_tile_mesh** out);

/* Grows a surface from a given partial one: puts the seed triangles into the surface (those that do not
 * fit it as an oriented manifold are left out), then region growing runs from their boundary edges over
 * the Delaunay tetrahedralization of `points` with the usual candidate order, examinations and
 * open-surface test, followed by hole filling's Delaunay pass over the edges left unresolved, its ears
 * over the holes that pass through no fixed point, and the edge flips (no handle cut). No new triangle
 * uses a fixed point, and a fixed point where the seeds meet in two fans keeps both. The seam stitch of
 * tiled reconstruction, and a way to impose seeds or a border. The result holds the whole surface, the seeds that fitted included. Points all in one plane
 * give DBRG_ERR_DEGENERATE_INPUT.
 * points, point_ids: as in dbrg_reconstruct_tile.
 * seed_triangles: 3 * seed_count global ids of `points`, each triangle counter-clockwise and all oriented
 *   alike; a triangle with an id not among point_ids is left out. May be NULL when seed_count is 0
 *   (then nothing grows).
 * fixed: NULL, or points->count flags: non-zero marks a point no new triangle may use (its fan is
 *   complete outside these points).
 * params, out: as in dbrg_reconstruct_tile. */
DBRG_API dbrg_status dbrg_grow_from_surface(const dbrg_points* points, const uint64_t* point_ids,
                                            const uint64_t* seed_triangles, size_t seed_count, const uint8_t* fixed,
                                            const dbrg_params* params, dbrg_tile_mesh** out);

/* How a cloud is cut into slabs (EXPERIMENTAL, since 0.5.0): the plan dbrg_reconstruct_tiled follows, which
 * a driver running the steps elsewhere (dbrg_reconstruct_tile, dbrg_seam_stitch, dbrg_mesh_assemble) gets from
 * dbrg_tiling_plan to give the same mesh. Tile k (0-based) of wall_count + 1 has the half-open core
 * [walls[k-1], walls[k]) on `axis` (unbounded outward for the first and the last; the other axes
 * unbounded) and its points are those whose coordinate on `axis` lies in [low - halo, high + halo). The
 * functions that take a dbrg_tiling read struct_size, axis and spacing; the other fields are for the caller. */
typedef struct dbrg_tiling {
    size_t struct_size;    /* sizeof(dbrg_tiling), set by the caller */
    uint32_t axis;         /* 0, 1, 2: the slabs are cut across x, y or z (the box's longest side) */
    uint32_t wall_count;   /* inner walls: the tiles number wall_count + 1 (0: run as one piece) */
    double spacing;        /* the point spacing s: the 90th percentile of nearest-neighbour distances */
    double halo;           /* how far a tile's points reach past its core: 8 s */
    double seam_reach;     /* how far from a wall its stitch looks: 6 s (a strip of 3 s cut, 3 s of seeds) */
} dbrg_tiling;

/* Plans `tile_count` slabs over `points` as dbrg_reconstruct_tiled does: the spacing, the longest axis of
 * the points' box, and walls at point-count quantiles on it, fewer where a slab would be thinner than 12
 * spacings or points share a coordinate (a small cloud gets no walls and runs as one piece). Depends on the
 * set of points, not their order.
 * Returns DBRG_OK, DBRG_ERR_INVALID_ARGUMENT (tiling or walls NULL, tiling->struct_size too small),
 * or the status of dbrg_reconstruct for bad points (too few, too many, not finite, ...), with a message.
 * points: the whole cloud, at most DBRG_MAX_POINTS points (an out-of-core caller plans from its own
 *   summary and fills a dbrg_tiling itself); read during the call only.
 * tile_count: the number of slabs wanted; 0 and 1 mean one piece.
 * params: NULL for the defaults; only its allocator is used.
 * tiling: receives the plan; tiling->struct_size must be set.
 * walls: room for tile_count - 1 doubles, receiving wall_count wall positions, ascending; may be NULL
 *   when tile_count <= 1.
 * message: NULL, or room for `capacity` bytes receiving a NUL-terminated message ("" on success). */
DBRG_API dbrg_status dbrg_tiling_plan(const dbrg_points* points, uint32_t tile_count, const dbrg_params* params,
                                      dbrg_tiling* tiling, double* walls, char* message, size_t capacity);

/* Stitches the seam around one wall (since 0.5.0): the faces with a corner closer than 3 spacings to the
 * wall are cut, the faces with a corner closer than 6 spacings or at a cut face's corner are the seeds;
 * these are oriented alike (joined across the wall by the cut faces) and the strip is regrown from the
 * seeds as dbrg_grow_from_surface does, the seeds' corners beyond 6 spacings fixed. The result lists the
 * faces to drop (the cut faces and the seeds) and the faces to add in their place (the regrown strip,
 * the seeds that fitted included). It depends on the points and faces near the wall only — not on their
 * order, nor on the points and faces further away that a caller includes — so stitches whose walls are two
 * slabs apart change disjoint sets of faces and may run at the same time. dbrg_reconstruct_tiled stitches
 * the walls of even index (0, 2, ...) on the tiles' faces, then those of odd index on the result: a driver
 * that does the same gets the same mesh.
 * Returns DBRG_OK, DBRG_ERR_INVALID_ARGUMENT (a NULL pointer, a bad tiling or wall, a face with a repeated
 * corner or an id not among point_ids, repeated point ids), or another status as dbrg_grow_from_surface,
 * with a message; a strip with no volume to grow in (flat, fewer than 4 points) keeps its seeds.
 * points, point_ids: at least every point within tiling->seam_reach of the wall and every corner of
 *   `faces`, with distinct 64-bit global ids, any number up to DBRG_MAX_POINTS (point_ids may be NULL
 *   when there are none); read during the call only.
 * faces: 3 * face_count global ids: the faces so far (the tiles' owned faces, oriented as their tiles
 *   grew them, after the even walls' stitches for an odd wall), at least those with a corner within
 *   seam_reach of the wall or sharing a corner with a face that has one within 3 spacings. May be NULL
 *   when face_count is 0.
 * tiling: the plan (axis and spacing are used). wall: the wall's position on tiling->axis.
 * params, out: as in dbrg_reconstruct_tile; the faces to add are dbrg_tile_mesh_triangles, the faces to
 *   drop dbrg_tile_mesh_dropped. */
DBRG_API dbrg_status dbrg_seam_stitch(const dbrg_points* points, const uint64_t* point_ids, const uint64_t* faces,
                                      size_t face_count, const dbrg_tiling* tiling, double wall,
                                      const dbrg_params* params, dbrg_tile_mesh** out);

/* Assembles stitched faces into one mesh as dbrg_reconstruct_tiled ends (since 0.5.0): orients them
 * together (a walk across shared edges from the faces in sorted order; each component turned outward when
 * closed, else as region growing seeds it), puts them into one surface in the walk's order leaving out a
 * face that would break the manifold (counted in seam_faces_dropped), keeps the largest fan at a pinched
 * vertex, cuts small handles as dbrg_reconstruct's hole filling does (not when params->fill_holes is 0;
 * here because no tile or strip holds a whole closed component to find them in), and hands
 * the surface over as dbrg_reconstruct does (boundary loops, statistics). Depends on the
 * set of faces, not their order or orientation. A whole-mesh step: it holds all points and faces, with
 * 32-bit indices.
 * The tiles' outliers that no face uses (a neighbouring tile may have kept and joined a point of another's
 * core) become the mesh's (dbrg_mesh_outliers, stats.outliers), as in dbrg_reconstruct.
 * Returns DBRG_OK, DBRG_ERR_INVALID_ARGUMENT (NULL triangles or outliers with a count, an index past the
 * points, a triangle repeating a corner), or the status of dbrg_reconstruct for bad points.
 * points: the whole cloud; read during the call only.
 * triangles: 3 * triangle_count indices into `points`. May be NULL when triangle_count is 0.
 * outliers: outlier_count indices into `points`, in any order (the tiles' dbrg_tile_mesh_outliers). May be
 *   NULL when outlier_count is 0.
 * params, out_mesh: as in dbrg_reconstruct. */
DBRG_API dbrg_status dbrg_mesh_assemble(const dbrg_points* points, const uint32_t* triangles, size_t triangle_count,
                                        const uint32_t* outliers, size_t outlier_count, const dbrg_params* params,
                                        dbrg_mesh** out_mesh);

/* Frees a tile result. NULL is accepted and ignored. */
DBRG_API void dbrg_tile_mesh_destroy(dbrg_tile_mesh* mesh);

/* Returns the status of the call that made `mesh` (DBRG_ERR_INVALID_ARGUMENT for NULL). */
DBRG_API dbrg_status dbrg_tile_mesh_status(const dbrg_tile_mesh* mesh);

/* Returns a NUL-terminated message on what went wrong, or "". NULL gives "". */
DBRG_API const char* dbrg_tile_mesh_message(const dbrg_tile_mesh* mesh);

/* Returns the number of triangles (0 for NULL or a failed call). */
DBRG_API uint64_t dbrg_tile_mesh_triangle_count(const dbrg_tile_mesh* mesh);

/* Returns 3 * dbrg_tile_mesh_triangle_count global point ids, each triangle counter-clockwise as grown
 * (a tile's piece of a closed surface is open: orient the pieces together after stitching). NULL when
 * there are none. */
DBRG_API const uint64_t* dbrg_tile_mesh_triangles(const dbrg_tile_mesh* mesh);

/* Returns the faces a dbrg_seam_stitch call drops, as ascending indices into its `faces` (since 0.5.0), and
 * writes their number to *out_count. NULL and 0 for other results, NULL or failed ones. out_count may be
 * NULL. */
DBRG_API const uint64_t* dbrg_tile_mesh_dropped(const dbrg_tile_mesh* mesh, uint64_t* out_count);

/* Returns the global ids of the points of a dbrg_reconstruct_tile call's core left out as outliers,
 * ascending (since 0.5.0), and writes their number to *out_count. NULL and 0 for other results, NULL or
 * failed ones. out_count may be NULL. */
DBRG_API const uint64_t* dbrg_tile_mesh_outliers(const dbrg_tile_mesh* mesh, uint64_t* out_count);

/* Copies the statistics of the call, as dbrg_mesh_stats. */
DBRG_API dbrg_status dbrg_tile_mesh_stats(const dbrg_tile_mesh* mesh, dbrg_stats* stats);

/* Adds the statistics of one piece of a tiled run (dbrg_tile_mesh_stats of a dbrg_reconstruct_tile or
 * dbrg_seam_stitch result) to `total` as dbrg_reconstruct_tiled adds its own pieces' (since 0.5.0): counts
 * and seconds add up, noise_level and smoothing_iterations become the larger of the two, tile_peak_bytes the
 * larger of total's and the piece's peak_bytes; the figures of the whole mesh (points, triangles, loops,
 * components, outliers, tiles) stay total's. A driver that runs the pieces elsewhere calls it once a piece
 * on dbrg_mesh_stats of its dbrg_mesh_assemble result to report what the C loop reports. Counts stop at
 * their type's largest value rather than wrap. Fields beyond either struct_size are neither read nor
 * written. Returns DBRG_ERR_INVALID_ARGUMENT when either is NULL or its struct_size does not reach
 * points_inserted (the fields of 0.5.0). */
DBRG_API dbrg_status dbrg_stats_add_piece(dbrg_stats* total, const dbrg_stats* piece);

/* ------------------------------------------------------------------------------------------------
 * Delaunay tetrahedralization — EXPERIMENTAL
 * ---------------------------------------------------------------------------------------------- */

typedef struct dbrg_tetrahedralization dbrg_tetrahedralization;

/* Computes the Delaunay tetrahedralization of the points (exact predicates, symbolic perturbation for
 * cospherical points). Uses params->backend, allocator and progress; the surface parameters are ignored.
 * Returns and fills *out exactly like dbrg_reconstruct; points all in one plane have no tetrahedra:
 * DBRG_ERR_DEGENERATE_INPUT. */
DBRG_API dbrg_status dbrg_tetrahedralize(const dbrg_points* points, const dbrg_params* params,
                                         dbrg_tetrahedralization** out);

/* Frees a tetrahedralization. NULL is accepted and ignored. */
DBRG_API void dbrg_tetrahedralization_destroy(dbrg_tetrahedralization* tets);

/* Returns the status of the call that made `tets` (DBRG_ERR_INVALID_ARGUMENT for NULL). */
DBRG_API dbrg_status dbrg_tetrahedralization_status(const dbrg_tetrahedralization* tets);

/* Returns a NUL-terminated message on what went wrong, or "". NULL gives "". */
DBRG_API const char* dbrg_tetrahedralization_message(const dbrg_tetrahedralization* tets);

/* Returns the number of finite tetrahedra (0 for NULL or a failed call). */
DBRG_API uint32_t dbrg_tetrahedralization_tet_count(const dbrg_tetrahedralization* tets);

/* Returns 4 * tet_count indices into the caller's points; each tetrahedron (a, b, c, d) is
 * positively oriented: d lies on the side of plane (a, b, c) from which a, b, c appear clockwise.
 * Their order, and the order of each one's corners, depend on the points only, not on
 * params->threads. NULL when there are none. */
DBRG_API const uint32_t* dbrg_tetrahedralization_tets(const dbrg_tetrahedralization* tets);

/* Returns 4 * tet_count entries: entry 4*t + f is the tetrahedron across the face of t opposite its
 * vertex f, or DBRG_NO_NEIGHBOR on the convex hull. NULL when there are none. */
DBRG_API const uint32_t* dbrg_tetrahedralization_adjacency(const dbrg_tetrahedralization* tets);

/* Returns the number of distinct points (duplicates merged), 0 for NULL. */
DBRG_API uint32_t dbrg_tetrahedralization_unique_point_count(const dbrg_tetrahedralization* tets);

#ifdef __cplusplus
}
#endif

#endif /* DBRG_DBRG_H */
