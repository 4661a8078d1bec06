"""The dbrg program's files and exits: outputs replaced only when completely written, outputs checked before
any work, no abort, and the messages a user reads. Usage: python3 test_cli_files.py PATH_TO_DBRG"""
import json
import math
import os
import resource
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest

DBRG = None


def run(*args, limit_file_bytes=None, limit_memory_bytes=None, timeout=120):
    """Runs dbrg; returns (exit code, stdout, stderr). Limits apply to the child only."""
    def limits():
        if limit_file_bytes is not None:
            # A write past the limit fails with EFBIG, as on a full disk, instead of killing the process.
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_file_bytes, limit_file_bytes))
        if limit_memory_bytes is not None:
            resource.setrlimit(resource.RLIMIT_AS, (limit_memory_bytes, limit_memory_bytes))
    done = subprocess.run([DBRG, *args], capture_output=True, text=True, timeout=timeout, preexec_fn=limits)
    return done.returncode, done.stdout, done.stderr


class Folder(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.dir = self.folder.name

    def tearDown(self):
        self.folder.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def demo(self, output, points=2000, *extra):
        return run("reconstruct", "--demo", "--demo-points", str(points), "-q", "-o", output, *extra)

    def assert_no_temporaries(self):
        self.assertEqual([name for name in os.listdir(self.dir) if name.startswith(".")], [])


class FailedWrites(Folder):
    """A write that fails (here: a file size limit, as a full disk) leaves the old file as it was."""

    def test_failed_mesh_write_keeps_the_old_file(self):
        target = self.path("prev.ply")
        self.assertEqual(self.demo(target)[0], 0)
        os.chmod(target, 0o640)
        with open(target, "rb") as f:
            before = f.read()
        code, _, err = run("reconstruct", "--demo", "--demo-points", "6000", "-q", "-o", target,
                           limit_file_bytes=len(before) // 2)
        self.assertEqual(code, 1)
        self.assertIn("prev.ply", err)
        self.assertIn("File too large", err)
        with open(target, "rb") as f:
            self.assertEqual(f.read(), before)
        self.assertEqual(stat.S_IMODE(os.stat(target).st_mode), 0o640)
        self.assert_no_temporaries()

    def test_replaced_file_keeps_its_permissions(self):
        target = self.path("prev.obj")
        self.assertEqual(self.demo(target)[0], 0)
        os.chmod(target, 0o604)
        self.assertEqual(self.demo(target, 3000)[0], 0)
        self.assertEqual(stat.S_IMODE(os.stat(target).st_mode), 0o604)
        self.assert_no_temporaries()

    def test_failed_stats_json_write_keeps_the_old_file(self):
        stats = self.path("stats.json")
        with open(stats, "w") as f:
            f.write("{}\n" * 4000)
        code, _, err = run("reconstruct", "--demo", "--demo-points", "2000", "-q", "-o", self.path("x.off"),
                           "--stats-json", stats, limit_file_bytes=1000)
        self.assertEqual(code, 1)
        with open(stats) as f:
            self.assertEqual(f.read(), "{}\n" * 4000)
        self.assert_no_temporaries()

    def test_a_fifo_is_written_directly(self):
        fifo = self.path("stats.json")
        os.mkfifo(fifo)
        received = []
        def read_all():
            with open(fifo) as f:
                received.append(f.read())
        reader = threading.Thread(target=read_all)
        reader.start()
        code, _, _ = self.demo(self.path("x.ply"), 2000, "--stats-json", fifo)
        reader.join(60)
        self.assertEqual(code, 0)
        self.assertIn('"triangles"', received[0])
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))


