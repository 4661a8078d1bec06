#!/usr/bin/env python3
"""Checks of the virtual scanner (scan_simulator.py) on a faceted unit sphere, whose true surface gives
measures that do not go through the scanner's own code. Python 3 with numpy; a few seconds.

    python3 tests/bench/test_scan_simulator.py
"""
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scan_simulator as ss  # noqa: E402  (found beside this file)

SIMULATOR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scan_simulator.py")


def uv_sphere(rings=48, segments=96):
    """The unit sphere as a closed triangle mesh, faces turned outwards."""
    return ss.ellipsoid_mesh((1.0, 1.0, 1.0), rings, segments)


def sphere_ranges(eyes, directions):
    """Distances from each eye along each unit direction to the unit sphere (the nearer crossing)."""
    b = ss.dot(eyes, directions)
    return -b - np.sqrt(b * b - (ss.dot(eyes, eyes) - 1))


def outward_planes(vertices, triangles):
    """Each facet's plane n . x = h of a convex mesh around the origin, n the unit normal pointing out."""
    corners = vertices[triangles]
    normals = ss.unit(ss.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]))
    heights = ss.dot(normals, corners[:, 0])
    return normals * np.sign(heights)[:, None], np.abs(heights)


class SphereScan(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.vertices, cls.triangles = uv_sphere()
        cls.scan = ss.scan(cls.vertices, cls.triangles)
        cls.side = cls.scan.side
        cls.levels = {level: ss.degrade(cls.scan, level, cls.vertices, cls.triangles) for level in ss.LEVELS}

    def test_clean_points_are_first_hits_on_the_mesh(self):
        points, labels = self.levels["clean"]
        distance = ss.distance_to_mesh(points, self.vertices, self.triangles, 1e-6)
        self.assertLess(distance.max(), 1e-9)
        # The faceted sphere is convex: a ray enters it where it crosses the last of the facet planes that
        # face the eye (the slab method), and that is where the first hit must be.
        some = slice(None, None, 7)
        eyes, offsets = self.scan.eyes[labels[some]], points[some] - self.scan.eyes[labels[some]]
        directions = ss.unit(offsets)
        normals, heights = outward_planes(self.vertices, self.triangles)
        facing = directions @ normals.T
        with np.errstate(divide="ignore"):
            crossing = (heights[None, :] - eyes @ normals.T) / facing
        entry = np.where(facing < 0, crossing, -np.inf).max(axis=1)
        self.assertLess(np.abs(np.linalg.norm(offsets, axis=1) - entry).max(), 1e-9)

    def test_about_three_hits_per_vertex_denser_from_nearer_eyes(self):
        _, labels = self.levels["clean"]
        self.assertAlmostEqual(len(labels) / len(self.vertices), 3.0, delta=0.3)
        per_view = np.bincount(labels, minlength=8)
        distance = np.linalg.norm(self.scan.eyes, axis=1)
        self.assertTrue(np.all(per_view > 0))
        nearest, farthest = distance < distance.min() + 1e-9, distance > distance.max() - 1e-9
        self.assertGreater(per_view[nearest].min(), 2 * per_view[farthest].max())

    def test_noisy_ranges_have_the_requested_sigma(self):
        points, labels = self.levels["noisy"]
        eyes = self.scan.eyes[labels]
        offsets = points - eyes
        residual = np.linalg.norm(offsets, axis=1) - sphere_ranges(eyes, ss.unit(offsets))
        sigma = 0.25 * self.side
        robust_sigma = 1.4826 * np.median(np.abs(residual - np.median(residual)))
        self.assertAlmostEqual(robust_sigma / sigma, 1.0, delta=0.05)
        self.assertLess(abs(residual.mean()), 0.1 * sigma)
        # Along the ray: the noisy point, its clean point and the eye are on one line.
        clean, _ = self.levels["clean"]
        sine = np.linalg.norm(ss.cross(ss.unit(offsets), ss.unit(clean - eyes)), axis=1)
        self.assertLess(sine.max(), 1e-12)

    def test_rough_views_move_rigidly_and_outliers_stay_away(self):
        points, labels = self.levels["rough"]
        clean, _ = self.levels["clean"]
        noisy, _ = self.levels["noisy"]
        scanned = labels != ss.OUTLIER_LABEL
        self.assertEqual(np.count_nonzero(~scanned), round(0.005 * np.count_nonzero(scanned)))
        self.assertTrue(np.array_equal(labels[scanned], self.levels["clean"][1]))

        # Before its view's motion a rough point is its noisy point moved twice as far along the ray.
        eyes = self.scan.eyes[labels[scanned]]
        along = ss.unit(clean - eyes)
        noise = ss.dot(noisy - clean, along)
        before = clean + (2 * noise)[:, None] * along
        after = points[scanned]
        diagonal = np.linalg.norm(self.vertices.max(axis=0) - self.vertices.min(axis=0))
        for view in range(8):
            mine = labels[scanned] == view
            b, a = before[mine], after[mine]
            shift = (a - b).mean(axis=0)
            self.assertAlmostEqual(np.linalg.norm(shift), 0.3 * self.side, delta=1e-9)
            pairs = np.arange(len(b)), np.roll(np.arange(len(b)), len(b) // 2)
            self.assertLess(np.abs(np.linalg.norm(b[pairs[0]] - b[pairs[1]], axis=1)
                                   - np.linalg.norm(a[pairs[0]] - a[pairs[1]], axis=1)).max(), 1e-9)
            turn = np.linalg.norm(a - b - shift, axis=1)
            reach = np.linalg.norm(b - b.mean(axis=0), axis=1)
            self.assertTrue(np.all(turn <= 0.3 * self.side / diagonal * reach + 1e-9))
            self.assertGreater(turn.max(), 0)

        # No point of the faceted sphere is nearer the centre than its nearest facet plane, nor farther than 1.
        inner = outward_planes(self.vertices, self.triangles)[1].min()
        radius = np.linalg.norm(points[~scanned], axis=1)
        self.assertTrue(np.all(np.maximum(radius - 1, inner - radius) > 2 * self.side))
        self.assertTrue(np.all((points[~scanned] >= -1) & (points[~scanned] <= 1)))


class Distance(unittest.TestCase):
    def test_each_region_of_a_triangle(self):
        vertices = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
        points = np.array([[0.2, 0.2, 0.5], [-1, -1, 0], [2, -1, 0], [0.5, -2, 1], [1, 1, 0], [-3, 0.5, 0]])
        expected = [0.5, math.sqrt(2), math.sqrt(2), math.sqrt(5), math.sqrt(0.5), 3]
        distance = ss.distance_to_mesh(points, vertices, np.array([[0, 1, 2]]), 10.0)
        np.testing.assert_allclose(distance, expected, rtol=1e-12)


class Files(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.path = lambda name: os.path.join(self.folder.name, name)

    def tearDown(self):
        self.folder.cleanup()

    def run_simulator(self, *args):
        subprocess.run([sys.executable, SIMULATOR, *args], check=True, capture_output=True)

    def read(self, name):
        with open(self.path(name), "rb") as f:
            return f.read()

    def test_same_arguments_same_files(self):
        vertices, triangles = uv_sphere(12, 24)
        ss.write_off(self.path("sphere.off"), vertices, triangles)
        for name, seed in (("a", "7"), ("b", "7"), ("c", "8")):
            self.run_simulator(self.path("sphere.off"), "rough", "--seed", seed, "-o", self.path(name + ".xyz"),
                               "--labels", self.path(name + ".txt"))
        self.assertEqual(self.read("a.xyz"), self.read("b.xyz"))
        self.assertEqual(self.read("a.txt"), self.read("b.txt"))
        self.assertNotEqual(self.read("a.xyz"), self.read("c.xyz"))
        points = np.loadtxt(self.path("a.xyz"))
        self.assertEqual(len(points), len(np.loadtxt(self.path("a.txt"))))

    def test_ply_encodings_and_strips_read_as_off(self):
        # A cube of quads, with a property before x and one after the corner lists.
        corners = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
        quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        with open(self.path("cube.off"), "w") as f:
            f.write("OFF\n8 6 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in corners)
                    + "".join("4 " + " ".join(map(str, q)) + "\n" for q in quads))
        expected = ss.read_triangle_mesh(self.path("cube.off"))
        header = ("ply\nformat {} 1.0\ncomment a cube\nelement vertex 8\nproperty uchar flag\nproperty float x\n"
                  "property float y\nproperty float z\nelement face 6\nproperty list uchar int vertex_indices\n"
                  "property ushort part\nend_header\n")
        with open(self.path("ascii.ply"), "w") as f:
            f.write(header.format("ascii") + "".join(f"1 {x} {y} {z}\n" for x, y, z in corners)
                    + "".join("4 " + " ".join(map(str, q)) + " 9\n" for q in quads))
        for name, order in (("little.ply", "<"), ("big.ply", ">")):
            with open(self.path(name), "wb") as f:
                f.write(header.format("binary_little_endian" if order == "<" else "binary_big_endian").encode())
                vertex = np.dtype([("flag", "u1"), ("xyz", order + "f4", 3)])
                f.write(np.array([(1, c) for c in corners], dtype=vertex).tobytes())
                for q in quads:
                    f.write(np.array([4], "u1").tobytes() + np.array(q, order + "i4").tobytes()
                            + np.array([9], order + "u2").tobytes())
        for name in ("ascii.ply", "little.ply", "big.ply"):
            vertices, triangles = ss.read_triangle_mesh(self.path(name))
            np.testing.assert_array_equal(vertices, expected[0])
            np.testing.assert_array_equal(triangles, expected[1])

        strip = []
        for a, b, c, d in quads:
            strip += [a, b, d, c, -1]
        with open(self.path("strips.ply"), "wb") as f:
            f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                    b"property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n")
            f.write(corners.astype("<f4").tobytes() + np.array([len(strip)] + strip, "<i4").tobytes())
        _, triangles = ss.read_triangle_mesh(self.path("strips.ply"))
        # Each quad's strip cuts it along the other diagonal: (a, b, d) and (b, c, d), turned like the quad.
        turned = lambda t: tuple(int(i) for i in np.roll(t, -int(np.argmin(t))))  # noqa: E731
        split = [t for a, b, c, d in quads for t in ((a, b, d), (b, c, d))]
        self.assertEqual(sorted(map(turned, triangles)), sorted(map(turned, split)))


if __name__ == "__main__":
    unittest.main(verbosity=2)
