"""dbrg.distributed on local Dask clusters: the faces of the C library's tiled loop, whatever the number of
workers, the order tasks finish in, or a worker killed in the middle of the run."""

import ctypes
import os
import platform
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np

import dbrg
from dbrg import _capi
from dbrg.__main__ import program_path

try:
    import distributed
    from distributed import Client, WorkerPlugin
    import dbrg.distributed as dbrg_distributed
except ImportError as error:  # the tests below skip, saying why
    distributed = None
    WorkerPlugin = object
    MISSING = "dask.distributed cannot be imported (%s; Debian: python3-dask python3-distributed)" % error

TILES = 4  # 3 walls on the torus below: two stitched at once, then one


def torus(count, seed=1):
    rng = np.random.default_rng(seed)
    u, v = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, 2 * np.pi, count)
    ring = 1.0 + 0.35 * np.cos(v)
    return np.stack([ring * np.cos(u), ring * np.sin(u), 0.35 * np.sin(v)], axis=1)


def c_loop(points, tiles):
    """The triangles of dbrg_reconstruct_tiled: the loop the driver must agree with."""
    lib = dbrg.library()
    array, view = dbrg._point_array(points)
    handle = _capi.mesh_p()
    status = lib.dbrg_reconstruct_tiled(ctypes.byref(view), tiles, None, ctypes.byref(handle))
    try:
        assert status == 0, lib.dbrg_mesh_message(handle)
        return dbrg._mesh(lib, handle, array)
    finally:
        lib.dbrg_mesh_destroy(handle)


def local_cluster(workers):
    cluster = dbrg_distributed.local_cluster(workers, memory_limit="1GiB")
    return cluster, Client(cluster)


def block_mapped_alone(size=16 << 20):
    """Whether glibc maps a block of `size` bytes on its own instead of taking it from a heap (the IS_MMAPPED
    bit of its chunk's size word): true under Dask's settings for a worker, false once the tasks have set
    dbrg's (run on the workers)."""
    libc = ctypes.CDLL(None)
    libc.malloc.restype, libc.malloc.argtypes, libc.free.argtypes = ctypes.c_void_p, [ctypes.c_size_t], [ctypes.c_void_p]
    block = libc.malloc(size)
    size_word = ctypes.c_size_t.from_address(block - ctypes.sizeof(ctypes.c_size_t)).value
    libc.free(block)
    return bool(size_word & 2)


class HoldEarlyTasks(WorkerPlugin):
    """Holds each tile and each stitch, once computed, the longer the earlier it started among its kind (by the
    lines of `log`, which every worker appends to when a task starts and when it is done), so that tasks are
    done in another order than they started."""

    def __init__(self, log):
        self.log = log

    def setup(self, worker):
        self.rank = {}

    def transition(self, key, start, finish, **kwargs):
        kind = str(key).split("-")[0]
        if kind not in ("tile_task", "stitch_task") or finish not in ("executing", "memory"):
            return
        if finish == "executing":
            with open(self.log) as log:
                self.rank[key] = sum(line.startswith("executing " + kind) for line in log)
        else:
            time.sleep(0.3 * max(TILES - 1 - self.rank.get(key, TILES), 0))
        with open(self.log, "a") as log:
            log.write("%s %s\n" % (finish, key))


class KillOnFirstTile(WorkerPlugin):
    """Kills the worker process that starts the first tile task of the run (the marker file says it was done)."""

    def __init__(self, marker):
        self.marker = marker

    def transition(self, key, start, finish, **kwargs):
        if finish == "executing" and str(key).startswith("tile_task") and not os.path.exists(self.marker):
            open(self.marker, "w").close()
            os._exit(1)


def seam_input_by_definition(xyz, faces, axis, wall, reach, outliers=()):
    """What dbrg_seam_stitch asks to be sent for `wall`, read off its contract one wall at a time: the points
    within `reach` but the tiles' outliers, the faces touching them or sharing a corner with such a face, and
    those faces' corners."""
    near = np.abs(xyz[:, axis] - wall) < reach
    near[list(outliers)] = False
    marked = near.copy()
    marked[faces[near[faces].any(axis=1)]] = True
    given = np.flatnonzero(marked[faces].any(axis=1))
    wanted = near.copy()
    wanted[faces[given]] = True
    return given, np.flatnonzero(wanted)


