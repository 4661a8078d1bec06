"""dbrg.reconstruct on generated point sets: real results, every input layout, parameters, stats."""

import ctypes
import math
import unittest
import warnings

import numpy as np

import dbrg
from dbrg import _capi
from _support import (canonical_triangles, euler_characteristic, fibonacci_sphere, manifold_problems,
                      paraboloid_patch, signed_volume)

SPHERE = fibonacci_sphere(400)


class ClosedSphere(unittest.TestCase):
    def assert_closed_sphere(self, mesh, points):
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])
        self.assertEqual(euler_characteristic(mesh.triangles), 2)
        self.assertEqual(mesh.boundary_loops, [])
        self.assertGreater(signed_volume(points, mesh.triangles), 0, "a closed surface must face outward")
        self.assertEqual(len(np.unique(mesh.triangles)), len(points), "every sphere point lies on the surface")

    def test_fibonacci_sphere_is_closed_oriented_genus_zero(self):
        mesh = dbrg.reconstruct(SPHERE)
        self.assertEqual(mesh.triangles.dtype, np.uint32)
        self.assertEqual(mesh.triangles.shape, (2 * len(SPHERE) - 4, 3))
        self.assertTrue(mesh.triangles.flags.c_contiguous and mesh.triangles.flags.owndata)
        self.assert_closed_sphere(mesh, SPHERE)
        self.assertEqual(mesh.point_count, len(SPHERE))

    def test_float32_input(self):
        points = SPHERE.astype(np.float32)
        array, view = dbrg._point_array(points)
        self.assertIs(array, points)
        self.assertEqual(view.type, _capi.ENUMS["dbrg_scalar_type"]["DBRG_FLOAT32"])
        self.assertEqual(view.stride_bytes, 12)
        self.assert_closed_sphere(dbrg.reconstruct(points), points)

    def test_python_lists_and_integers_are_converted(self):
        cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
        mesh = dbrg.reconstruct(cube)
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])
        self.assertEqual(len(mesh.triangles), 12)

    def test_stats_carry_every_field(self):
        mesh = dbrg.reconstruct(SPHERE)
        names = [name for name, _ in _capi.dbrg_stats._fields_ if name != "struct_size"]
        self.assertEqual(list(mesh.stats), names)
        self.assertEqual(mesh.stats["input_points"], len(SPHERE))
        self.assertEqual(mesh.stats["unique_points"], len(SPHERE))
        self.assertEqual(mesh.stats["triangles"], len(mesh.triangles))
        self.assertEqual(mesh.stats["vertices_used"], len(SPHERE))
        self.assertEqual(mesh.stats["boundary_edges"], 0)
        self.assertGreater(mesh.stats["tetrahedra"], 0)
        self.assertGreater(mesh.stats["seconds_total"], 0.0)
        self.assertGreater(mesh.stats["peak_bytes"], 0)

    def test_duplicates_are_merged_to_the_smallest_index(self):
        points = np.concatenate([SPHERE, SPHERE[:10]])
        mesh = dbrg.reconstruct(points)
        self.assertEqual(mesh.stats["duplicates_merged"], 10)
        self.assertLess(int(mesh.triangles.max()), len(SPHERE))
        self.assertEqual(canonical_triangles(mesh.triangles), canonical_triangles(dbrg.reconstruct(SPHERE).triangles))


