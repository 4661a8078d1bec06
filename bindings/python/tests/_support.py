"""Point sets the tests generate, and checks of a triangle mesh that do not trust the library."""

import collections

import numpy as np


def fibonacci_sphere(count, radius=1.0, dtype=np.float64):
    """`count` points spread evenly over a sphere (the golden-angle spiral)."""
    i = np.arange(count, dtype=np.float64) + 0.5
    polar = np.arccos(1.0 - 2.0 * i / count)
    azimuth = np.pi * (1.0 + 5.0 ** 0.5) * i
    points = np.stack([np.cos(azimuth) * np.sin(polar), np.sin(azimuth) * np.sin(polar), np.cos(polar)], axis=1)
    return (radius * points).astype(dtype)


def paraboloid_patch(side, seed=7):
    """A jittered side x side grid on z = 0.2 (x^2 + y^2): an open surface with one border."""
    rng = np.random.default_rng(seed)
    u, v = np.meshgrid(np.linspace(-1, 1, side), np.linspace(-1, 1, side))
    x = u + rng.uniform(-0.15, 0.15, u.shape) / side
    y = v + rng.uniform(-0.15, 0.15, v.shape) / side
    return np.stack([x.ravel(), y.ravel(), 0.2 * (x.ravel() ** 2 + y.ravel() ** 2)], axis=1)


def directed_edges(triangles):
    t = np.asarray(triangles, dtype=np.int64)
    return [(int(a), int(b)) for tri in t for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0]))]


def canonical_triangles(triangles):
    """The set of oriented triangles, each rotated to start at its smallest index."""
    result = set()
    for a, b, c in np.asarray(triangles).tolist():
        rotations = [(a, b, c), (b, c, a), (c, a, b)]
        result.add(min(rotations))
    return result


def signed_volume(points, triangles):
    p = np.asarray(points, dtype=np.float64)
    t = np.asarray(triangles, dtype=np.int64)
    a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0


def manifold_problems(triangles, allow_boundary):
    """Returns a list of sentences describing every way `triangles` fails to be an oriented manifold
    (an empty list when it is one): degenerate or duplicate faces, an edge with more than two faces, two
    faces traversing an edge in the same direction, a vertex whose faces do not form one fan."""
    problems = []
    t = np.asarray(triangles, dtype=np.int64)
    if t.ndim != 2 or t.shape[1] != 3:
        return ["triangles have shape %s" % (t.shape,)]
    for tri in t.tolist():
        if len(set(tri)) != 3:
            problems.append("degenerate triangle %s" % tri)
    if len({tuple(sorted(tri)) for tri in t.tolist()}) != len(t):
        problems.append("duplicate triangles")
    directed = collections.Counter(directed_edges(t))
    for edge, count in directed.items():
        if count > 1:
            problems.append("directed edge %s appears %d times (inconsistent orientation)" % (edge, count))
    undirected = collections.Counter(tuple(sorted(e)) for e in directed_edges(t))
    for edge, count in undirected.items():
        if count > 2 or (count == 1 and not allow_boundary):
            problems.append("edge %s has %d triangles" % (edge, count))
    # Around each vertex, the opposite edges (b -> c of every face (v, b, c)) must chain into one fan.
    link = collections.defaultdict(dict)
    for a, b, c in t.tolist():
        for v, p, q in ((a, b, c), (b, c, a), (c, a, b)):
            link[v][p] = q
    for v, step in link.items():
        starts = set(step) - set(step.values())  # a fan on the border starts where nothing leads in
        if len(starts) > 1:
            problems.append("vertex %d has %d fans (bow-tie)" % (v, len(starts)))
            continue
        start = starts.pop() if starts else next(iter(step))
        seen, p = 0, start
        while p in step and seen <= len(step):
            p = step[p]
            seen += 1
            if p == start:
                break
        if seen != len(step):
            problems.append("the faces around vertex %d form more than one fan" % v)
    return problems


def euler_characteristic(triangles):
    t = np.asarray(triangles, dtype=np.int64)
    vertices = len(np.unique(t))
    edges = len({tuple(sorted(e)) for e in directed_edges(t)})
    return vertices - edges + len(t)
