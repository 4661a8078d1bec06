"""ctypes declarations mirroring include/dbrg/dbrg.h, one for one.

This module only declares: it neither loads the library nor imports numpy, so that the agreement
check (bindings/check_agreement.py) can read it on any Python. Names are the header's names; the
friendly interface lives in dbrg/__init__.py.
"""

import ctypes
from ctypes import POINTER, c_char_p, c_double, c_int, c_size_t, c_uint32, c_uint64, c_void_p

# The header these declarations were written against (DBRG_VERSION_*).
DBRG_VERSION_MAJOR = 0
DBRG_VERSION_MINOR = 5
DBRG_VERSION_PATCH = 0
DBRG_VERSION_STRING = "0.5.0"
DBRG_VERSION_NUMBER = DBRG_VERSION_MAJOR * 10000 + DBRG_VERSION_MINOR * 100 + DBRG_VERSION_PATCH

DBRG_MAX_POINTS = 0x7FFFFFFF
DBRG_NO_NEIGHBOR = 0xFFFFFFFF
DBRG_MAX_SNAPSHOTS = 1000

# Every enum in the header has values 0..10, so the compiler gives it the size of an int.
c_enum = c_int

ENUMS = {
    "dbrg_status": {
        "DBRG_OK": 0,
        "DBRG_ERR_INVALID_ARGUMENT": 1,
        "DBRG_ERR_INVALID_PARAMETER": 2,
        "DBRG_ERR_NON_FINITE_INPUT": 3,
        "DBRG_ERR_TOO_FEW_POINTS": 4,
        "DBRG_ERR_DEGENERATE_INPUT": 5,
        "DBRG_ERR_TOO_MANY_POINTS": 6,
        "DBRG_ERR_OUT_OF_MEMORY": 7,
        "DBRG_ERR_CANCELLED": 8,
        "DBRG_ERR_UNSUPPORTED": 9,
        "DBRG_ERR_INTERNAL": 10,
    },
    "dbrg_stage": {
        "DBRG_STAGE_VALIDATE": 0,
        "DBRG_STAGE_SORT": 1,
        "DBRG_STAGE_DELAUNAY": 2,
        "DBRG_STAGE_GROW": 3,
        "DBRG_STAGE_FILL_HOLES": 4,
        "DBRG_STAGE_OUTPUT": 5,
        "DBRG_STAGE_CLEAN": 6,
    },
    "dbrg_scalar_type": {
        "DBRG_FLOAT32": 0,
        "DBRG_FLOAT64": 1,
    },
    "dbrg_backend": {
        "DBRG_BACKEND_BUILTIN": 0,
        "DBRG_BACKEND_TETGEN": 1,
    },
    "dbrg_boundary_mean": {
        "DBRG_BOUNDARY_MEAN_LOCAL": 0,
        "DBRG_BOUNDARY_MEAN_GLOBAL": 1,
    },
    "dbrg_cleaning": {
        "DBRG_CLEANING_AUTO": 0,
        "DBRG_CLEANING_OFF": 1,
        "DBRG_CLEANING_ON": 2,
    },
    "dbrg_face_flag": {
        "DBRG_FACE_FILLED": 1,
    },
}


class dbrg_allocator(ctypes.Structure):
    pass


ALLOCATE_FN = ctypes.CFUNCTYPE(c_void_p, c_void_p, c_size_t)
REALLOCATE_FN = ctypes.CFUNCTYPE(c_void_p, c_void_p, c_void_p, c_size_t, c_size_t)
DEALLOCATE_FN = ctypes.CFUNCTYPE(None, c_void_p, c_void_p, c_size_t)
dbrg_allocator._fields_ = [
    ("allocate", ALLOCATE_FN),
    ("reallocate", REALLOCATE_FN),
    ("deallocate", DEALLOCATE_FN),
    ("user", c_void_p),
]

# int (*)(void* user, dbrg_stage stage, double fraction)
PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, c_enum, c_double)
SNAPSHOT_FN = ctypes.CFUNCTYPE(c_int, c_void_p, POINTER(c_uint32), c_uint32, c_double)


class dbrg_points(ctypes.Structure):
    _fields_ = [
        ("data", c_void_p),
        ("count", c_size_t),
        ("stride_bytes", c_size_t),
        ("type", c_enum),
    ]


