"""dbrg.distributed: tiled reconstruction on a Dask cluster (EXPERIMENTAL; docs/tiles.md, "Running on Dask").

    import dbrg.distributed
    mesh = dbrg.distributed.reconstruct(points, tiles=8)                      # a LocalCluster of 2 processes
    mesh = dbrg.distributed.reconstruct(points, tiles=64, scheduler="tcp://host:8786")

The driver runs the steps of the C library's tiled loop (dbrg_reconstruct_tiled) as Dask tasks and gives the
same mesh: the plan (here), one task per slab (dbrg_reconstruct_tile), one task per wall
(dbrg_seam_stitch: the even walls, then the odd ones), and the assembly (here, dbrg_mesh_assemble). Every
task is a pure function of the points and faces it is sent, so a task whose worker fails or is killed is
run again and the mesh does not change; the mesh depends on the tiling, never on the number of workers or
the order in which tasks finish. Each task is sent its own points only, inside the task (not scattered:
scattered data dies with its worker, a task's arguments do not). The client holds the whole cloud and
the whole mesh: the plan and the assembly are whole-cloud steps.

Needs dask and distributed (Debian: python3-dask python3-distributed) on the client and the workers, and
this package importable on the workers.
"""

import ctypes
import platform
import time
import warnings

import numpy as np

from . import _capi
from . import _error, _mesh, _params, _point_array, _read_stats, _stats_of, library, reconstruct as _reconstruct_one

__all__ = ["reconstruct", "plan", "Plan", "local_cluster"]

_OK = _capi.ENUMS["dbrg_status"]["DBRG_OK"]
# What a task is given of the caller's options: the surface parameters, one thread (a worker is one task).
_OPTIONS = ("sliver_angle", "boundary_factor", "boundary_mean", "fill_holes", "max_hole_edges", "max_components",
            "backend", "cleaning")

# glibc's allocator settings for the processes that run the tasks, the dbrg program's own
# (cli/allocator_settings.cpp): freed blocks up to 64 MiB stay for the next task, and arrays under 32 MiB come
# from the heap. Dask starts its workers with MALLOC_TRIM_THRESHOLD_=65536, so that freed memory leaves the
# resident size it watches at once; that also stops glibc from raising its mmap threshold, so every large
# array of every tile was mapped, faulted in page by page and unmapped afresh: on a 1M-point cloud's tiles
# 1.2-1.4 times slower than glibc's defaults, and these settings 0.95 times (docs/tiles.md). Each task sets
# them in its worker (mallopt, once a process), so every worker has them: those a cluster starts later or in
# place of a failed one, and those of a cluster the caller runs. Unlike the dbrg program they override
# MALLOC_* variables in the environment: Dask sets one for every worker, so a worker's environment cannot
# tell the caller's choice from Dask's.
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # glibc's malloc.h
_TRIM_THRESHOLD, _MMAP_THRESHOLD = 64 << 20, 32 << 20
_allocator_checked = False


def _keep_freed_blocks():
    """Sets this process's trim and mmap thresholds when the C library is glibc (elsewhere: nothing). Two
    tasks at once may both set them: the same values, and mallopt takes glibc's lock."""
    global _allocator_checked
    if _allocator_checked:
        return
    _allocator_checked = True
    if platform.libc_ver()[0] != "glibc":
        return
    mallopt = ctypes.CDLL(None).mallopt
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    mallopt(_M_TRIM_THRESHOLD, _TRIM_THRESHOLD)
    mallopt(_M_MMAP_THRESHOLD, _MMAP_THRESHOLD)


class Plan:
    """How the cloud is cut (dbrg_tiling_plan): slabs across `axis` between `walls`, each tile's points
    reaching `halo` past its core, each stitch looking `seam_reach` either side of its wall."""

    def __init__(self, tiling, walls):
        self.tiling = tiling
        self.axis = tiling.axis
        self.walls = list(walls)
        self.spacing = tiling.spacing
        self.halo = tiling.halo
        self.seam_reach = tiling.seam_reach

    def core(self, k):
        """The half-open core [low, high) of tile k, 3 bounds each."""
        low, high = [-np.inf] * 3, [np.inf] * 3
        if k > 0:
            low[self.axis] = self.walls[k - 1]
        if k < len(self.walls):
            high[self.axis] = self.walls[k]
        return low, high


def plan(points, tiles):
    """The plan dbrg_reconstruct_tiled follows for `points` cut into `tiles` slabs (fewer where slabs would
    be thinner than 12 point spacings: no walls at all for a small cloud)."""
    lib = library()
    array, view = _point_array(points)
    tiling = _capi.dbrg_tiling()
    tiling.struct_size = ctypes.sizeof(tiling)
    walls = (ctypes.c_double * max(tiles - 1, 1))()
    message = ctypes.create_string_buffer(512)
    status = lib.dbrg_tiling_plan(ctypes.byref(view), tiles, None, ctypes.byref(tiling), walls, message, len(message))
    del array
    if status != _OK:
        raise _error(lib, status, message.value)
    return Plan(tiling, walls[:tiling.wall_count])


