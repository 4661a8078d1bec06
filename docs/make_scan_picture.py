"""Draws docs/images/scan-before-after.png: a rough simulated scan of a torus (range noise, misregistered views,
outliers; tests/bench/scan_simulator.py), the mesh dbrg makes of it with the cleaning stage off, and the mesh
it makes by default, with the border edges in red.

Usage (Debian: apt-get install python3-matplotlib python3-numpy):
    /usr/bin/python3 docs/make_scan_picture.py [PATH_TO_DBRG]
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
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

from make_picture import HERE, framed, read_off, save, shaded, topology  # noqa: E402

sys.path.insert(0, os.path.join(HERE, "..", "tests", "bench"))
import scan_simulator as ss  # noqa: E402

LEVEL = "rough"


def boundary_segments(vertices, triangles):
    """The segments of the edges used by one triangle only."""
    edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    unique, uses = np.unique(edges, axis=0, return_counts=True)
    return vertices[unique[uses == 1]]


def reconstruct(program, points_path, folder, cleaning):
    mesh_path = os.path.join(folder, f"cleaning-{cleaning}.off")
    subprocess.run([program, "reconstruct", points_path, "--cleaning", cleaning, "--no-normals", "-q",
                    "-o", mesh_path], check=True)
    return read_off(mesh_path)


def main():
    program = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "src", "cli", "dbrg")
    mesh_vertices, mesh_triangles = ss.torus_mesh()
    points, labels = ss.degrade(ss.scan(mesh_vertices, mesh_triangles), LEVEL, mesh_vertices, mesh_triangles)
    with tempfile.TemporaryDirectory() as folder:
        points_path = os.path.join(folder, "scan.xyz")
        ss.write_points(points_path, points)
        meshes = [reconstruct(program, points_path, folder, cleaning) for cleaning in ("off", "auto")]

    outliers = int(np.count_nonzero(labels == ss.OUTLIER_LABEL))
    titles = ["%s scan: %d points, %d outliers" % (LEVEL, len(points), outliers),
              "--cleaning off: %s" % topology(meshes[0][1]),
              "default: %s" % topology(meshes[1][1])]
    figure = plt.figure(figsize=(13.5, 4.4), dpi=80)
    limits = [(points[:, k].min(), points[:, k].max()) for k in range(3)]
    for column, title in enumerate(titles):
        axes = figure.add_subplot(1, 3, column + 1, projection="3d")
        if column == 0:
            axes.scatter(points[:, 0], points[:, 1], points[:, 2], s=0.3, c="0.2", depthshade=False)
        else:
            vertices, triangles = meshes[column - 1]
            axes.add_collection3d(Poly3DCollection(vertices[triangles], facecolors=shaded(vertices, triangles),
                                                   edgecolors="none"))
            borders = boundary_segments(vertices, triangles)
            if len(borders):
                axes.add_collection3d(Line3DCollection(borders, colors="red", linewidths=0.8))
        framed(axes, limits, 50, title)
    save(figure, "scan-before-after.png")


if __name__ == "__main__":
    main()
