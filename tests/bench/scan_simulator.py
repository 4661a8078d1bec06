#!/usr/bin/env python3
"""A virtual range scanner: the points a scanner would give of a triangle mesh, clean, noisy or rough, for the
scan tests and benchmarks. Python 3 with numpy only; the same arguments give the same points.

    python3 tests/bench/scan_simulator.py MESH|torus LEVEL -o POINTS.xyz [--labels LABELS.txt] [--seed N]
                                          [--hits-per-vertex H] [--mesh-out MESH.off]

MESH is a triangle mesh (.off, .obj, .ply ascii or binary); `torus` scans a generated torus (--mesh-out
writes the mesh scanned, the reference for measures). LEVEL, with s the mesh's mean side length:
  clean  the first hits as they are;
  noisy  Gaussian range noise along each ray, sigma = 0.25 s;
  rough  sigma = 0.5 s, each view moved by a rigid motion (a rotation of 0.3 s / bounding diagonal radians
         about a random axis through the centroid of the view's points, and a translation of 0.3 s), and
         0.5 % outliers: points drawn uniformly in the bounding box, farther than 2 s from the mesh.
The levels share their rays and their noise draws: before its view's motion, a rough point is the noisy
point moved twice as far from the clean hit along the same ray. --labels writes one integer a line, for
the point on the same line: the view it came from, or -1 for an outlier.

The scanner stands at the 8 corners of a cube around the mesh's bounding-box centre, at 1.5, 2 and 3 times
the bounding-sphere radius in turn (corner k at the (k mod 3)-th distance). Each view casts rays from its
eye on a jittered grid of one fixed angular step for all views (one ray per grid cell, at a random place
in it), so the density of hits falls with distance and with the angle of incidence; only the first hit of
a ray counts, so occluded parts get no points, and views overlap. The step is chosen so that the views
give about H hits per mesh vertex in all (3 by default). Rays are cast per view on the image plane: each
triangle's projection is binned into the grid cells it covers, and only the rays of those cells are
tested against it (Moller-Trumbore), so a 70k-triangle mesh scans in a few seconds.
"""
import argparse
import math
import sys
from dataclasses import dataclass

try:
    import numpy as np
except ImportError:
    sys.exit("scan_simulator.py needs numpy (Debian: apt-get install python3-numpy, then run it with /usr/bin/python3)")

from subdivide import read_mesh

LEVELS = ("clean", "noisy", "rough")
RANGE_SIGMA = {"clean": 0.0, "noisy": 0.25, "rough": 0.5}  # in mean side lengths
MISREGISTRATION = 0.3  # rough level: the views' rotation (over the bounding diagonal) and translation, in sides
OUTLIER_SHARE = 0.005  # rough level: outliers per scanned point
OUTLIER_DISTANCE = 2.0  # an outlier is farther than this many sides from the mesh
DISTANCE_FACTORS = (1.5, 2.0, 3.0)  # the eyes' distances from the centre, in bounding-sphere radii
OUTLIER_LABEL = -1

# One random stream per purpose, so that the levels share their rays and their noise draws.
JITTER_STREAM, NOISE_STREAM, MOTION_STREAM, OUTLIER_STREAM = range(4)


def random_stream(seed, stream):
    return np.random.default_rng([seed, stream])


# --- meshes -----------------------------------------------------------------------------------------------

PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
             "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
             "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def read_ply(path):
    """Vertices and triangles of an ascii or binary PLY file: vertex x, y, z; face lists (as fans) and
    tristrips (-1 restarts a strip, every other triangle turned round); other elements are read past."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header")
    body = data[data.index(b"\n", end) + 1:]
    elements = []  # [name, count, [(property name, type, list count type or None)]]
    encoding = None
    for line in data[:end].decode("ascii").splitlines():
        fields = line.split()
        if not fields or fields[0] in ("ply", "comment", "obj_info"):
            continue
        if fields[0] == "format":
            encoding = {"ascii": None, "binary_little_endian": "<", "binary_big_endian": ">"}[fields[1]]
        elif fields[0] == "element":
            elements.append([fields[1], int(fields[2]), []])
        elif fields[0] == "property" and fields[1] == "list":
            elements[-1][2].append((fields[4], PLY_TYPES[fields[3]], PLY_TYPES[fields[2]]))
        elif fields[0] == "property":
            elements[-1][2].append((fields[2], PLY_TYPES[fields[1]], None))
    tokens = body.split() if encoding is None else None
    position = 0  # in tokens (ascii) or bytes (binary)

    def read(dtype, count):
        """The next `count` values of `dtype` (in ascii, of scalar types only)."""
        nonlocal position
        if encoding is None:
            values = np.array(tokens[position:position + count], dtype=float)
            position += count
            return values
        dtype = np.dtype(dtype).newbyteorder(encoding) if np.dtype(dtype).names is None else dtype
        values = np.frombuffer(body, dtype, count, position)
        position += count * dtype.itemsize
        return values

    vertices, triangles = None, []
    for name, count, properties in elements:
        if all(list_type is None for _, _, list_type in properties):  # a table: read at once
            if encoding is None:
                table = read("f8", count * len(properties)).reshape(count, len(properties))
                columns = {prop[0]: table[:, k] for k, prop in enumerate(properties)}
            else:
                table = read(np.dtype([(prop[0], np.dtype(prop[1]).newbyteorder(encoding)) for prop in properties]),
                             count)
                columns = {prop[0]: table[prop[0]] for prop in properties}
            if name == "vertex":
                vertices = np.stack([columns[axis].astype(float) for axis in "xyz"], axis=1)
            continue
        for _ in range(count):
            for prop_name, item_type, list_type in properties:
                values = read(item_type, int(read(list_type, 1)[0])) if list_type else read(item_type, 1)
                if prop_name not in ("vertex_indices", "vertex_index"):
                    continue
                corners = [int(i) for i in values]
                if name == "face":
                    triangles += [(corners[0], corners[i], corners[i + 1]) for i in range(1, len(corners) - 1)]
                elif name == "tristrips":
                    triangles += strip_triangles(corners)
    triangles = [t for t in triangles if len(set(t)) == 3]
    return vertices, np.array(triangles, dtype=np.int64).reshape(-1, 3)


def strip_triangles(corners):
    """The triangles of PLY triangle strips, turned alike; a negative index starts a new strip."""
    triangles, strip = [], []
    for index in corners:
        if index < 0:
            strip = []
            continue
        strip.append(index)
        if len(strip) >= 3:
            a, b, c = strip[-3:]
            triangles.append((a, b, c) if len(strip) % 2 == 1 else (b, a, c))
    return triangles


def read_triangle_mesh(path):
    """(vertices (n, 3) float, triangles (m, 3) int) of an OFF, OBJ or PLY file."""
    if path.lower().endswith(".ply"):
        return read_ply(path)
    vertices, triangles = read_mesh(path)
    return np.array(vertices, dtype=float).reshape(-1, 3), np.array(triangles, dtype=np.int64).reshape(-1, 3)


def write_off(path, vertices, triangles):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
        np.savetxt(f, vertices, fmt="%.17g")
        np.savetxt(f, np.column_stack([np.full(len(triangles), 3), triangles]), fmt="%d")


def torus_mesh(major=1.0, minor=0.4, rings=96, sides=48):
    """A closed torus about the z axis: `rings` around the axis times `sides` around the tube, each quad cut
    in two, faces turned outwards."""
    u = 2 * math.pi * np.arange(rings) / rings
    v = 2 * math.pi * np.arange(sides) / sides
    uu, vv = np.meshgrid(u, v, indexing="ij")
    tube = major + minor * np.cos(vv)
    vertices = np.stack([tube * np.cos(uu), tube * np.sin(uu), minor * np.sin(vv)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij")
    a = i * sides + j
    b = ((i + 1) % rings) * sides + j
    c = ((i + 1) % rings) * sides + (j + 1) % sides
    d = i * sides + (j + 1) % sides
    triangles = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return vertices, triangles


def ellipsoid_mesh(radii=(1.0, 1.0, 1.0), rings=48, segments=96):
    """A closed ellipsoid with the given semi-axes, faces turned outwards: two poles and rings - 1
    parallels of `segments` vertices each."""
    polar = math.pi * np.arange(1, rings) / rings
    azimuth = 2 * math.pi * np.arange(segments) / segments
    pp, aa = np.meshgrid(polar, azimuth, indexing="ij")
    parallels = np.stack([np.sin(pp) * np.cos(aa), np.sin(pp) * np.sin(aa), np.cos(pp)], axis=-1).reshape(-1, 3)
    vertices = np.concatenate([[[0.0, 0.0, 1.0]], parallels, [[0.0, 0.0, -1.0]]]) * np.array(radii)
    south = len(vertices) - 1
    ring = lambda r, k: 1 + r * segments + k % segments  # noqa: E731
    triangles = []
    for k in range(segments):
        triangles.append((0, ring(0, k), ring(0, k + 1)))
        triangles.append((south, ring(rings - 2, k + 1), ring(rings - 2, k)))
        for r in range(rings - 2):
            triangles.append((ring(r, k), ring(r + 1, k), ring(r + 1, k + 1)))
            triangles.append((ring(r, k), ring(r + 1, k + 1), ring(r, k + 1)))
    return vertices, np.array(triangles)


def mean_side(vertices, triangles):
    """The mean length of the triangles' sides, each triangle's three counted (as `dbrg stats` does)."""
    corners = vertices[triangles]
    lengths = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2).ravel()
    return float(lengths[lengths > 0].mean())


# --- geometry ---------------------------------------------------------------------------------------------
# Row-wise products written out, so that no result depends on which BLAS kernel numpy picks.

def dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def cross(a, b):
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def unit(a):
    return a / np.sqrt(dot(a, a))[..., None]


def rotate(points, axis, angle):
    """Rodrigues' rotation of row vectors about a unit axis through the origin."""
    cos, sin = math.cos(angle), math.sin(angle)
    return points * cos + cross(axis, points) * sin + axis * (dot(points, axis) * (1 - cos))[:, None]


