#!/usr/bin/env python3
"""Benchmark of `dbrg reconstruct` on simulated range scans against CGAL's advancing front and scale-space
reconstructions: every closed mesh of the data folder, a torus and a double torus, each scanned by
scan_simulator.py at the clean, noisy and rough levels, reconstructed by each program, and measured by
`dbrg stats --reference` against the mesh scanned. Prints markdown tables and the targets of issue #12
(section 4) each scan misses. Not a test: run it by hand on a release build, with a Python that has numpy
(Debian's /usr/bin/python3 with python3-numpy).

    /usr/bin/python3 tests/bench/bench_scans.py [--dbrg build/src/cli/dbrg] [--data ../shared/data]
        [--only NAME[,NAME...]] [--levels clean,noisy,rough] [--include-open] [--hits-per-vertex H]
        [--repeat N] [--no-peers] [--keep DIR] [--json FILE]

Programs: dbrg on one thread and on its default threads (the same mesh; the table shows it once), and the
comparison programs cgal-advancing-front and cgal-scale-space (jet smoothing, 4 iterations of 12
neighbours, then advancing front, the triangles on the original points), found beside the dbrg program's
build tree (tests/bench/) when built: `ninja -C build tests/bench/cgal-advancing-front
tests/bench/cgal-scale-space` (libcgal-dev, libeigen3-dev). Every program's seconds are its own
reconstruction's (reading and writing left out), the median of --repeat runs (1 by default); the speed table
gives each peer's seconds over dbrg's, from the same runs.

--only keeps the models whose name contains one of the NAMEs (`--only torus` keeps both tori); --levels
keeps those levels. --include-open adds the data meshes that are not closed (the bunny: open under its base),
for speed; the closed-model targets are not judged on them. --hits-per-vertex scans denser (3 by default;
the scans stay deterministic, seeded). A closed mesh has neither boundary nor non-manifold edges (`dbrg
stats`); the double torus is the mesh dbrg reconstructs from its own 20,000-point demo sample (closed,
genus 2); where the reference has no genus (the cow: a non-manifold vertex), the genus is not judged.
Distances are in the reference's mean side lengths s. "outlier triangles" counts the triangles
with a corner on a simulated outlier (rough level). --keep DIR keeps the scans (MODEL-LEVEL.xyz, their labels
MODEL-LEVEL.labels), the meshes and the references; --json FILE writes every figure measured.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import scan_simulator as ss

MESH_SUFFIXES = (".obj", ".off", ".ply")
PEERS = ("cgal-advancing-front", "cgal-scale-space")
PEER_NAMES = {"cgal-advancing-front": "CGAL advancing front", "cgal-scale-space": "CGAL scale-space"}


def run_json(command):
    completed = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(completed.stdout)


def is_closed(report):
    return report["edges_boundary"] == 0 and report["edges_nonmanifold"] == 0


def data_meshes(dbrg, data, include_open):
    """The data folder's closed meshes (and the others too with include_open), as (name, path, closed)."""
    found = []
    for name in sorted(os.listdir(data)):
        path = os.path.join(data, name)
        if name.endswith(MESH_SUFFIXES):
            closed = is_closed(run_json([dbrg, "stats", path]))
            if closed or include_open:
                found.append((os.path.splitext(name)[0], path, closed))
    return found


def generated_meshes(dbrg, workdir):
    torus = os.path.join(workdir, "torus.off")
    ss.write_off(torus, *ss.torus_mesh())
    double_torus = os.path.join(workdir, "double-torus.off")
    subprocess.run([dbrg, "reconstruct", "--demo", "--demo-shape", "double_torus", "--demo-points", "20000",
                    "-o", double_torus, "--quiet"], check=True)
    return [("torus", torus, True), ("double torus", double_torus, True)]


def outlier_triangles(mesh_path, labels):
    """Triangles of the mesh (on the scan's points, in their order) with a corner on a simulated outlier."""
    vertices, triangles = ss.read_triangle_mesh(mesh_path)
    if len(vertices) != len(labels):
        raise ValueError(f"{mesh_path}: {len(vertices)} vertices for {len(labels)} scan points")
    if len(triangles) == 0:
        return 0
    return int(np.count_nonzero((labels[triangles] == ss.OUTLIER_LABEL).any(axis=1)))