def _view(xyz):
    xyz = np.ascontiguousarray(xyz, dtype=np.float64)
    return xyz, _capi.dbrg_points(xyz.ctypes.data, len(xyz), 24, _capi.ENUMS["dbrg_scalar_type"]["DBRG_FLOAT64"])


def _index_type(count):
    """The narrowest unsigned type that holds the ids of `count` points. Ids and faces travel between the
    client and the tasks in it: half the bytes of uint64 below 2^32 points."""
    return np.uint32 if count <= 2 ** 32 else np.uint64


def _tile_result(lib, status, handle, index_type):
    """The triangles of a dbrg_tile_mesh as an (M, 3) array of global ids of `index_type`; raises on failure."""
    if status != _OK:
        raise _error(lib, status, lib.dbrg_tile_mesh_message(handle) if handle else b"")
    count = lib.dbrg_tile_mesh_triangle_count(handle)
    pointer = lib.dbrg_tile_mesh_triangles(handle)
    if count == 0:
        return np.empty((0, 3), dtype=index_type)
    return np.ctypeslib.as_array(pointer, shape=(count, 3)).astype(index_type)


def _piece_stats(lib, handle):
    """The statistics of a tile's or a stitch's call as the bytes of a dbrg_stats, for the assembly to add
    up (dbrg_stats_add_piece)."""
    return bytes(_read_stats(lib, lib.dbrg_tile_mesh_stats, handle))


def _ids(pointer, count, index_type):
    """`count` uint64 ids at `pointer` as an array of `index_type`."""
    if count == 0:
        return np.empty(0, dtype=index_type)
    return np.ctypeslib.as_array(pointer, shape=(count,)).astype(index_type)


def tile_task(xyz, ids, low, high, options):
    """A tile: dbrg_reconstruct_tile on its points (core and halo) with their global ids. Returns (faces,
    outliers, stats): the owned faces as an (M, 3) array of global ids and the ids of its core's outliers, of
    the ids' type, and the call's statistics (_piece_stats)."""
    _keep_freed_blocks()
    lib = library()
    xyz, view = _view(xyz)
    index_type, ids = ids.dtype, np.ascontiguousarray(ids, dtype=np.uint64)
    params = _params(lib, threads=1, **options)
    handle = _capi.tile_mesh_p()
    core_low, core_high = (ctypes.c_double * 3)(*low), (ctypes.c_double * 3)(*high)
    status = lib.dbrg_reconstruct_tile(ctypes.byref(view), ids.ctypes.data_as(_capi.u64_p), core_low, core_high,
                                       ctypes.byref(params), ctypes.byref(handle))
    try:
        faces = _tile_result(lib, status, handle, index_type)
        count = ctypes.c_uint64()
        pointer = lib.dbrg_tile_mesh_outliers(handle, ctypes.byref(count))
        return faces, _ids(pointer, count.value, index_type), _piece_stats(lib, handle)
    finally:
        lib.dbrg_tile_mesh_destroy(handle)


def stitch_task(xyz, ids, faces, axis, spacing, wall, options):
    """A wall's stitch: dbrg_seam_stitch on the points and faces near the wall (global ids). Returns
    (dropped, added, stats): the indices into `faces` of the faces to drop, the (K, 3) faces to add, of the
    ids' type, and the call's statistics (_piece_stats)."""
    _keep_freed_blocks()
    lib = library()
    xyz, view = _view(xyz)
    index_type, ids = ids.dtype, np.ascontiguousarray(ids, dtype=np.uint64)
    faces = np.ascontiguousarray(faces, dtype=np.uint64)
    tiling = _capi.dbrg_tiling()
    tiling.struct_size = ctypes.sizeof(tiling)
    tiling.axis = axis
    tiling.spacing = spacing
    params = _params(lib, threads=1, **options)
    handle = _capi.tile_mesh_p()
    status = lib.dbrg_seam_stitch(ctypes.byref(view), ids.ctypes.data_as(_capi.u64_p),
                                  faces.ctypes.data_as(_capi.u64_p), len(faces), ctypes.byref(tiling), wall,
                                  ctypes.byref(params), ctypes.byref(handle))
    try:
        added = _tile_result(lib, status, handle, index_type)
        count = ctypes.c_uint64()
        pointer = lib.dbrg_tile_mesh_dropped(handle, ctypes.byref(count))
        return _ids(pointer, count.value, np.int64), added, _piece_stats(lib, handle)
    finally:
        lib.dbrg_tile_mesh_destroy(handle)


