#!/usr/bin/env python3
"""Throughput of the Dask driver (dbrg.distributed) against one worker, the C library's tiled loop and one
call, on the same points. Not a test: run it by hand on a release build.

    DBRG_LIBRARY=build/src/libdbrg.so DBRG_IO_LIBRARY=build/src/io/libdbrg_io.so \\
        python3 tests/bench/bench_distributed.py POINTS.ply [--tiles 8] [--repeat 3] [--warm]

Every run is a fresh child process (and, for Dask, a fresh LocalCluster of one-thread worker processes), the
configurations alternating within each repeat. With --warm a Dask run is the cluster's second on the points,
as on a cluster that serves run after run; else its first, worker start-up costs included. Reported per run:
wall seconds, processor seconds of the child and of the Dask workers (getrusage, read on each worker before
the cluster closes) — processor time because the machine may be shared — and the peak resident set of the
child (which holds the cloud and the mesh) and of the largest worker. Every run's faces are compared with
the first tiled run's.
"""
import argparse
import ctypes
import hashlib
import json
import os
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "bindings", "python"))

CONFIGURATIONS = ("single", "c-loop", "dask-1", "dask-2")


def cpu_seconds(usage):
    return usage.ru_utime + usage.ru_stime


def worker_seconds():
    return cpu_seconds(resource.getrusage(resource.RUSAGE_SELF))


def peak_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def run_one(configuration, path, tiles, warm):
    import numpy as np
    import dbrg
    points, _ = dbrg.read_points(path)
    start_cpu, start = cpu_seconds(resource.getrusage(resource.RUSAGE_SELF)), time.monotonic()
    workers_cpu = 0.0
    if configuration == "single":
        mesh = dbrg.reconstruct(points, threads=1)
        triangles = mesh.triangles
    elif configuration == "c-loop":
        from dbrg import _capi
        lib = dbrg.library()
        array, view = dbrg._point_array(points)
        params = dbrg._params(lib, threads=1)
        handle = _capi.mesh_p()
        assert lib.dbrg_reconstruct_tiled(ctypes.byref(view), tiles, ctypes.byref(params), ctypes.byref(handle)) == 0
        triangles = dbrg._mesh(lib, handle, array).triangles
        lib.dbrg_mesh_destroy(handle)
    else:
        import dbrg.distributed
        from distributed import Client
        cluster = dbrg.distributed.local_cluster(int(configuration[-1]), memory_limit="1.5GiB")
        client = Client(cluster)
        client.wait_for_workers(int(configuration[-1]))
        if warm:  # a cluster that has served a run: the workers have loaded the library and hold freed memory
            dbrg.distributed.reconstruct(points, tiles=tiles, client=client, progress=False)
        before = sum(client.run(worker_seconds).values())
        start_cpu, start = cpu_seconds(resource.getrusage(resource.RUSAGE_SELF)), time.monotonic()
        triangles = dbrg.distributed.reconstruct(points, tiles=tiles, client=client, progress=False).triangles
        wall = time.monotonic() - start
        workers_cpu = sum(client.run(worker_seconds).values()) - before
        workers_rss = max(client.run(peak_rss_mb).values())
        client.close()
        cluster.close()
        return {"wall": wall, "cpu": cpu_seconds(resource.getrusage(resource.RUSAGE_SELF)) - start_cpu,
                "workers_cpu": workers_cpu, "rss": peak_rss_mb(), "workers_rss": workers_rss,
                "faces": hashlib.sha1(np.ascontiguousarray(triangles).tobytes()).hexdigest()}
    return {"wall": time.monotonic() - start, "cpu": cpu_seconds(resource.getrusage(resource.RUSAGE_SELF)) - start_cpu,
            "workers_cpu": workers_cpu, "rss": peak_rss_mb(), "workers_rss": 0.0,
            "faces": hashlib.sha1(np.ascontiguousarray(triangles).tobytes()).hexdigest()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("points")
    parser.add_argument("--tiles", type=int, default=8)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--only", default=",".join(CONFIGURATIONS))
    parser.add_argument("--warm", action="store_true",
                        help="time each Dask configuration's second run on its cluster, not its first")
    parser.add_argument("--one", help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.one:
        print(json.dumps(run_one(arguments.one, arguments.points, arguments.tiles, arguments.warm)))
        return
    runs = {name: [] for name in arguments.only.split(",")}
    for repeat in range(arguments.repeat):
        for name in runs:
            output = subprocess.run([sys.executable, __file__, arguments.points, "--tiles", str(arguments.tiles),
                                     "--one", name] + ["--warm"] * arguments.warm, check=True, capture_output=True,
                                    text=True).stdout
            result = json.loads(output.strip().splitlines()[-1])
            runs[name].append(result)
            print("%-7s wall %7.1f s, processor %7.1f s (this process %6.1f, workers %6.1f), peak RSS %5.0f MB "
                  "(a worker %5.0f MB)  faces %s"
                  % (name, result["wall"], result["cpu"] + result["workers_cpu"], result["cpu"], result["workers_cpu"],
                     result["rss"], result["workers_rss"], result["faces"][:10]), flush=True)
    print("\nmedians over %d runs, %d tiles asked:" % (arguments.repeat, arguments.tiles))
    for name, results in runs.items():
        print("%-7s wall %7.1f s, processor %7.1f s" % (
            name, statistics.median(r["wall"] for r in results),
            statistics.median(r["cpu"] + r["workers_cpu"] for r in results)))
    tiled = {r["faces"] for name in runs if name != "single" for r in runs[name]}
    print("tiled runs with the same faces: %s" % ("yes" if len(tiled) == 1 else "NO: %s" % sorted(tiled)))


if __name__ == "__main__":
    main()