class OutputsCheckedFirst(Folder):
    """Outputs that cannot be written are refused before the input is even read."""

    def test_missing_folder(self):
        code, _, err = run("reconstruct", self.path("no-such-input.xyz"), "-o", self.path("none/x.ply"))
        self.assertEqual(code, 1)
        self.assertIn("none/x.ply", err)
        self.assertIn("No such file or directory", err)
        self.assertNotIn("no-such-input", err)

    def test_output_is_a_folder(self):
        os.mkdir(self.path("d.ply"))
        code, _, err = self.demo(self.path("d.ply"))
        self.assertEqual(code, 1)
        self.assertIn("is a folder", err)

    def test_read_only_folder(self):
        if os.geteuid() == 0:
            self.skipTest("root writes into read-only folders")
        os.chmod(self.dir, 0o500)
        try:
            code, _, err = self.demo(self.path("x.ply"))
        finally:
            os.chmod(self.dir, 0o700)
        self.assertEqual(code, 1)
        self.assertIn("Permission denied", err)

    def test_delaunay_tets_names_the_reason_and_prints_no_report(self):
        points = self.path("p.xyz")
        with open(points, "w") as f:
            f.write("0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
        code, out, err = run("delaunay", points, "--tets", self.path("none/t.txt"))
        self.assertEqual(code, 1)
        self.assertEqual(out, "")
        self.assertIn("No such file or directory", err)
        code, out, _ = run("delaunay", points, "--tets", self.path("t.txt"))
        self.assertEqual(code, 0)
        self.assertIn('"tetrahedra": 1,', out)
        with open(self.path("t.txt")) as f:
            self.assertEqual(sorted(int(i) for i in f.read().split()), [0, 1, 2, 3])

    def test_stats_output_checked(self):
        mesh = self.path("m.off")
        self.assertEqual(self.demo(mesh)[0], 0)
        code, _, err = run("stats", mesh, "-o", self.path("none/s.json"))
        self.assertEqual(code, 1)
        self.assertIn("No such file or directory", err)


class RefusedOutputs(Folder):
    def test_xyz_cannot_hold_triangles(self):
        code, _, err = self.demo(self.path("x.xyz"))
        self.assertEqual(code, 2)
        self.assertIn("without the triangles", err)
        self.assertFalse(os.path.exists(self.path("x.xyz")))

    def test_las_is_not_written(self):
        code, _, err = self.demo(self.path("x.las"))
        self.assertEqual(code, 2)
        self.assertIn("LAS files are read, not written", err)
        self.assertFalse(os.path.exists(self.path("x.las")))

    def test_output_that_is_the_input(self):
        source = self.path("in.ply")
        self.assertEqual(self.demo(source)[0], 0)
        with open(source, "rb") as f:
            before = f.read()
        os.link(source, self.path("alias.ply"))
        for output in (source, os.path.join(self.dir, ".", "in.ply"), self.path("alias.ply")):
            code, _, err = run("reconstruct", source, "-q", "-o", output)
            self.assertEqual(code, 1, output)
            self.assertIn("is the input file", err)
        code, _, err = run("reconstruct", source, "-q", "-o", self.path("out.ply"), "--stats-json", source)
        self.assertEqual(code, 1)
        self.assertIn("is the input file", err)
        with open(source, "rb") as f:
            self.assertEqual(f.read(), before)


class NeverAbort(Folder):
    def test_demo_points_bounded(self):
        code, _, err = run("reconstruct", "--demo", "--demo-points", "4294967295", "-o", self.path("x.ply"))
        self.assertEqual(code, 2)
        self.assertIn("--demo-points takes a whole number from 4 to", err)

    @unittest.skipIf(os.environ.get("DBRG_SANITIZED") == "1", "sanitizers reserve more address space than the limit")
    def test_out_of_memory_is_a_message(self):
        # 100 million demo points need gigabytes; with 1 GiB of address space the sample cannot be made.
        code, _, err = run("reconstruct", "--demo", "--demo-points", "100000000", "-q", "-o", self.path("x.ply"),
                           limit_memory_bytes=1 << 30)
        self.assertEqual(code, 1, err)
        self.assertIn("out of memory", err)
        self.assertGreater(code, 0)  # a signal would be negative


class EndlessInput(Folder):
    def test_an_endless_stream_of_zero_bytes_fails_at_once(self):
        for name in ("zeros.ply", "zeros.xyz"):
            fifo = self.path(name)
            os.mkfifo(fifo)

            def feed():
                try:
                    with open(fifo, "wb") as f:
                        while True:
                            f.write(bytes(1 << 16))
                except (BrokenPipeError, OSError):
                    pass
            writer = threading.Thread(target=feed, daemon=True)
            writer.start()
            code, _, err = run("stats", fifo, timeout=30)
            self.assertEqual(code, 1, name)
            self.assertIn(name, err)
            self.assertTrue("zero byte" in err or "'ply'" in err, err)


class Messages(Folder):
    def test_tight_boundary_factor_warns(self):
        code, _, err = run("reconstruct", "--demo", "--demo-shape", "sphere", "--demo-points", "2000",
                           "--boundary-factor", "1.1", "-q", "-o", self.path("s.ply"),
                           "--stats-json", self.path("s.json"))
        self.assertEqual(code, 0)
        self.assertIn("warning: only", err)
        self.assertIn("boundary_factor", err)
        with open(self.path("s.json")) as f:
            self.assertRegex(f.read(), r'"unused_points": [1-9]')
        code, _, err = run("reconstruct", "--demo", "--demo-shape", "sphere", "--demo-points", "2000", "-q",
                           "-o", self.path("s.ply"))
        self.assertEqual((code, err), (0, ""))

    def test_sliver_angle_in_degrees(self):
        code, _, err = self.demo(self.path("s.ply"), 2000, "--sliver-angle", "200")
        self.assertEqual(code, 2)
        self.assertIn("degrees strictly between 90 and 180", err)
        self.assertNotIn("radian", err)

    def test_non_finite_point_names_the_file_and_line(self):
        # The library knows the point by its index alone; the reader knows its line. Normals are not judged.
        samples = {
            "pts.xyz": ["# a scan", "0 0 0", "1 0 0", "0 nan 0", "0 0 1", "1 1 1"],
            "mesh.obj": ["# made by hand", "# four points", "vn nan 0 0", "v 0 0 0", "v 1 0 0", "v 0 1 0",
                         "v inf 0 0", "v 1 1 1", "f 1 2 3"],
        }
        for name, lines in samples.items():
            path = self.path(name)
            with open(path, "w") as f:
                f.write("\n".join(lines) + "\n")
            vertex_lines = [(number, line.split()[-3:]) for number, line in enumerate(lines, 1)
                            if line.startswith("v ") or (name.endswith(".xyz") and not line.startswith("#"))]
            expected = next(
                f"point {point} has {'a NaN' if math.isnan(float(value)) else 'an infinite'} {'xyz'[axis]} coordinate"
                f" ({path} line {number})"
                for point, (number, values) in enumerate(vertex_lines)
                for axis, value in enumerate(values) if not math.isfinite(float(value)))
            commands = [("reconstruct", path, "-q", "-o", self.path("out.ply")), ("delaunay", path)]
            for command in commands:
                code, _, err = run(*command)
                self.assertEqual(code, 1, err)
                self.assertEqual(err, f"dbrg: DBRG_ERR_NON_FINITE_INPUT: {expected}\n")

    def test_help_lists_every_input_format(self):
        code, out, _ = run("reconstruct", "--help")
        self.assertEqual(code, 0)
        for extension in (".ply", ".obj", ".off", ".stl", ".xyz", ".pts", ".las"):
            self.assertIn(extension, out.split("writes it")[0])


def read_obj(path):
    """(positions, normals, faces) of an OBJ the program wrote; a face is a list of (v, vn) 0-based pairs
    (vn None when the corner names no normal)."""
    positions, normals, faces = [], [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "v":
                positions.append(tuple(float(w) for w in words[1:4]))
            elif words and words[0] == "vn":
                normals.append(tuple(float(w) for w in words[1:4]))
            elif words and words[0] == "f":
                corners = [corner.split("//") for corner in words[1:]]
                faces.append([(int(c[0]) - 1, int(c[1]) - 1 if len(c) > 1 else None) for c in corners])
    return positions, normals, faces


def sphere_points(count):
    """`count` points on the unit sphere (golden-angle spiral)."""
    points = []
    for i in range(count):
        z = 1 - 2 * (i + 0.5) / count
        r, angle = math.sqrt(1 - z * z), math.pi * (1 + 5 ** 0.5) * i
        points.append((r * math.cos(angle), r * math.sin(angle), z))
    return points


def write_las(path, records, scale=0.001, offset=(1000.0, 2000.0, 0.0)):
    """A LAS 1.2 file of point format 2 (ASPRS layout): records are (X, Y, Z, intensity, red, green, blue)
    integers; positions are X * scale + offset."""
    header = b"LASF" + bytes(20) + bytes([1, 2]) + bytes(64) + struct.pack("<HH", 1, 2024)
    header += struct.pack("<HIIBHI", 227, 227, 0, 2, 26, len(records)) + bytes(20)
    header += struct.pack("<3d", scale, scale, scale) + struct.pack("<3d", *offset) + bytes(48)
    assert len(header) == 227
    with open(path, "wb") as f:
        f.write(header + b"".join(struct.pack("<3iH6x3H", *r) for r in records))


def read_binary_ply_vertices(path):
    """(property names, one tuple of values per vertex) of a binary little-endian PLY's vertex element."""
    types = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f", "double": "d"}
    with open(path, "rb") as f:
        data = f.read()
    header, body = data.split(b"end_header\n", 1)
    names, codes, count, in_vertex = [], "", 0, False
    for line in header.decode().splitlines():
        words = line.split()
        if words[0] == "element":
            in_vertex = words[1] == "vertex"
            count = int(words[2]) if in_vertex else count
        elif words[0] == "property" and in_vertex:
            names.append(words[2])
            codes += types[words[1]]
    record = struct.Struct("<" + codes)
    return names, [record.unpack_from(body, i * record.size) for i in range(count)]


def ply_header(path):
    with open(path, "rb") as f:
        return f.read().split(b"end_header\n")[0].decode()


def read_binary_ply_face_flags(path):
    """The 'flags' byte of each face of a binary little-endian PLY the program wrote (faces of 3 uint
    corners, then uchar flags)."""
    names, vertices = read_binary_ply_vertices(path)
    header = ply_header(path)
    codes = {"double": "d", "float": "f"}
    vertex = struct.Struct("<" + "".join(codes[line.split()[1]] for line in header.splitlines()
                                         if line.startswith("property") and line.split()[2] in names))
    face_count = int(next(line.split()[2] for line in header.splitlines() if line.startswith("element face")))
    assert "property list uchar uint vertex_indices\nproperty uchar flags" in header
    with open(path, "rb") as f:
        body = f.read().split(b"end_header\n", 1)[1]
    start = vertex.size * len(vertices)
    return [body[start + 14 * t + 13] for t in range(face_count)]


class Interrupts(Folder):
    """Ctrl-C cancels a reconstruction: exit status 130, no output, no temporary files (docs/tiles.md)."""

    def interrupt(self, args, ready):
        """Runs dbrg with `args`, sends SIGINT once ready() holds; returns (exit code, stderr)."""
        child = subprocess.Popen([DBRG, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        try:
            for _ in range(12000):
                if ready() or child.poll() is not None:
                    break
                time.sleep(0.005)
            if child.poll() is not None:
                self.skipTest("the run ended before it could be interrupted")
            child.send_signal(signal.SIGINT)
            _, stderr = child.communicate(timeout=120)
        finally:
            if child.poll() is None:
                child.kill()
                child.wait()
        return child.returncode, stderr

    def test_out_of_core_run_removes_its_bucket_files(self):
        cloud = self.path("cloud.xyz")
        with open(cloud, "w") as f:
            f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in sphere_points(300_000))
        code, stderr = self.interrupt(
            ["reconstruct", cloud, "-o", self.path("mesh.ply"), "--max-memory", "64M", "-q"],
            ready=lambda: any(name.startswith(".out.dbrg-tiles-") for name in os.listdir(self.dir)))
        self.assertEqual(code, 128 + signal.SIGINT, stderr)
        self.assertIn("dbrg: interrupted; no output written", stderr)
        self.assertEqual(os.listdir(self.dir), ["cloud.xyz"])

    def test_reconstruction_writes_nothing(self):
        started = time.monotonic()
        code, stderr = self.interrupt(
            ["reconstruct", "--demo", "--demo-points", "400000", "-o", self.path("mesh.ply"), "-q"],
            ready=lambda: time.monotonic() - started > 1.0)
        self.assertEqual(code, 128 + signal.SIGINT, stderr)
        self.assertIn("dbrg: interrupted; no output written", stderr)
        self.assertEqual(os.listdir(self.dir), [])


class FaceFlags(Folder):
    """The faces hole filling made carry bit 0 of the PLY face property 'flags'; --stats-json counts them."""

    def test_filled_faces_are_flagged(self):
        code, _, err = run("reconstruct", "--demo", "--demo-shape", "torus", "--demo-points", "3000", "-q",
                           "--no-normals", "-o", self.path("torus.ply"))
        self.assertEqual(code, 0, err)
        _, vertices = read_binary_ply_vertices(self.path("torus.ply"))
        # Points taken out near one spot of the outer equator leave a hole that filling closes.
        kept = [v for v in vertices if (v[0] - 1.35) ** 2 + v[1] ** 2 + v[2] ** 2 > 0.2 ** 2]
        self.assertLess(len(kept), len(vertices))
        with open(self.path("holed.xyz"), "w") as f:
            f.writelines("%r %r %r\n" % v[:3] for v in kept)
        counts = {}
        for name, extra in (("filled", ()), ("open", ("--no-fill-holes",))):
            code, _, err = run("reconstruct", self.path("holed.xyz"), "-q", "-o", self.path(name + ".ply"),
                               "--stats-json", self.path(name + ".json"), *extra)
            self.assertEqual(code, 0, err)
            flags = read_binary_ply_face_flags(self.path(name + ".ply"))
            with open(self.path(name + ".json")) as f:
                stats = json.load(f)
            self.assertEqual(len(flags), stats["triangles"])
            self.assertEqual(sum(1 for b in flags if b & 1), stats["faces_filled"])
            self.assertTrue(all(b & ~1 == 0 for b in flags))
            counts[name] = (stats["faces_filled"], stats["holes_filled"])
        self.assertGreater(counts["filled"][1], 0)
        self.assertGreater(counts["filled"][0], 0)
        self.assertEqual(counts["open"][0], 0)


class ViewerOutput(Folder):
    """Vertex normals on by default in .ply and .obj, --no-normals, --drop-unused, float in gives float out."""

    def sphere(self, output, *extra):
        code, _, err = run("reconstruct", "--demo", "--demo-shape", "sphere", "--demo-points", "1500", "-q",
                           "-o", output, *extra)
        self.assertEqual(code, 0, err)

    def test_obj_normals_are_unit_and_outward(self):
        self.sphere(self.path("s.obj"))
        positions, normals, faces = read_obj(self.path("s.obj"))
        self.assertEqual(len(normals), len(positions))
        centre = [sum(p[k] for p in positions) / len(positions) for k in range(3)]
        for p, n in zip(positions, normals):
            self.assertAlmostEqual(math.hypot(*n), 1.0, places=5)
            self.assertGreater(sum((p[k] - centre[k]) * n[k] for k in range(3)), 0.0)
        self.assertTrue(all(v == vn for face in faces for v, vn in face))

    def test_ply_normals_by_default_and_none_when_asked(self):
        self.sphere(self.path("s.ply"))
        self.assertIn("property float nx\nproperty float ny\nproperty float nz", ply_header(self.path("s.ply")))
        self.sphere(self.path("plain.ply"), "--no-normals")
        self.assertNotIn("nx", ply_header(self.path("plain.ply")))
        self.sphere(self.path("plain.obj"), "--no-normals")
        positions, normals, faces = read_obj(self.path("plain.obj"))
        self.assertEqual(normals, [])
        self.assertTrue(all(vn is None for face in faces for _, vn in face))

    def test_drop_unused_keeps_the_same_triangles(self):
        # A boundary factor this tight leaves most points out of the surface.
        tight = ("--boundary-factor", "1.1")
        self.sphere(self.path("all.obj"), *tight)
        self.sphere(self.path("used.obj"), *tight, "--drop-unused")
        all_positions, _, all_faces = read_obj(self.path("all.obj"))
        positions, normals, faces = read_obj(self.path("used.obj"))
        used = {v for face in faces for v, _ in face}
        self.assertEqual(used, set(range(len(positions))))
        self.assertLess(len(positions), len(all_positions))
        self.assertEqual(len(normals), len(positions))
        by_position = lambda points, face: [points[v] for v, _ in face]
        self.assertEqual([by_position(positions, face) for face in faces],
                         [by_position(all_positions, face) for face in all_faces])
        # The kept vertices are in their input order.
        order = [all_positions.index(p) for p in positions]
        self.assertEqual(order, sorted(order))

    def test_las_input(self):
        scale, offset = 0.001, (1000.0, 2000.0, 0.0)
        records = [(round(x * 1000), round(y * 1000), round(z * 1000), 7 * i, i, 2 * i, 3 * i)
                   for i, (x, y, z) in enumerate(sphere_points(600))]
        write_las(self.path("scan.las"), records, scale, offset)
        code, _, err = run("reconstruct", self.path("scan.las"), "-q", "-o", self.path("out.obj"))
        self.assertEqual(code, 0, err)
        positions, _, faces = read_obj(self.path("out.obj"))
        self.assertEqual(positions, [tuple(r[k] * scale + offset[k] for k in range(3)) for r in records])
        self.assertGreater(len(faces), len(records))

    def test_colours_and_other_properties_are_carried(self):
        # Three points inside the sphere, which the surface leaves out.
        points = sphere_points(700) + [(0.0, 0.0, 0.0), (0.1, 0.05, 0.02), (0.3, -0.2, 0.1)]
        colour = lambda i: (i % 256, (7 * i) % 256, (13 * i) % 256, 255 - i % 256)
        rows = [f"{x!r} {y!r} {z!r} {' '.join(map(str, colour(i)))} 0 0 1 {i / 3!r} {i * 11}"
                for i, (x, y, z) in enumerate(points)]
        source = self.path("coloured.ply")
        with open(source, "w") as f:
            f.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\nproperty double x\nproperty double y\n"
                    "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                    "property uchar alpha\nproperty float nx\nproperty float ny\nproperty float nz\n"
                    "property double confidence\nproperty int label\nend_header\n" + "\n".join(rows) + "\n")
        by_position = {p: i for i, p in enumerate(points)}
        for extra in ((), ("--drop-unused",)):
            code, _, err = run("reconstruct", source, "-q", "-o", self.path("out.ply"), *extra)
            self.assertEqual(code, 0, err)
            names, vertices = read_binary_ply_vertices(self.path("out.ply"))
            self.assertEqual(names, ["x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "alpha", "confidence", "label"])
            self.assertIn("property uchar red", ply_header(self.path("out.ply")))
            if extra:
                self.assertLess(len(vertices), len(points))
            else:
                self.assertEqual(len(vertices), len(points))
            for vertex in vertices:
                i = by_position[vertex[:3]]
                self.assertEqual(vertex[6:10], colour(i))
                self.assertEqual(vertex[10:], (i / 3, i * 11))
                # The surface's normal, not the input's (0, 0, 1): outward on the sphere, none off it.
                if i < 700:
                    self.assertGreater(sum(vertex[k] * vertex[3 + k] for k in range(3)), 0.0)
                else:
                    self.assertEqual(vertex[3:6], (0.0, 0.0, 0.0))

    def test_las_intensity_and_colour_are_carried(self):
        records = [(round(x * 1000), round(y * 1000), round(z * 1000), 7 * i, i, 2 * i, 3 * i)
                   for i, (x, y, z) in enumerate(sphere_points(600))]
        write_las(self.path("scan.las"), records)
        code, _, err = run("reconstruct", self.path("scan.las"), "-q", "-o", self.path("out.ply"))
        self.assertEqual(code, 0, err)
        names, vertices = read_binary_ply_vertices(self.path("out.ply"))
        self.assertEqual(names[6:], ["intensity", "red", "green", "blue"])
        self.assertIn("property ushort intensity", ply_header(self.path("out.ply")))
        self.assertEqual([v[6:] for v in vertices], [r[3:] for r in records])

    def test_float_input_gives_float_output(self):
        code, _, err = run("reconstruct", "--demo", "--demo-shape", "sphere", "--demo-points", "800", "-q",
                           "-o", self.path("double.ply"))
        self.assertEqual(code, 0, err)
        self.assertIn("property double x", ply_header(self.path("double.ply")))
        # Points on a sphere stored as float32 (golden-angle spiral) give float32 positions out.
        count = 800
        rows = []
        for i in range(count):
            z = 1 - 2 * (i + 0.5) / count
            r, angle = math.sqrt(1 - z * z), math.pi * (1 + 5 ** 0.5) * i
            rows.append(struct.pack("<3f", r * math.cos(angle), r * math.sin(angle), z))
        points = self.path("points.ply")
        with open(points, "wb") as f:
            f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % count)
            f.write(b"property float x\nproperty float y\nproperty float z\nend_header\n" + b"".join(rows))
        code, _, err = run("reconstruct", points, "-q", "-o", self.path("float.ply"))
        self.assertEqual(code, 0, err)
        self.assertIn("property float x\nproperty float y\nproperty float z\n", ply_header(self.path("float.ply")))

if __name__ == "__main__":
    DBRG = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
