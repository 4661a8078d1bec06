"""dbrg: an oriented manifold triangle mesh through an unorganized 3D point cloud, by Delaunay-based
region growing (Kuo & Yau 2005). A ctypes binding over the dbrg shared library.

    import numpy as np, dbrg
    mesh = dbrg.reconstruct(points)      # points: any (N, 3) float32/float64 array-like
    mesh.triangles                       # (M, 3) uint32 indices into points, counter-clockwise from outside
    mesh.boundary_loops, mesh.stats      # list of uint32 arrays; dict of figures

The shared library is looked up through the environment variable DBRG_LIBRARY (the file's path),
then next to this package, then on the system library path; see dbrg/_library.py.

The GIL is released while the library computes, so other Python threads keep running; a progress
callback takes it back for as long as it runs. Ctrl-C cancels a computation at its next progress
report and raises KeyboardInterrupt.
"""

import collections
import ctypes
import operator
import os
import signal
import threading
import warnings

import numpy as np

from . import _capi, _convert, _io
from ._library import LibraryError, io_library, library, library_path

__version__ = _capi.DBRG_VERSION_STRING
LibraryError.__module__ = __name__

__all__ = [
    "reconstruct", "delaunay", "validate_points", "read_points", "library_version", "library_path",
    "Mesh", "Delaunay", "STAGES", "FACE_FILLED",
    "Error", "InvalidArgumentError", "InvalidParameterError", "NonFiniteInputError", "TooFewPointsError",
    "DegenerateInputError", "TooManyPointsError", "OutOfMemoryError", "CancelledError", "UnsupportedError",
    "InternalError", "LibraryError",
]

_STAGE_PREFIX = "DBRG_STAGE_"
# Stage names passed to progress callbacks, by their value: "validate", "sort", "delaunay", ...
STAGES = {value: name[len(_STAGE_PREFIX):].lower() for name, value in _capi.ENUMS["dbrg_stage"].items()}

_BACKENDS = {"builtin": _capi.ENUMS["dbrg_backend"]["DBRG_BACKEND_BUILTIN"],
             "tetgen": _capi.ENUMS["dbrg_backend"]["DBRG_BACKEND_TETGEN"]}
_BOUNDARY_MEANS = {"local": _capi.ENUMS["dbrg_boundary_mean"]["DBRG_BOUNDARY_MEAN_LOCAL"],
                   "global": _capi.ENUMS["dbrg_boundary_mean"]["DBRG_BOUNDARY_MEAN_GLOBAL"]}
_CLEANING = {"auto": _capi.ENUMS["dbrg_cleaning"]["DBRG_CLEANING_AUTO"],
             "off": _capi.ENUMS["dbrg_cleaning"]["DBRG_CLEANING_OFF"],
             "on": _capi.ENUMS["dbrg_cleaning"]["DBRG_CLEANING_ON"]}
_OK = _capi.ENUMS["dbrg_status"]["DBRG_OK"]
FACE_FILLED = _capi.ENUMS["dbrg_face_flag"]["DBRG_FACE_FILLED"]
_UINT32_MAX = 0xFFFFFFFF


# ---------------------------------------------------------------------------------------------------
# Errors
# ---------------------------------------------------------------------------------------------------

class Error(Exception):
    """A dbrg call failed. `status` is the C status name ("DBRG_ERR_NON_FINITE_INPUT"), `message` the
    library's sentence on what was wrong."""

    def __init__(self, status, message):
        super().__init__(status, message)
        self.status = status
        self.message = message

    def __str__(self):
        return "%s (%s)" % (self.message, self.status) if self.message else self.status


class InvalidArgumentError(Error, ValueError):
    """DBRG_ERR_INVALID_ARGUMENT"""


class InvalidParameterError(Error, ValueError):
    """DBRG_ERR_INVALID_PARAMETER: a parameter is out of range (the message names it)."""


class NonFiniteInputError(Error, ValueError):
    """DBRG_ERR_NON_FINITE_INPUT: a coordinate is NaN or infinite (the message names the point index)."""


