#!/usr/bin/env python3
"""End-to-end benchmark of `dbrg reconstruct`, printed in the form of the paper's Table 1 (n input points,
v points used, t triangles, DT, RG, HF and total seconds) with the quality figures of `dbrg stats` beside
it. Not a test: run it by hand on a release build.

    python3 tests/bench/bench_reconstruct.py [--dbrg build/src/cli/dbrg] [--data ../shared/data] [--large]
    python3 tests/bench/bench_reconstruct.py --holes     # boundaries before and after hole filling
    python3 tests/bench/bench_reconstruct.py --cgal      # against CGAL's advancing front, same inputs
    python3 tests/bench/bench_reconstruct.py --threads 2 # one thread against two on the large samples
    python3 tests/bench/bench_reconstruct.py --cgal --shapes  # random points on a sphere, cylinder, torus

Inputs: the vertices of every mesh in the data folder (face recall measured against the mesh itself),
two of them refined by Loop subdivision (subdivide.py: the spot to about 190k points and the rocker arm to
about 160k; with --large also to 750k and 640k), their recall measured against the subdivided mesh, and
generated samples of closed and open shapes (100k points; 1M and 2M too with --large). With --holes: the
data meshes and generated poor data (graded density, sharp edges, a thin plate), each reconstructed
with and without hole filling. With --holes and --cgal also the bunny's vertices under Gaussian noise of
0.3 and 0.6 mean side lengths (a scanner's noise), measured against the clean mesh. With --shapes only
uniformly random (not evenly spaced) points on a unit sphere (20k and 200k), an open cylinder of radius 1 and
height 6 (200k) and a torus of radii 1 and 0.35 (200k): nearly degenerate for the predicates (issue #13).
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile

from subdivide import read_mesh, subdivide_file

MESH_SUFFIXES = (".obj", ".off", ".ply")


def run_json(command):
    completed = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(completed.stdout)


def measure(dbrg, source, workdir, reference=None, options=(), threads=1):
    """Reconstructs `source` (a file, or ('demo', shape, points)) on `threads` threads (0: all) and returns
    (stats, report)."""
    output = os.path.join(workdir, "out.ply")
    if isinstance(source, tuple):
        _, shape, points = source
        command = [dbrg, "reconstruct", "--demo", "--demo-shape", shape, "--demo-points", str(points)]
    else:
        command = [dbrg, "reconstruct", source]
    # One thread by default, like CGAL's advancing front; --threads N measures the second core separately.
    stats = run_json(command + ["--threads", str(threads)] + list(options) + ["-o", output, "--quiet", "--stats-json", "-"])
    stats_command = [dbrg, "stats", output]
    if reference:
        stats_command += ["--reference", reference]
    report = run_json(stats_command)
    return stats, report


def row(name, stats, report):
    recall = report.get("face_recall")
    return (
        f"| {name} | {stats['points']} | {stats['vertices_used']} | {stats['triangles']} "
        f"| {stats['seconds_delaunay']:.3f} | {stats['seconds_growing']:.3f} | {stats['seconds_fill_holes']:.3f} "
        f"| {stats['seconds_total']:.3f} | {stats['points'] / max(stats['seconds_total'], 1e-9) / 1e6:.2f} "
        f"| {stats['library_peak_bytes'] / stats['points']:.0f} "
        f"| {report['edges_boundary']} | {report['boundary_loops']} | {report['edges_nonmanifold']} "
        f"| {report['vertices_nonmanifold']} | {'yes' if report['oriented'] else 'no'} "
        f"| {report['genus'] if report['genus'] is not None else '-'} "
        f"| {'-' if recall is None else f'{recall:.3f}'} |"
    )


def hole_table(dbrg, inputs, workdir):
    print("| input | boundary edges / loops without filling | with filling | holes found | filled "
          "| left open | Delaunay triangles | new triangles | removed | genus | face recall |")
    print("|---|" + "---:|" * 10)
    for name, source, reference in inputs:
        before, _ = measure(dbrg, source, workdir, reference, ["--no-fill-holes"])
        after, report = measure(dbrg, source, workdir, reference)
        recall = report.get("face_recall")
        print(f"| {name} | {before['boundary_edges']} / {before['boundary_loops']} "
              f"| {after['boundary_edges']} / {after['boundary_loops']} | {after['holes_found']} "
              f"| {after['holes_filled']} | {after['holes_left_open']} | {after['hole_triangles_delaunay']} "
              f"| {after['hole_triangles_added']} | {after['hole_triangles_removed']} "
              f"| {report['genus'] if report['genus'] is not None else '-'} "
              f"| {'-' if recall is None else f'{recall:.3f}'} |", flush=True)


def sample_file(dbrg, source, workdir):
    """A generated source ('demo', shape, points) written to a point file once; files stay as they are."""
    if not isinstance(source, tuple):
        return source
    _, shape, points = source
    path = os.path.join(workdir, f"{shape}-{points}.ply")
    if not os.path.exists(path):
        subprocess.run([dbrg, "reconstruct", "--demo", "--demo-shape", shape, "--demo-points", str(points),
                        "-o", path, "--quiet"], check=True)
    return path


def add_subdivided(inputs, data, subdivided, workdir):
    """The data meshes refined by Loop subdivision, each file both the input and the reference."""
    for name, levels in subdivided:
        path = os.path.join(workdir, f"{os.path.splitext(name)[0]}-loop{levels}.ply")
        points = subdivide_file(os.path.join(data, name), levels, path)
        inputs.append((f"{name} Loop x{levels} ({points // 1000}k)", path, path))


def add_noisy(inputs, data, workdir, model="stanford-bunny.obj", sigmas=(0.3, 0.6)):
    """A scan's noise: the model's vertices moved by Gaussian noise of `sigma` mean side lengths in each
    coordinate (a fixed seed), as point files; the clean mesh stays the reference of the distances."""
    source = os.path.join(data, model)
    if not os.path.exists(source):
        return
    vertices, faces = read_mesh(source)
    sides = [math.dist(vertices[t[k]], vertices[t[(k + 1) % 3]]) for t in faces for k in range(3)]
    side = sum(sides) / len(sides)
    for sigma in sigmas:
        rng = random.Random(1)
        path = os.path.join(workdir, f"{os.path.splitext(model)[0]}-noise{sigma}.xyz")
        with open(path, "w") as f:
            for v in vertices:
                f.write(" ".join(repr(c + rng.gauss(0, sigma * side)) for c in v) + "\n")
        inputs.append((f"{model} + noise {sigma} side", path, source))


def add_random_shapes(inputs, workdir):
    """Uniformly random points (a fixed seed) on a sphere, an open cylinder and a torus, as point files."""
    rng = random.Random(13)

    def sphere():
        while True:
            x, y, z = (rng.gauss(0, 1) for _ in range(3))
            length = math.sqrt(x * x + y * y + z * z)
            if length > 1e-3:
                return x / length, y / length, z / length

    def cylinder():
        angle = rng.uniform(0, 2 * math.pi)
        return math.cos(angle), math.sin(angle), rng.uniform(0, 6)

    def torus(radius=1.0, tube=0.35):
        while True:  # uniform by area: the tube angle with density radius + tube cos(v)
            u, v = rng.uniform(0, 2 * math.pi), rng.uniform(0, 2 * math.pi)
            if rng.uniform(0, radius + tube) <= radius + tube * math.cos(v):
                ring = radius + tube * math.cos(v)
                return ring * math.cos(u), ring * math.sin(u), tube * math.sin(v)

    for name, point, count in (("sphere", sphere, 20_000), ("sphere", sphere, 200_000),
                               ("open cylinder", cylinder, 200_000), ("torus", torus, 200_000)):
        path = os.path.join(workdir, f"random-{name.replace(' ', '_')}-{count}.xyz")
        with open(path, "w") as f:
            for _ in range(count):
                f.write(" ".join(repr(c) for c in point()) + "\n")
        inputs.append((f"random {name} {count // 1000}k", path, None))


def compare_threads(dbrg, threads, inputs, workdir, repeats=3):
    """One thread against `threads`, the best of `repeats` runs each (read and write included), and whether
    the two meshes are byte-identical."""
    print(f"| input | n | 1 thread s | {threads} threads s | speed-up | validate s (1 / {threads}) "
          f"| Delaunay s (1 / {threads}) | same mesh |")
    print("|---|" + "---:|" * 6 + "---|")
    for name, source, _ in inputs:
        path = sample_file(dbrg, source, workdir)
        best, meshes = {}, {}
        for count in (1, threads):
            output = os.path.join(workdir, f"threads-{count}.ply")
            for _ in range(repeats):
                stats = run_json([dbrg, "reconstruct", path, "-o", output, "--quiet", "--threads", str(count),
                                  "--stats-json", "-"])
                stats["wall"] = stats["seconds_read"] + stats["seconds_total"] + stats["seconds_write"]
                if count not in best or stats["wall"] < best[count]["wall"]:
                    best[count] = stats
            with open(output, "rb") as f:
                meshes[count] = f.read()
        one, many = best[1], best[threads]
        print(f"| {name} | {one['points']} | {one['wall']:.3f} | {many['wall']:.3f} "
              f"| {one['wall'] / max(many['wall'], 1e-9):.2f}x "
              f"| {one['seconds_validate']:.3f} / {many['seconds_validate']:.3f} "
              f"| {one['seconds_delaunay']:.3f} / {many['seconds_delaunay']:.3f} "
              f"| {'yes' if meshes[1] == meshes[threads] else 'NO'} |", flush=True)


def farthest(report):
    """The farthest a point of the mesh is from the reference surface, in the reference's mean side lengths."""
    distance, side = report.get("distance_to_reference_max"), report.get("reference_side_mean")
    return "-" if distance is None or not side else f"{distance / side:.2f}"


