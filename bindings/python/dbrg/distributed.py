"""dbrg.distributed: tiled reconstruction on a Dask cluster (EXPERIMENTAL; docs/tiles.md, "Running on Dask").

    import dbrg.distributed
    mesh = dbrg.distributed.reconstruct(points, tiles=8)                      # a LocalCluster of 2 processes
    mesh = dbrg.distributed.reconstruct(points, tiles=64, scheduler="tcp://host:8786")

The driver runs the steps of the C library's tiled loop (dbrg_reconstruct_tiled) as Dask tasks and gives the
same mesh: the plan (here), one task per slab (dbrg_reconstruct_tile), one task per wall
(dbrg_seam_stitch, sent as soon as its input is known: _Stitching), and the assembly (here,
dbrg_mesh_assemble). Every
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
import threading
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


def _seam_input(coordinate, faces, wall, reach, near=None):
    """What the stitch of `wall` is sent, as dbrg_seam_stitch asks: the points within `reach` of the wall
    (`coordinate`: the points' coordinates on the plan's axis, NaN for the outliers, which no stitch is
    given), the faces touching them or sharing a corner with such a face, and those faces' corners. Returns
    (indices of the faces in `faces`, ids of the points, ascending); `near`, when given, is the points
    within reach (_near)."""
    near = _near(coordinate, wall, reach) if near is None else near
    marked = np.zeros(len(coordinate), dtype=bool)
    marked[near] = True
    marked[faces[_any_corner(marked, faces)]] = True
    given = np.flatnonzero(_any_corner(marked, faces))
    marked[:] = False
    marked[near] = True
    marked[faces[given]] = True
    return given, np.flatnonzero(marked)


def _any_corner(mask, faces):
    """Whether each of `faces` has a corner where `mask` (one flag a point) holds. (Three column ors:
    numpy's any() over an axis of length 3 takes several times as long.)"""
    flags = mask[faces]
    return flags[:, 0] | flags[:, 1] | flags[:, 2]


def _near(coordinate, wall, reach):
    """The points within `reach` of `wall` on the axis (NaN, an outlier, is never near)."""
    return np.flatnonzero(np.abs(coordinate - wall) < reach)


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
    progress: show Dask's progress bar for the tiles (the stitches, sent as the tiles around them finish, are
        a few percent of the work).
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
            faces, outliers, pieces = _tiles_and_stitches(client, array, cut, options, progress)
    finally:
        for thing in opened:
            thing.close()
    mesh = _assemble(lib, points, array, faces, outliers, len(cut.walls) + 1, pieces)
    mesh.stats["seconds_total"] = time.monotonic() - started
    return mesh


class _Source:
    """Faces of the mesh being built: a tile's owned faces, or the faces a stitch added. `low` and `high`
    bound, on the plan's axis, the points its faces may use (those of its task) and so every face its task
    may add or drop. `faces` is None until its task is done; then `after_even` flags the faces that no even
    wall's stitch dropped (what an odd wall's stitch is given to choose from) and `kept` those no stitch
    dropped."""

    def __init__(self, low, high):
        self.low, self.high = low, high
        self.faces = self.after_even = self.kept = None

    def done(self):
        return self.faces is not None

    def reaches(self, low, high):
        return self.low <= high and low <= self.high

    def finish(self, faces):
        self.faces = faces
        self.after_even = np.ones(len(faces), dtype=bool)
        self.kept = np.ones(len(faces), dtype=bool)


class _Stitch:
    """A wall's stitch: the sources it may read (the tiles; for an odd wall also the even walls' stitches'),
    the source of the faces it adds, and once sent, the faces it was given as (source, indices) pairs and its
    task's key."""

    def __init__(self, wall, odd, reads, added):
        self.wall, self.odd, self.reads, self.added = wall, odd, reads, added
        # Once the sources reaching the wall are done: the points near it and where its input may reach.
        self.near = self.reach = None
        self.blocker = None  # a source it waits for, found not done when last asked
        self.given = self.key = None

    def choices(self, source):
        """The indices of the faces of `source` this stitch chooses from: an even wall's stitch all the
        tiles' faces, an odd wall's those left after the even walls' stitches, as in the C loop."""
        return np.flatnonzero(source.after_even) if self.odd else np.arange(len(source.faces))


def _extent(values):
    """The smallest interval holding `values` (an empty one when there are none)."""
    return (values.min(), values.max()) if len(values) else (np.inf, -np.inf)