class TooFewPointsError(Error, ValueError):
    """DBRG_ERR_TOO_FEW_POINTS: fewer than 4 distinct points."""


class DegenerateInputError(Error, ValueError):
    """DBRG_ERR_DEGENERATE_INPUT: all points are collinear (or, for delaunay, coplanar)."""


class TooManyPointsError(Error, ValueError):
    """DBRG_ERR_TOO_MANY_POINTS"""


class OutOfMemoryError(Error, MemoryError):
    """DBRG_ERR_OUT_OF_MEMORY"""


class CancelledError(Error):
    """DBRG_ERR_CANCELLED: the progress callback returned False."""


class UnsupportedError(Error):
    """DBRG_ERR_UNSUPPORTED: the feature (e.g. the TetGen backend) is not in this build of the library."""


class InternalError(Error):
    """DBRG_ERR_INTERNAL: a bug in dbrg; please report it with the input."""


_ERRORS = {
    "DBRG_ERR_INVALID_ARGUMENT": InvalidArgumentError,
    "DBRG_ERR_INVALID_PARAMETER": InvalidParameterError,
    "DBRG_ERR_NON_FINITE_INPUT": NonFiniteInputError,
    "DBRG_ERR_TOO_FEW_POINTS": TooFewPointsError,
    "DBRG_ERR_DEGENERATE_INPUT": DegenerateInputError,
    "DBRG_ERR_TOO_MANY_POINTS": TooManyPointsError,
    "DBRG_ERR_OUT_OF_MEMORY": OutOfMemoryError,
    "DBRG_ERR_CANCELLED": CancelledError,
    "DBRG_ERR_UNSUPPORTED": UnsupportedError,
    "DBRG_ERR_INTERNAL": InternalError,
}


def _error(lib, status, message):
    name = lib.dbrg_status_string(status).decode()
    return _ERRORS.get(name, Error)(name, (message or b"").decode("utf-8", "replace"))


def _parameter_error(message):
    return InvalidParameterError("DBRG_ERR_INVALID_PARAMETER", message)


# ---------------------------------------------------------------------------------------------------
# Arguments
# ---------------------------------------------------------------------------------------------------

def _point_array(points):
    """Returns (array, dbrg_points) describing `points` without copying when the library can read them
    in place: float32/float64 in native byte order, scalars of a point adjacent, any positive row stride
    of at least one point. Anything else is copied once into a C-contiguous array."""
    array = np.asarray(points)
    if array.dtype.kind == "f" and array.dtype.itemsize in (4, 8):
        if not array.dtype.isnative:
            array = array.astype(array.dtype.newbyteorder("="))
    elif array.dtype.kind in "iuf":
        array = array.astype(np.float64)
    else:
        raise TypeError("points must hold numbers; got dtype %s" % array.dtype)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError("points must have shape (N, 3); got %s" % (array.shape,))
    scalar = array.itemsize
    row_stride, column_stride = array.strides
    if array.shape[0] <= 1:
        row_stride = 3 * scalar  # the row stride of a single row is meaningless
    if column_stride != scalar or row_stride < 3 * scalar:
        array = np.ascontiguousarray(array)
        row_stride = 3 * scalar
    scalar_type = _capi.ENUMS["dbrg_scalar_type"]["DBRG_FLOAT32" if scalar == 4 else "DBRG_FLOAT64"]
    view = _capi.dbrg_points(array.ctypes.data, array.shape[0], row_stride, scalar_type)
    return array, view


def _real(name, value):
    try:
        return float(value)
    except (TypeError, ValueError):
        raise _parameter_error("%s must be a number; got %r" % (name, value)) from None


def _count(name, value):
    try:
        number = operator.index(value)
    except TypeError:
        raise _parameter_error("%s must be an integer; got %r" % (name, value)) from None
    if not 0 <= number <= _UINT32_MAX:
        raise _parameter_error("%s must lie in [0, 2**32 - 1]; got %d" % (name, number))
    return number


