#!/usr/bin/env python3
"""Points on a triangle mesh whose density changes steadily across it, for the open-or-closed tests and
benchmarks (a closed object sampled unevenly must still come out closed). Python 3 with numpy only; the
same arguments give the same points.

    python3 tests/bench/resample_graded.py MESH|torus -o POINTS.xyz [--points N] [--ratio R] [--seed N]
                                           [--mesh-out MESH.off]

The points are spread evenly (no two closer than the local spacing) with a spacing that grows
geometrically along the mesh's longest bounding-box axis, so that the density (points per area) is R times
higher at one end than at the other (R = 30 by default). About N points (default: the mesh's vertex
count). `torus` resamples a generated torus; --mesh-out writes the mesh sampled, the reference.
"""
import argparse
import math
import sys

try:
    import numpy as np
except ImportError:
    sys.exit("resample_graded.py needs numpy (Debian: apt-get install python3-numpy, then run it with /usr/bin/python3)")

from scan_simulator import read_triangle_mesh, torus_mesh, write_off, write_points

OVERSAMPLING = 8  # candidates drawn per point kept


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


def relative_spacing(points, ratio):
    """The spacing at each point relative to the densest end: sqrt(ratio) at the sparse end of the longest
    axis (density falls as the square of the spacing)."""
    low, high = points.min(axis=0), points.max(axis=0)
    axis = int(np.argmax(high - low))
    t = (points[:, axis] - low[axis]) / (high[axis] - low[axis])
    return ratio ** (0.5 * t)


def thin(points, spacing):
    """Keeps, in order, each point at least its own `spacing` away from every point kept before it."""
    cell = spacing.max()
    keys = np.floor(points / cell).astype(np.int64)
    cells = {}
    kept = []
    for i in range(len(points)):
        p, need, (ci, cj, ck) = points[i], spacing[i], keys[i]
        clear = True
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                for dk in (-1, 0, 1):
                    for q in cells.get((ci + di, cj + dj, ck + dk), ()):
                        d = points[q] - p
                        if d @ d < need * need:
                            clear = False
                            break
                    if not clear:
                        break
                if not clear:
                    break
        if clear:
            cells.setdefault((ci, cj, ck), []).append(i)
            kept.append(i)
    return points[kept]


def resample(vertices, triangles, count, ratio, seed):
    rng = np.random.default_rng(seed)
    candidates = surface_candidates(vertices, triangles, OVERSAMPLING * count, rng)
    relative = relative_spacing(candidates, ratio)
    corners = vertices[triangles]
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1).sum()
    # Points thinned at spacing h cover about 1.6 h^2 of area each (hexagonal packing would be 0.87 h^2;
    # random sequential thinning leaves more room); relative^-2 is the density's share at each place.
    base = math.sqrt(1.6 * area * np.mean(relative ** -2.0) / count)
    return thin(candidates, base * relative)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--points", type=int, default=0)
    parser.add_argument("--ratio", type=float, default=30.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--mesh-out")
    args = parser.parse_args()
    vertices, triangles = torus_mesh() if args.mesh == "torus" else read_triangle_mesh(args.mesh)
    points = resample(vertices, triangles, args.points or len(vertices), args.ratio, args.seed)
    write_points(args.output, points)
    if args.mesh_out:
        write_off(args.mesh_out, vertices, triangles)
    print(f"{len(points)} points, density ratio {args.ratio:g}", file=sys.stderr)


if __name__ == "__main__":
    main()
