#!/usr/bin/env python3
"""Points on a triangle mesh spread as the vertices of an unevenly decimated mesh are, for the open-or-closed
benchmarks (a closed object sampled unevenly must still come out closed). Python 3 with numpy only; the same
arguments give the same points.

    python3 tests/bench/resample_graded.py MESH|torus -o POINTS.xyz [--points N] [--ratio R] [--stretch S]
                                           [--seed N] [--mesh-out MESH.off]

Random points drawn uniformly over the mesh's area are clustered on a grid: one point per cell is kept. The
cells grow geometrically along the mesh's longest bounding-box axis, so that the density of kept points
falls R times (default 30) from one end to the other, and are S times (default 2) longer along one of the
other axes, as a decimated mesh's triangles are long on its smooth parts. About N points (default: the
mesh's vertex count). `torus` resamples a generated torus; --mesh-out writes the mesh sampled, the reference.
The library's tests draw the same kind of sample on their built-in shapes (samples::sample_clustered).
"""
import argparse
import math
import sys

try:
    import numpy as np
except ImportError:
    sys.exit("resample_graded.py needs numpy (Debian: apt-get install python3-numpy, then run it with /usr/bin/python3)")

from scan_simulator import read_triangle_mesh, torus_mesh, write_off, write_points

CANDIDATES_PER_POINT = 30


def surface_candidates(vertices, triangles, count, rng):
    """`count` points drawn uniformly by area over the mesh."""
    corners = vertices[triangles]
    areas = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    picked = rng.choice(len(triangles), size=count, p=areas / areas.sum())
    s, t = rng.random(count), rng.random(count)
    flip = s + t > 1
    s[flip], t[flip] = 1 - s[flip], 1 - t[flip]
    a, b, c = corners[picked, 0], corners[picked, 1], corners[picked, 2]
    return a + s[:, None] * (b - a) + t[:, None] * (c - a)


def first_per_cell(points, cell, ratio, stretch):
    """The indices of the first point in each cell, the cells `cell` long at the dense end of the longest
    axis and sqrt(ratio) times that at the other end."""
    low, high = points.min(axis=0), points.max(axis=0)
    axis = int(np.argmax(high - low))
    across = [i for i in range(3) if i != axis]
    extent = high[axis] - low[axis]
    half_log = 0.5 * math.log(ratio)
    t = (points[:, axis] - low[axis]) / extent
    growth = np.exp(half_log * t)
    along = extent * (1 - 1 / growth) / half_log if half_log > 0 else points[:, axis] - low[axis]
    keys = np.stack([np.floor(along / cell),
                     np.floor(points[:, across[0]] / (cell * growth * stretch)),
                     np.floor(points[:, across[1]] / (cell * growth))], axis=1).astype(np.int64)
    _, first = np.unique(keys, axis=0, return_index=True)
    return np.sort(first)


def resample(vertices, triangles, count, ratio, stretch, seed):
    rng = np.random.default_rng(seed)
    candidates = surface_candidates(vertices, triangles, CANDIDATES_PER_POINT * count, rng)
    cell = np.linalg.norm(candidates.max(axis=0) - candidates.min(axis=0)) / math.sqrt(count)
    # The number of cells hit falls as the square of the cell size: a few corrections home in on `count`.
    for _ in range(8):
        kept = first_per_cell(candidates, cell, ratio, stretch)
        if abs(len(kept) / count - 1) < 0.03:
            break
        cell *= math.sqrt(len(kept) / count)
    return candidates[kept]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", help="a .off, .obj or .ply triangle mesh, or 'torus'")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--points", type=int, default=0)
    parser.add_argument("--ratio", type=float, default=30.0)
    parser.add_argument("--stretch", type=float, default=2.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--mesh-out")
    args = parser.parse_args()
    vertices, triangles = torus_mesh() if args.mesh == "torus" else read_triangle_mesh(args.mesh)
    points = resample(vertices, triangles, args.points or len(vertices), args.ratio, args.stretch, args.seed)
    write_points(args.output, points)
    if args.mesh_out:
        write_off(args.mesh_out, vertices, triangles)
    print(f"{len(points)} points, density ratio {args.ratio:g}, stretch {args.stretch:g}", file=sys.stderr)


if __name__ == "__main__":
    main()