def _seam_inputs(coordinate, faces, walls, reach):
    """What each stitch of a half is sent, as dbrg_seam_stitch asks: the points within `reach` of its wall
    (`coordinate`: the points' coordinates on the plan's axis, NaN for the outliers, which no stitch is
    given), the faces touching them or sharing a corner with such a face, and those faces' corners. Yields (indices of the faces in `faces`, ids of the points,
    ascending) for each wall in turn, so that its stitch can start while the next wall's input is found.

    Two passes over all the faces serve the whole half: every face a stitch is sent has a corner near one of
    the walls or a corner of a face that has one (`marked`); each wall then looks at those few faces only."""
    near = [np.flatnonzero(np.abs(coordinate - wall) < reach) for wall in walls]
    marked = np.zeros(len(coordinate), dtype=bool)
    for points in near:
        marked[points] = True
    marked[faces[_any_corner(marked, faces)]] = True
    candidates = np.flatnonzero(_any_corner(marked, faces))
    nearby = faces[candidates]
    for points in near:
        marked[:] = False
        marked[points] = True
        marked[nearby[_any_corner(marked, nearby)]] = True
        given = _any_corner(marked, nearby)
        marked[:] = False
        marked[points] = True
        marked[nearby[given]] = True
        yield candidates[given], np.flatnonzero(marked)


def _any_corner(mask, faces):
    """Whether each of `faces` has a corner where `mask` (one flag a point) holds. (Three column ors:
    numpy's any() over an axis of length 3 takes several times as long.)"""
    flags = mask[faces]
    return flags[:, 0] | flags[:, 1] | flags[:, 2]


def _open_client(client, scheduler, n_workers, memory_limit):
    """The client to run on, and what to close afterwards (what this call started)."""
    from distributed import Client
    if client is not None:
        return client, []
    if scheduler is not None:
        client = Client(scheduler)
        return client, [client]
    cluster = local_cluster(n_workers, memory_limit)
    client = Client(cluster)
    return client, [client, cluster]


def local_cluster(n_workers=2, memory_limit="1GiB"):
    """A distributed.LocalCluster of `n_workers` worker processes of one thread and `memory_limit` each, as
    reconstruct() starts when given no client or scheduler."""
    from distributed import LocalCluster
    return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, memory_limit=memory_limit,
                        dashboard_address=":0")


def _wait(client, futures, progress):
    if progress:
        from distributed import progress as progress_bar
        progress_bar(futures)
    return client.gather(futures)


def reconstruct(points, tiles=8, client=None, scheduler=None, n_workers=2, memory_limit="1GiB", progress=True,
                **options):
    """Reconstructs `points` as `tiles` slabs on a Dask cluster and returns a dbrg.Mesh, with the faces of
    dbrg_reconstruct_tiled(points, tiles) (the C loop, `dbrg reconstruct --tiles N`).

    points: an (N, 3) array-like, as for dbrg.reconstruct (read as float64).
    tiles: slabs wanted; fewer where slabs would be thinner than 12 point spacings. A cloud that gets no
        walls runs as one dbrg.reconstruct call here, as the C loop does.
    client: a distributed.Client to run on; else `scheduler`, a scheduler's address ("tcp://host:8786");
        else a LocalCluster of `n_workers` worker processes of one thread and `memory_limit` each, closed
        on return.
    progress: show Dask's progress bar for the tiles and for each half of the stitches.
    options: the surface parameters of dbrg.reconstruct (sliver_angle, boundary_factor, boundary_mean,
        fill_holes, max_hole_edges, max_components, backend, cleaning); every task uses one thread.
    Mesh.stats holds the assembly's figures with the tiles' and stitches' added as the C loop adds them
    (dbrg_stats_add_piece), `tiles` the number of slabs run, seconds_total the whole run on this machine
    (the other seconds are the pieces' own, added up); Mesh.outliers the points
    the tiles left out as outliers, each decided by the tile whose core holds it. Raises ImportError when
    distributed cannot be imported, and dbrg.Error subclasses as dbrg.reconstruct does.
    """
    started = time.monotonic()
    unknown = set(options) - set(_OPTIONS)
    if unknown:
        raise TypeError("reconstruct() got unexpected keyword arguments %s" % ", ".join(sorted(unknown)))
    try:
        import distributed  # noqa: F401  (fail early, before any work)
    except ImportError as error:
        raise ImportError("dbrg.distributed needs dask and distributed (Debian: python3-dask python3-distributed; "
                          "pip: distributed): %s" % error) from None
    lib = library()
    # The tasks' parameters, checked here so that a bad one fails before any cluster work.
    params = _params(lib, threads=1, **options)
    message = ctypes.create_string_buffer(512)
    status = lib.dbrg_params_validate(ctypes.byref(params), message, len(message))
    if status != _OK:
        raise _error(lib, status, message.value)
    array = np.ascontiguousarray(np.asarray(points), dtype=np.float64)
    cut = plan(array, tiles)
    if not cut.walls:
        return _reconstruct_one(points, **options)
    client, opened = _open_client(client, scheduler, n_workers, memory_limit)
    try:
        with warnings.catch_warnings():
            # Dask advises scattering large task arguments; here they are sent in the tasks on purpose, so
            # that a task outlives the worker it ran on (module docstring).
            warnings.filterwarnings("ignore", message="Large object of size", category=UserWarning)
            faces, outliers, pieces = _tiles(client, array, cut, options, progress)
            for half in (0, 1):
                faces, stitched = _stitch_half(client, array, faces, outliers, cut, cut.walls[half::2], options,
                                               progress)
                pieces += stitched
    finally:
        for thing in opened:
            thing.close()
    mesh = _assemble(lib, points, array, faces, outliers, len(cut.walls) + 1, pieces)
    mesh.stats["seconds_total"] = time.monotonic() - started
    return mesh