def _choice(name, value, choices):
    key = value.lower() if isinstance(value, str) else value
    if key not in choices:
        raise _parameter_error("%s must be one of %s; got %r" % (name, ", ".join(map(repr, choices)), value))
    return choices[key]


def _params(lib, sliver_angle=None, boundary_factor=None, boundary_mean=None, fill_holes=True,
            max_hole_edges=None, max_components=None, backend=None, threads=None, cleaning=None,
            output_smoothed=False):
    """A dbrg_params with the library's defaults, overridden by every argument that is not None.
    Range checks are the library's (dbrg_params_validate)."""
    params = _capi.dbrg_params()
    lib.dbrg_params_init_sized(ctypes.byref(params), ctypes.sizeof(params))
    if sliver_angle is not None:
        params.sliver_angle = _real("sliver_angle", sliver_angle)
    if boundary_factor is not None:
        params.boundary_factor = _real("boundary_factor", boundary_factor)
    if boundary_mean is not None:
        params.boundary_mean = _choice("boundary_mean", boundary_mean, _BOUNDARY_MEANS)
    if fill_holes is not None:
        params.fill_holes = 1 if fill_holes else 0
    if max_hole_edges is not None:
        params.max_hole_edges = _count("max_hole_edges", max_hole_edges)
    if max_components is not None:
        params.max_components = _count("max_components", max_components)
    if backend is not None:
        params.backend = _choice("backend", backend, _BACKENDS)
    if threads is not None:
        params.threads = _count("threads", threads)
    if cleaning is not None:
        params.cleaning = _choice("cleaning", cleaning, _CLEANING)
    params.output_smoothed = 1 if output_smoothed else 0
    return params