def closest_on_triangles(p, a, b, c):
    """The closest point to p on triangle abc, row by row (Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap, bp, cp = b - a, c - a, p - a, p - b, p - c
    d1, d2, d3, d4, d5, d6 = dot(ab, ap), dot(ac, ap), dot(ab, bp), dot(ac, bp), dot(ab, cp), dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        on_ab = a + ab * (d1 / (d1 - d3))[:, None]
        on_ac = a + ac * (d2 / (d2 - d6))[:, None]
        on_bc = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None]
        area = va + vb + vc
        inside = a + ab * (vb / area)[:, None] + ac * (vc / area)[:, None]
    regions = [(d1 <= 0) & (d2 <= 0), (d3 >= 0) & (d4 <= d3), (vc <= 0) & (d1 >= 0) & (d3 <= 0),
               (d6 >= 0) & (d5 <= d6), (vb <= 0) & (d2 >= 0) & (d6 <= 0),
               (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)]
    choices = [a, b, on_ab, c, on_ac, on_bc]
    return np.select([r[:, None] for r in regions], choices, inside)


def smallest_per(index, values, size):
    """The smallest of the values given to each of `size` slots (infinity for a slot given none)."""
    order = np.lexsort((values, index))
    index, values = index[order], values[order]
    first = np.ones(len(index), dtype=bool)
    first[1:] = index[1:] != index[:-1]
    smallest = np.full(size, np.inf)
    smallest[index[first]] = values[first]
    return smallest


def box_cells(low, high):
    """Every cell of integer boxes: for boxes low[k]..high[k] (inclusive, rows of d integers), the box of
    each cell and the cell (rows of d integers)."""
    sizes = high - low + 1
    count = sizes.prod(axis=1)
    box = np.repeat(np.arange(len(low)), count)
    rest = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    cells = np.empty((len(box), low.shape[1]), dtype=np.int64)
    for axis in reversed(range(low.shape[1])):
        cells[:, axis] = low[box, axis] + rest % sizes[box, axis]
        rest //= sizes[box, axis]
    return box, cells


def distance_to_mesh(points, vertices, triangles, within):
    """Each point's distance to the mesh where it is at most `within`; larger distances may come out as
    infinity. Triangles are binned in a uniform grid of cells about the size of their boxes grown by
    `within`, and each point is measured against the triangles of its cell."""
    corners = vertices[triangles]
    low, high = corners.min(axis=1) - within, corners.max(axis=1) + within
    origin = low.min(axis=0)
    size = float(np.median((high - low).max(axis=1)))
    shape = np.floor((high.max(axis=0) - origin) / size).astype(np.int64) + 1

    def key(cells):
        return (cells[:, 0] * shape[1] + cells[:, 1]) * shape[2] + cells[:, 2]

    triangle, cells = box_cells(np.floor((low - origin) / size).astype(np.int64),
                                np.floor((high - origin) / size).astype(np.int64))
    order = np.argsort(key(cells), kind="stable")
    triangle, sorted_keys = triangle[order], key(cells)[order]

    point_cells = np.floor((points - origin) / size).astype(np.int64)
    inside = np.all((point_cells >= 0) & (point_cells < shape), axis=1)
    point_keys = np.where(inside, key(np.clip(point_cells, 0, shape - 1)), -1)
    first, last = np.searchsorted(sorted_keys, point_keys), np.searchsorted(sorted_keys, point_keys, side="right")
    point_index, slot = box_cells(first[:, None], last[:, None] - 1)
    pair_triangle = triangle[slot[:, 0]]
    p = points[point_index]
    closest = closest_on_triangles(p, *(corners[pair_triangle, k] for k in range(3)))
    distance = np.sqrt(dot(p - closest, p - closest))
    distance[np.isnan(distance)] = np.inf  # a degenerate triangle: its neighbours' sides measure it
    return smallest_per(point_index, distance, len(points))


# --- the scanner ------------------------------------------------------------------------------------------

@dataclass
class Scan:
    """The first hits of all views: hit i is eyes[view[i]] + ranges[i] * directions[i]."""
    eyes: np.ndarray  # (views, 3)
    view: np.ndarray  # (hits,) int
    directions: np.ndarray  # (hits, 3), unit
    ranges: np.ndarray  # (hits,)
    side: float  # the mesh's mean side length s
    low: np.ndarray  # the mesh's bounding box
    high: np.ndarray


@dataclass
class View:
    eye: np.ndarray
    forward: np.ndarray
    right: np.ndarray
    up: np.ndarray
    half_extent: float  # of the bounding sphere's image on the plane at unit distance in front of the eye


def cube_views(centre, radius):
    views = []
    for k in range(8):
        direction = unit(np.array([1.0 if k & bit else -1.0 for bit in (1, 2, 4)]))
        distance = DISTANCE_FACTORS[k % len(DISTANCE_FACTORS)] * radius
        forward = -direction
        helper = np.zeros(3)
        helper[np.argmin(np.abs(forward))] = 1.0
        right = unit(cross(forward, helper))
        views.append(View(centre + distance * direction, forward, right, cross(forward, right),
                          radius / math.sqrt(distance * distance - radius * radius)))
    return views


class RayCaster:
    """First hits of rays from one eye, one ray per cell of a square grid on the image plane."""

    def __init__(self, vertices, triangles):
        self.vertices = vertices
        self.triangles = triangles
        self.a = vertices[triangles[:, 0]]
        self.ab = vertices[triangles[:, 1]] - self.a
        self.ac = vertices[triangles[:, 2]] - self.a

    def cast(self, view, cells, step, offsets):
        """Rays through the cells of a cells-by-cells grid of side `step` centred on the view's axis, each at
        offsets[cell] (in [0, 1)^2) inside its cell. Returns (directions, ranges with inf for a miss)."""
        relative = self.vertices - view.eye
        depth = dot(relative, view.forward)  # positive: the eye is outside the bounding sphere
        origin = -0.5 * cells * step
        image = np.stack([(dot(relative, axis) / depth - origin) / step for axis in (view.right, view.up)], axis=1)
        # The grid cells each triangle's image covers: a triangle projects to the triangle of its corners'
        # projections, so the box of those is the box of its image.
        corner_cells = image[self.triangles]
        low = np.floor(corner_cells.min(axis=1)).astype(np.int64)
        high = np.floor(corner_cells.max(axis=1)).astype(np.int64)
        keep = np.nonzero(np.all((high >= 0) & (low < cells), axis=1))[0]
        box, covered = box_cells(np.clip(low[keep], 0, cells - 1), np.clip(high[keep], 0, cells - 1))
        pair_triangle, pair_cell = keep[box], covered[:, 0] * cells + covered[:, 1]

        grid = np.arange(cells * cells)
        x = origin + (grid // cells + offsets[:, 0]) * step
        y = origin + (grid % cells + offsets[:, 1]) * step
        directions = unit(view.forward + x[:, None] * view.right + y[:, None] * view.up)
        ranges = np.full(cells * cells, np.inf)
        chunk = 1 << 21
        for start in range(0, len(pair_cell), chunk):
            cell, distance = self._intersect(view.eye, directions, pair_cell[start:start + chunk],
                                             pair_triangle[start:start + chunk])
            ranges = np.minimum(ranges, smallest_per(cell, distance, len(ranges)))
        return directions, ranges

    def _intersect(self, eye, directions, cell, triangle):
        """Moller-Trumbore for each (ray, triangle) pair; returns the pairs that hit and their distances."""
        d, ab, ac = directions[cell], self.ab[triangle], self.ac[triangle]
        p = cross(d, ac)
        det = dot(ab, p)
        s = eye - self.a[triangle]
        q = cross(s, ab)
        with np.errstate(divide="ignore", invalid="ignore"):
            u, v, t = dot(s, p) / det, dot(d, q) / det, dot(ac, q) / det
        hit = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        return cell[hit], t[hit]


def scan(vertices, triangles, seed=1, hits_per_vertex=3.0):
    """The clean first hits of the eight views of the mesh, about hits_per_vertex per vertex in all."""
    if len(triangles) == 0:
        raise ValueError("the mesh has no triangles")
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    centre = 0.5 * (low + high)
    radius = float(np.sqrt(dot(vertices - centre, vertices - centre)).max())
    views = cube_views(centre, radius)
    caster = RayCaster(vertices, triangles)

    # The angular step: a coarse pass through the cells' centres measures how much of each view's
    # square the mesh covers, and the step is set for the wanted number of hits.
    coarse = 64
    covered_area = 0.0
    for view in views:
        _, ranges = caster.cast(view, coarse, 2 * view.half_extent / coarse, np.full((coarse * coarse, 2), 0.5))
        covered_area += np.isfinite(ranges).mean() * (2 * view.half_extent) ** 2
    if covered_area == 0:
        raise ValueError("no ray hit the mesh")
    step = math.sqrt(covered_area / (hits_per_vertex * len(vertices)))

    jitter = random_stream(seed, JITTER_STREAM)
    eyes, view_of_hit, all_directions, all_ranges = [], [], [], []
    for index, view in enumerate(views):
        cells = math.ceil(2 * view.half_extent / step)
        directions, ranges = caster.cast(view, cells, step, jitter.random((cells * cells, 2)))
        hit = np.isfinite(ranges)
        eyes.append(view.eye)
        view_of_hit.append(np.full(hit.sum(), index))
        all_directions.append(directions[hit])
        all_ranges.append(ranges[hit])
    return Scan(np.array(eyes), np.concatenate(view_of_hit), np.concatenate(all_directions),
                np.concatenate(all_ranges), mean_side(vertices, triangles), low, high)


def degrade(scan_result, level, vertices, triangles, seed=1):
    """The points of `level` (clean, noisy or rough) and each point's label: its view, or -1 (an outlier)."""
    if level not in LEVELS:
        raise ValueError(f"unknown level {level!r} (expected one of {', '.join(LEVELS)})")
    s = scan_result.side
    noise = random_stream(seed, NOISE_STREAM).standard_normal(len(scan_result.ranges))
    ranges = scan_result.ranges + RANGE_SIGMA[level] * s * noise
    points = scan_result.eyes[scan_result.view] + ranges[:, None] * scan_result.directions
    labels = scan_result.view.copy()
    if level != "rough":
        return points, labels

    motion = random_stream(seed, MOTION_STREAM)
    diagonal = float(np.linalg.norm(scan_result.high - scan_result.low))
    for index in range(len(scan_result.eyes)):
        mine = labels == index
        if not mine.any():
            continue
        centre = points[mine].mean(axis=0)
        axis, shift = unit(motion.standard_normal(3)), unit(motion.standard_normal(3))
        moved = rotate(points[mine] - centre, axis, MISREGISTRATION * s / diagonal)
        points[mine] = moved + centre + MISREGISTRATION * s * shift

    outliers = random_stream(seed, OUTLIER_STREAM)
    wanted = round(OUTLIER_SHARE * len(points))
    found = np.empty((0, 3))
    while len(found) < wanted:
        candidates = scan_result.low + (scan_result.high - scan_result.low) * outliers.random((2 * wanted, 3))
        far = distance_to_mesh(candidates, vertices, triangles, OUTLIER_DISTANCE * s) > OUTLIER_DISTANCE * s
        found = np.concatenate([found, candidates[far]])
    found = found[:wanted]
    # Outliers come interleaved with the scan, as a scanner's stray returns would.
    total = len(points) + wanted
    at = np.sort(outliers.choice(total, wanted, replace=False))
    is_outlier = np.zeros(total, dtype=bool)
    is_outlier[at] = True
    mixed = np.empty((total, 3))
    mixed[is_outlier], mixed[~is_outlier] = found, points
    mixed_labels = np.full(total, OUTLIER_LABEL)
    mixed_labels[~is_outlier] = labels
    return mixed, mixed_labels


