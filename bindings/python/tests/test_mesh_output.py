"""Mesh.vertices, Mesh.vertex_normals and Mesh.write: the project's own writers and normals (libdbrg_io)."""

import os
import tempfile
import unittest

import numpy as np

import dbrg
from _support import fibonacci_sphere, paraboloid_patch


class VerticesAndNormals(unittest.TestCase):
    def test_vertices_are_a_copy_of_the_points_in_their_type(self):
        for dtype in (np.float32, np.float64):
            points = fibonacci_sphere(300, dtype=dtype)
            mesh = dbrg.reconstruct(points)
            self.assertEqual(mesh.vertices.dtype, dtype)
            np.testing.assert_array_equal(mesh.vertices, points)
            points[0] = 9  # the mesh keeps its own copy
            self.assertNotEqual(mesh.vertices[0, 0], 9)

    def test_strided_points_give_packed_vertices(self):
        wide = np.hstack([fibonacci_sphere(300), np.ones((300, 2))])
        mesh = dbrg.reconstruct(wide[:, :3])
        self.assertEqual(mesh.vertices.shape, (300, 3))
        np.testing.assert_array_equal(mesh.vertices, wide[:, :3])

    def test_normals_of_a_closed_sphere_are_unit_and_outward(self):
        mesh = dbrg.reconstruct(fibonacci_sphere(500, radius=2.0))
        normals = mesh.vertex_normals
        self.assertEqual((normals.shape, normals.dtype), ((500, 3), np.float32))
        np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=1e-6)
        self.assertTrue((np.einsum("ij,ij->i", normals, mesh.vertices) > 0).all())

    def test_unused_vertices_have_zero_normals(self):
        points = np.vstack([fibonacci_sphere(400), [[0.0, 0.0, 0.01]]])  # a point inside, left out
        mesh = dbrg.reconstruct(points)
        used = np.zeros(len(points), dtype=bool)
        used[mesh.triangles.ravel()] = True
        self.assertFalse(used.all())
        self.assertTrue((mesh.vertex_normals[~used] == 0).all())


class Write(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.mesh = dbrg.reconstruct(paraboloid_patch(14))

    def tearDown(self):
        self.folder.cleanup()

    def path(self, name):
        return os.path.join(self.folder.name, name)

    def test_obj_holds_the_vertices_normals_and_triangles(self):
        self.mesh.write(self.path("patch.obj"))
        with open(self.path("patch.obj")) as f:
            lines = [line.split() for line in f]
        vertices = np.array([line[1:] for line in lines if line[0] == "v"], dtype=np.float64)
        normals = np.array([line[1:] for line in lines if line[0] == "vn"], dtype=np.float32)
        faces = [[corner.split("//") for corner in line[1:]] for line in lines if line[0] == "f"]
        np.testing.assert_array_equal(vertices, self.mesh.vertices)
        np.testing.assert_array_equal(normals, self.mesh.vertex_normals)
        self.assertTrue(all(v == vn for face in faces for v, vn in face))
        np.testing.assert_array_equal(np.array([[int(v) - 1 for v, _ in face] for face in faces]), self.mesh.triangles)

    def test_ply_header_and_size(self):
        self.mesh.write(self.path("patch.ply"))
        self.mesh.write(self.path("plain.ply"), normals=False)
        with open(self.path("patch.ply"), "rb") as f:
            data = f.read()
        header, body = data.split(b"end_header\n", 1)
        self.assertIn(b"element vertex %d\n" % len(self.mesh.vertices), header)
        self.assertIn(b"property float nx\nproperty float ny\nproperty float nz\n", header)
        self.assertIn(b"element face %d\n" % len(self.mesh.triangles), header)
        coordinate = 4 if b"property float x" in header else 8
        self.assertEqual(len(body), len(self.mesh.vertices) * (3 * coordinate + 12) + len(self.mesh.triangles) * 13)
        with open(self.path("plain.ply"), "rb") as f:
            self.assertNotIn(b"nx", f.read().split(b"end_header\n", 1)[0])

    def test_errors(self):
        with self.assertRaisesRegex(ValueError, "unknown file type"):
            self.mesh.write(self.path("patch.docx"))
        with self.assertRaisesRegex(OSError, "no-such-folder"):
            self.mesh.write(self.path(os.path.join("no-such-folder", "patch.ply")))


if __name__ == "__main__":
    unittest.main()
