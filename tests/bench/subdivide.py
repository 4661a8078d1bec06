#!/usr/bin/env python3
"""Loop subdivision of a triangle mesh, for benchmark inputs: a real model at hundreds of thousands of points,
whose subdivided mesh is the reference for face recall. Pure Python (no numpy), text OBJ and OFF in,
binary PLY out.

    python3 tests/bench/subdivide.py INPUT.{obj,off} LEVELS OUTPUT.ply

Each level splits every triangle into four and smooths with Loop's weights (C. Loop, "Smooth subdivision
surfaces based on triangles", 1987; Warren's vertex weights): an edge point is 3/8 of each end and 1/8 of
each opposite corner, an old vertex of valence k keeps 1 - k*beta of itself and beta of each neighbour,
beta = 3/16 for k = 3 and 3/(8k) otherwise. Border edges and vertices use the curve rule (1/2, 1/2 and
3/4, 1/8, 1/8), so open meshes (the bunny) keep their openings; a vertex where more than one border
passes stays where it is. An edge with more than two faces is an error.
"""
import struct
import sys


def read_mesh(path):
    """Vertices [(x, y, z)] and triangles [(a, b, c)] of a text OBJ or OFF file. Polygons become fans, faces
    with a repeated corner are dropped, OBJ's negative (relative) indices are resolved, and fields after an
    OFF face's corners (colours) are ignored."""
    vertices, faces = [], []

    def add_polygon(corners):
        for i in range(1, len(corners) - 1):
            triangle = (corners[0], corners[i], corners[i + 1])
            if len(set(triangle)) == 3:
                faces.append(triangle)

    with open(path) as f:
        if path.lower().endswith(".off"):
            lines = (line.split("#", 1)[0].split() for line in f)
            lines = [fields for fields in lines if fields]
            if not lines[0][0].endswith("OFF"):
                raise ValueError(f"{path}: not an OFF file")
            header = lines[0][1:] if len(lines[0]) > 1 else lines[1]  # counts on the first line or the next
            body = lines[1:] if len(lines[0]) > 1 else lines[2:]
            n_vertices, n_faces = int(header[0]), int(header[1])
            vertices = [tuple(float(t) for t in fields[:3]) for fields in body[:n_vertices]]
            for fields in body[n_vertices:n_vertices + n_faces]:
                add_polygon([int(t) for t in fields[1:1 + int(fields[0])]])
        else:
            for line in f:
                fields = line.split()
                if not fields:
                    continue
                if fields[0] == "v":
                    vertices.append(tuple(float(t) for t in fields[1:4]))
                elif fields[0] == "f":
                    indices = [int(t.split("/")[0]) for t in fields[1:]]
                    add_polygon([i - 1 if i > 0 else len(vertices) + i for i in indices])
    return vertices, faces


def loop_subdivide(vertices, faces):
    """One level of Loop subdivision; raises ValueError on an edge with more than two faces."""
    opposite = {}  # edge (min, max) -> the corners opposite it
    for a, b, c in faces:
        for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
            opposite.setdefault((min(u, v), max(u, v)), []).append(w)
    neighbours = [set() for _ in vertices]
    border_neighbours = [[] for _ in vertices]
    edge_point = {}
    new_vertices = []
    n = len(vertices)
    for (u, v), across in opposite.items():
        if len(across) > 2:
            raise ValueError(f"edge {u}-{v} has {len(across)} faces")
        neighbours[u].add(v)
        neighbours[v].add(u)
        pu, pv = vertices[u], vertices[v]
        if len(across) == 2:
            pc, pd = vertices[across[0]], vertices[across[1]]
            point = tuple(0.375 * (pu[k] + pv[k]) + 0.125 * (pc[k] + pd[k]) for k in range(3))
        else:
            border_neighbours[u].append(v)
            border_neighbours[v].append(u)
            point = tuple(0.5 * (pu[k] + pv[k]) for k in range(3))
        edge_point[(u, v)] = n + len(new_vertices)
        new_vertices.append(point)
    moved = []
    for i, p in enumerate(vertices):
        if len(border_neighbours[i]) == 2:
            q, r = vertices[border_neighbours[i][0]], vertices[border_neighbours[i][1]]
            moved.append(tuple(0.75 * p[k] + 0.125 * (q[k] + r[k]) for k in range(3)))
            continue
        k_valence = len(neighbours[i])
        if k_valence == 0 or border_neighbours[i]:  # unused, or a border corner: kept in place
            moved.append(p)
            continue
        beta = 3.0 / 16.0 if k_valence == 3 else 3.0 / (8.0 * k_valence)
        sums = [sum(vertices[j][k] for j in neighbours[i]) for k in range(3)]
        moved.append(tuple((1 - k_valence * beta) * p[k] + beta * sums[k] for k in range(3)))
    new_faces = []
    for a, b, c in faces:
        ab, bc, ca = (edge_point[(min(u, v), max(u, v))] for u, v in ((a, b), (b, c), (c, a)))
        new_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return moved + new_vertices, new_faces


def write_ply(path, vertices, faces):
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        f.write(b"".join(struct.pack("<3f", *p) for p in vertices))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in faces))


def subdivide_file(source, levels, output):
    vertices, faces = read_mesh(source)
    for _ in range(levels):
        vertices, faces = loop_subdivide(vertices, faces)
    write_ply(output, vertices, faces)
    return len(vertices)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__.split("\n\n")[1])
    print(subdivide_file(sys.argv[1], int(sys.argv[2]), sys.argv[3]), "vertices")
