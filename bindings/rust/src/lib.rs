//! Surface reconstruction from unorganized 3D points by Delaunay-based region growing (Kuo & Yau
//! 2005): a safe binding over the `dbrg` C library.
//!
//! ```
//! let points: Vec<[f64; 3]> = (0..500).map(|i| {
//!     let (z, a) = (1.0 - (2 * i + 1) as f64 / 500.0, i as f64 * 2.399963229728653);
//!     let r = (1.0 - z * z).sqrt();
//!     [r * a.cos(), r * a.sin(), z]
//! }).collect();
//! let mesh = dbrg::reconstruct(&points, &dbrg::Params::default())?;
//! assert_eq!(mesh.triangles().len(), 2 * 500 - 4); // a closed sphere
//! assert_eq!(mesh.boundary_loops().count(), 0);
//! # Ok::<(), dbrg::Error>(())
//! ```
//!
//! The libraries are linked at build time: set `DBRG_LIB_DIR` to the directory holding `libdbrg.so`
//! (for example `build/src`), or install dbrg so that `pkg-config --libs dbrg dbrg_io` finds them.
//!
//! [`sys`] and [`io_sys`] hold the raw declarations of `dbrg.h` and `dbrg_io.h`; everything else is
//! the safe interface: [`Params`], [`reconstruct`] and [`reconstruct_with_progress`], the owning
//! [`Mesh`], [`Error`] with the status and the library's message, the EXPERIMENTAL [`tetrahedralize`],
//! and the dbrg program's own readers and writers: [`read_points`], [`write_mesh`] and
//! [`Mesh::write`], [`vertex_normals`] and [`Mesh::vertex_normals`].

use std::any::Any;
use std::ffi::CStr;
use std::fmt;
use std::marker::PhantomData;
use std::os::raw::{c_char, c_int, c_void};
use std::panic::{self, AssertUnwindSafe};
use std::ptr::{self, NonNull};
use std::slice;

pub mod io_sys;
pub mod sys;

mod io;
pub use io::{read_points, vertex_normals, write_mesh, Attribute, AttributeValues};

/// Statistics of one reconstruction, exactly the C `dbrg_stats` (counts, rejections by rule,
/// seconds per stage, peak memory).
pub type Stats = sys::dbrg_stats;

/// Bit of [`Mesh::face_flags`]: the triangle was made by hole filling, not grown from the points.
pub const FACE_FILLED: u8 = sys::DBRG_FACE_FILLED as u8;

// ------------------------------------------------------------------------------------------------
// Status and errors
// ------------------------------------------------------------------------------------------------

/// Why a call failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Status {
    /// An invalid argument (for example a stride shorter than a point).
    InvalidArgument,
    /// A parameter is out of range; the message names it.
    InvalidParameter,
    /// A coordinate is NaN or infinite; the message names the point.
    NonFiniteInput,
    /// Fewer than 4 distinct points.
    TooFewPoints,
    /// All points are collinear (or, for tetrahedralize, coplanar).
    DegenerateInput,
    /// More than `DBRG_MAX_POINTS` points.
    TooManyPoints,
    /// An allocation failed.
    OutOfMemory,
    /// The progress callback asked to stop.
    Cancelled,
    /// The feature (for example the TetGen backend) is not part of this build of the library.
    Unsupported,
    /// A bug in dbrg: please report it with the input.
    Internal,
    /// A file could not be read or written, or is not valid in its format; only the I/O functions
    /// ([`read_points`], [`write_mesh`], [`Mesh::write`]) give it (`DBRG_IO_ERR_FILE`).
    File,
    /// A status this binding does not know (from a newer library).
    Other(u32),
}

impl Status {
    fn from_raw(status: sys::dbrg_status) -> Status {
        match status {
            sys::DBRG_ERR_INVALID_ARGUMENT => Status::InvalidArgument,
            sys::DBRG_ERR_INVALID_PARAMETER => Status::InvalidParameter,
            sys::DBRG_ERR_NON_FINITE_INPUT => Status::NonFiniteInput,
            sys::DBRG_ERR_TOO_FEW_POINTS => Status::TooFewPoints,
            sys::DBRG_ERR_DEGENERATE_INPUT => Status::DegenerateInput,
            sys::DBRG_ERR_TOO_MANY_POINTS => Status::TooManyPoints,
            sys::DBRG_ERR_OUT_OF_MEMORY => Status::OutOfMemory,
            sys::DBRG_ERR_CANCELLED => Status::Cancelled,
            sys::DBRG_ERR_UNSUPPORTED => Status::Unsupported,
            sys::DBRG_ERR_INTERNAL => Status::Internal,
            other => Status::Other(other),
        }
    }

