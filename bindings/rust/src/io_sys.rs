//! Raw declarations of `include/dbrg/dbrg_io.h` (the I/O library's C interface, in `libdbrg_io`), one
//! for one, under the header's names. Enums are integer types with one constant per value, as in
//! [`crate::sys`]; `bindings/check_agreement.py` compares this file with the header.
#![allow(non_camel_case_types)]

use std::os::raw::{c_char, c_uint, c_void};

pub type dbrg_io_status = c_uint;
pub const DBRG_IO_OK: dbrg_io_status = 0;
pub const DBRG_IO_ERR_INVALID_ARGUMENT: dbrg_io_status = 1;
pub const DBRG_IO_ERR_FILE: dbrg_io_status = 2;
pub const DBRG_IO_ERR_OUT_OF_MEMORY: dbrg_io_status = 3;

pub type dbrg_io_value_type = c_uint;
pub const DBRG_IO_INT8: dbrg_io_value_type = 0;
pub const DBRG_IO_UINT8: dbrg_io_value_type = 1;
pub const DBRG_IO_INT16: dbrg_io_value_type = 2;
pub const DBRG_IO_UINT16: dbrg_io_value_type = 3;
pub const DBRG_IO_INT32: dbrg_io_value_type = 4;
pub const DBRG_IO_UINT32: dbrg_io_value_type = 5;
pub const DBRG_IO_FLOAT32: dbrg_io_value_type = 6;
pub const DBRG_IO_FLOAT64: dbrg_io_value_type = 7;

/// Opaque result of `dbrg_io_read_points`.
#[repr(C)]
pub struct dbrg_io_points {
    _private: [u8; 0],
}

extern "C" {
    pub fn dbrg_io_read_points(
        path: *const c_char,
        out_points: *mut *mut dbrg_io_points,
        message: *mut c_char,
        message_capacity: usize,
    ) -> dbrg_io_status;
    pub fn dbrg_io_points_destroy(points: *mut dbrg_io_points);
    pub fn dbrg_io_points_count(points: *const dbrg_io_points) -> u32;
    pub fn dbrg_io_points_positions(points: *const dbrg_io_points) -> *const f64;
    pub fn dbrg_io_points_normals(points: *const dbrg_io_points) -> *const f32;
    pub fn dbrg_io_points_attribute_count(points: *const dbrg_io_points) -> u32;
    pub fn dbrg_io_points_attribute_name(points: *const dbrg_io_points, index: u32) -> *const c_char;
    pub fn dbrg_io_points_attribute_type(points: *const dbrg_io_points, index: u32) -> dbrg_io_value_type;
    pub fn dbrg_io_points_attribute_values(points: *const dbrg_io_points, index: u32) -> *const c_void;

    pub fn dbrg_io_vertex_normals(
        positions: *const f64,
        vertex_count: u32,
        triangles: *const u32,
        triangle_count: u32,
        out_normals: *mut f32,
    ) -> dbrg_io_status;
    pub fn dbrg_io_write_mesh(
        path: *const c_char,
        positions: *const f64,
        vertex_count: u32,
        triangles: *const u32,
        triangle_count: u32,
        normals: *const f32,
        message: *mut c_char,
        message_capacity: usize,
    ) -> dbrg_io_status;
}
