"""Draws docs/images/double-torus.png: the demo's points and the mesh dbrg makes of them, side by side.

Usage (Debian: apt-get install python3-matplotlib): /usr/bin/python3 docs/make_picture.py [PATH_TO_DBRG]
The program defaults to build/src/cli/dbrg; the picture is made from its own output, so it shows what the
built version does."""
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def read_off(path):
    """Vertices (N, 3) and triangles (M, 3) of a triangle-only OFF file as dbrg writes it."""
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF"
    vertex_count, face_count = int(words[1]), int(words[2])
    start = 4
    vertices = np.array(words[start:start + 3 * vertex_count], dtype=float).reshape(-1, 3)
    faces = np.array(words[start + 3 * vertex_count:], dtype=int).reshape(face_count, 4)
    return vertices, faces[:, 1:]


def topology(triangles):
    """'closed, genus g' or 'N boundary edges', counted from the triangles (one component assumed)."""
    edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    unique, uses = np.unique(edges, axis=0, return_counts=True)
    boundary = int((uses == 1).sum())
    if boundary:
        return "%d boundary edges" % boundary
    euler = len(np.unique(triangles)) - len(unique) + len(triangles)
    return "closed, genus %d" % ((2 - euler) // 2)


def shaded(vertices, triangles, light=(0.4, -0.6, 0.7)):
    """Face colours by Lambert shading, so the surface's shape reads without a renderer."""
    corners = vertices[triangles]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    light = np.asarray(light) / np.linalg.norm(light)
    brightness = 0.35 + 0.65 * np.clip(normals @ light, 0, 1)
    base = np.array([0.30, 0.55, 0.85])
    return np.clip(brightness[:, None] * base, 0, 1)


def framed(axes, limits, elevation, title):
    """Sets a 3-D panel to the points' box at true proportions, seen from `elevation` degrees, without axes."""
    axes.set_xlim(*limits[0])
    axes.set_ylim(*limits[1])
    axes.set_zlim(*limits[2])
    axes.set_box_aspect([hi - lo for lo, hi in limits])
    axes.view_init(elev=elevation, azim=-60)
    axes.set_axis_off()
    axes.set_title(title)


def save(figure, name):
    """Writes the figure to docs/images/NAME."""
    figure.tight_layout()
    output = os.path.join(HERE, "images", name)
    os.makedirs(os.path.dirname(output), exist_ok=True)
    figure.savefig(output, bbox_inches="tight")
    print("wrote", output)


def main():
    program = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "src", "cli", "dbrg")
    with tempfile.TemporaryDirectory() as folder:
        mesh_path = os.path.join(folder, "demo.off")
        subprocess.run([program, "reconstruct", "--demo", "--demo-points", "4000", "-q", "-o", mesh_path],
                       check=True)
        vertices, triangles = read_off(mesh_path)

    figure = plt.figure(figsize=(10, 4.2), dpi=100)
    limits = [(vertices[:, k].min(), vertices[:, k].max()) for k in range(3)]
    for column, title in enumerate(("%d points" % len(vertices),
                                    "dbrg: %d triangles, %s" % (len(triangles), topology(triangles)))):
        axes = figure.add_subplot(1, 2, column + 1, projection="3d")
        if column == 0:
            axes.scatter(vertices[:, 0], vertices[:, 1], vertices[:, 2], s=0.6, c="0.2", depthshade=False)
        else:
            axes.add_collection3d(Poly3DCollection(vertices[triangles], facecolors=shaded(vertices, triangles),
                                                   edgecolors=(0, 0, 0, 0.15), linewidths=0.15))
        framed(axes, limits, 38, title)
    save(figure, "double-torus.png")


if __name__ == "__main__":
    main()
