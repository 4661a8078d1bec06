"""Mesh.to_open3d and Mesh.to_trimesh: the same vertices, triangles and normals in the other package's mesh
type, where that package is installed; an ImportError naming it where it is not."""

import importlib.util
import sys
import unittest
from unittest import mock

import numpy as np

import dbrg
from _support import fibonacci_sphere


def installed(package):
    return importlib.util.find_spec(package) is not None


def sphere_with_a_point_inside():
    """A closed sphere and one point left out of it: the conversions keep it, unused, at its index."""
    points = np.vstack([fibonacci_sphere(400), [[0.0, 0.0, 0.01]]])
    mesh = dbrg.reconstruct(points)
    assert 400 in mesh.unused_points
    return mesh


class MissingPackages(unittest.TestCase):
    def test_a_missing_package_is_named(self):
        mesh = dbrg.reconstruct(fibonacci_sphere(100))
        for package, convert in (("open3d", mesh.to_open3d), ("trimesh", mesh.to_trimesh)):
            # None in sys.modules makes `import package` fail, installed or not.
            with mock.patch.dict(sys.modules, {package: None}):
                with self.assertRaises(ImportError) as caught:
                    convert()
            self.assertIn("needs the %s package" % package, str(caught.exception))
            self.assertIn("pip install %s" % package, str(caught.exception))
            self.assertEqual(caught.exception.name, package)


@unittest.skipUnless(installed("open3d"), "open3d is not installed (pip install open3d; Debian: python3-open3d)")
class Open3D(unittest.TestCase):
    def test_vertices_triangles_and_normals(self):
        import open3d
        mesh = sphere_with_a_point_inside()
        converted = mesh.to_open3d()
        self.assertIsInstance(converted, open3d.geometry.TriangleMesh)
        np.testing.assert_array_equal(np.asarray(converted.vertices), mesh.vertices)
        np.testing.assert_array_equal(np.asarray(converted.triangles), mesh.triangles)
        self.assertTrue(converted.has_vertex_normals())
        np.testing.assert_array_equal(np.asarray(converted.vertex_normals), mesh.vertex_normals)
        # Open3D's own checks agree that the surface is closed, manifold and consistently oriented.
        converted.remove_unreferenced_vertices()
        self.assertTrue(converted.is_edge_manifold() and converted.is_vertex_manifold())
        self.assertTrue(converted.is_watertight() and converted.is_orientable())
        self.assertEqual(len(converted.vertices), 400)


@unittest.skipUnless(installed("trimesh"), "trimesh is not installed (pip install trimesh)")
class Trimesh(unittest.TestCase):
    def test_vertices_triangles_and_normals(self):
        import trimesh
        mesh = sphere_with_a_point_inside()
        converted = mesh.to_trimesh()
        self.assertIsInstance(converted, trimesh.Trimesh)
        np.testing.assert_array_equal(converted.vertices, mesh.vertices)
        np.testing.assert_array_equal(converted.faces, mesh.triangles)
        np.testing.assert_allclose(converted.vertex_normals, mesh.vertex_normals, atol=1e-6)
        # trimesh's own checks: closed, consistently wound, and facing outward (positive volume).
        self.assertTrue(converted.is_watertight and converted.is_winding_consistent)
        self.assertGreater(converted.volume, 0)


if __name__ == "__main__":
    unittest.main()