class Layouts(unittest.TestCase):
    """Strided arrays are read in place; other layouts are copied; the answer never changes."""

    reference = None

    @classmethod
    def setUpClass(cls):
        cls.reference = canonical_triangles(dbrg.reconstruct(SPHERE).triangles)

    def test_column_slice_of_a_wider_array_is_read_in_place(self):
        wide = np.full((len(SPHERE), 7), np.nan)
        wide[:, 2:5] = SPHERE
        columns = wide[:, 2:5]
        self.assertFalse(columns.flags.c_contiguous)
        array, view = dbrg._point_array(columns)
        self.assertIs(array, columns)
        self.assertEqual(view.data, columns.ctypes.data)
        self.assertEqual(view.stride_bytes, 7 * 8)
        self.assertEqual(canonical_triangles(dbrg.reconstruct(columns).triangles), self.reference)

    def test_every_other_row_of_float32_is_read_in_place(self):
        doubled = np.repeat(SPHERE.astype(np.float32), 2, axis=0)
        doubled[1::2] = np.nan  # rows the library must skip
        rows = doubled[::2]
        array, view = dbrg._point_array(rows)
        self.assertIs(array, rows)
        self.assertEqual(view.stride_bytes, 24)
        mesh = dbrg.reconstruct(rows)
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])

    def test_reversed_rows_are_copied_and_give_the_same_triangles(self):
        reversed_rows = SPHERE[::-1]
        self.assertLess(reversed_rows.strides[0], 0)
        array, _ = dbrg._point_array(reversed_rows)
        self.assertIsNot(array, reversed_rows)
        mesh = dbrg.reconstruct(reversed_rows)
        back = (len(SPHERE) - 1) - mesh.triangles.astype(np.int64)
        self.assertEqual(canonical_triangles(back), self.reference)

    def test_reversed_columns_are_copied_and_still_face_outward(self):
        mirrored = SPHERE[:, ::-1]  # a reflection: the same surface, mirrored
        array, _ = dbrg._point_array(mirrored)
        self.assertIsNot(array, mirrored)
        mesh = dbrg.reconstruct(mirrored)
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])
        self.assertGreater(signed_volume(mirrored, mesh.triangles), 0)

    def test_fortran_order_is_copied(self):
        fortran = np.asfortranarray(SPHERE)
        array, view = dbrg._point_array(fortran)
        self.assertIsNot(array, fortran)
        self.assertEqual(view.stride_bytes, 24)
        self.assertEqual(canonical_triangles(dbrg.reconstruct(fortran).triangles), self.reference)

    def test_big_endian_is_converted(self):
        big = SPHERE.astype(">f8")
        self.assertEqual(canonical_triangles(dbrg.reconstruct(big).triangles), self.reference)

    def test_the_input_is_not_modified(self):
        points = SPHERE.copy()
        points.flags.writeable = False
        dbrg.reconstruct(points)
        np.testing.assert_array_equal(points, SPHERE)


class OpenSurface(unittest.TestCase):
    def test_patch_keeps_its_border_as_a_boundary_loop(self):
        points = paraboloid_patch(14)
        mesh = dbrg.reconstruct(points)
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=True), [])
        self.assertGreaterEqual(len(mesh.boundary_loops), 1)
        self.assertEqual(len(mesh.boundary_loops), mesh.stats["boundary_loops"])
        directed = {(int(a), int(b)) for tri in mesh.triangles for a, b in zip(tri, np.roll(tri, -1))}
        loop_edges = 0
        for loop in mesh.boundary_loops:
            self.assertEqual(loop.dtype, np.uint32)
            for a, b in zip(loop.tolist(), np.roll(loop, -1).tolist()):
                self.assertIn((a, b), directed, "a loop step is an edge its triangle traverses that way")
                self.assertNotIn((b, a), directed, "and no triangle lies on its other side")
                loop_edges += 1
        self.assertEqual(loop_edges, mesh.stats["boundary_edges"])


