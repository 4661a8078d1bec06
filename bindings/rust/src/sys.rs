//! Raw declarations of `include/dbrg/dbrg.h`, one for one, under the header's names.
//!
//! C enums are plain integer types with one constant per value (not Rust enums), so that a value a
//! newer library adds can never be undefined behaviour here. `bindings/check_agreement.py` compares
//! this file with the header.
#![allow(non_camel_case_types)]

use std::os::raw::{c_char, c_int, c_uint, c_void};

pub const DBRG_VERSION_MAJOR: u32 = 0;
pub const DBRG_VERSION_MINOR: u32 = 5;
pub const DBRG_VERSION_PATCH: u32 = 0;
pub const DBRG_VERSION_NUMBER: u32 = DBRG_VERSION_MAJOR * 10000 + DBRG_VERSION_MINOR * 100 + DBRG_VERSION_PATCH;
pub const DBRG_VERSION_STRING: &str = "0.5.0";

pub const DBRG_MAX_POINTS: usize = 0x7fff_ffff;
pub const DBRG_NO_NEIGHBOR: u32 = u32::MAX;
pub const DBRG_MAX_SNAPSHOTS: u32 = 1000;

pub type dbrg_status = c_uint;
pub const DBRG_OK: dbrg_status = 0;
pub const DBRG_ERR_INVALID_ARGUMENT: dbrg_status = 1;
pub const DBRG_ERR_INVALID_PARAMETER: dbrg_status = 2;
pub const DBRG_ERR_NON_FINITE_INPUT: dbrg_status = 3;
pub const DBRG_ERR_TOO_FEW_POINTS: dbrg_status = 4;
pub const DBRG_ERR_DEGENERATE_INPUT: dbrg_status = 5;
pub const DBRG_ERR_TOO_MANY_POINTS: dbrg_status = 6;
pub const DBRG_ERR_OUT_OF_MEMORY: dbrg_status = 7;
pub const DBRG_ERR_CANCELLED: dbrg_status = 8;
pub const DBRG_ERR_UNSUPPORTED: dbrg_status = 9;
pub const DBRG_ERR_INTERNAL: dbrg_status = 10;

pub type dbrg_stage = c_uint;
pub const DBRG_STAGE_VALIDATE: dbrg_stage = 0;
pub const DBRG_STAGE_SORT: dbrg_stage = 1;
pub const DBRG_STAGE_DELAUNAY: dbrg_stage = 2;
pub const DBRG_STAGE_GROW: dbrg_stage = 3;
pub const DBRG_STAGE_FILL_HOLES: dbrg_stage = 4;
pub const DBRG_STAGE_OUTPUT: dbrg_stage = 5;
pub const DBRG_STAGE_CLEAN: dbrg_stage = 6;

pub type dbrg_scalar_type = c_uint;
pub const DBRG_FLOAT32: dbrg_scalar_type = 0;
pub const DBRG_FLOAT64: dbrg_scalar_type = 1;

pub type dbrg_cleaning = c_uint;
pub const DBRG_CLEANING_AUTO: dbrg_cleaning = 0;
pub const DBRG_CLEANING_OFF: dbrg_cleaning = 1;
pub const DBRG_CLEANING_ON: dbrg_cleaning = 2;

pub type dbrg_face_flag = c_uint;
pub const DBRG_FACE_FILLED: dbrg_face_flag = 1;

pub type dbrg_backend = c_uint;
pub const DBRG_BACKEND_BUILTIN: dbrg_backend = 0;
pub const DBRG_BACKEND_TETGEN: dbrg_backend = 1;

pub type dbrg_boundary_mean = c_uint;
pub const DBRG_BOUNDARY_MEAN_LOCAL: dbrg_boundary_mean = 0;
pub const DBRG_BOUNDARY_MEAN_GLOBAL: dbrg_boundary_mean = 1;

#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct dbrg_allocator {
    pub allocate: Option<unsafe extern "C" fn(user: *mut c_void, size: usize) -> *mut c_void>,
    pub reallocate: Option<
        unsafe extern "C" fn(user: *mut c_void, block: *mut c_void, old_size: usize, new_size: usize) -> *mut c_void,
    >,
    pub deallocate: Option<unsafe extern "C" fn(user: *mut c_void, block: *mut c_void, size: usize)>,
    pub user: *mut c_void,
}

pub type dbrg_progress_fn = Option<unsafe extern "C" fn(user: *mut c_void, stage: dbrg_stage, fraction: f64) -> c_int>;
pub type dbrg_snapshot_fn = Option<
    unsafe extern "C" fn(user: *mut c_void, triangles: *const u32, triangle_count: u32, points_reached: f64) -> c_int,
>;

