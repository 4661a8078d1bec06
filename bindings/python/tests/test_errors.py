"""Bad input becomes a dbrg.Error subclass with the status name and the library's message."""

import unittest

import numpy as np

import dbrg
from _support import fibonacci_sphere

SPHERE = fibonacci_sphere(200)


class Errors(unittest.TestCase):
    def assert_error(self, points, kind, status, *fragments):
        with self.assertRaises(kind) as caught:
            dbrg.reconstruct(points)
        error = caught.exception
        self.assertIsInstance(error, dbrg.Error)
        self.assertEqual(error.status, status)
        for fragment in fragments:
            self.assertIn(fragment, error.message)
        self.assertIn(status, str(error))
        return error

    def test_nan_names_the_point(self):
        points = SPHERE.copy()
        points[137, 1] = np.nan
        self.assert_error(points, dbrg.NonFiniteInputError, "DBRG_ERR_NON_FINITE_INPUT", "137", "NaN")

    def test_infinity_in_float32_names_the_point(self):
        points = SPHERE.astype(np.float32)
        points[42, 2] = np.inf
        self.assert_error(points, dbrg.NonFiniteInputError, "DBRG_ERR_NON_FINITE_INPUT", "42")

    def test_nan_in_a_strided_view_names_the_index_within_the_view(self):
        wide = np.zeros((len(SPHERE), 6))
        wide[:, :3] = SPHERE
        wide[:, 3:] = np.nan  # outside the view: never read
        wide[9, 0] = np.nan
        self.assert_error(wide[:, :3], dbrg.NonFiniteInputError, "DBRG_ERR_NON_FINITE_INPUT", "point 9")

    def test_too_few_points(self):
        self.assert_error(SPHERE[:3], dbrg.TooFewPointsError, "DBRG_ERR_TOO_FEW_POINTS", "3")

    def test_too_few_distinct_points(self):
        points = np.repeat(SPHERE[:3], 5, axis=0)
        self.assert_error(points, dbrg.TooFewPointsError, "DBRG_ERR_TOO_FEW_POINTS")

    def test_no_points(self):
        self.assert_error(np.empty((0, 3)), dbrg.TooFewPointsError, "DBRG_ERR_TOO_FEW_POINTS")

    def test_coplanar_points_are_a_flat_surface_without_tetrahedra(self):
        rng = np.random.default_rng(3)
        plane = np.column_stack([rng.uniform(size=(50, 2)), np.full(50, 0.25)])
        self.assertGreater(len(dbrg.reconstruct(plane).triangles), 0)
        with self.assertRaises(dbrg.DegenerateInputError) as caught:
            dbrg.delaunay(plane)
        self.assertIn("coplanar", caught.exception.message)
        self.assertIsInstance(caught.exception, ValueError)

    def test_collinear_points(self):
        line = np.outer(np.linspace(0, 1, 20), [1.0, 2.0, 3.0])
        self.assert_error(line, dbrg.DegenerateInputError, "DBRG_ERR_DEGENERATE_INPUT")

    def test_shape_and_dtype_mistakes_are_python_errors(self):
        with self.assertRaises(ValueError):
            dbrg.reconstruct(np.zeros((10, 2)))
        with self.assertRaises(ValueError):
            dbrg.reconstruct(np.zeros(30))
        with self.assertRaises(TypeError):
            dbrg.reconstruct(np.array([["a", "b", "c"]] * 5))
        with self.assertRaises(TypeError):
            dbrg.reconstruct(SPHERE, progress="not callable")

    def test_validate_points(self):
        self.assertIsNone(dbrg.validate_points(SPHERE))
        points = SPHERE.copy()
        points[5, 0] = -np.inf
        with self.assertRaises(dbrg.NonFiniteInputError) as caught:
            dbrg.validate_points(points)
        self.assertIn("5", caught.exception.message)

    def test_errors_survive_pickling(self):
        import pickle
        error = pickle.loads(pickle.dumps(dbrg.TooFewPointsError("DBRG_ERR_TOO_FEW_POINTS", "3 points given")))
        self.assertEqual((error.status, error.message), ("DBRG_ERR_TOO_FEW_POINTS", "3 points given"))


if __name__ == "__main__":
    unittest.main()
