#!/usr/bin/env python3
"""Benchmark of `dbrg reconstruct` on simulated range scans: every closed mesh of the data folder, a torus and
a double torus, each scanned by scan_simulator.py at the clean, noisy and rough levels, reconstructed, and
measured by `dbrg stats --reference` against the mesh scanned. Prints a markdown table. Not a test: run it
by hand on a release build, with a Python that has numpy (Debian's /usr/bin/python3 with python3-numpy).

    /usr/bin/python3 tests/bench/bench_scans.py [--dbrg build/src/cli/dbrg] [--data ../shared/data]
                                                [--threads N] [--keep DIR]

A closed mesh is one with neither boundary nor non-manifold edges (`dbrg stats`); the double torus is the
mesh dbrg reconstructs from its own 20,000-point demo sample (closed, genus 2). Distances are in the
reference's mean side lengths s; the seconds are dbrg's own (reading and writing left out), on one thread
unless --threads says otherwise. --keep DIR keeps the scans (MODEL-LEVEL.xyz), the meshes and the
references there.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import scan_simulator as ss

MESH_SUFFIXES = (".obj", ".off", ".ply")


def run_json(command):
    completed = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(completed.stdout)


def closed_meshes(dbrg, data):
    """The data folder's meshes with neither boundary nor non-manifold edges."""
    found = []
    for name in sorted(os.listdir(data)):
        path = os.path.join(data, name)
        if name.endswith(MESH_SUFFIXES):
            report = run_json([dbrg, "stats", path])
            if report["edges_boundary"] == 0 and report["edges_nonmanifold"] == 0:
                found.append((name, path))
    return found


def generated_meshes(dbrg, workdir):
    torus = os.path.join(workdir, "torus.off")
    ss.write_off(torus, *ss.torus_mesh())
    double_torus = os.path.join(workdir, "double-torus.off")
    subprocess.run([dbrg, "reconstruct", "--demo", "--demo-shape", "double_torus", "--demo-points", "20000",
                    "-o", double_torus, "--quiet"], check=True)
    return [("torus", torus), ("double torus", double_torus)]


def in_sides(report, key):
    value = report.get(key)
    return "-" if value is None else f"{value / report['reference_side_mean']:.2f}"


def describe(report):
    """A mesh's topology in a few words: parts, Euler characteristic, genus when it has one."""
    parts = f"{report['components']} part{'s' if report['components'] != 1 else ''}"
    genus = "-" if report["genus"] is None else report["genus"]
    return f"{parts}, χ {report['euler_characteristic']}, genus {genus}"


def bench(dbrg, models, workdir, threads):
    print("| model (reference) | level | points | scan s | boundary edges | loops | components | χ | genus "
          "| to reference, mean / max (s) | from reference, mean / max (s) | dbrg s |")
    print("|---|---|" + "---:|" * 10)
    for name, path in models:
        reference = run_json([dbrg, "stats", path])
        vertices, triangles = ss.read_triangle_mesh(path)
        started = time.perf_counter()
        scan = ss.scan(vertices, triangles)
        scan_seconds = time.perf_counter() - started
        for level in ss.LEVELS:
            started = time.perf_counter()
            points, _ = ss.degrade(scan, level, vertices, triangles)
            seconds = scan_seconds + time.perf_counter() - started
            stem = os.path.join(workdir, f"{os.path.splitext(os.path.basename(path))[0]}-{level}")
            ss.write_points(stem + ".xyz", points)
            first = f"| {name} ({describe(reference)}) | {level} | {len(points)} | {seconds:.1f} "
            try:
                stats = run_json([dbrg, "reconstruct", stem + ".xyz", "-o", stem + ".ply", "--quiet",
                                  "--threads", str(threads), "--stats-json", "-"])
                report = run_json([dbrg, "stats", stem + ".ply", "--reference", path])
            except subprocess.CalledProcessError as error:
                message = (error.stderr or "").strip().splitlines()
                print(first + f"| failed (exit {error.returncode}): {message[-1] if message else ''} |", flush=True)
                continue
            distances = " | ".join(f"{in_sides(report, f'distance_{way}_reference_mean')} / "
                                   f"{in_sides(report, f'distance_{way}_reference_max')}" for way in ("to", "from"))
            print(first + f"| {report['edges_boundary']} | {report['boundary_loops']} | {report['components']} "
                  f"| {report['euler_characteristic']} | {'-' if report['genus'] is None else report['genus']} "
                  f"| {distances} | {stats['seconds_total']:.2f} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--dbrg", default=os.path.join(here, "..", "..", "build", "src", "cli", "dbrg"))
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "..", "shared", "data"))
    parser.add_argument("--threads", type=int, default=1, help="dbrg's threads (0: all; default 1)")
    parser.add_argument("--keep", metavar="DIR", help="keep the scans, meshes and references in DIR")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        workdir = args.keep or scratch
        os.makedirs(workdir, exist_ok=True)
        models = []
        if os.path.isdir(args.data):
            models = closed_meshes(args.dbrg, args.data)
        else:
            print(f"note: no data folder at {args.data}; generated shapes only", file=sys.stderr)
        bench(args.dbrg, models + generated_meshes(args.dbrg, workdir), workdir, args.threads)


if __name__ == "__main__":
    main()