class dbrg_params(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_size_t),
        ("sliver_angle", c_double),
        ("boundary_factor", c_double),
        ("boundary_mean", c_enum),
        ("fill_holes", c_uint32),
        ("max_hole_edges", c_uint32),
        ("max_components", c_uint32),
        ("backend", c_enum),
        ("threads", c_uint32),
        ("allocator", POINTER(dbrg_allocator)),
        ("progress", PROGRESS_FN),
        ("progress_user", c_void_p),
        ("snapshot", SNAPSHOT_FN),
        ("snapshot_user", c_void_p),
        ("snapshot_count", c_uint32),
        ("reserved", c_uint32),
        ("cleaning", c_enum),
        ("output_smoothed", c_uint32),
    ]


class dbrg_stats(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_size_t),
        ("input_points", c_uint32),
        ("unique_points", c_uint32),
        ("duplicates_merged", c_uint32),
        ("tetrahedra", c_uint32),
        ("triangles", c_uint32),
        ("vertices_used", c_uint32),
        ("boundary_edges", c_uint32),
        ("boundary_loops", c_uint32),
        ("components", c_uint32),
        ("pinch_faces_removed", c_uint32),
        ("candidates_evaluated", c_uint64),
        ("rejected_edge_nonmanifold", c_uint64),
        ("rejected_orientation", c_uint64),
        ("rejected_bowtie", c_uint64),
        ("rejected_dihedral", c_uint64),
        ("rejected_boundary", c_uint64),
        ("holes_found", c_uint32),
        ("holes_filled", c_uint32),
        ("holes_left_open", c_uint32),
        ("hole_triangles_delaunay", c_uint32),
        ("hole_triangles_added", c_uint32),
        ("hole_triangles_removed", c_uint32),
        ("predicate_calls", c_uint64),
        ("predicate_filter_failures", c_uint64),
        ("predicate_perturbations", c_uint64),
        ("seconds_validate", c_double),
        ("seconds_sort", c_double),
        ("seconds_delaunay", c_double),
        ("seconds_grow", c_double),
        ("seconds_fill_holes", c_double),
        ("seconds_output", c_double),
        ("seconds_total", c_double),
        ("peak_bytes", c_size_t),
        ("handles_removed", c_uint32),
        ("outliers", c_uint32),
        ("near_duplicates_merged", c_uint32),
        ("points_smoothed", c_uint32),
        ("smoothing_iterations", c_uint32),
        ("noise_level", c_double),
        ("seconds_clean", c_double),
        ("tiles", c_uint32),
        ("seam_faces_dropped", c_uint32),
        ("tile_peak_bytes", c_size_t),
        ("points_inserted", c_uint32),
    ]


class dbrg_tiling(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_size_t),
        ("axis", c_uint32),
        ("wall_count", c_uint32),
        ("spacing", c_double),
        ("halo", c_double),
        ("seam_reach", c_double),
    ]


# Opaque handles.
class dbrg_mesh(ctypes.Structure):
    pass


class dbrg_tile_mesh(ctypes.Structure):
    pass


class dbrg_tetrahedralization(ctypes.Structure):
    pass


mesh_p = POINTER(dbrg_mesh)
tile_mesh_p = POINTER(dbrg_tile_mesh)
tets_p = POINTER(dbrg_tetrahedralization)
u32_p = POINTER(c_uint32)
u64_p = POINTER(c_uint64)
f64_p = POINTER(c_double)