    /// The C value of the status in `dbrg_status`; [`Status::File`], which `dbrg_status` lacks, gives
    /// its value in `dbrg_io_status`.
    pub fn code(self) -> u32 {
        match self {
            Status::InvalidArgument => sys::DBRG_ERR_INVALID_ARGUMENT,
            Status::InvalidParameter => sys::DBRG_ERR_INVALID_PARAMETER,
            Status::NonFiniteInput => sys::DBRG_ERR_NON_FINITE_INPUT,
            Status::TooFewPoints => sys::DBRG_ERR_TOO_FEW_POINTS,
            Status::DegenerateInput => sys::DBRG_ERR_DEGENERATE_INPUT,
            Status::TooManyPoints => sys::DBRG_ERR_TOO_MANY_POINTS,
            Status::OutOfMemory => sys::DBRG_ERR_OUT_OF_MEMORY,
            Status::Cancelled => sys::DBRG_ERR_CANCELLED,
            Status::Unsupported => sys::DBRG_ERR_UNSUPPORTED,
            Status::Internal => sys::DBRG_ERR_INTERNAL,
            Status::File => io_sys::DBRG_IO_ERR_FILE,
            Status::Other(code) => code,
        }
    }

    /// The C name, from the library: `"DBRG_ERR_NON_FINITE_INPUT"`.
    pub fn name(self) -> &'static str {
        if self == Status::File {
            return "DBRG_IO_ERR_FILE";
        }
        // SAFETY: dbrg_status_string returns a static NUL-terminated string for any value.
        let name = unsafe { CStr::from_ptr(sys::dbrg_status_string(self.code())) };
        name.to_str().unwrap_or("DBRG_STATUS_UNKNOWN")
    }
}

/// A failed call: the status and the library's sentence on what was wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Error {
    pub status: Status,
    pub message: String,
}

impl Error {
    fn new(status: Status, message: impl Into<String>) -> Error {
        Error { status, message: message.into() }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.message.is_empty() {
            f.write_str(self.status.name())
        } else {
            write!(f, "{} ({})", self.message, self.status.name())
        }
    }
}

impl std::error::Error for Error {}

/// Copies a NUL-terminated string the library owns; NULL gives "".
///
/// # Safety
/// `text` is NULL or points to a NUL-terminated string that stays valid during the call.
unsafe fn owned_string(text: *const c_char) -> String {
    if text.is_null() {
        String::new()
    } else {
        CStr::from_ptr(text).to_string_lossy().into_owned()
    }
}

// ------------------------------------------------------------------------------------------------
// Parameters
// ------------------------------------------------------------------------------------------------

/// Which Delaunay tetrahedralization to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Backend {
    /// The built-in Bowyer-Watson tetrahedralization (always available).
    Builtin,
    /// TetGen (AGPL); only in libraries configured with `-Dtetgen=enabled`, else [`Status::Unsupported`].
    Tetgen,
}

/// Over which triangles the mean circumradius r_a of the boundary test is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoundaryMean {
    /// The triangles around the candidate's edge.
    Local,
    /// All of the surface so far, as in the paper (section 4).
    Global,
}

/// Whether the points are cleaned before the tetrahedralization.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cleaning {
    /// The default: outliers left out, near-duplicates merged, noisy points smoothed for growing, each
    /// only where the data call for it.
    Auto,
    /// The points go to the tetrahedralization as given (exact duplicates merged).
    Off,
    /// As `Auto`, and the points are smoothed whatever the noise estimate says.
    On,
}

