//! The project's own readers, mesh writers and vertex normals, through the I/O library's C interface
//! (`dbrg_io.h`, linked from `libdbrg_io`): files are read and written exactly as the `dbrg` program
//! reads and writes them.

use std::ffi::CString;
use std::os::raw::{c_char, c_void};
use std::path::Path;
use std::ptr;

use crate::{io_sys, owned_string, Error, Mesh, Points, Status};

/// The values of one per-point attribute, one per point, in the type the file stores them in.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum AttributeValues {
    I8(Vec<i8>),
    U8(Vec<u8>),
    I16(Vec<i16>),
    U16(Vec<u16>),
    I32(Vec<i32>),
    U32(Vec<u32>),
    F32(Vec<f32>),
    F64(Vec<f64>),
}

impl AttributeValues {
    /// The number of values (the number of points).
    pub fn len(&self) -> usize {
        match self {
            AttributeValues::I8(v) => v.len(),
            AttributeValues::U8(v) => v.len(),
            AttributeValues::I16(v) => v.len(),
            AttributeValues::U16(v) => v.len(),
            AttributeValues::I32(v) => v.len(),
            AttributeValues::U32(v) => v.len(),
            AttributeValues::F32(v) => v.len(),
            AttributeValues::F64(v) => v.len(),
        }
    }