@unittest.skipIf(distributed is None, MISSING if distributed is None else "")
class SeamInputs(unittest.TestCase):
    def test_each_wall_gets_what_its_stitch_asks(self):
        # The tiled loop's faces, and long random ones that reach across several walls and share corners
        # with faces far from any wall.
        points = torus(6000)
        cut = dbrg_distributed.plan(points, TILES)
        rng = np.random.default_rng(2)
        faces = np.concatenate([c_loop(points, TILES).triangles,
                                rng.integers(0, len(points), size=(300, 3))]).astype(np.uint32)
        # Outliers (their coordinate NaN, as the driver marks them) near the walls, some of them corners of
        # the random faces: those are sent as corners, the others not at all.
        coordinate = points[:, cut.axis].copy()
        near_a_wall = np.flatnonzero(np.min(np.abs(coordinate[:, None] - np.array(cut.walls)), axis=1) < cut.seam_reach)
        outliers = near_a_wall[::7]
        coordinate[outliers] = np.nan
        for wall in cut.walls:
            given, ids = dbrg_distributed._seam_input(coordinate, faces, wall, cut.seam_reach)
            expected_given, expected_ids = seam_input_by_definition(points, faces, cut.axis, wall, cut.seam_reach,
                                                                    outliers)
            self.assertTrue(np.array_equal(given, expected_given))
            self.assertTrue(np.array_equal(ids, expected_ids))
            self.assertFalse(np.isin(np.setdiff1d(outliers, faces[given]), ids).any())


def tube(count, length=8.0, radius=0.3, seed=3):
    """An open tube along x, long enough for slabs much wider than the halo and the seam reach."""
    rng = np.random.default_rng(seed)
    u, x = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, length, count)
    return np.stack([x, radius * np.cos(u), radius * np.sin(u)], axis=1)


def sorted_rows(faces):
    return sorted(map(tuple, np.asarray(faces).tolist()))


@unittest.skipIf(distributed is None, MISSING if distributed is None else "")
class Stitching(unittest.TestCase):
    """The driver sends a stitch as soon as its input is known (_Stitching): never before, and then with the
    input it gets when every task before it is done, whatever order the tasks finish in."""

    def test_inputs_and_faces_whatever_order_tasks_finish_in(self):
        points = tube(12000)
        cut = dbrg_distributed.plan(points, 6)
        self.assertEqual(len(cut.walls), 5)
        axis_values = points[:, cut.axis]
        loop_faces = c_loop(points, 6).triangles
        rng = np.random.default_rng(4)
        # Outliers near the walls, each listed by the tile whose core holds it: no stitch is given one but
        # as a corner of a face it is given.
        near_a_wall = np.min(np.abs(axis_values[:, None] - np.array(cut.walls)), axis=1) < cut.seam_reach
        outliers = np.flatnonzero(near_a_wall)[::40]
        core_of = np.searchsorted(cut.walls, axis_values[outliers], side="right")
        early = 0
        for _ in range(8):
            # Each tile's faces: some of the tiled loop's among its points, and long random ones among them
            # that reach across walls.
            tile_extents, tile_faces = [], []
            free = rng.random(len(loop_faces)) < 0.5  # each face in one tile at most
            for k in range(len(cut.walls) + 1):
                low, high = cut.core(k)
                inside = np.flatnonzero((axis_values >= low[cut.axis] - cut.halo)
                                        & (axis_values < high[cut.axis] + cut.halo))
                mine = free & np.isin(loop_faces, inside).all(axis=1)
                free &= ~mine
                tile_extents.append((axis_values[inside].min(), axis_values[inside].max()))
                long_faces = rng.choice(inside, size=(40, 3))
                tile_faces.append(np.concatenate([loop_faces[mine], long_faces]).astype(np.uint32))
            stitching = dbrg_distributed._Stitching(axis_values, tile_extents, cut.walls, cut.seam_reach)
            # Tiles and sent stitches finish in random order. A stitch drops every third face it is given
            # and grows faces among its points.
            to_finish = [("tile", k) for k in range(len(tile_faces))]
            sent, results = {}, {}
            while to_finish:
                kind, what = to_finish.pop(rng.integers(len(to_finish)))
                if kind == "tile":
                    stitching.tile_done(what, tile_faces[what], outliers[core_of == what])
                else:
                    stitching.stitch_done(what, *results[what.wall])
                for stitch, ids, given in stitching.ready():
                    unfinished = sum(1 for other, _ in to_finish if other == "tile") + sum(
                        1 for other, task in to_finish if other == "stitch" and not task.odd)
                    early += unfinished > 0
                    sent[stitch.wall] = (ids, given)
                    grown = rng.choice(ids, size=(30, 3)).astype(np.uint32)
                    results[stitch.wall] = (np.arange(0, len(given), 3), grown)
                    to_finish.append(("stitch", stitch))
            self.assertEqual(sorted(sent), sorted(cut.walls))
            # What each stitch is given in the C loop: the even walls' from the tiles' faces, the odd walls'
            # from those the even walls' stitches left and added.
            before = np.concatenate(tile_faces)
            dropped = [sent[wall][1][results[wall][0]] for wall in cut.walls[0::2]]
            after_even = remove_rows(before, np.concatenate(dropped)) + [
                row for wall in cut.walls[0::2] for row in results[wall][1].tolist()]
            for walls, faces in ((cut.walls[0::2], before), (cut.walls[1::2], np.array(after_even))):
                for wall in walls:
                    expected_given, expected_ids = seam_input_by_definition(points, faces, cut.axis, wall,
                                                                            cut.seam_reach, outliers)
                    self.assertTrue(np.array_equal(sent[wall][0], expected_ids))
                    self.assertEqual(sorted_rows(sent[wall][1]), sorted_rows(faces[expected_given]))
            dropped = [sent[wall][1][results[wall][0]] for wall in cut.walls[1::2]]
            final = remove_rows(np.array(after_even), np.concatenate(dropped)) + [
                row for wall in cut.walls[1::2] for row in results[wall][1].tolist()]
            self.assertEqual(stitching.faces().tolist(), final)  # in the C loop's order too
            self.assertTrue(np.array_equal(np.sort(np.concatenate(stitching.outliers)), outliers))
        self.assertGreater(early, 0)  # some stitches were sent before every task was done