/// Reconstruction parameters; `Params::default()` takes the library's defaults (`dbrg_params_init_sized`,
/// the paper's values where it gives one). Change fields after creating it:
///
/// ```
/// let mut params = dbrg::Params::default();
/// params.boundary_factor = 0.0; // closed surfaces only
/// params.sliver_angle = 160f64.to_radians();
/// ```
/// Range checks are the library's: an out-of-range value gives [`Status::InvalidParameter`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// theta_sliver, radians in (pi/2, pi): a Delaunay triangle meeting its neighbour in the surface
    /// at a dihedral angle this large or larger is never attached.
    pub sliver_angle: f64,
    /// M: a candidate whose circumradius exceeds M * r_a is not attached, which keeps open surfaces
    /// open. 0 turns the test off (closed surfaces only); otherwise greater than 1.
    pub boundary_factor: f64,
    /// Over which triangles r_a is averaged.
    pub boundary_mean: BoundaryMean,
    /// Fill the holes left by rejected candidates (paper section 5).
    pub fill_holes: bool,
    /// Holes with more boundary edges than this stay open; at least 3.
    pub max_hole_edges: u32,
    /// How many surface components may grow from separate seeds; at least 1.
    pub max_components: u32,
    /// Which tetrahedralization to use.
    pub backend: Backend,
    /// Threads for the stages that split into parts; 1 runs on the calling thread only, 0 (the
    /// default) uses every hardware thread. The result is the same for any value.
    pub threads: u32,
    /// The point-cleaning stage.
    pub cleaning: Cleaning,
    /// Keep the smoothed positions for [`Mesh::smoothed_points`].
    pub output_smoothed: bool,
}

impl Default for Params {
    fn default() -> Params {
        let raw = default_raw_params();
        Params {
            sliver_angle: raw.sliver_angle,
            boundary_factor: raw.boundary_factor,
            boundary_mean: if raw.boundary_mean == sys::DBRG_BOUNDARY_MEAN_GLOBAL {
                BoundaryMean::Global
            } else {
                BoundaryMean::Local
            },
            fill_holes: raw.fill_holes != 0,
            max_hole_edges: raw.max_hole_edges,
            max_components: raw.max_components,
            backend: if raw.backend == sys::DBRG_BACKEND_TETGEN { Backend::Tetgen } else { Backend::Builtin },
            threads: raw.threads,
            cleaning: match raw.cleaning {
                sys::DBRG_CLEANING_OFF => Cleaning::Off,
                sys::DBRG_CLEANING_ON => Cleaning::On,
                _ => Cleaning::Auto,
            },
            output_smoothed: raw.output_smoothed != 0,
        }
    }
}

fn default_raw_params() -> sys::dbrg_params {
    let mut raw = sys::dbrg_params {
        struct_size: 0,
        sliver_angle: 0.0,
        boundary_factor: 0.0,
        boundary_mean: 0,
        fill_holes: 0,
        max_hole_edges: 0,
        max_components: 0,
        backend: 0,
        threads: 0,
        allocator: ptr::null(),
        progress: None,
        progress_user: ptr::null_mut(),
        snapshot: None,
        snapshot_user: ptr::null_mut(),
        snapshot_count: 0,
        reserved: 0,
        cleaning: 0,
        output_smoothed: 0,
    };
    // SAFETY: raw is a valid dbrg_params to write.
    let status = unsafe { sys::dbrg_params_init_sized(&mut raw, std::mem::size_of::<sys::dbrg_params>()) };
    debug_assert_eq!(status, sys::DBRG_OK);
    raw
}

impl Params {
    /// The C parameter struct with these values (no allocator, no progress callback).
    pub fn to_raw(&self) -> sys::dbrg_params {
        let mut raw = default_raw_params();
        raw.sliver_angle = self.sliver_angle;
        raw.boundary_factor = self.boundary_factor;
        raw.boundary_mean = match self.boundary_mean {
            BoundaryMean::Local => sys::DBRG_BOUNDARY_MEAN_LOCAL,
            BoundaryMean::Global => sys::DBRG_BOUNDARY_MEAN_GLOBAL,
        };
        raw.fill_holes = self.fill_holes as u32;
        raw.max_hole_edges = self.max_hole_edges;
        raw.max_components = self.max_components;
        raw.backend = match self.backend {
            Backend::Builtin => sys::DBRG_BACKEND_BUILTIN,
            Backend::Tetgen => sys::DBRG_BACKEND_TETGEN,
        };
        raw.threads = self.threads;
        raw.cleaning = match self.cleaning {
            Cleaning::Auto => sys::DBRG_CLEANING_AUTO,
            Cleaning::Off => sys::DBRG_CLEANING_OFF,
            Cleaning::On => sys::DBRG_CLEANING_ON,
        };
        raw.output_smoothed = self.output_smoothed as u32;
        raw
    }
}

