"""dbrg.delaunay: orientation, adjacency, volume and the empty-sphere property, checked in numpy."""

import unittest

import numpy as np

import dbrg


def cube_points(count, seed):
    rng = np.random.default_rng(seed)
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    return np.concatenate([corners, rng.uniform(0.02, 0.98, size=(count, 3))])


def orientations(points, tets):
    a, b, c, d = (points[tets[:, k].astype(np.int64)] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))


class Delaunay(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.points = cube_points(150, seed=11)
        cls.result = dbrg.delaunay(cls.points)

    def test_shapes_and_types(self):
        tets, adjacency = self.result
        self.assertEqual(tets.dtype, np.uint32)
        self.assertEqual(adjacency.dtype, np.uint32)
        self.assertEqual(tets.ndim, 2)
        self.assertEqual(tets.shape[1], 4)
        self.assertEqual(adjacency.shape, tets.shape)
        self.assertIs(self.result.tets, tets)
        self.assertEqual(sorted(np.unique(tets)), list(range(len(self.points))))

    def test_every_tet_has_the_documented_orientation(self):
        # "d lies on the side of plane (a, b, c) from which a, b, c appear clockwise": (b-a) x (c-a)
        # points away from d, so the triple product with d - a is negative.
        volumes = orientations(self.points, self.result.tets)
        self.assertTrue(np.all(volumes < 0), volumes.max())

    def test_tets_fill_the_convex_hull(self):
        volumes = -orientations(self.points, self.result.tets) / 6.0
        self.assertAlmostEqual(float(volumes.sum()), 1.0, places=9)

    def test_adjacency_is_mutual_and_shares_the_face(self):
        tets, adjacency = self.result
        hull_faces = 0
        for t in range(len(tets)):
            for f in range(4):
                n = int(adjacency[t, f])
                if n == dbrg.NO_NEIGHBOR:
                    hull_faces += 1
                    continue
                face = set(tets[t].tolist()) - {int(tets[t, f])}
                self.assertIn(t, adjacency[n].tolist())
                back = adjacency[n].tolist().index(t)
                self.assertEqual(face, set(tets[n].tolist()) - {int(tets[n, back])})
        self.assertEqual(hull_faces, 12, "the cube's hull: 6 squares, two triangles each")

    def test_no_point_inside_any_circumsphere(self):
        tets = self.result.tets.astype(np.int64)
        p = self.points
        a = p[tets[:, 0]]
        # Circumcentre c of each tet: 2 (v_k - a) . c' = |v_k - a|^2 for k = 1..3, with c = a + c'.
        rows = np.stack([p[tets[:, k]] - a for k in (1, 2, 3)], axis=1)
        rhs = 0.5 * np.einsum("tkj,tkj->tk", rows, rows)
        centres = a + np.linalg.solve(rows, rhs[..., None])[..., 0]
        radii = np.linalg.norm(p[tets[:, 0]] - centres, axis=1)
        distances = np.linalg.norm(p[None, :, :] - centres[:, None, :], axis=2)
        inside = distances < radii[:, None] * (1 - 1e-9)
        self.assertFalse(inside.any(), "a point lies strictly inside a circumsphere")

    def test_float32_and_strided_input_give_the_same_tets(self):
        wide = np.zeros((len(self.points), 5), dtype=np.float64)
        wide[:, 1:4] = self.points
        strided = dbrg.delaunay(wide[:, 1:4])
        np.testing.assert_array_equal(strided.tets, self.result.tets)
        np.testing.assert_array_equal(strided.adjacency, self.result.adjacency)
        single = dbrg.delaunay(self.points.astype(np.float32))
        self.assertTrue(np.all(orientations(self.points.astype(np.float32).astype(np.float64), single.tets) < 0))

    def test_errors(self):
        with self.assertRaises(dbrg.DegenerateInputError):
            dbrg.delaunay(np.column_stack([np.random.default_rng(1).uniform(size=(20, 2)), np.zeros(20)]))
        with self.assertRaises(dbrg.TooFewPointsError):
            dbrg.delaunay(self.points[:3])
        bad = self.points.copy()
        bad[3, 0] = np.nan
        with self.assertRaises(dbrg.NonFiniteInputError) as caught:
            dbrg.delaunay(bad)
        self.assertIn("3", caught.exception.message)


if __name__ == "__main__":
    unittest.main()