#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct dbrg_points {
    pub data: *const c_void,
    pub count: usize,
    pub stride_bytes: usize,
    pub r#type: dbrg_scalar_type,
}

#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct dbrg_params {
    pub struct_size: usize,
    pub sliver_angle: f64,
    pub boundary_factor: f64,
    pub boundary_mean: dbrg_boundary_mean,
    pub fill_holes: u32,
    pub max_hole_edges: u32,
    pub max_components: u32,
    pub backend: dbrg_backend,
    pub threads: u32,
    pub allocator: *const dbrg_allocator,
    pub progress: dbrg_progress_fn,
    pub progress_user: *mut c_void,
    pub snapshot: dbrg_snapshot_fn,
    pub snapshot_user: *mut c_void,
    pub snapshot_count: u32,
    pub reserved: u32,
    pub cleaning: dbrg_cleaning,
    pub output_smoothed: u32,
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct dbrg_stats {
    pub struct_size: usize,
    pub input_points: u32,
    pub unique_points: u32,
    pub duplicates_merged: u32,
    pub tetrahedra: u32,
    pub triangles: u32,
    pub vertices_used: u32,
    pub boundary_edges: u32,
    pub boundary_loops: u32,
    pub components: u32,
    pub pinch_faces_removed: u32,
    pub candidates_evaluated: u64,
    pub rejected_edge_nonmanifold: u64,
    pub rejected_orientation: u64,
    pub rejected_bowtie: u64,
    pub rejected_dihedral: u64,
    pub rejected_boundary: u64,
    pub holes_found: u32,
    pub holes_filled: u32,
    pub holes_left_open: u32,
    pub hole_triangles_delaunay: u32,
    pub hole_triangles_added: u32,
    pub hole_triangles_removed: u32,
    pub predicate_calls: u64,
    pub predicate_filter_failures: u64,
    pub predicate_perturbations: u64,
    pub seconds_validate: f64,
    pub seconds_sort: f64,
    pub seconds_delaunay: f64,
    pub seconds_grow: f64,
    pub seconds_fill_holes: f64,
    pub seconds_output: f64,
    pub seconds_total: f64,
    pub peak_bytes: usize,
    pub handles_removed: u32,
    pub outliers: u32,
    pub near_duplicates_merged: u32,
    pub points_smoothed: u32,
    pub smoothing_iterations: u32,
    pub noise_level: f64,
    pub seconds_clean: f64,
    pub tiles: u32,
    pub seam_faces_dropped: u32,
    pub tile_peak_bytes: usize,
    pub points_inserted: u32,
}

/// How a cloud is cut into slabs (`dbrg_tiling_plan`). EXPERIMENTAL.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct dbrg_tiling {
    pub struct_size: usize,
    pub axis: u32,
    pub wall_count: u32,
    pub spacing: f64,
    pub halo: f64,
    pub seam_reach: f64,
}

/// Opaque result of `dbrg_reconstruct`.
#[repr(C)]
pub struct dbrg_mesh {
    _private: [u8; 0],
}

/// Opaque result of `dbrg_reconstruct_tile`, `dbrg_grow_from_surface` and `dbrg_seam_stitch`.
#[repr(C)]
pub struct dbrg_tile_mesh {
    _private: [u8; 0],
}

/// Opaque result of `dbrg_tetrahedralize`.
#[repr(C)]
pub struct dbrg_tetrahedralization {
    _private: [u8; 0],
}