// ------------------------------------------------------------------------------------------------
// Points
// ------------------------------------------------------------------------------------------------

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A coordinate type the library reads: `f32` or `f64`.
pub trait Scalar: sealed::Sealed + Copy {
    #[doc(hidden)]
    const TYPE: sys::dbrg_scalar_type;
}
impl Scalar for f32 {
    const TYPE: sys::dbrg_scalar_type = sys::DBRG_FLOAT32;
}
impl Scalar for f64 {
    const TYPE: sys::dbrg_scalar_type = sys::DBRG_FLOAT64;
}

/// A borrowed view of input points: pointer, count and byte stride, read during a call only and
/// never copied by the binding. Made from `&[[f64; 3]]`, `&[[f32; 3]]` (and `Vec`s or arrays of them)
/// with `From`, or from interleaved data with [`Points::strided`].
#[derive(Clone, Copy, Debug)]
pub struct Points<'a> {
    raw: sys::dbrg_points,
    _data: PhantomData<&'a [u8]>,
}

impl<'a> Points<'a> {
    fn from_slice<T: Scalar>(points: &'a [[T; 3]]) -> Points<'a> {
        Points {
            raw: sys::dbrg_points {
                data: points.as_ptr() as *const c_void,
                count: points.len(),
                stride_bytes: std::mem::size_of::<[T; 3]>(),
                r#type: T::TYPE,
            },
            _data: PhantomData,
        }
    }

    /// Points whose x, y, z start every `stride` scalars of `data` (for example positions
    /// interleaved with normals: stride 6). The count is how many whole points `data` holds.
    /// A stride below 3 is [`Status::InvalidArgument`].
    pub fn strided<T: Scalar>(data: &'a [T], stride: usize) -> Result<Points<'a>, Error> {
        if stride < 3 {
            return Err(Error::new(Status::InvalidArgument, format!("a stride of {} scalars is shorter than a point", stride)));
        }
        let count = if data.len() < 3 { 0 } else { (data.len() - 3) / stride + 1 };
        Ok(Points {
            raw: sys::dbrg_points {
                data: data.as_ptr() as *const c_void,
                count,
                stride_bytes: stride * std::mem::size_of::<T>(),
                r#type: T::TYPE,
            },
            _data: PhantomData,
        })
    }

    /// Points at an arbitrary byte stride, for example the position field of a `#[repr(C)]` vertex
    /// struct: `data` is the first point's x, each next point `stride_bytes` further.
    ///
    /// # Safety
    /// For `count` points, the 3 scalars at `data + i * stride_bytes` must be readable for `'a`.
    pub unsafe fn from_raw_parts<T: Scalar>(data: *const T, count: usize, stride_bytes: usize) -> Points<'a> {
        Points {
            raw: sys::dbrg_points { data: data as *const c_void, count, stride_bytes, r#type: T::TYPE },
            _data: PhantomData,
        }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.raw.count
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.raw.count == 0
    }

    /// The C description of the points.
    pub fn as_raw(&self) -> &sys::dbrg_points {
        &self.raw
    }

    /// A copy of the points as `f64`, in order.
    fn to_f64(self) -> Vec<[f64; 3]> {
        let base = self.raw.data as *const u8;
        (0..self.raw.count)
            .map(|i| {
                // SAFETY: every constructor guarantees 3 readable scalars of the type at each stride step
                // for 'a (safe ones by construction, from_raw_parts by its contract); unaligned reads
                // because a byte stride need not keep the scalars aligned.
                unsafe {
                    let point = base.add(i * self.raw.stride_bytes);
                    if self.raw.r#type == sys::DBRG_FLOAT32 {
                        let p = point as *const f32;
                        [0, 1, 2].map(|k| f64::from(ptr::read_unaligned(p.add(k))))
                    } else {
                        let p = point as *const f64;
                        [0, 1, 2].map(|k| ptr::read_unaligned(p.add(k)))
                    }
                }
            })
            .collect()
    }
}

impl<'a, T: Scalar> From<&'a [[T; 3]]> for Points<'a> {
    fn from(points: &'a [[T; 3]]) -> Points<'a> {
        Points::from_slice(points)
    }
}

impl<'a, T: Scalar> From<&'a Vec<[T; 3]>> for Points<'a> {
    fn from(points: &'a Vec<[T; 3]>) -> Points<'a> {
        Points::from_slice(points)
    }
}

impl<'a, T: Scalar, const N: usize> From<&'a [[T; 3]; N]> for Points<'a> {
    fn from(points: &'a [[T; 3]; N]) -> Points<'a> {
        Points::from_slice(points)
    }
}

// ------------------------------------------------------------------------------------------------
// Progress
// ------------------------------------------------------------------------------------------------

/// A stage of the pipeline, as reported to a progress callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stage {
    /// Checking and conditioning the input points.
    Validate,
    /// Spatial sort of the points.
    Sort,
    /// Delaunay tetrahedralization.
    Delaunay,
    /// Region growing; the fraction follows the faces grown, then the removal of small islands and the
    /// edge flips.
    Grow,
    /// Recursive hole filling.
    FillHoles,
    /// Building the result.
    Output,
    /// Cleaning the points (outliers, near-duplicates, noise), between `Validate` and `Delaunay`.
    Clean,
    /// A stage this binding does not know (from a newer library).
    Other(u32),
}