def _hull_of_reaching(sources, low, high):
    """The smallest interval holding [low, high] and every one of `sources` that reaches it."""
    reaching = [source for source in sources if source.reaches(low, high)]
    return min([low] + [source.low for source in reaching]), max([high] + [source.high for source in reaching])


def _stitch_input(stitch, axis_values, coordinate, reach, near):
    """What `stitch` is to be sent, once everything it may be sent is known: (ids of its points, the faces it
    is given as (source, indices into the source's faces) pairs); else None.

    A stitch is given the faces with a corner within `reach` of its wall and those sharing a corner with
    them. Every corner of a source's faces lies where the source reaches, so only the sources reaching the
    wall hold faces of the first kind, and only those reaching the first ones' corners faces of the second:
    once those are done, the input is what it is when every task is done, as in the C loop. near(wall): the
    points within `reach` of a wall, as _near gives them."""
    if stitch.blocker is not None and not stitch.blocker.done():
        return None  # at once: a driver of thousands of tiles asks after every task
    if stitch.reach is None:
        low, high = stitch.wall - reach, stitch.wall + reach
        first = [source for source in stitch.reads if source.reaches(low, high)]
        stitch.blocker = next((source for source in first if not source.done()), None)
        if stitch.blocker is not None:
            return None
        # Final now: the outliers near the wall are known (the tiles holding them are among the first), and
        # so are the faces touching the points near it.
        stitch.near = near(stitch.wall)
        marked = np.zeros(len(coordinate), dtype=bool)
        marked[stitch.near] = True
        touching = [source.faces[stitch.choices(source)] for source in first]
        corners = np.concatenate([np.empty(0, dtype=np.intp)] +
                                 [faces[_any_corner(marked, faces)].ravel() for faces in touching])
        corner_low, corner_high = _extent(axis_values[corners])
        stitch.reach = min(low, corner_low), max(high, corner_high)
    second = [source for source in stitch.reads if source.reaches(*stitch.reach)]
    stitch.blocker = next((source for source in second if not source.done()), None)
    if stitch.blocker is not None:
        return None
    choices = [stitch.choices(source) for source in second]
    faces = np.concatenate([np.empty((0, 3), dtype=np.uint64)] +
                           [source.faces[indices] for source, indices in zip(second, choices)])
    given, ids = _seam_input(coordinate, faces, stitch.wall, reach, stitch.near)
    starts = np.cumsum([0] + [len(indices) for indices in choices])
    return ids, [(source, indices[given[(given >= begin) & (given < end)] - begin])
                 for source, indices, begin, end in zip(second, choices, starts[:-1], starts[1:])]