class _Progress:
    """Adapts a Python progress callable to dbrg_progress_fn. An exception raised by the callable
    cancels the C call and is kept, to be raised again once the call has returned.

    Used as a context manager around the C call on the main thread, it also turns Ctrl-C into a
    cancel: Python runs signal handlers at the entry of the next Python function, here the ctypes
    callback, where a KeyboardInterrupt would escape every try block and be dropped by ctypes. So
    for the length of the call SIGINT only sets a flag; the callback then cancels, and the
    KeyboardInterrupt is raised once the call has returned."""

    def __init__(self, callback):
        self.callback = callback
        self.error = None
        self.interrupted = False
        self.previous_handler = None
        self.c_function = _capi.PROGRESS_FN(self._call)

    def __enter__(self):
        if (threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self.previous_handler = signal.signal(signal.SIGINT, self._on_interrupt)
        return self

    def __exit__(self, *exception):
        if self.previous_handler is not None:
            signal.signal(signal.SIGINT, self.previous_handler)
            self.previous_handler = None
        return False

    def _on_interrupt(self, signum, frame):
        self.interrupted = True

    def _call(self, user, stage, fraction):
        if self.error is not None or self.interrupted:
            return 1
        try:
            keep_going = self.callback(STAGES.get(stage, "stage %d" % stage), fraction)
            return 1 if keep_going is not None and not keep_going else 0
        except BaseException as error:  # KeyboardInterrupt too: it must not vanish inside ctypes
            self.error = error
            return 1

    def attach(self, params):
        params.progress = self.c_function

    def raise_pending(self):
        error, self.error = self.error, None
        self.c_function = None  # drops the cycle self -> c_function -> self._call
        if self.interrupted:
            raise KeyboardInterrupt
        if error is not None:
            raise error


def _keep_going(stage, fraction):
    return True


def _attach_progress(params, progress):
    """Always installs a callback, the caller's or one that only continues: the library's progress
    reports are where Python gets to run its signal handlers, so Ctrl-C (KeyboardInterrupt) cancels a
    long computation at its next report instead of after it."""
    if progress is None:
        progress = _keep_going
    elif not callable(progress):
        raise TypeError("progress must be callable as progress(stage_name, fraction)")
    watcher = _Progress(progress)
    watcher.attach(params)
    return watcher


def _copy_u32(pointer, rows, columns=None):
    """A numpy copy of rows (x columns) uint32 values the library owns."""
    shape = (rows,) if columns is None else (rows, columns)
    if rows == 0 or not pointer:
        return np.empty(shape, dtype=np.uint32)
    return np.ctypeslib.as_array(pointer, shape=shape).copy()


# ---------------------------------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------------------------------

class Mesh:
    """The result of reconstruct(); everything is copied out of the library, so it lives on its own.

    vertices       (N, 3) copy of the input points (float32 or float64 as given), which the triangles
                   index, or smoothed_points when output_smoothed was asked and the points were smoothed;
                   points left out of the surface are among them, used by no triangle.
    vertex_normals (N, 3) float32 unit normals, each the angle-weighted mean of its triangles' normals,
                   outward on closed surfaces; (0, 0, 0) where no triangle uses the vertex. Computed
                   on first use by libdbrg_io, as the dbrg program writes them.
    write(path)    writes the mesh with the project's own writers (libdbrg_io), as the dbrg program does.
    to_open3d(), to_trimesh()  the mesh as an open3d.geometry.TriangleMesh or a trimesh.Trimesh, with its
                   vertex normals; ImportError naming the package when it is not installed.
    unused_points  uint32 indices of the input points no triangle uses, ascending (a merged duplicate
                   point is among them: the triangles use the smallest index of its copies).
    triangles      (M, 3) uint32 indices into the input points, counter-clockwise seen from outside
                   (closed components face outward); merged duplicate points are represented by the
                   smallest input index among them.
    boundary_loops list of uint32 arrays: point indices along each open border, in the direction the
                   border's triangles traverse it.
    stats          dict of every dbrg_stats field (counts, rejections by rule, seconds per stage,
                   peak_bytes), except struct_size.
    point_count    the number of input points the indices refer to.
    warning        "" or the library's warning about a result that leaves most points out (also
                   issued as a RuntimeWarning by reconstruct()).
    outliers       uint32 array: the input points left out as outliers, ascending.
    smoothed_points (N, 3) float64 positions the points were smoothed to (input positions for duplicates
                   and outliers), or None unless output_smoothed was asked and the points were smoothed.
    face_flags     (M,) uint8, one per triangle: FACE_FILLED (bit 0) set on the triangles hole filling
                   made rather than growing from the points; all 0 with fill_holes=False.
    """

    __slots__ = ("vertices", "triangles", "boundary_loops", "stats", "point_count", "warning", "outliers",
                 "smoothed_points", "face_flags", "_vertex_normals")

    def __init__(self, vertices, triangles, boundary_loops, stats, point_count, warning="", outliers=None,
                 smoothed_points=None, face_flags=None):
        self.vertices = vertices
        self.triangles = triangles
        self.boundary_loops = boundary_loops
        self.stats = stats
        self.point_count = point_count
        self.warning = warning
        self.outliers = np.empty(0, dtype=np.uint32) if outliers is None else outliers
        self.smoothed_points = smoothed_points
        self.face_flags = np.zeros(len(triangles), dtype=np.uint8) if face_flags is None else face_flags
        self._vertex_normals = None

    def _arrays(self):
        """The vertices as C-contiguous float64 and the triangles as C-contiguous uint32, as libdbrg_io
        takes them."""
        positions = np.ascontiguousarray(self.vertices, dtype=np.float64)
        triangles = np.ascontiguousarray(self.triangles, dtype=np.uint32)
        return positions, triangles

    @property
    def vertex_normals(self):
        if self._vertex_normals is None:
            positions, triangles = self._arrays()
            normals = np.empty((len(positions), 3), dtype=np.float32)
            status = io_library().dbrg_io_vertex_normals(
                _pointer(positions, ctypes.c_double), len(positions), _pointer(triangles, ctypes.c_uint32),
                len(triangles), _pointer(normals, ctypes.c_float))
            if status != 0:
                raise ValueError("the mesh's triangles do not index its vertices (%s)" % _io.DBRG_IO_STATUS.get(status))
            self._vertex_normals = normals
        return self._vertex_normals

    def write(self, path, *, normals=True):
        """Writes the mesh to `path`, the format chosen by its extension (.ply binary, .obj, .off, .stl,
        .xyz), with the dbrg program's writers: the file is replaced only once completely written.
        normals: write vertex_normals too (PLY nx ny nz, OBJ vn; other formats have no place for them).
        Raises ValueError for an unknown extension, OSError when the file cannot be written."""
        positions, triangles = self._arrays()
        normal_array = self.vertex_normals if normals else None
        message = ctypes.create_string_buffer(1024)
        status = io_library().dbrg_io_write_mesh(
            os.fsencode(path), _pointer(positions, ctypes.c_double), len(positions),
            _pointer(triangles, ctypes.c_uint32), len(triangles),
            None if normal_array is None else _pointer(normal_array, ctypes.c_float), message, len(message))
        _raise_for_io_status(status, message)

    def to_open3d(self):
        """An open3d.geometry.TriangleMesh with these vertices (unused points among them), triangles and
        vertex_normals. Raises ImportError naming open3d when it cannot be imported."""
        return _convert.to_open3d(self)

    def to_trimesh(self):
        """A trimesh.Trimesh with these vertices (unused points among them, in order), triangles and
        vertex_normals, made with process=False (nothing merged or removed). Raises ImportError naming
        trimesh when it cannot be imported."""
        return _convert.to_trimesh(self)

    @property
    def unused_points(self):
        used = np.zeros(self.point_count, dtype=bool)
        used[np.asarray(self.triangles, dtype=np.int64).ravel()] = True
        return np.flatnonzero(~used).astype(np.uint32)

    def __repr__(self):
        return "<dbrg.Mesh: %d triangles over %d points, %d boundary loops>" % (
            len(self.triangles), self.point_count, len(self.boundary_loops))


def _raise_for_io_status(status, message):
    """Raises the exception for a libdbrg_io status other than DBRG_IO_OK, with the library's message."""
    text = message.value.decode("utf-8", "replace")
    if status == 1:
        raise ValueError(text)
    if status == 3:
        raise MemoryError(text)
    if status != 0:
        raise OSError(text)


def read_points(path):
    """Reads the points of a file with the dbrg program's readers (libdbrg_io): .ply .obj .off .stl .xyz
    .pts .las, chosen by the extension; faces are not read.

    Returns (points, attributes): points an (N, 3) float64 array, attributes a dict of per-point
    arrays of N values by name, in the file's order and types: a PLY's other vertex properties
    ("red" uint8, "intensity", "confidence", ...; its normals as "nx", "ny", "nz" float32), a LAS
    file's "intensity" and, in the formats with colour, "red", "green", "blue" (uint16).
    Raises ValueError for an unknown extension or a .laz file (decompress it first), OSError for a file
    that cannot be read or is malformed (the message says where), MemoryError."""
    lib = io_library()
    handle = ctypes.c_void_p()
    message = ctypes.create_string_buffer(1024)
    status = lib.dbrg_io_read_points(os.fsencode(path), ctypes.byref(handle), message, len(message))
    _raise_for_io_status(status, message)
    try:
        count = lib.dbrg_io_points_count(handle)

        def copy(address, dtype, shape):
            if not address or count == 0:
                return np.zeros(shape, dtype=dtype)
            items = int(np.prod(shape))
            buffer = (ctypes.c_char * (items * np.dtype(dtype).itemsize)).from_address(address)
            return np.frombuffer(buffer, dtype=dtype, count=items).reshape(shape).copy()

        points = copy(lib.dbrg_io_points_positions(handle), np.float64, (count, 3))
        attributes = {}
        for index in range(lib.dbrg_io_points_attribute_count(handle)):
            name = lib.dbrg_io_points_attribute_name(handle, index).decode("utf-8", "replace")
            dtype = _io.VALUE_TYPES[lib.dbrg_io_points_attribute_type(handle, index)]
            attributes[name] = copy(lib.dbrg_io_points_attribute_values(handle, index), dtype, (count,))
        normals = lib.dbrg_io_points_normals(handle)
        if normals:
            xyz = copy(normals, np.float32, (count, 3))
            attributes.update({"nx": xyz[:, 0].copy(), "ny": xyz[:, 1].copy(), "nz": xyz[:, 2].copy()})
        return points, attributes
    finally:
        lib.dbrg_io_points_destroy(handle)


# tets: (T, 4) uint32, each positively oriented; adjacency: (T, 4) uint32, entry [t, f] the tetrahedron
# across the face opposite vertex f of t, or 0xFFFFFFFF (dbrg.NO_NEIGHBOR) on the convex hull.
Delaunay = collections.namedtuple("Delaunay", ["tets", "adjacency"])
NO_NEIGHBOR = _capi.DBRG_NO_NEIGHBOR


def _stats_of(stats):
    """A dbrg_stats as Mesh.stats: every field but struct_size."""
    return {name: getattr(stats, name) for name, _ in _capi.dbrg_stats._fields_ if name != "struct_size"}


def _read_stats(lib, copy, handle):
    """The dbrg_stats that `copy` (lib.dbrg_mesh_stats or lib.dbrg_tile_mesh_stats) gives of `handle`."""
    stats = _capi.dbrg_stats()
    stats.struct_size = ctypes.sizeof(stats)
    status = copy(handle, ctypes.byref(stats))
    if status != _OK:
        raise _error(lib, status, b"the call's statistics could not be copied")
    return stats


def _stats_dict(lib, handle):
    return _stats_of(_read_stats(lib, lib.dbrg_mesh_stats, handle))


def _pointer(array, c_type):
    return array.ctypes.data_as(ctypes.POINTER(c_type))


def _mesh(lib, handle, points):
    count = lib.dbrg_mesh_triangle_count(handle)
    triangles = _copy_u32(lib.dbrg_mesh_triangles(handle), count, 3)
    loops = []
    for loop in range(lib.dbrg_mesh_boundary_loop_count(handle)):
        length = ctypes.c_uint32()
        pointer = lib.dbrg_mesh_boundary_loop(handle, loop, ctypes.byref(length))
        loops.append(_copy_u32(pointer, length.value))
    warning = lib.dbrg_mesh_message(handle).decode("utf-8", "replace")
    outlier_count = ctypes.c_uint32()
    outliers = _copy_u32(lib.dbrg_mesh_outliers(handle, ctypes.byref(outlier_count)), outlier_count.value)
    point_count = lib.dbrg_mesh_point_count(handle)
    smoothed = lib.dbrg_mesh_smoothed_points(handle)
    smoothed_points = np.ctypeslib.as_array(smoothed, shape=(point_count, 3)).copy() if smoothed else None
    # The mesh's vertices are where its surface passes: the smoothed positions when they were asked for.
    vertices = np.array(points) if smoothed_points is None else smoothed_points
    flags = lib.dbrg_mesh_face_flags(handle)
    face_flags = np.ctypeslib.as_array(flags, shape=(count,)).copy() if flags else np.zeros(count, dtype=np.uint8)
    return Mesh(vertices, triangles, loops, _stats_dict(lib, handle), point_count, warning, outliers, smoothed_points,
                face_flags)


# ---------------------------------------------------------------------------------------------------
# Entry points
# ---------------------------------------------------------------------------------------------------

def reconstruct(points, *, sliver_angle=None, boundary_factor=None, boundary_mean=None, fill_holes=True,
                max_hole_edges=None, max_components=None, backend=None, threads=None, progress=None,
                cleaning=None, output_smoothed=False):
    """Reconstructs an oriented manifold triangle mesh through `points` and returns a Mesh.

    points: any (N, 3) array-like of numbers; float32 and float64 arrays are read in place when each
        point's x, y, z are adjacent (any positive row stride, e.g. a column slice of a wider array);
        other layouts and dtypes are copied once.
    sliver_angle: theta_sliver in radians, in (pi/2, pi); default 5*pi/6.
    boundary_factor: M; a candidate with circumradius above M * r_a is not attached, leaving open
        surfaces open. 0 turns the test off (closed surfaces only); otherwise > 1. Default: the library's.
    boundary_mean: "local" or "global", over which triangles r_a is averaged.
    fill_holes: fill the holes left by rejected candidates.
    max_hole_edges: holes with more boundary edges stay open (at least 3).
    max_components: how many surfaces may grow from separate seeds (at least 1).
    backend: "builtin" or "tetgen" (the latter only in builds configured with -Dtetgen=enabled).
    threads: threads for the stages that split into parts; 0 (the default) for every processor, 1 for
        none besides the calling one; the result is the same for any value.
    progress: None, or progress(stage_name, fraction) called on the calling thread; returning False
        cancels (CancelledError), and an exception raised inside it cancels the computation and is
        raised again from here. Ctrl-C (KeyboardInterrupt) cancels at the next progress report too.
    cleaning: "auto" (the library's default: outliers left out, near-duplicates merged, noisy points
        smoothed for growing, each only where the data call for it), "off", or "on" (always smooth).
    output_smoothed: also return the smoothed positions (Mesh.smoothed_points).
    None keeps the library's default for every parameter.

    Raises a dbrg.Error subclass naming the status and the problem (NonFiniteInputError for a NaN,
    with the point index in the message; TooFewPointsError; DegenerateInputError; ...).
    """
    lib = library()
    array, view = _point_array(points)
    params = _params(lib, sliver_angle, boundary_factor, boundary_mean, fill_holes, max_hole_edges,
                     max_components, backend, threads, cleaning, output_smoothed)
    watcher = _attach_progress(params, progress)
    handle = _capi.mesh_p()
    with watcher:
        status = lib.dbrg_reconstruct(ctypes.byref(view), ctypes.byref(params), ctypes.byref(handle))
    try:
        watcher.raise_pending()
        if status != _OK:
            raise _error(lib, status, lib.dbrg_mesh_message(handle) if handle else b"")
        mesh = _mesh(lib, handle, array)
        if mesh.warning:
            warnings.warn(mesh.warning, RuntimeWarning, stacklevel=2)
        return mesh
    finally:
        lib.dbrg_mesh_destroy(handle)


def delaunay(points, *, backend=None, threads=None, progress=None):
    """Returns the Delaunay tetrahedralization of `points` as Delaunay(tets, adjacency), two (T, 4)
    uint32 arrays (see Delaunay). Duplicate points are merged (the smallest index represents them).
    EXPERIMENTAL in the C API. Arguments and errors as for reconstruct()."""
    lib = library()
    array, view = _point_array(points)
    params = _params(lib, backend=backend, threads=threads)
    watcher = _attach_progress(params, progress)
    handle = _capi.tets_p()
    with watcher:
        status = lib.dbrg_tetrahedralize(ctypes.byref(view), ctypes.byref(params), ctypes.byref(handle))
    del array
    try:
        watcher.raise_pending()
        if status != _OK:
            raise _error(lib, status, lib.dbrg_tetrahedralization_message(handle) if handle else b"")
        count = lib.dbrg_tetrahedralization_tet_count(handle)
        tets = _copy_u32(lib.dbrg_tetrahedralization_tets(handle), count, 4)
        adjacency = _copy_u32(lib.dbrg_tetrahedralization_adjacency(handle), count, 4)
        return Delaunay(tets, adjacency)
    finally:
        lib.dbrg_tetrahedralization_destroy(handle)


def validate_points(points):
    """Checks `points` as reconstruct() would (finite, at least 4 distinct, not all collinear... as far as
    dbrg_points_validate goes) without computing anything; raises the same dbrg.Error, else returns None."""
    lib = library()
    array, view = _point_array(points)
    message = ctypes.create_string_buffer(512)
    status = lib.dbrg_points_validate(ctypes.byref(view), None, message, len(message))
    del array
    if status != _OK:
        raise _error(lib, status, message.value)


def library_version():
    """The version string of the loaded shared library ("0.5.0")."""
    return library().dbrg_version_string().decode()