def _tiles(client, array, cut, options, progress):
    """Every tile's owned faces, concatenated in tile order: an (F, 3) array of point indices (_index_type),
    the tiles' outliers, ascending (each point lies in one core: none comes twice), and their statistics.
    Each tile is sent as soon as its points are cut, so the first tiles run while the next are cut. (Tasks
    are submitted as impure: their keys are not hashed from their arguments, megabytes of points.)"""
    coordinate = array[:, cut.axis]
    index_type = _index_type(len(array))
    futures = []
    for k in range(len(cut.walls) + 1):
        low, high = cut.core(k)
        inside = np.flatnonzero((coordinate >= low[cut.axis] - cut.halo) & (coordinate < high[cut.axis] + cut.halo))
        futures.append(client.submit(tile_task, array[inside], inside.astype(index_type), low, high, options,
                                     pure=False))
    results = _wait(client, futures, progress)
    return (np.concatenate([faces for faces, _, _ in results]), np.sort(np.concatenate([ids for _, ids, _ in results])),
            [stats for _, _, stats in results])


def _stitch_half(client, array, faces, outliers, cut, walls, options, progress):
    """The faces after stitching `walls` (a half: two slabs apart, so their stitches touch disjoint faces),
    each stitch on `faces` as they are, and the stitches' statistics."""
    futures, given_faces = [], []
    coordinate = array[:, cut.axis].copy()
    coordinate[outliers] = np.nan
    inputs = _seam_inputs(coordinate, faces, walls, cut.seam_reach)
    for wall, (given, ids) in zip(walls, inputs):
        given_faces.append(given)
        futures.append(client.submit(stitch_task, array[ids], ids.astype(faces.dtype), faces[given], cut.axis,
                                     cut.spacing, wall, options, pure=False))
    results = _wait(client, futures, progress)
    keep = np.ones(len(faces), dtype=bool)
    added = []
    for given, (dropped, grown, _) in zip(given_faces, results):
        keep[given[dropped]] = False
        added.append(grown)
    return np.concatenate([faces[keep]] + added), [stats for _, _, stats in results]


def _added_up(lib, handle, pieces):
    """dbrg_mesh_stats of the assembly with every piece's added (dbrg_stats_add_piece), as the C loop adds
    its own: a dbrg_stats."""
    total = _read_stats(lib, lib.dbrg_mesh_stats, handle)
    for piece in pieces:
        status = lib.dbrg_stats_add_piece(ctypes.byref(total), ctypes.byref(_capi.dbrg_stats.from_buffer_copy(piece)))
        if status != _OK:
            raise _error(lib, status, b"a piece's statistics could not be added")
    return total


def _assemble(lib, points, array, faces, outliers, tiles, pieces):
    """dbrg_mesh_assemble on the whole cloud, the stitched faces and the tiles' outliers: the dbrg.Mesh, its
    statistics with those of the pieces (_piece_stats of the tiles and stitches) added."""
    xyz, view = _view(array)
    triangles = np.ascontiguousarray(faces, dtype=np.uint32)
    left_out = np.ascontiguousarray(outliers, dtype=np.uint32)
    handle = _capi.mesh_p()
    status = lib.dbrg_mesh_assemble(ctypes.byref(view), triangles.ctypes.data_as(_capi.u32_p), len(triangles),
                                    left_out.ctypes.data_as(_capi.u32_p), len(left_out), None,
                                    ctypes.byref(handle))
    try:
        if status != _OK:
            raise _error(lib, status, lib.dbrg_mesh_message(handle) if handle else b"")
        mesh = _mesh(lib, handle, np.asarray(points))
        mesh.stats = _stats_of(_added_up(lib, handle, pieces))
        mesh.stats["tiles"] = tiles
        return mesh
    finally:
        lib.dbrg_mesh_destroy(handle)