def remove_rows(faces, removed):
    """The rows of `faces` that are not rows of `removed` (a face two stitches of a half both drop goes once),
    as a list."""
    gone = set(sorted_rows(removed))
    return [row for row in np.asarray(faces).tolist() if tuple(row) not in gone]


@unittest.skipIf(distributed is None, MISSING if distributed is None else "")
class Distributed(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.points = torus(6000)
        cls.reference = c_loop(cls.points, TILES)
        cls.cluster, cls.client = local_cluster(2)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.cluster.close()

    def run_on(self, client):
        return dbrg_distributed.reconstruct(self.points, tiles=TILES, client=client, progress=False)

    def test_the_faces_of_the_c_loop(self):
        self.assertEqual(len(dbrg_distributed.plan(self.points, TILES).walls), 3)
        started = time.monotonic()
        mesh = self.run_on(self.client)
        elapsed = time.monotonic() - started
        self.assertTrue(np.array_equal(mesh.triangles, self.reference.triangles))
        self.assertEqual(len(mesh.boundary_loops), len(self.reference.boundary_loops))
        # The statistics are the C loop's: the tiles' and stitches' added to the assembly's. Times and the
        # driver's own memory peak are the run's own.
        self.assertEqual(mesh.stats["tiles"], TILES)
        self.assertGreater(mesh.stats["tetrahedra"], 0)
        # (A piece's peak is its call's, with the result; the loop counts its working memory alone.)
        for name, value in self.reference.stats.items():
            if not name.startswith("seconds_") and name not in ("peak_bytes", "tile_peak_bytes"):
                self.assertEqual(mesh.stats[name], value, name)
        self.assertGreater(mesh.stats["tile_peak_bytes"], 0)
        # seconds_total is the whole run's on the driver: at least half the pieces' work, on two workers.
        self.assertLessEqual(mesh.stats["seconds_total"], elapsed)
        pieces_work = mesh.stats["seconds_delaunay"] + mesh.stats["seconds_grow"]
        self.assertGreaterEqual(mesh.stats["seconds_total"], pieces_work / 2)

    def test_the_outliers_of_the_c_loop(self):
        # Points far above and below the torus (20 spacings and more): each tile lists those of its core, the
        # assembly gets them, and no stitch grows over them.
        grid = np.array([(x, y, z) for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0) for z in (-1.2, 1.2)])
        points = np.concatenate([self.points, grid])
        reference = c_loop(points, TILES)
        mesh = dbrg_distributed.reconstruct(points, tiles=TILES, client=self.client, progress=False)
        self.assertEqual(reference.outliers.tolist(), list(range(len(self.points), len(points))))
        self.assertTrue(np.array_equal(mesh.outliers, reference.outliers))
        self.assertEqual(mesh.stats["outliers"], len(grid))
        self.assertTrue(np.array_equal(mesh.triangles, reference.triangles))
        self.assertFalse(np.isin(mesh.triangles, mesh.outliers).any())

    def test_a_bad_parameter_fails_before_any_task(self):
        with self.assertRaises(dbrg.InvalidParameterError) as raised:
            dbrg_distributed.reconstruct(self.points, tiles=TILES, client=self.client, progress=False,
                                         boundary_factor=0.5)
        self.assertIn("boundary_factor", raised.exception.message)
        self.assertEqual(self.client.who_has(), {})  # nothing was submitted
        with self.assertRaises(TypeError):
            dbrg_distributed.reconstruct(self.points, client=self.client, threads=2)

    @unittest.skipUnless(platform.libc_ver()[0] == "glibc" and not os.environ.get("LD_PRELOAD"),
                         "the allocator settings and the chunk header read here are glibc malloc's")
    def test_tasks_set_the_allocator_on_a_cluster_started_by_hand(self):
        # A plain LocalCluster: its worker starts with Dask's MALLOC_TRIM_THRESHOLD_, large blocks mapped alone,
        # and still after one was freed (glibc's defaults would raise the threshold past it then).
        cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0")
        client = Client(cluster)
        try:
            for _ in range(2):
                self.assertEqual(list(client.run(block_mapped_alone).values()), [True])
            mesh = self.run_on(client)
            self.assertEqual(list(client.run(block_mapped_alone).values()), [False])
        finally:
            client.close()
            cluster.close()
        self.assertTrue(np.array_equal(mesh.triangles, self.reference.triangles))

    def test_one_worker_gives_what_two_give(self):
        cluster, client = local_cluster(1)
        try:
            mesh = self.run_on(client)
        finally:
            client.close()
            cluster.close()
        self.assertTrue(np.array_equal(mesh.triangles, self.reference.triangles))

    def test_tasks_done_in_another_order(self):
        with tempfile.TemporaryDirectory() as folder:
            log = os.path.join(folder, "tiles")
            open(log, "w").close()
            cluster, client = local_cluster(TILES)  # a worker for each tile, so that they run side by side
            try:
                client.register_worker_plugin(HoldEarlyTasks(log))
                mesh = self.run_on(client)
            finally:
                client.close()
                cluster.close()
            with open(log) as lines:
                events = [line.split() for line in lines]
        for kind, count in (("tile_task", TILES), ("stitch_task", TILES - 1)):
            started = [key for event, key in events if event == "executing" and key.startswith(kind)]
            finished = [key for event, key in events if event == "memory" and key.startswith(kind)]
            self.assertEqual(len(finished), count)
            if kind == "tile_task":  # 3 stitches, the last waiting for the other two: little order to change
                self.assertNotEqual(started, finished)
        self.assertTrue(np.array_equal(mesh.triangles, self.reference.triangles))

    def test_a_worker_killed_in_the_middle_of_a_tile(self):
        with tempfile.TemporaryDirectory() as folder:
            marker = os.path.join(folder, "killed")
            cluster, client = local_cluster(2)
            try:
                client.register_worker_plugin(KillOnFirstTile(marker))
                mesh = self.run_on(client)
            finally:
                client.close()
                cluster.close()
            self.assertTrue(os.path.exists(marker))  # a worker did die running a tile
        self.assertTrue(np.array_equal(mesh.triangles, self.reference.triangles))

    @unittest.skipUnless(os.access(program_path(), os.X_OK), "no dbrg program at %s (set DBRG_PROGRAM)" % program_path())
    def test_the_command_line(self):
        with tempfile.TemporaryDirectory() as folder:
            source = os.path.join(folder, "torus.xyz")
            np.savetxt(source, self.points, fmt="%.17g")
            meshes = {}
            for name, command in (
                    ("program", [program_path(), "reconstruct", source, "--tiles", str(TILES)]),
                    ("dask", [sys.executable, "-m", "dbrg", "reconstruct", source, "--tiles", str(TILES),
                              "--distributed", "--workers", "1"])):
                output = os.path.join(folder, name + ".obj")
                subprocess.run(command + ["-o", output, "-q", "--no-normals"], check=True, timeout=120)
                with open(output) as mesh:
                    meshes[name] = [line for line in mesh if line.startswith("f ")]
        self.assertGreater(len(meshes["dask"]), 0)
        self.assertEqual(meshes["dask"], meshes["program"])


if __name__ == "__main__":
    unittest.main()