def run_dbrg(dbrg, scan_path, mesh_path, threads):
    stats = run_json([dbrg, "reconstruct", scan_path, "-o", mesh_path, "--quiet", "--no-normals",
                      "--threads", str(threads), "--stats-json", "-"])
    return stats["seconds_total"], stats


def run_peer(program, scan_path, mesh_path):
    return run_json([program, scan_path, mesh_path])["seconds"], None


def timed(run, repeat):
    """The median seconds of `repeat` runs and the last run's details."""
    times, details = [], None
    for _ in range(repeat):
        seconds, details = run()
        times.append(seconds)
    return statistics.median(times), times, details


def measure_mesh(dbrg, mesh_path, reference_path, labels):
    report = run_json([dbrg, "stats", mesh_path, "--reference", reference_path])
    report["outlier_triangles"] = outlier_triangles(mesh_path, labels) if (labels == ss.OUTLIER_LABEL).any() else None
    return report


def same_bytes(first, second):
    with open(first, "rb") as a, open(second, "rb") as b:
        return a.read() == b.read()


def bench_scan(args, peers, name, path, level, points, labels, stem):
    """Every program's figures on one scan: {program: {"seconds", "times", "report", "stats"}}."""
    scan_path = stem + ".xyz"
    results = {}
    for program, threads in (("dbrg", 1), ("dbrg threads", 0)):
        mesh_path = f"{stem}-{program.replace(' ', '-')}.ply"
        seconds, times, stats = timed(lambda: run_dbrg(args.dbrg, scan_path, mesh_path, threads), args.repeat)
        results[program] = {"seconds": seconds, "times": times, "stats": stats, "mesh": mesh_path}
    one, default = results["dbrg"]["mesh"], results["dbrg threads"]["mesh"]
    results["dbrg threads"]["same_mesh"] = same_bytes(one, default)
    results["dbrg"]["report"] = measure_mesh(args.dbrg, one, path, labels)
    for program, binary in peers.items():
        mesh_path = f"{stem}-{program}.ply"
        try:
            seconds, times, _ = timed(lambda: run_peer(binary, scan_path, mesh_path), args.repeat)
        except subprocess.CalledProcessError as error:
            message = (error.stderr or "").strip().splitlines()
            results[program] = {"failed": f"exit {error.returncode}: {message[-1] if message else ''}"}
            continue
        results[program] = {"seconds": seconds, "times": times, "mesh": mesh_path,
                            "report": measure_mesh(args.dbrg, mesh_path, path, labels)}
    return results


def in_sides(report, key):
    value = report.get(key)
    return "-" if value is None else f"{value / report['reference_side_mean']:.3f}"


def describe(report):
    """A mesh's topology in a few words: parts, Euler characteristic, genus when it has one."""
    parts = f"{report['components']} part{'s' if report['components'] != 1 else ''}"
    genus = "-" if report["genus"] is None else report["genus"]
    return f"{parts}, χ {report['euler_characteristic']}, genus {genus}"


def dash(value):
    return "-" if value is None else str(value)


QUALITY_HEADER = ("| model (reference) | level | points | program | boundary edges | loops | components | χ | genus "
                  "| manifold, oriented | to ref. mean (s) | from ref. mean (s) | outlier triangles | seconds |\n"
                  "|---|---|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")


def quality_rows(row, programs):
    lines = []
    for program in programs:
        result = row["results"].get(program)
        if result is None:
            continue
        first = f"| {row['model']} ({describe(row['reference'])}) | {row['level']} | {row['points']} | {program} "
        if "failed" in result:
            lines.append(first + f"| failed ({result['failed']}) |")
            continue
        report = result["report"]
        manifold = (report["edges_nonmanifold"] == 0 and report["vertices_nonmanifold"] == 0)
        shape = f"{'yes' if manifold else 'no'}, {'yes' if report['oriented'] else 'no'}"
        lines.append(first + f"| {report['edges_boundary']} | {report['boundary_loops']} | {report['components']} "
                     f"| {report['euler_characteristic']} | {dash(report['genus'])} | {shape} "
                     f"| {in_sides(report, 'distance_to_reference_mean')} "
                     f"| {in_sides(report, 'distance_from_reference_mean')} "
                     f"| {dash(report['outlier_triangles'])} | {result['seconds']:.3f} |")
    return lines