impl Stage {
    fn from_raw(stage: sys::dbrg_stage) -> Stage {
        match stage {
            sys::DBRG_STAGE_VALIDATE => Stage::Validate,
            sys::DBRG_STAGE_SORT => Stage::Sort,
            sys::DBRG_STAGE_DELAUNAY => Stage::Delaunay,
            sys::DBRG_STAGE_GROW => Stage::Grow,
            sys::DBRG_STAGE_FILL_HOLES => Stage::FillHoles,
            sys::DBRG_STAGE_OUTPUT => Stage::Output,
            sys::DBRG_STAGE_CLEAN => Stage::Clean,
            other => Stage::Other(other),
        }
    }
}

struct ProgressState<F> {
    callback: F,
    panic: Option<Box<dyn Any + Send + 'static>>,
}

/// The C callback: runs the closure, turns `false` into a cancel, and catches a panic so that it never
/// unwinds through C; the panic cancels the call and is resumed once the call has returned.
unsafe extern "C" fn progress_trampoline<F: FnMut(Stage, f64) -> bool>(
    user: *mut c_void,
    stage: sys::dbrg_stage,
    fraction: f64,
) -> c_int {
    // SAFETY: user is the ProgressState<F> that run_with_progress keeps alive through the call.
    let state = &mut *(user as *mut ProgressState<F>);
    if state.panic.is_some() {
        return 1;
    }
    let callback = &mut state.callback;
    match panic::catch_unwind(AssertUnwindSafe(|| callback(Stage::from_raw(stage), fraction))) {
        Ok(true) => 0,
        Ok(false) => 1,
        Err(payload) => {
            state.panic = Some(payload);
            1
        }
    }
}