def compare_with_cgal(dbrg, cgal, inputs, workdir, repeats=3):
    """dbrg against CGAL's advancing-front reconstruction on the same point files, in the same run: dbrg on
    one thread (CGAL's reconstruction has no parallel mode) and with its default, every processor. Each of
    the three runs `repeats` times, taking turns, and the best time of each counts: on a shared machine the
    fastest run is the one least disturbed."""
    print("| input | n | dbrg s | CGAL AFSR s | speed-up | dbrg s, all threads | speed-up, all threads "
          "| dbrg recall | CGAL recall | dbrg / CGAL farthest from the reference | dbrg boundary edges "
          "| CGAL boundary edges | dbrg non-manifold edges / vertices | CGAL non-manifold edges / vertices |")
    print("|---|" + "---:|" * 13)
    for name, source, reference in inputs:
        source = sample_file(dbrg, source, workdir)  # generated: one file both programs read
        theirs_path = os.path.join(workdir, "cgal.ply")
        ours = all_threads = theirs = float("inf")
        our_report = None
        for _ in range(repeats):
            # The output is the same every time: compare it with the reference once.
            stats, report = measure(dbrg, source, workdir, None if our_report else reference)
            our_report = our_report or report
            ours = min(ours, stats["seconds_total"])
            stats, _ = measure(dbrg, source, workdir, threads=0)
            all_threads = min(all_threads, stats["seconds_total"])
            theirs = min(theirs, run_json([cgal, source, theirs_path])["seconds"])
        their_report = run_json([dbrg, "stats", theirs_path] + (["--reference", reference] if reference else []))
        recall = lambda report: "-" if report.get("face_recall") is None else f"{report['face_recall']:.3f}"
        print(f"| {name} | {stats['points']} | {ours:.3f} | {theirs:.3f} | {theirs / max(ours, 1e-9):.1f}x "
              f"| {all_threads:.3f} | {theirs / max(all_threads, 1e-9):.1f}x | {recall(our_report)} "
              f"| {recall(their_report)} | {farthest(our_report)} / {farthest(their_report)} | {our_report['edges_boundary']} | {their_report['edges_boundary']} "
              f"| {our_report['edges_nonmanifold']} / {our_report['vertices_nonmanifold']} "
              f"| {their_report['edges_nonmanifold']} / {their_report['vertices_nonmanifold']} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--dbrg", default=os.path.join(here, "..", "..", "build", "src", "cli", "dbrg"))
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "..", "shared", "data"))
    parser.add_argument("--large", action="store_true", help="also 1M and 2M-point samples")
    parser.add_argument("--holes", action="store_true", help="boundaries before and after hole filling")
    parser.add_argument("--cgal", action="store_true",
                        help="compare with CGAL's advancing front (build tests/bench/cgal-advancing-front first; "
                             "needs libcgal-dev)")
    parser.add_argument("--shapes", action="store_true",
                        help="only random points on a sphere, an open cylinder and a torus (with --cgal: against it)")
    parser.add_argument("--threads", type=int, metavar="N",
                        help="one thread against N on the inputs of 100k points or more (and the same mesh?)")
    args = parser.parse_args()

    inputs = []
    if args.shapes:
        with tempfile.TemporaryDirectory() as workdir:
            add_random_shapes(inputs, workdir)
            if args.cgal:
                compare_with_cgal(args.dbrg, cgal_program(args.dbrg), inputs, workdir)
            else:
                table(args.dbrg, inputs, workdir)
        return
    if os.path.isdir(args.data):
        for name in sorted(os.listdir(args.data)):
            if name.endswith(MESH_SUFFIXES):
                path = os.path.join(args.data, name)
                inputs.append((name, path, path))
    else:
        print(f"note: no data folder at {args.data}; generated samples only", file=sys.stderr)
    if args.holes:
        for shape in ("graded_sphere", "cube", "capped_cylinder", "thin_plate"):
            inputs.append((f"{shape} 10k", ("demo", shape, 10_000), None))
        with tempfile.TemporaryDirectory() as workdir:
            add_noisy(inputs, args.data, workdir)
            hole_table(args.dbrg, inputs, workdir)
        return
    sizes = [100_000] + ([1_000_000, 2_000_000] if args.large else [])
    for points in sizes:
        for shape in ("torus", "bumpy_sphere", "saddle"):
            inputs.append((f"{shape} {points // 1000}k", ("demo", shape, points), None))
    subdivided = [("spot.obj", 3), ("rocker-arm.off", 2)] + ([("spot.obj", 4), ("rocker-arm.off", 3)] if args.large else [])
    subdivided = [(name, levels) for name, levels in subdivided if os.path.exists(os.path.join(args.data, name))]

    if args.threads:
        with tempfile.TemporaryDirectory() as workdir:
            large = [i for i in inputs if isinstance(i[1], tuple)]
            add_subdivided(large, args.data, subdivided, workdir)
            compare_threads(args.dbrg, args.threads, large, workdir)
        return
    if args.cgal:
        cgal = cgal_program(args.dbrg)
        with tempfile.TemporaryDirectory() as workdir:
            add_subdivided(inputs, args.data, subdivided, workdir)
            add_noisy(inputs, args.data, workdir)
            compare_with_cgal(args.dbrg, cgal, inputs, workdir)
        return
    with tempfile.TemporaryDirectory() as workdir:
        add_subdivided(inputs, args.data, subdivided, workdir)
        table(args.dbrg, inputs, workdir)


def cgal_program(dbrg):
    """The CGAL peer built beside `dbrg` (build/src/cli/dbrg -> build/tests/bench/cgal-advancing-front)."""
    cgal = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(dbrg)))),
                        "tests", "bench", "cgal-advancing-front")
    if not os.path.exists(cgal):
        sys.exit(f"no {cgal}: install libcgal-dev, reconfigure, and build it: "
                 f"ninja -C build tests/bench/cgal-advancing-front")
    return cgal


def table(dbrg, inputs, workdir):
    print("| input | n | v | t | DT s | RG s | HF s | total s | Mpts/s | peak B/pt | boundary edges "
          "| loops | non-manifold edges | non-manifold vertices | oriented | genus | face recall |")
    print("|---|" + "---:|" * 16)
    for name, source, reference in inputs:
        stats, report = measure(dbrg, source, workdir, reference)
        print(row(name, stats, report), flush=True)


if __name__ == "__main__":
    main()