class Parameters(unittest.TestCase):
    def test_defaults_come_from_the_library(self):
        lib = dbrg.library()
        params = dbrg._params(lib)
        self.assertEqual(params.struct_size, ctypes.sizeof(_capi.dbrg_params),
                         "the ctypes dbrg_params has the size the library expects")
        self.assertAlmostEqual(params.sliver_angle, 5 * math.pi / 6)
        self.assertEqual(params.fill_holes, 1)

    def test_every_keyword_reaches_the_library(self):
        params = dbrg._params(dbrg.library(), sliver_angle=2.5, boundary_factor=0, boundary_mean="global",
                              fill_holes=False, max_hole_edges=12, max_components=2, backend="builtin", threads=2)
        self.assertEqual((params.sliver_angle, params.boundary_factor, params.boundary_mean, params.fill_holes,
                          params.max_hole_edges, params.max_components, params.backend, params.threads),
                         (2.5, 0.0, 1, 0, 12, 2, 0, 2))

    def test_closed_surface_options_still_give_a_closed_sphere(self):
        mesh = dbrg.reconstruct(SPHERE, boundary_factor=0, sliver_angle=math.radians(160), fill_holes=False,
                                boundary_mean="global", max_components=1, threads=2)
        self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])

    def test_a_tight_boundary_factor_warns_and_the_default_does_not(self):
        with self.assertWarnsRegex(RuntimeWarning, "warning: only .*boundary_factor"):
            mesh = dbrg.reconstruct(SPHERE, boundary_factor=1.001)
        self.assertTrue(mesh.warning.startswith("warning: only"))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            self.assertEqual(dbrg.reconstruct(SPHERE).warning, "")

    def test_out_of_range_values_name_the_parameter(self):
        cases = {
            "sliver_angle": dict(sliver_angle=1.0),
            "boundary_factor": dict(boundary_factor=0.5),
            "max_hole_edges": dict(max_hole_edges=2),
            "max_components": dict(max_components=0),
        }
        for name, keywords in cases.items():
            with self.subTest(name), self.assertRaises(dbrg.InvalidParameterError) as caught:
                dbrg.reconstruct(SPHERE, **keywords)
            self.assertEqual(caught.exception.status, "DBRG_ERR_INVALID_PARAMETER")
            self.assertIn(name, caught.exception.message)

    def test_values_a_c_field_cannot_hold_are_refused_before_the_call(self):
        for keywords in (dict(max_hole_edges=-1), dict(threads=2 ** 32), dict(max_components=1.5),
                         dict(sliver_angle="wide"), dict(backend="cgal"), dict(boundary_mean="median")):
            with self.subTest(keywords), self.assertRaises(dbrg.InvalidParameterError) as caught:
                dbrg.reconstruct(SPHERE, **keywords)
            self.assertIn(next(iter(keywords)), caught.exception.message)
            self.assertIsInstance(caught.exception, ValueError)

    def test_tetgen_backend_works_or_says_it_is_not_built(self):
        try:
            mesh = dbrg.reconstruct(SPHERE, backend="tetgen")
        except dbrg.UnsupportedError as error:
            self.assertIn("TetGen", error.message)
        else:
            self.assertEqual(manifold_problems(mesh.triangles, allow_boundary=False), [])


class Library(unittest.TestCase):
    def test_version_matches_the_package(self):
        self.assertEqual(dbrg.library_version(), dbrg.__version__)
        self.assertEqual(dbrg.library().dbrg_version_number(), _capi.DBRG_VERSION_NUMBER)

    def test_repr(self):
        self.assertIn("triangles", repr(dbrg.reconstruct(SPHERE)))



class FaceFlags(unittest.TestCase):
    def test_the_faces_filling_made_are_flagged(self):
        # A sphere without its points around one pole: growing leaves a hole there that filling closes.
        points = fibonacci_sphere(1000)
        points = points[points[:, 2] < 0.9]
        filled = dbrg.reconstruct(points)
        unfilled = dbrg.reconstruct(points, fill_holes=False)
        self.assertGreater(filled.stats["holes_filled"], 0)
        for mesh in (filled, unfilled):
            self.assertEqual(mesh.face_flags.dtype, np.uint8)
            self.assertEqual(mesh.face_flags.shape, (len(mesh.triangles),))
            self.assertFalse(np.any(mesh.face_flags & ~np.uint8(dbrg.FACE_FILLED)))
        self.assertFalse(np.any(unfilled.face_flags))
        flagged = filled.triangles[(filled.face_flags & dbrg.FACE_FILLED) != 0]
        self.assertGreater(len(flagged), 0)
        # The flagged faces are over the hole: none is one growing made.
        grown = canonical_triangles(unfilled.triangles)
        self.assertFalse(canonical_triangles(flagged) & grown)

if __name__ == "__main__":
    unittest.main()