# name: (result type, argument types), in the header's order. Strings come back as bytes.
FUNCTIONS = {
    "dbrg_version_number": (c_uint32, []),
    "dbrg_version_string": (c_char_p, []),
    "dbrg_status_string": (c_char_p, [c_enum]),
    "dbrg_params_init_sized": (c_enum, [POINTER(dbrg_params), c_size_t]),
    "dbrg_params_validate": (c_enum, [POINTER(dbrg_params), c_char_p, c_size_t]),
    "dbrg_points_validate": (c_enum, [POINTER(dbrg_points), POINTER(dbrg_allocator), c_char_p, c_size_t]),
    "dbrg_reconstruct": (c_enum, [POINTER(dbrg_points), POINTER(dbrg_params), POINTER(mesh_p)]),
    "dbrg_mesh_destroy": (None, [mesh_p]),
    "dbrg_mesh_status": (c_enum, [mesh_p]),
    "dbrg_mesh_message": (c_char_p, [mesh_p]),
    "dbrg_mesh_point_count": (c_uint32, [mesh_p]),
    "dbrg_mesh_triangle_count": (c_uint32, [mesh_p]),
    "dbrg_mesh_triangles": (u32_p, [mesh_p]),
    "dbrg_mesh_boundary_loop_count": (c_uint32, [mesh_p]),
    "dbrg_mesh_boundary_loop": (u32_p, [mesh_p, c_uint32, u32_p]),
    "dbrg_mesh_outliers": (u32_p, [mesh_p, u32_p]),
    "dbrg_mesh_face_flags": (POINTER(ctypes.c_uint8), [mesh_p]),
    "dbrg_mesh_smoothed_points": (POINTER(c_double), [mesh_p]),
    "dbrg_mesh_stats": (c_enum, [mesh_p, POINTER(dbrg_stats)]),
    "dbrg_reconstruct_tiled": (c_enum, [POINTER(dbrg_points), c_uint32, POINTER(dbrg_params), POINTER(mesh_p)]),
    "dbrg_reconstruct_tile": (c_enum, [POINTER(dbrg_points), u64_p, f64_p, f64_p, POINTER(dbrg_params),
                                       POINTER(tile_mesh_p)]),
    "dbrg_grow_from_surface": (c_enum, [POINTER(dbrg_points), u64_p, u64_p, c_size_t, POINTER(ctypes.c_uint8),
                                        POINTER(dbrg_params), POINTER(tile_mesh_p)]),
    "dbrg_tiling_plan": (c_enum, [POINTER(dbrg_points), c_uint32, POINTER(dbrg_params), POINTER(dbrg_tiling), f64_p,
                                  c_char_p, c_size_t]),
    "dbrg_seam_stitch": (c_enum, [POINTER(dbrg_points), u64_p, u64_p, c_size_t, POINTER(dbrg_tiling), c_double,
                                  POINTER(dbrg_params), POINTER(tile_mesh_p)]),
    "dbrg_mesh_assemble": (c_enum, [POINTER(dbrg_points), u32_p, c_size_t, u32_p, c_size_t, POINTER(dbrg_params),
                                    POINTER(mesh_p)]),
    "dbrg_tile_mesh_destroy": (None, [tile_mesh_p]),
    "dbrg_tile_mesh_status": (c_enum, [tile_mesh_p]),
    "dbrg_tile_mesh_message": (c_char_p, [tile_mesh_p]),
    "dbrg_tile_mesh_triangle_count": (c_uint64, [tile_mesh_p]),
    "dbrg_tile_mesh_triangles": (u64_p, [tile_mesh_p]),
    "dbrg_tile_mesh_dropped": (u64_p, [tile_mesh_p, u64_p]),
    "dbrg_tile_mesh_outliers": (u64_p, [tile_mesh_p, u64_p]),
    "dbrg_tile_mesh_stats": (c_enum, [tile_mesh_p, POINTER(dbrg_stats)]),
    "dbrg_stats_add_piece": (c_enum, [POINTER(dbrg_stats), POINTER(dbrg_stats)]),
    "dbrg_tetrahedralize": (c_enum, [POINTER(dbrg_points), POINTER(dbrg_params), POINTER(tets_p)]),
    "dbrg_tetrahedralization_destroy": (None, [tets_p]),
    "dbrg_tetrahedralization_status": (c_enum, [tets_p]),
    "dbrg_tetrahedralization_message": (c_char_p, [tets_p]),
    "dbrg_tetrahedralization_tet_count": (c_uint32, [tets_p]),
    "dbrg_tetrahedralization_tets": (u32_p, [tets_p]),
    "dbrg_tetrahedralization_adjacency": (u32_p, [tets_p]),
    "dbrg_tetrahedralization_unique_point_count": (c_uint32, [tets_p]),
}


def declare(library):
    """Sets restype/argtypes of every function on a loaded ctypes.CDLL; raises AttributeError naming
    the first function the library lacks."""
    for name, (restype, argtypes) in FUNCTIONS.items():
        function = getattr(library, name)
        function.restype = restype
        function.argtypes = argtypes
    return library