SPEED_HEADER = ("| model | level | points | dbrg 1 thread s | clean s | Delaunay s | dbrg default threads s "
                "| advancing front s | scale-space s | AF / dbrg 1t | SS / dbrg 1t | AF / dbrg | SS / dbrg |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")


def speed_row(row):
    results = row["results"]
    one, default = results["dbrg"], results["dbrg threads"]

    def seconds(program):
        result = results.get(program)
        return None if result is None or "failed" in result else result["seconds"]

    def ratio(program, ours):
        theirs = seconds(program)
        return "-" if theirs is None else f"{theirs / ours['seconds']:.2f}"

    def shown(value):
        return "-" if value is None else f"{value:.3f}"

    note = "" if default["same_mesh"] else " (meshes differ!)"
    return (f"| {row['model']} | {row['level']} | {row['points']} | {one['seconds']:.3f} "
            f"| {one['stats']['seconds_clean']:.3f} | {one['stats']['seconds_delaunay']:.3f} "
            f"| {default['seconds']:.3f}{note} | {shown(seconds(PEERS[0]))} | {shown(seconds(PEERS[1]))} "
            f"| {ratio(PEERS[0], one)} | {ratio(PEERS[1], one)} | {ratio(PEERS[0], default)} "
            f"| {ratio(PEERS[1], default)} |")


def missed_targets(row):
    """Issue #12's section-4 targets this scan misses, in words (an empty list: all met or not judged)."""
    results, reference, level = row["results"], row["reference"], row["level"]
    ours = results["dbrg"]["report"]
    scale_space = results.get(PEERS[1])
    scale_space = None if scale_space is None or "failed" in scale_space else scale_space
    missed = []
    if not (ours["edges_nonmanifold"] == 0 and ours["vertices_nonmanifold"] == 0 and ours["oriented"]):
        missed.append("not manifold and oriented")
    if row["closed"] and level in ("clean", "noisy"):
        if ours["edges_boundary"] != 0:
            missed.append(f"not closed ({ours['edges_boundary']} boundary edges)")
        if ours["components"] != reference["components"]:
            missed.append(f"{ours['components']} components, not {reference['components']}")
        if reference["genus"] is not None and ours["genus"] != reference["genus"]:
            missed.append(f"genus {dash(ours['genus'])}, not {reference['genus']}")
    if row["closed"] and level == "rough":
        genus = ours["genus"]
        if genus is None and ours["components"] == 1 and ours["edges_nonmanifold"] == 0:
            # The genus of a surface with borders: chi = 2 - 2g - loops.
            genus = (2 - ours["euler_characteristic"] - ours["boundary_loops"]) // 2
        if reference["genus"] is not None and genus != reference["genus"]:
            missed.append(f"genus {dash(genus)}, not {reference['genus']}")
        if ours["outlier_triangles"]:
            missed.append(f"{ours['outlier_triangles']} triangles touch an outlier")
        if scale_space is not None:
            theirs = scale_space["report"]["edges_boundary"]
            allowed = 0.01 * theirs if theirs else 0.01 * row["points"]
            if ours["edges_boundary"] > allowed:
                missed.append(f"{ours['edges_boundary']} boundary edges, above {allowed:.1f} "
                              f"(1 % of {'scale-space' if theirs else 'the points'})")
    if scale_space is not None:
        for way in ("to", "from"):
            key = f"distance_{way}_reference_mean"
            if ours[key] > scale_space["report"][key]:
                missed.append(f"mean distance {way} the reference {ours[key] / scale_space['report'][key]:.4f} "
                              f"times scale-space's ({in_sides(ours, key)} s)")
    if row["points"] >= 100_000:
        for program, factor in ((PEERS[1], 5.0), (PEERS[0], 1.0)):
            peer = results.get(program)
            if peer is None or "failed" in peer:
                continue
            for ours_name in ("dbrg", "dbrg threads"):
                speedup = peer["seconds"] / results[ours_name]["seconds"]
                if speedup < factor:
                    missed.append(f"{ours_name} {speedup:.2f}x as fast as {PEER_NAMES[program]}, "
                                  f"not {factor:g}x or more")
    stats = results["dbrg"]["stats"]
    if stats["seconds_clean"] >= stats["seconds_delaunay"]:
        missed.append(f"cleaning {stats['seconds_clean']:.3f} s, not less than Delaunay's "
                      f"{stats['seconds_delaunay']:.3f} s")
    return missed