extern "C" {
    pub fn dbrg_version_number() -> u32;
    pub fn dbrg_version_string() -> *const c_char;
    pub fn dbrg_status_string(status: dbrg_status) -> *const c_char;

    pub fn dbrg_params_init_sized(params: *mut dbrg_params, struct_size: usize) -> dbrg_status;
    pub fn dbrg_params_validate(params: *const dbrg_params, message: *mut c_char, message_capacity: usize) -> dbrg_status;
    pub fn dbrg_points_validate(
        points: *const dbrg_points,
        allocator: *const dbrg_allocator,
        message: *mut c_char,
        message_capacity: usize,
    ) -> dbrg_status;

    pub fn dbrg_reconstruct(points: *const dbrg_points, params: *const dbrg_params, out_mesh: *mut *mut dbrg_mesh) -> dbrg_status;
    pub fn dbrg_mesh_destroy(mesh: *mut dbrg_mesh);
    pub fn dbrg_mesh_status(mesh: *const dbrg_mesh) -> dbrg_status;
    pub fn dbrg_mesh_message(mesh: *const dbrg_mesh) -> *const c_char;
    pub fn dbrg_mesh_point_count(mesh: *const dbrg_mesh) -> u32;
    pub fn dbrg_mesh_triangle_count(mesh: *const dbrg_mesh) -> u32;
    pub fn dbrg_mesh_triangles(mesh: *const dbrg_mesh) -> *const u32;
    pub fn dbrg_mesh_boundary_loop_count(mesh: *const dbrg_mesh) -> u32;
    pub fn dbrg_mesh_boundary_loop(mesh: *const dbrg_mesh, loop_: u32, out_count: *mut u32) -> *const u32;
    pub fn dbrg_mesh_outliers(mesh: *const dbrg_mesh, out_count: *mut u32) -> *const u32;
    pub fn dbrg_mesh_face_flags(mesh: *const dbrg_mesh) -> *const u8;
    pub fn dbrg_mesh_smoothed_points(mesh: *const dbrg_mesh) -> *const f64;
    pub fn dbrg_mesh_stats(mesh: *const dbrg_mesh, stats: *mut dbrg_stats) -> dbrg_status;

    pub fn dbrg_reconstruct_tiled(
        points: *const dbrg_points,
        tile_count: u32,
        params: *const dbrg_params,
        out_mesh: *mut *mut dbrg_mesh,
    ) -> dbrg_status;
    pub fn dbrg_reconstruct_tile(
        points: *const dbrg_points,
        point_ids: *const u64,
        core_low: *const f64,
        core_high: *const f64,
        params: *const dbrg_params,
        out: *mut *mut dbrg_tile_mesh,
    ) -> dbrg_status;
    pub fn dbrg_grow_from_surface(
        points: *const dbrg_points,
        point_ids: *const u64,
        seed_triangles: *const u64,
        seed_count: usize,
        fixed: *const u8,
        params: *const dbrg_params,
        out: *mut *mut dbrg_tile_mesh,
    ) -> dbrg_status;
    pub fn dbrg_tiling_plan(
        points: *const dbrg_points,
        tile_count: u32,
        params: *const dbrg_params,
        tiling: *mut dbrg_tiling,
        walls: *mut f64,
        message: *mut c_char,
        message_capacity: usize,
    ) -> dbrg_status;
    pub fn dbrg_seam_stitch(
        points: *const dbrg_points,
        point_ids: *const u64,
        faces: *const u64,
        face_count: usize,
        tiling: *const dbrg_tiling,
        wall: f64,
        params: *const dbrg_params,
        out: *mut *mut dbrg_tile_mesh,
    ) -> dbrg_status;
    pub fn dbrg_mesh_assemble(
        points: *const dbrg_points,
        triangles: *const u32,
        triangle_count: usize,
        outliers: *const u32,
        outlier_count: usize,
        params: *const dbrg_params,
        out_mesh: *mut *mut dbrg_mesh,
    ) -> dbrg_status;
    pub fn dbrg_tile_mesh_destroy(mesh: *mut dbrg_tile_mesh);
    pub fn dbrg_tile_mesh_status(mesh: *const dbrg_tile_mesh) -> dbrg_status;
    pub fn dbrg_tile_mesh_message(mesh: *const dbrg_tile_mesh) -> *const c_char;
    pub fn dbrg_tile_mesh_triangle_count(mesh: *const dbrg_tile_mesh) -> u64;
    pub fn dbrg_tile_mesh_triangles(mesh: *const dbrg_tile_mesh) -> *const u64;
    pub fn dbrg_tile_mesh_dropped(mesh: *const dbrg_tile_mesh, out_count: *mut u64) -> *const u64;
    pub fn dbrg_tile_mesh_outliers(mesh: *const dbrg_tile_mesh, out_count: *mut u64) -> *const u64;
    pub fn dbrg_tile_mesh_stats(mesh: *const dbrg_tile_mesh, stats: *mut dbrg_stats) -> dbrg_status;
    pub fn dbrg_stats_add_piece(total: *mut dbrg_stats, piece: *const dbrg_stats) -> dbrg_status;

    pub fn dbrg_tetrahedralize(
        points: *const dbrg_points,
        params: *const dbrg_params,
        out: *mut *mut dbrg_tetrahedralization,
    ) -> dbrg_status;
    pub fn dbrg_tetrahedralization_destroy(tets: *mut dbrg_tetrahedralization);
    pub fn dbrg_tetrahedralization_status(tets: *const dbrg_tetrahedralization) -> dbrg_status;
    pub fn dbrg_tetrahedralization_message(tets: *const dbrg_tetrahedralization) -> *const c_char;
    pub fn dbrg_tetrahedralization_tet_count(tets: *const dbrg_tetrahedralization) -> u32;
    pub fn dbrg_tetrahedralization_tets(tets: *const dbrg_tetrahedralization) -> *const u32;
    pub fn dbrg_tetrahedralization_adjacency(tets: *const dbrg_tetrahedralization) -> *const u32;
    pub fn dbrg_tetrahedralization_unique_point_count(tets: *const dbrg_tetrahedralization) -> u32;
}
