"""dbrg.read_points: the project's own readers (libdbrg_io) give the points and their per-point attributes;
Mesh.unused_points."""

import os
import struct
import tempfile
import unittest

import numpy as np

import dbrg
from _support import fibonacci_sphere


def write_las(path, records, scale, offset):
    """A LAS 1.2 file of point format 3 (GPS time and colour), laid out as the ASPRS specification says:
    records are (X, Y, Z, intensity, red, green, blue) integers, positions X * scale + offset."""
    header = b"LASF" + bytes(20) + bytes([1, 2]) + bytes(64) + struct.pack("<HH", 1, 2024)
    header += struct.pack("<HIIBHI", 227, 227, 0, 3, 34, len(records)) + bytes(20)
    header += struct.pack("<3d", *scale) + struct.pack("<3d", *offset) + bytes(48)
    with open(path, "wb") as f:
        f.write(header + b"".join(struct.pack("<3iH6xd3H", *r[:4], 0.0, *r[4:]) for r in records))


class ReadPoints(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.folder.cleanup()

    def path(self, name):
        return os.path.join(self.folder.name, name)

    def test_ply_vertex_properties_with_their_names_and_types(self):
        with open(self.path("c.ply"), "w") as f:
            f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float confidence\n"
                    "property float nx\nproperty float ny\nproperty float nz\nproperty int label\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0.1 0.2 0.3 255 0 7 0.5 0 0 1 -4\n1 2 3 1 2 3 0.25 0 1 0 70000\n4 5 6.5 9 8 7 1 1 0 0 0\n"
                    "3 0 1 2\n")
        points, attributes = dbrg.read_points(self.path("c.ply"))
        self.assertEqual((points.shape, points.dtype), ((3, 3), np.float64))
        np.testing.assert_array_equal(points, [[0.1, 0.2, 0.3], [1, 2, 3], [4, 5, 6.5]])
        self.assertEqual(list(attributes), ["red", "green", "blue", "confidence", "label", "nx", "ny", "nz"])
        self.assertEqual(attributes["red"].dtype, np.uint8)
        np.testing.assert_array_equal(attributes["red"], [255, 1, 9])
        np.testing.assert_array_equal(attributes["blue"], [7, 3, 7])
        self.assertEqual(attributes["confidence"].dtype, np.float32)
        np.testing.assert_array_equal(attributes["confidence"], np.float32([0.5, 0.25, 1]))
        self.assertEqual(attributes["label"].dtype, np.int32)
        np.testing.assert_array_equal(attributes["label"], [-4, 70000, 0])
        np.testing.assert_array_equal(attributes["nz"], np.float32([1, 0, 0]))

    def test_las_positions_intensity_and_colour(self):
        scale, offset = (0.01, 0.001, 0.25), (500000.0, 4e6, -10.0)
        records = [(0, 0, 0, 0, 0, 0, 0), (123456, -7, 2**31 - 1, 65535, 256, 512, 65535), (-5, 5, -2**31, 3, 1, 2, 3)]
        write_las(self.path("scan.las"), records, scale, offset)
        points, attributes = dbrg.read_points(self.path("scan.las"))
        np.testing.assert_array_equal(points, [[r[k] * scale[k] + offset[k] for k in range(3)] for r in records])
        self.assertEqual(list(attributes), ["intensity", "red", "green", "blue"])
        for k, name in enumerate(["intensity", "red", "green", "blue"]):
            self.assertEqual(attributes[name].dtype, np.uint16)
            np.testing.assert_array_equal(attributes[name], [r[3 + k] for r in records])

    def test_a_written_mesh_reads_back_as_its_vertices(self):
        mesh = dbrg.reconstruct(fibonacci_sphere(300))
        for name in ("m.ply", "m.obj", "m.xyz"):
            mesh.write(self.path(name))
            points, attributes = dbrg.read_points(self.path(name))
            np.testing.assert_array_equal(points, mesh.vertices)
            if name == "m.ply":
                np.testing.assert_array_equal(np.stack([attributes[a] for a in ("nx", "ny", "nz")], axis=1),
                                              mesh.vertex_normals)

    def test_errors(self):
        with self.assertRaisesRegex(ValueError, "decompress it to .las first"):
            dbrg.read_points(self.path("scan.laz"))
        with self.assertRaisesRegex(ValueError, "unknown file type"):
            dbrg.read_points(self.path("scan.docx"))
        with self.assertRaisesRegex(OSError, "No such file"):
            dbrg.read_points(self.path("missing.ply"))
        with open(self.path("bad.xyz"), "w") as f:
            f.write("0 0 0\n1 2 three\n")
        with self.assertRaisesRegex(OSError, "bad.xyz.*line 2"):
            dbrg.read_points(self.path("bad.xyz"))
        with open(self.path("empty.xyz"), "w"):
            pass
        points, attributes = dbrg.read_points(self.path("empty.xyz"))
        self.assertEqual((points.shape, attributes), ((0, 3), {}))


class UnusedPoints(unittest.TestCase):
    def test_the_points_no_triangle_uses(self):
        points = np.vstack([fibonacci_sphere(400), [[0.0, 0.0, 0.01]], [[0.1, 0.0, 0.0]]])  # two inside, left out
        mesh = dbrg.reconstruct(points)
        self.assertEqual(mesh.unused_points.dtype, np.uint32)
        np.testing.assert_array_equal(mesh.unused_points, [400, 401])
        used = set(mesh.triangles.ravel().tolist())
        self.assertEqual(set(range(len(points))) - used, {400, 401})


if __name__ == "__main__":
    unittest.main()