def find_peers(dbrg, wanted):
    """The comparison programs built beside the dbrg program's build tree: {name: path}."""
    build = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(dbrg))))
    peers = {}
    for name in wanted:
        path = os.path.join(build, "tests", "bench", name)
        if os.path.exists(path):
            peers[name] = path
        else:
            print(f"note: no {path} (install libcgal-dev and libeigen3-dev, reconfigure, and "
                  f"`ninja -C {build} tests/bench/{name}`); left out", file=sys.stderr)
    return peers


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--dbrg", default=os.path.join(here, "..", "..", "build", "src", "cli", "dbrg"))
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "..", "shared", "data"))
    parser.add_argument("--only", help="comma-separated parts of model names to keep (e.g. torus,fandisk)")
    parser.add_argument("--levels", default=",".join(ss.LEVELS), help="comma-separated levels to run")
    parser.add_argument("--include-open", action="store_true", help="also the data meshes that are not closed")
    parser.add_argument("--hits-per-vertex", type=float, default=3.0, help="scan density (default 3)")
    parser.add_argument("--repeat", type=int, default=1, help="runs of each program per scan; medians reported")
    parser.add_argument("--no-peers", action="store_true", help="dbrg only")
    parser.add_argument("--keep", metavar="DIR", help="keep the scans, labels, meshes and references in DIR")
    parser.add_argument("--json", metavar="FILE", help="write every figure measured to FILE")
    args = parser.parse_args()
    levels = args.levels.split(",")
    for level in levels:
        if level not in ss.LEVELS:
            parser.error(f"unknown level {level!r} (expected some of {', '.join(ss.LEVELS)})")
    wanted = args.only.split(",") if args.only else None
    peers = {} if args.no_peers else find_peers(args.dbrg, PEERS)
    programs = ["dbrg"] + list(peers)

    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        workdir = args.keep or scratch
        os.makedirs(workdir, exist_ok=True)
        models = []
        if os.path.isdir(args.data):
            models = data_meshes(args.dbrg, args.data, args.include_open)
        else:
            print(f"note: no data folder at {args.data}; generated shapes only", file=sys.stderr)
        models += generated_meshes(args.dbrg, workdir)
        if wanted:
            models = [model for model in models if any(part in model[0] for part in wanted)]
        print(QUALITY_HEADER, flush=True)
        for name, path, closed in models:
            reference = run_json([args.dbrg, "stats", path])
            vertices, triangles = ss.read_triangle_mesh(path)
            started = time.perf_counter()
            scan = ss.scan(vertices, triangles, hits_per_vertex=args.hits_per_vertex)
            scan_seconds = time.perf_counter() - started
            for level in levels:
                points, labels = ss.degrade(scan, level, vertices, triangles)
                stem = os.path.join(workdir, f"{name.replace(' ', '-')}-{level}")
                ss.write_points(stem + ".xyz", points)
                np.savetxt(stem + ".labels", labels, fmt="%d")
                row = {"model": name, "level": level, "points": len(points), "closed": closed,
                       "reference": reference, "scan_seconds": scan_seconds}
                try:
                    row["results"] = bench_scan(args, peers, name, path, level, points, labels, stem)
                except subprocess.CalledProcessError as error:
                    message = (error.stderr or "").strip().splitlines()
                    print(f"| {name} | {level} | {len(points)} | dbrg failed (exit {error.returncode}): "
                          f"{message[-1] if message else ''} |", flush=True)
                    continue
                rows.append(row)
                print("\n".join(quality_rows(row, programs)), flush=True)

    print("\n" + SPEED_HEADER)
    for row in rows:
        print(speed_row(row))
    print("\nTargets of issue #12 (section 4) missed:\n")
    for row in rows:
        missed = missed_targets(row)
        if missed:
            print(f"- {row['model']} {row['level']}: " + "; ".join(missed))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1, default=str)


if __name__ == "__main__":
    main()