def write_points(path, points):
    """An .xyz file, each coordinate with the digits that give it back exactly."""
    np.savetxt(path, points, fmt="%.17g")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", help="a .off, .obj or .ply triangle mesh, or 'torus'")
    parser.add_argument("level", choices=LEVELS)
    parser.add_argument("-o", "--output", required=True, help="the points, an .xyz file")
    parser.add_argument("--labels", help="also write each point's view (-1: outlier), one a line")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--hits-per-vertex", type=float, default=3.0)
    parser.add_argument("--mesh-out", help="also write the mesh scanned as OFF (the reference of a generated shape)")
    args = parser.parse_args()

    vertices, triangles = torus_mesh() if args.mesh == "torus" else read_triangle_mesh(args.mesh)
    if args.mesh_out:
        write_off(args.mesh_out, vertices, triangles)
    result = scan(vertices, triangles, args.seed, args.hits_per_vertex)
    points, labels = degrade(result, args.level, vertices, triangles, args.seed)
    write_points(args.output, points)
    if args.labels:
        np.savetxt(args.labels, labels, fmt="%d")
    print(f"{len(points)} points ({np.count_nonzero(labels == OUTLIER_LABEL)} outliers) from "
          f"{len(result.eyes)} views of {len(vertices)} vertices; mean side {result.side:.6g}", file=sys.stderr)


if __name__ == "__main__":
    main()