class _Stitching:
    """Which stitch can be sent when, and the faces as the tasks finish: the driver's bookkeeping, apart from
    Dask. An even wall's stitch is sent once the tiles around it are done, an odd wall's once the even walls'
    stitches next to it are (_stitch_input), so that stitches run beside the last tiles and no step waits for
    all; every stitch is still given what it is given when every task before it is done, as in the C loop."""

    def __init__(self, axis_values, tile_extents, walls, reach):
        """tile_extents: (lowest, highest) coordinate on the axis of each tile's points."""
        self.axis_values = axis_values
        self.coordinate = axis_values.copy()  # NaN at the tiles' outliers, as each tile reports them
        self.reach = reach
        self.tiles = [_Source(low, high) for low, high in tile_extents]
        # The points in order along the axis, so that finding those near a wall looks at them alone.
        self.by_coordinate = np.argsort(axis_values, kind="stable")
        self.sorted_values = axis_values[self.by_coordinate]
        # Until it is sent, an even wall's stitch may be given points as far as the tiles it may read reach.
        self.even = [_Stitch(wall, False, self.tiles, _Source(*_hull_of_reaching(
            self.tiles, *_hull_of_reaching(self.tiles, wall - reach, wall + reach)))) for wall in walls[0::2]]
        self.odd = [_Stitch(wall, True, self.tiles + [stitch.added for stitch in self.even], _Source(np.inf, -np.inf))
                    for wall in walls[1::2]]
        self.waiting = self.even + self.odd
        self.outliers = []

    def tile_done(self, k, faces, outliers):
        self.coordinate[outliers] = np.nan
        self.outliers.append(outliers)
        self.tiles[k].finish(faces)

    def stitch_done(self, stitch, dropped, added):
        """`dropped`: indices into the faces `stitch` was given; `added`: the faces it grew."""
        start = 0
        for source, indices in stitch.given:
            mine = indices[dropped[(dropped >= start) & (dropped < start + len(indices))] - start]
            source.kept[mine] = False
            if not stitch.odd:
                source.after_even[mine] = False
            start += len(indices)
        stitch.added.finish(added)

    def ready(self):
        """The stitches whose input is now known, each as (stitch, ids of its points, the faces it is
        given), taken off the waiting list."""
        found = []
        for stitch in list(self.waiting):
            sent = _stitch_input(stitch, self.axis_values, self.coordinate, self.reach, self.near)
            if sent is None:
                continue
            ids, stitch.given = sent
            stitch.added.low, stitch.added.high = _extent(self.axis_values[ids])
            self.waiting.remove(stitch)
            found.append((stitch, ids, np.concatenate([source.faces[indices] for source, indices in stitch.given])))
        return found

    def near(self, wall):
        """_near(self.coordinate, wall, self.reach) from the points within twice the reach alone (a wider
        slice than the test's bounds, which round otherwise)."""
        begin = np.searchsorted(self.sorted_values, wall - 2 * self.reach, side="left")
        end = np.searchsorted(self.sorted_values, wall + 2 * self.reach, side="right")
        candidates = np.sort(self.by_coordinate[begin:end])
        return candidates[np.abs(self.coordinate[candidates] - wall) < self.reach]

    def faces(self):
        """The faces no stitch dropped: the tiles', in tile order, then the stitches', even walls first."""
        sources = self.tiles + [stitch.added for stitch in self.even + self.odd]
        return np.concatenate([source.faces[source.kept] for source in sources])


def _tiles_and_stitches(client, array, cut, options, progress):
    """Every tile and stitch, each stitch sent as soon as its input is known (_Stitching). Returns the faces
    (_Stitching.faces), the tiles' outliers, ascending, and the tasks' statistics (tiles, even walls, odd
    walls). (Tasks are submitted as impure: their keys are not hashed from their arguments, megabytes of
    points.)"""
    from distributed import as_completed
    axis_values = array[:, cut.axis]
    index_type = _index_type(len(array))
    tile_extents, tile_futures = [], []
    for k in range(len(cut.walls) + 1):
        low, high = cut.core(k)
        inside = np.flatnonzero((axis_values >= low[cut.axis] - cut.halo) & (axis_values < high[cut.axis] + cut.halo))
        tile_extents.append(_extent(axis_values[inside]))
        tile_futures.append(client.submit(tile_task, array[inside], inside.astype(index_type), low, high, options,
                                          pure=False))
    stitching = _Stitching(axis_values, tile_extents, cut.walls, cut.seam_reach)
    # A finished task's result stays on its worker while a future of it is held: only the progress bar's
    # thread holds the tiles' until they are all done, and no stitch's is kept.
    bar = _progress_bar(tile_futures) if progress else None
    tile_keys = [future.key for future in tile_futures]
    tile_of = {key: k for k, key in enumerate(tile_keys)}
    running = as_completed(tile_futures, with_results=True)
    del tile_futures
    stitch_of, stats = {}, {}
    for future, result in running:
        key = future.key
        del future
        if key in stitch_of:
            dropped, added, stats[key] = result
            stitching.stitch_done(stitch_of[key], dropped, added)
        else:
            faces, outliers, stats[key] = result
            stitching.tile_done(tile_of[key], faces, outliers)
        for stitch, ids, given in stitching.ready():
            future = client.submit(stitch_task, array[ids], ids.astype(index_type), given, cut.axis, cut.spacing,
                                   stitch.wall, options, pure=False)
            stitch.key = future.key
            stitch_of[stitch.key] = stitch
            running.add(future)
            del future
    if bar is not None:
        bar.join()
    keys = tile_keys + [stitch.key for stitch in stitching.even + stitching.odd]
    return stitching.faces(), np.sort(np.concatenate(stitching.outliers)), [stats[key] for key in keys]


def _progress_bar(futures):
    """Dask's progress bar for `futures`, drawn by a thread while the driver goes on sending tasks."""
    from distributed import progress as progress_bar
    thread = threading.Thread(target=progress_bar, args=(futures,), daemon=True)
    thread.start()
    return thread


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