    /// Whether there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Value `index` as an `f64`, which holds every value of every type exactly; `None` past the end.
    pub fn get(&self, index: usize) -> Option<f64> {
        match self {
            AttributeValues::I8(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::U8(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::I16(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::U16(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::I32(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::U32(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::F32(v) => v.get(index).map(|&x| f64::from(x)),
            AttributeValues::F64(v) => v.get(index).copied(),
        }
    }
}

/// A named per-point attribute read with the points: a colour channel, an intensity, a confidence...
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    pub name: String,
    pub values: AttributeValues,
}

/// Reads the points (the vertices) of a `.ply .obj .off .stl .xyz .pts .las` file, chosen by its
/// extension, with the dbrg program's readers; faces are not read.
///
/// Returns the positions and the per-point attributes in the file's order and types: a PLY's other
/// vertex properties (`red` as [`AttributeValues::U8`], `intensity`, `confidence`, ...), then its
/// normals as `nx`, `ny`, `nz` ([`AttributeValues::F32`]); a LAS file's `intensity` and, in the formats
/// with colour, `red`, `green`, `blue` ([`AttributeValues::U16`]).
///
/// Fails with [`Status::InvalidArgument`] for an unknown extension or a `.laz` file (decompress it
/// first), [`Status::File`] for a file that cannot be read or is malformed (the message says where),
/// [`Status::OutOfMemory`].
pub fn read_points(path: impl AsRef<Path>) -> Result<(Vec<[f64; 3]>, Vec<Attribute>), Error> {
    let path = c_path(path.as_ref())?;
    let mut message = [0 as c_char; 1024];
    let mut raw: *mut io_sys::dbrg_io_points = ptr::null_mut();
    let status = unsafe { io_sys::dbrg_io_read_points(path.as_ptr(), &mut raw, message.as_mut_ptr(), message.len()) };
    if status != io_sys::DBRG_IO_OK {
        return Err(io_error(status, &message));
    }
    let points = ReadPoints { raw };
    let count = unsafe { io_sys::dbrg_io_points_count(points.raw) } as usize;
    // SAFETY (every copy below): the accessors' pointers hold `count` values of their type and live as
    // long as `points`.
    let positions =
        unsafe { copy_values::<[f64; 3]>(io_sys::dbrg_io_points_positions(points.raw) as *const c_void, count) };
    let mut attributes = Vec::new();
    for index in 0..unsafe { io_sys::dbrg_io_points_attribute_count(points.raw) } {
        let (name, kind, values) = unsafe {
            (
                owned_string(io_sys::dbrg_io_points_attribute_name(points.raw, index)),
                io_sys::dbrg_io_points_attribute_type(points.raw, index),
                io_sys::dbrg_io_points_attribute_values(points.raw, index),
            )
        };
        let values = unsafe {
            match kind {
                io_sys::DBRG_IO_INT8 => AttributeValues::I8(copy_values(values, count)),
                io_sys::DBRG_IO_UINT8 => AttributeValues::U8(copy_values(values, count)),
                io_sys::DBRG_IO_INT16 => AttributeValues::I16(copy_values(values, count)),
                io_sys::DBRG_IO_UINT16 => AttributeValues::U16(copy_values(values, count)),
                io_sys::DBRG_IO_INT32 => AttributeValues::I32(copy_values(values, count)),
                io_sys::DBRG_IO_UINT32 => AttributeValues::U32(copy_values(values, count)),
                io_sys::DBRG_IO_FLOAT32 => AttributeValues::F32(copy_values(values, count)),
                io_sys::DBRG_IO_FLOAT64 => AttributeValues::F64(copy_values(values, count)),
                other => {
                    return Err(Error::new(
                        Status::Other(other),
                        format!("attribute {} has a value type ({}) this binding does not know", name, other),
                    ))
                }
            }
        };
        attributes.push(Attribute { name, values });
    }
    let normals = unsafe { io_sys::dbrg_io_points_normals(points.raw) };
    if !normals.is_null() {
        let normals = unsafe { copy_values::<[f32; 3]>(normals as *const c_void, count) };
        for (axis, name) in ["nx", "ny", "nz"].iter().enumerate() {
            let values = AttributeValues::F32(normals.iter().map(|n| n[axis]).collect());
            attributes.push(Attribute { name: name.to_string(), values });
        }
    }
    Ok((positions, attributes))
}

/// Frees what `dbrg_io_read_points` gave on every path out of [`read_points`].
struct ReadPoints {
    raw: *mut io_sys::dbrg_io_points,
}

impl Drop for ReadPoints {
    fn drop(&mut self) {
        unsafe { io_sys::dbrg_io_points_destroy(self.raw) }
    }
}

/// Copies `count` values of type `T` from `data` (the library gives NULL only when there are no points).
///
/// # Safety
/// `data` is NULL or points to `count` readable values of `T`, aligned or not.
unsafe fn copy_values<T: Copy>(data: *const c_void, count: usize) -> Vec<T> {
    if data.is_null() {
        debug_assert_eq!(count, 0, "the library gave no values for {} points", count);
        return Vec::new();
    }
    let data = data as *const T;
    (0..count).map(|i| ptr::read_unaligned(data.add(i))).collect()
}

/// Unit vertex normals of a triangle mesh: for each vertex, its triangles' normals weighted by their
/// angle at the vertex, summed and normalized; `[0.0; 3]` for a vertex no triangle uses. Outward on a
/// closed surface whose triangles are counter-clockwise seen from outside, as [`crate::reconstruct`]
/// gives them.
///
/// Fails with [`Status::InvalidArgument`] when a triangle indexes past `vertices` or there are more
/// than `u32::MAX` vertices or triangles.
pub fn vertex_normals(vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<Vec<[f32; 3]>, Error> {
    let (vertex_count, triangle_count) =
        (count_u32(vertices.len(), "vertices")?, count_u32(triangles.len(), "triangles")?);
    let mut normals = vec![[0f32; 3]; vertices.len()];
    let status = unsafe {
        io_sys::dbrg_io_vertex_normals(
            vertices.as_ptr() as *const f64,
            vertex_count,
            triangles.as_ptr() as *const u32,
            triangle_count,
            normals.as_mut_ptr() as *mut f32,
        )
    };
    if status != io_sys::DBRG_IO_OK {
        // The function gives no message: say what it refused.
        let message = match first_index_past(vertices.len(), triangles) {
            Some(triangle) => format!("triangle {} refers to a vertex past the {} vertices", triangle, vertices.len()),
            None => String::from("out of memory computing vertex normals"),
        };
        return Err(Error::new(io_status(status), message));
    }
    Ok(normals)
}

/// Writes a triangle mesh to `path` in the format its extension names (`.ply` binary, `.obj`, `.off`,
/// `.stl`, `.xyz`) with the dbrg program's writers; the file is replaced only once completely written.
/// `normals`, one per vertex, go to `.ply` (`nx ny nz`) and `.obj` (`vn`); other formats have no place
/// for them. No triangles writes the points alone (with an empty face list where the format has one).
///
/// Fails with [`Status::InvalidArgument`] for an unknown extension, normals that are not one per
/// vertex, or a triangle indexing past `vertices`; [`Status::File`] when the file cannot be written
/// (the message gives the system's reason); [`Status::OutOfMemory`].
pub fn write_mesh(
    path: impl AsRef<Path>,
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    normals: Option<&[[f32; 3]]>,
) -> Result<(), Error> {
    let path = c_path(path.as_ref())?;
    let (vertex_count, triangle_count) =
        (count_u32(vertices.len(), "vertices")?, count_u32(triangles.len(), "triangles")?);
    if let Some(normals) = normals {
        if normals.len() != vertices.len() {
            return Err(Error::new(
                Status::InvalidArgument,
                format!("{} normals for {} vertices: give one per vertex", normals.len(), vertices.len()),
            ));
        }
    }
    let mut message = [0 as c_char; 1024];
    let status = unsafe {
        io_sys::dbrg_io_write_mesh(
            path.as_ptr(),
            vertices.as_ptr() as *const f64,
            vertex_count,
            triangles.as_ptr() as *const u32,
            triangle_count,
            normals.map_or(ptr::null(), |n| n.as_ptr() as *const f32),
            message.as_mut_ptr(),
            message.len(),
        )
    };
    if status != io_sys::DBRG_IO_OK {
        return Err(io_error(status, &message));
    }
    Ok(())
}

impl Mesh {
    /// The mesh's vertices: `points` (the points given to [`crate::reconstruct`]) as `f64`, or the
    /// smoothed positions when [`crate::Params::output_smoothed`] kept them. [`Status::InvalidArgument`]
    /// when `points` is not as long as [`Mesh::point_count`].
    pub fn vertices<'a>(&self, points: impl Into<Points<'a>>) -> Result<Vec<[f64; 3]>, Error> {
        if let Some(smoothed) = self.smoothed_points() {
            return Ok(smoothed.to_vec());
        }
        let points = points.into();
        if points.len() != self.point_count() as usize {
            return Err(Error::new(
                Status::InvalidArgument,
                format!(
                    "{} points given for a mesh over {}: pass the points it was reconstructed from",
                    points.len(),
                    self.point_count()
                ),
            ));
        }
        Ok(points.to_f64())
    }

    /// Unit vertex normals over `points` (see [`Mesh::vertices`]), one per point, angle-weighted as by
    /// [`vertex_normals`]: outward on closed surfaces, `[0.0; 3]` for a point no triangle uses.
    pub fn vertex_normals<'a>(&self, points: impl Into<Points<'a>>) -> Result<Vec<[f32; 3]>, Error> {
        vertex_normals(&self.vertices(points)?, self.triangles())
    }

    /// Writes the mesh over `points` (see [`Mesh::vertices`]) to `path` as [`write_mesh`] does, with its
    /// vertex normals when `normals` is true. Points no triangle uses are written as lone vertices.
    pub fn write<'a>(&self, path: impl AsRef<Path>, points: impl Into<Points<'a>>, normals: bool) -> Result<(), Error> {
        let vertices = self.vertices(points)?;
        let vertex_normals = if normals { Some(vertex_normals(&vertices, self.triangles())?) } else { None };
        write_mesh(path, &vertices, self.triangles(), vertex_normals.as_deref())
    }
}

fn io_status(status: io_sys::dbrg_io_status) -> Status {
    match status {
        io_sys::DBRG_IO_ERR_INVALID_ARGUMENT => Status::InvalidArgument,
        io_sys::DBRG_IO_ERR_FILE => Status::File,
        io_sys::DBRG_IO_ERR_OUT_OF_MEMORY => Status::OutOfMemory,
        other => Status::Other(other),
    }
}

fn io_error(status: io_sys::dbrg_io_status, message: &[c_char]) -> Error {
    // SAFETY: the library NUL-terminates the message within the buffer it was given.
    Error::new(io_status(status), unsafe { owned_string(message.as_ptr()) })
}

fn c_path(path: &Path) -> Result<CString, Error> {
    #[cfg(unix)]
    let bytes = {
        use std::os::unix::ffi::OsStrExt;
        path.as_os_str().as_bytes().to_vec()
    };
    #[cfg(not(unix))]
    let bytes = match path.to_str() {
        Some(text) => text.as_bytes().to_vec(),
        None => return Err(Error::new(Status::InvalidArgument, format!("{}: not valid Unicode", path.display()))),
    };
    CString::new(bytes)
        .map_err(|_| Error::new(Status::InvalidArgument, format!("{}: a file name with a NUL byte", path.display())))
}

fn count_u32(count: usize, what: &str) -> Result<u32, Error> {
    u32::try_from(count).map_err(|_| {
        Error::new(Status::InvalidArgument, format!("{} {}: more than the I/O library takes", count, what))
    })
}

fn first_index_past(vertex_count: usize, triangles: &[[u32; 3]]) -> Option<usize> {
    triangles.iter().position(|t| t.iter().any(|&v| v as usize >= vertex_count))
}
