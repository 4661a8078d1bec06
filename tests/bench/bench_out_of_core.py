#!/usr/bin/env python3
"""Out-of-core reconstruction against one process: `dbrg reconstruct --max-memory` (slabs from files on
disk, docs/tiles.md) beside `dbrg reconstruct` on the same generated cloud. Reports each run's peak resident
memory and times (from /usr/bin/time), the slabs run and the most one slab held, and the share of the single
process's faces the out-of-core mesh has. Not a test: run it by hand on a release build.

    python3 tests/bench/bench_out_of_core.py [--dbrg build/src/cli/dbrg] [--points 5000000] [--max-memory 1.5G]
        [--repeat N] [--workdir DIR] [--keep] [--skip-single]

With --repeat N the two runs alternate N times and the medians are reported (processor seconds are the
figures to read on a shared machine).

The cloud: `--points` points on a bumpy sphere (radius 1 +- 0.1, directions from the Fibonacci lattice: about
evenly spaced, no two alike, deterministic; not on one sphere, whose cospherical points give a degenerate,
unusually small tetrahedralization), written as binary PLY with float coordinates (12 bytes a point). The single process needs
about 375 bytes a point at its peak, so past about 50M points on this machine (24 GiB) only the out-of-core
run fits: --skip-single leaves it out.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

import numpy as np

GOLDEN_ANGLE = np.pi * (3 - np.sqrt(5))


def write_cloud(path, count, chunk=1 << 22):
    """`count` points on a bumpy sphere, as binary little-endian PLY floats."""
    with open(path, "wb") as out:
        out.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {count}\n"
                  "property float x\nproperty float y\nproperty float z\nend_header\n".encode())
        for start in range(0, count, chunk):
            i = np.arange(start, min(count, start + chunk), dtype=np.float64)
            z = 1 - (2 * i + 1) / count
            radius = np.sqrt(1 - z * z)
            angle = GOLDEN_ANGLE * i
            direction = np.stack([radius * np.cos(angle), radius * np.sin(angle), z], axis=1)
            bump = 1 + 0.1 * np.sin(7 * direction[:, 0]) * np.cos(5 * direction[:, 1]) * np.sin(3 * direction[:, 2] + 1)
            xyz = (direction * bump[:, None]).astype("<f4")
            out.write(xyz.tobytes())


def read_faces(path):
    """The faces of a binary PLY written by dbrg (float or double vertices, uchar count + uint or uint64
    corners, optional per-face uchar flags), as an (n, 3) uint64 array."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            header += f.readline()
        lines = header.decode().split("\n")
        vertices = faces = 0
        vertex_bytes = 0
        index_type, face_extra = "<u4", 0
        element = None
        for line in lines:
            words = line.split()
            if words[:1] == ["element"]:
                element = words[1]
                if element == "vertex":
                    vertices = int(words[2])
                elif element == "face":
                    faces = int(words[2])
            elif words[:1] == ["property"]:
                sizes = {"float": 4, "double": 8, "uchar": 1, "uint": 4, "uint64": 8}
                if element == "vertex":
                    vertex_bytes += sizes[words[1]]
                elif words[1] == "list":
                    index_type = "<u8" if words[3] == "uint64" else "<u4"
                else:
                    face_extra += sizes[words[1]]
        f.seek(vertices * vertex_bytes, os.SEEK_CUR)
        index_bytes = np.dtype(index_type).itemsize
        record = np.dtype([("n", "u1"), ("v", index_type, 3)] + ([("extra", f"V{face_extra}")] if face_extra else []))
        assert record.itemsize == 1 + 3 * index_bytes + face_extra
        data = np.fromfile(f, dtype=record, count=faces)
    return data["v"].astype(np.uint64)


def face_keys(faces):
    """One 64-bit hash per face, whatever the order of its corners (collisions: about n^2 / 2^64)."""
    v = np.sort(faces, axis=1)
    with np.errstate(over="ignore"):
        return (v[:, 0] * np.uint64(0x9E3779B97F4A7C15)) ^ (v[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F)) ^ \
            (v[:, 2] * np.uint64(0x165667B19E3779F9))