/// Runs `call` with `raw` carrying the progress closure, if any; returns its result and the payload of
/// a panic the closure raised.
fn run_with_progress<F, R>(
    mut raw: sys::dbrg_params,
    progress: Option<F>,
    call: impl FnOnce(&sys::dbrg_params) -> R,
) -> (R, Option<Box<dyn Any + Send + 'static>>)
where
    F: FnMut(Stage, f64) -> bool,
{
    match progress {
        None => (call(&raw), None),
        Some(callback) => {
            let mut state = ProgressState { callback, panic: None };
            raw.progress = Some(progress_trampoline::<F>);
            raw.progress_user = &mut state as *mut ProgressState<F> as *mut c_void;
            let result = call(&raw);
            (result, state.panic.take())
        }
    }
}

type NoProgress = fn(Stage, f64) -> bool;

// ------------------------------------------------------------------------------------------------
// Reconstruction
// ------------------------------------------------------------------------------------------------

/// An oriented manifold triangle mesh over the caller's points, owning the library's result.
pub struct Mesh {
    raw: NonNull<sys::dbrg_mesh>,
}

// SAFETY: the library allows concurrent reads of a result; it was made with the default allocator
// (the safe interface offers no other), so any thread may free it.
unsafe impl Send for Mesh {}
unsafe impl Sync for Mesh {}

impl Mesh {
    /// The number of input points the triangle indices refer to.
    pub fn point_count(&self) -> u32 {
        unsafe { sys::dbrg_mesh_point_count(self.raw.as_ptr()) }
    }

    /// The triangles as indices into the input points, each counter-clockwise seen from outside
    /// (closed components face outward). Merged duplicate points are represented by the smallest
    /// input index among them.
    pub fn triangles(&self) -> &[[u32; 3]] {
        unsafe {
            let count = sys::dbrg_mesh_triangle_count(self.raw.as_ptr()) as usize;
            let data = sys::dbrg_mesh_triangles(self.raw.as_ptr());
            if count == 0 || data.is_null() {
                &[]
            } else {
                // SAFETY: 3 * count u32 owned by the mesh, alive as long as &self; [u32; 3] has u32's alignment.
                slice::from_raw_parts(data as *const [u32; 3], count)
            }
        }
    }

    /// The number of boundary loops (open borders and holes left open).
    pub fn boundary_loop_count(&self) -> usize {
        unsafe { sys::dbrg_mesh_boundary_loop_count(self.raw.as_ptr()) as usize }
    }

    /// The point indices along boundary loop `index`, each step a boundary edge in the direction its
    /// triangle traverses it; `None` past the last loop.
    pub fn boundary_loop(&self, index: usize) -> Option<&[u32]> {
        if index >= self.boundary_loop_count() {
            return None;
        }
        let mut count = 0u32;
        unsafe {
            let data = sys::dbrg_mesh_boundary_loop(self.raw.as_ptr(), index as u32, &mut count);
            if data.is_null() {
                Some(&[])
            } else {
                Some(slice::from_raw_parts(data, count as usize))
            }
        }
    }

    /// Every boundary loop, in order.
    pub fn boundary_loops(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        (0..self.boundary_loop_count()).map(move |index| self.boundary_loop(index).unwrap_or(&[]))
    }

    /// The library's warning about this result (it leaves more than half of the points out, usually a
    /// parameter set too tight), or `None`.
    pub fn warning(&self) -> Option<String> {
        let message = unsafe { owned_string(sys::dbrg_mesh_message(self.raw.as_ptr())) };
        if message.is_empty() {
            None
        } else {
            Some(message)
        }
    }

    /// The input points left out as outliers, ascending.
    pub fn outliers(&self) -> &[u32] {
        let mut count = 0u32;
        unsafe {
            let data = sys::dbrg_mesh_outliers(self.raw.as_ptr(), &mut count);
            if data.is_null() {
                &[]
            } else {
                slice::from_raw_parts(data, count as usize)
            }
        }
    }

    /// One byte per triangle of [`Mesh::triangles`], in the same order: [`FACE_FILLED`] (bit 0) set on
    /// the triangles hole filling made rather than growing from the points; all 0 without hole filling.
    pub fn face_flags(&self) -> &[u8] {
        unsafe {
            let count = sys::dbrg_mesh_triangle_count(self.raw.as_ptr()) as usize;
            let data = sys::dbrg_mesh_face_flags(self.raw.as_ptr());
            if count == 0 || data.is_null() {
                &[]
            } else {
                // SAFETY: count bytes owned by the mesh, alive as long as &self.
                slice::from_raw_parts(data, count)
            }
        }
    }

    /// x, y, z of every input point as smoothed (input positions for duplicates and outliers), or `None`
    /// unless [`Params::output_smoothed`] was set and the points were smoothed.
    pub fn smoothed_points(&self) -> Option<&[[f64; 3]]> {
        unsafe {
            let data = sys::dbrg_mesh_smoothed_points(self.raw.as_ptr());
            if data.is_null() {
                None
            } else {
                Some(slice::from_raw_parts(data as *const [f64; 3], self.point_count() as usize))
            }
        }
    }

    /// The figures of the call that made this mesh.
    pub fn stats(&self) -> Stats {
        let mut stats = Stats { struct_size: std::mem::size_of::<Stats>(), ..Stats::default() };
        let status = unsafe { sys::dbrg_mesh_stats(self.raw.as_ptr(), &mut stats) };
        debug_assert_eq!(status, sys::DBRG_OK);
        stats
    }

    /// The C handle, for calls this binding does not wrap. It stays owned by the `Mesh`.
    pub fn as_raw(&self) -> *const sys::dbrg_mesh {
        self.raw.as_ptr()
    }
}

impl Drop for Mesh {
    fn drop(&mut self) {
        unsafe { sys::dbrg_mesh_destroy(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Mesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Mesh")
            .field("point_count", &self.point_count())
            .field("triangles", &self.triangles().len())
            .field("boundary_loops", &self.boundary_loop_count())
            .finish()
    }
}

/// Reconstructs an oriented manifold triangle mesh through `points`.
///
/// Fails with the library's status and message: [`Status::NonFiniteInput`] naming the point,
/// [`Status::TooFewPoints`], [`Status::DegenerateInput`], [`Status::InvalidParameter`] naming the field...
pub fn reconstruct<'a>(points: impl Into<Points<'a>>, params: &Params) -> Result<Mesh, Error> {
    reconstruct_impl(points.into(), params, None::<NoProgress>)
}

/// [`reconstruct`] with a progress closure, called on this thread with the stage and its completed
/// fraction in [0, 1]. Returning `false` cancels the call ([`Status::Cancelled`]). A panic in the
/// closure cancels the call and then continues unwinding from here; it never crosses the C library.
pub fn reconstruct_with_progress<'a, F>(points: impl Into<Points<'a>>, params: &Params, progress: F) -> Result<Mesh, Error>
where
    F: FnMut(Stage, f64) -> bool,
{
    reconstruct_impl(points.into(), params, Some(progress))
}

fn reconstruct_impl<F>(points: Points<'_>, params: &Params, progress: Option<F>) -> Result<Mesh, Error>
where
    F: FnMut(Stage, f64) -> bool,
{
    let mut out: *mut sys::dbrg_mesh = ptr::null_mut();
    let (status, panic) =
        run_with_progress(params.to_raw(), progress, |raw| unsafe { sys::dbrg_reconstruct(&points.raw, raw, &mut out) });
    // Owned from here, so it is freed on every path below.
    let mesh = NonNull::new(out).map(|raw| Mesh { raw });
    if let Some(payload) = panic {
        drop(mesh);
        panic::resume_unwind(payload);
    }
    match mesh {
        None => Err(Error::new(Status::from_raw(status), "the library could not allocate its result")),
        Some(mesh) if status == sys::DBRG_OK => Ok(mesh),
        Some(mesh) => Err(Error::new(Status::from_raw(status), unsafe {
            owned_string(sys::dbrg_mesh_message(mesh.raw.as_ptr()))
        })),
    }
}

/// Checks `points` as a reconstruction would (pointer, stride, count, finite coordinates, at least 4
/// distinct points) without computing anything.
pub fn validate_points<'a>(points: impl Into<Points<'a>>) -> Result<(), Error> {
    let points = points.into();
    let mut message = [0 as c_char; 512];
    let status = unsafe { sys::dbrg_points_validate(&points.raw, ptr::null(), message.as_mut_ptr(), message.len()) };
    if status == sys::DBRG_OK {
        Ok(())
    } else {
        Err(Error::new(Status::from_raw(status), unsafe { owned_string(message.as_ptr()) }))
    }
}

// ------------------------------------------------------------------------------------------------
// Delaunay tetrahedralization (EXPERIMENTAL in the C API)
// ------------------------------------------------------------------------------------------------

/// The Delaunay tetrahedralization of a point set, owning the library's result.
pub struct Tetrahedralization {
    raw: NonNull<sys::dbrg_tetrahedralization>,
}

// SAFETY: as for Mesh.
unsafe impl Send for Tetrahedralization {}
unsafe impl Sync for Tetrahedralization {}

impl Tetrahedralization {
    fn table(&self, data: *const u32) -> &[[u32; 4]] {
        let count = unsafe { sys::dbrg_tetrahedralization_tet_count(self.raw.as_ptr()) } as usize;
        if count == 0 || data.is_null() {
            &[]
        } else {
            // SAFETY: 4 * count u32 owned by the result, alive as long as &self.
            unsafe { slice::from_raw_parts(data as *const [u32; 4], count) }
        }
    }

    /// The finite tetrahedra as indices into the input points, each positively oriented: d lies on
    /// the side of plane (a, b, c) from which a, b, c appear clockwise.
    pub fn tets(&self) -> &[[u32; 4]] {
        self.table(unsafe { sys::dbrg_tetrahedralization_tets(self.raw.as_ptr()) })
    }

    /// Entry `[t][f]` is the tetrahedron across the face of `t` opposite its vertex `f`, or
    /// [`sys::DBRG_NO_NEIGHBOR`] on the convex hull.
    pub fn adjacency(&self) -> &[[u32; 4]] {
        self.table(unsafe { sys::dbrg_tetrahedralization_adjacency(self.raw.as_ptr()) })
    }

    /// The number of distinct points (duplicates merged).
    pub fn unique_point_count(&self) -> u32 {
        unsafe { sys::dbrg_tetrahedralization_unique_point_count(self.raw.as_ptr()) }
    }
}

impl Drop for Tetrahedralization {
    fn drop(&mut self) {
        unsafe { sys::dbrg_tetrahedralization_destroy(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Tetrahedralization {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Tetrahedralization")
            .field("tets", &self.tets().len())
            .field("unique_points", &self.unique_point_count())
            .finish()
    }
}

/// The Delaunay tetrahedralization of `points` (exact predicates, symbolic perturbation). Uses the
/// backend and threads of `params`; the surface parameters are ignored.
pub fn tetrahedralize<'a>(points: impl Into<Points<'a>>, params: &Params) -> Result<Tetrahedralization, Error> {
    tetrahedralize_impl(points.into(), params, None::<NoProgress>)
}

/// [`tetrahedralize`] with a progress closure, as in [`reconstruct_with_progress`].
pub fn tetrahedralize_with_progress<'a, F>(
    points: impl Into<Points<'a>>,
    params: &Params,
    progress: F,
) -> Result<Tetrahedralization, Error>
where
    F: FnMut(Stage, f64) -> bool,
{
    tetrahedralize_impl(points.into(), params, Some(progress))
}

fn tetrahedralize_impl<F>(points: Points<'_>, params: &Params, progress: Option<F>) -> Result<Tetrahedralization, Error>
where
    F: FnMut(Stage, f64) -> bool,
{
    let mut out: *mut sys::dbrg_tetrahedralization = ptr::null_mut();
    let (status, panic) =
        run_with_progress(params.to_raw(), progress, |raw| unsafe { sys::dbrg_tetrahedralize(&points.raw, raw, &mut out) });
    let tets = NonNull::new(out).map(|raw| Tetrahedralization { raw });
    if let Some(payload) = panic {
        drop(tets);
        panic::resume_unwind(payload);
    }
    match tets {
        None => Err(Error::new(Status::from_raw(status), "the library could not allocate its result")),
        Some(tets) if status == sys::DBRG_OK => Ok(tets),
        Some(tets) => Err(Error::new(Status::from_raw(status), unsafe {
            owned_string(sys::dbrg_tetrahedralization_message(tets.raw.as_ptr()))
        })),
    }
}

// ------------------------------------------------------------------------------------------------
// Version
// ------------------------------------------------------------------------------------------------

/// The version of the library linked at run time, as (major, minor, patch). Compare it with
/// `sys::DBRG_VERSION_*` (what this crate was written for) to detect a mismatched shared library.
pub fn library_version() -> (u32, u32, u32) {
    let number = unsafe { sys::dbrg_version_number() };
    (number / 10000, number / 100 % 100, number % 100)
}

/// The version string of the library linked at run time ("0.5.0").
pub fn library_version_string() -> &'static str {
    // SAFETY: a static NUL-terminated string.
    unsafe { CStr::from_ptr(sys::dbrg_version_string()) }.to_str().unwrap_or("")
}