def timed(command):
    """Runs `command` under /usr/bin/time; returns (wall s, processor s, peak RSS bytes, stats JSON)."""
    completed = subprocess.run(["/usr/bin/time", "-f", "TIME %e %U %S %M"] + command, capture_output=True, text=True)
    if completed.returncode != 0:
        sys.exit(f"failed: {' '.join(command)}\n{completed.stderr}")
    line = [l for l in completed.stderr.splitlines() if l.startswith("TIME ")][-1]
    wall, user, system, rss_kib = line.split()[1:]
    return float(wall), float(user) + float(system), int(rss_kib) * 1024, json.loads(completed.stdout)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dbrg", default="build/src/cli/dbrg")
    parser.add_argument("--points", type=int, default=5_000_000)
    parser.add_argument("--max-memory", default="1.5G")
    parser.add_argument("--workdir", help="where the cloud, the meshes and the tiles' files go (default: a new folder in .)")
    parser.add_argument("--keep", action="store_true", help="keep the cloud and the meshes")
    parser.add_argument("--skip-single", action="store_true", help="run only the out-of-core reconstruction")
    parser.add_argument("--repeat", type=int, default=1, help="alternate the runs this many times; medians")
    args = parser.parse_args()

    # The tiles' files go beside the output: a folder on disk, not a tmpfs /tmp, keeps them out of memory.
    workdir = args.workdir or tempfile.mkdtemp(prefix="dbrg_bench_out_of_core_", dir=".")
    os.makedirs(workdir, exist_ok=True)
    cloud = os.path.join(workdir, f"bumpy_sphere_{args.points}.ply")
    if not os.path.exists(cloud):
        write_cloud(cloud, args.points)
    print(f"cloud: {args.points} points, {os.path.getsize(cloud) / 2**20:.0f} MiB ({cloud})")

    tiled_out = os.path.join(workdir, "out_of_core.ply")
    single_out = os.path.join(workdir, "single.ply")
    runs = [("--max-memory " + args.max_memory,
             [args.dbrg, "reconstruct", cloud, "-o", tiled_out, "--max-memory", args.max_memory, "--quiet", "--stats-json", "-"])]
    if not args.skip_single:
        runs.append(("one process", [args.dbrg, "reconstruct", cloud, "-o", single_out, "--no-normals", "--quiet",
                                     "--stats-json", "-"]))
    measured = {name: [] for name, _ in runs}
    for _ in range(args.repeat):
        for name, command in runs:
            measured[name].append(timed(command))
    rows = []
    for name, _ in runs:
        samples = measured[name]
        median = lambda k: statistics.median(sample[k] for sample in samples)
        rows.append((name, median(0), median(1), median(2), samples[-1][3]))
        if args.repeat > 1:
            print(f"{name}: processor s {', '.join(f'{sample[1]:.1f}' for sample in samples)}")

    print()
    print("| run | tiles | triangles | peak RSS (MiB) | RSS B/pt | largest tile (MiB) | wall s | processor s |")
    print("|---|---|---|---|---|---|---|---|")
    for name, wall, cpu, rss, stats in rows:
        tile = stats.get("tile_peak_bytes", 0) / 2**20
        print(f"| {name} | {stats.get('tiles', 1)} | {stats['triangles']} | {rss / 2**20:.0f} | {rss / args.points:.0f} "
              f"| {tile:.0f} | {wall:.1f} | {cpu:.1f} |")
    if not args.skip_single:
        (_, tiled_wall, tiled_cpu, tiled_rss, _), (_, single_wall, single_cpu, single_rss, _) = rows
        tiled, single = face_keys(read_faces(tiled_out)), face_keys(read_faces(single_out))
        agreement = np.isin(single, tiled).mean()
        print(f"\nout of core / one process: peak RSS {tiled_rss / single_rss:.2f}x, wall {tiled_wall / single_wall:.2f}x, "
              f"processor {tiled_cpu / single_cpu:.2f}x; {agreement:.4%} of the single process's faces")
    print(f"\nthe 30M run for the lead:\n  python3 {sys.argv[0]} --dbrg {args.dbrg} --points 30000000 "
          f"--max-memory 1.5G --workdir {workdir}")
    if not args.keep and not args.workdir:
        shutil.rmtree(workdir)


if __name__ == "__main__":
    main()
