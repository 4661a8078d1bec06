"""python3 -m dbrg: the dbrg program installed inside this package, with the same arguments, output and
exit code. The Python process is replaced by the program, so signals and Ctrl-C behave as for the
program itself, and there is one implementation of the command line, not two.

The program is looked up as the environment variable DBRG_PROGRAM names it (e.g. build/src/cli/dbrg
in a build tree), else in dbrg/bin/ beside this file, where `pip install .` puts it.

One command runs here instead: `reconstruct ... --distributed`, the tiles of `--tiles N` run as tasks on a
Dask cluster (dbrg.distributed) rather than one after another in the program; the same mesh.
"""

import os
import sys

DISTRIBUTED_USAGE = """usage: python3 -m dbrg reconstruct INPUT -o OUTPUT --distributed [--tiles N] [--workers N | --scheduler ADDR] [options]

Reconstructs INPUT as `dbrg reconstruct --tiles N` does, the same mesh, with the tiles and the seam stitches
run as tasks on a Dask cluster (docs/tiles.md, "Running on Dask"): a local cluster of worker processes, or
the scheduler at ADDR. The points and the mesh stay in this process; each task is sent its own points.

  -o, --output FILE        the mesh to write (.ply binary, .obj, .off, .stl)
  --tiles N                slabs along the longest axis (default 8; fewer where a slab would be thinner
                           than 12 point spacings)
  --workers N              worker processes of the local cluster (default 2), one thread each
  --memory-limit SIZE      memory limit of each local worker, as Dask reads it (default 1GiB)
  --scheduler ADDR         run on the cluster of this scheduler (tcp://host:8786) instead
  --boundary-factor M, --boundary-mean local|global, --sliver-angle DEG, --no-fill-holes,
  --max-hole-edges N, --max-components N, --backend builtin|tetgen, --cleaning auto|off|on
                           as for `dbrg reconstruct`
  --no-normals             write no vertex normals
  --stats-json FILE        write the figures of the run as JSON (- for standard output)
  -q, --quiet              no progress bar
  -h, --help               show this help
"""


def program_path():
    """The dbrg program this package runs (it may not exist: the package can be used without it)."""
    explicit = os.environ.get("DBRG_PROGRAM")
    if explicit:
        return explicit
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "dbrg")


def reconstruct_distributed(arguments):
    """`reconstruct ... --distributed`: parses the arguments the way the program does and runs
    dbrg.distributed.reconstruct. Returns the exit status (2 for a usage error, 1 for a failed run)."""
    import argparse
    import contextlib
    import json
    import math
    import time

    parser = argparse.ArgumentParser(prog="python3 -m dbrg reconstruct", usage=DISTRIBUTED_USAGE, add_help=False)
    parser.add_argument("input", nargs="?")
    parser.add_argument("-o", "--output")
    parser.add_argument("--distributed", action="store_true")
    parser.add_argument("--tiles", type=int, default=8)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--memory-limit", default="1GiB")
    parser.add_argument("--scheduler")
    parser.add_argument("--boundary-factor", type=float)
    parser.add_argument("--boundary-mean", choices=["local", "global"])
    parser.add_argument("--sliver-angle", type=float)
    parser.add_argument("--no-fill-holes", action="store_true")
    parser.add_argument("--max-hole-edges", type=int)
    parser.add_argument("--max-components", type=int)
    parser.add_argument("--backend", choices=["builtin", "tetgen"])
    parser.add_argument("--cleaning", choices=["auto", "off", "on"])
    parser.add_argument("--no-normals", action="store_true")
    parser.add_argument("--stats-json")
    parser.add_argument("-q", "--quiet", action="store_true")
    parser.add_argument("-h", "--help", action="store_true")
    options, unknown = parser.parse_known_args(arguments)
    if options.help:
        sys.stdout.write(DISTRIBUTED_USAGE)
        return 0
    problem = None
    if unknown:
        problem = "%s: not an option of reconstruct --distributed" % unknown[0]
    elif not options.input or not options.output:
        problem = "reconstruct --distributed needs INPUT and -o OUTPUT"
    elif options.tiles < 1 or options.workers < 1:
        problem = "--tiles and --workers take a positive count"
    elif options.scheduler and "--workers" in arguments:
        problem = "--workers starts a local cluster; --scheduler uses another: give one of them"
    if problem:
        sys.stderr.write("dbrg: %s\n%s" % (problem, DISTRIBUTED_USAGE))
        return 2
    surface = {"boundary_factor": options.boundary_factor, "boundary_mean": options.boundary_mean,
               "max_hole_edges": options.max_hole_edges, "max_components": options.max_components,
               "backend": options.backend, "cleaning": options.cleaning,
               "sliver_angle": None if options.sliver_angle is None else math.radians(options.sliver_angle)}
    surface = {name: value for name, value in surface.items() if value is not None}
    if options.no_fill_holes:
        surface["fill_holes"] = False

    import dbrg
    import dbrg.distributed
    try:
        start = time.monotonic()
        points, _ = dbrg.read_points(options.input)
        with contextlib.redirect_stdout(sys.stderr):  # Dask's progress bar, as the program's, on stderr
            mesh = dbrg.distributed.reconstruct(points, tiles=options.tiles, scheduler=options.scheduler,
                                                n_workers=options.workers, memory_limit=options.memory_limit,
                                                progress=not options.quiet, **surface)
        mesh.write(options.output, normals=not options.no_normals)
    except (dbrg.Error, OSError, ValueError, MemoryError, ImportError) as error:
        sys.stderr.write("dbrg: %s\n" % error)
        return 1
    if options.stats_json:
        figures = dict(mesh.stats, seconds_total=time.monotonic() - start)
        text = json.dumps(figures, indent=2) + "\n"
        if options.stats_json == "-":
            sys.stdout.write(text)
        else:
            with open(options.stats_json, "w") as out:
                out.write(text)
    return 0


def main():
    if sys.argv[1:2] == ["reconstruct"] and "--distributed" in sys.argv[2:]:
        sys.exit(reconstruct_distributed(sys.argv[2:]))
    program = program_path()
    if not os.access(program, os.X_OK):
        sys.exit("dbrg: the dbrg program is not at %s; install the package with `pip install .` from the "
                 "repository, or set DBRG_PROGRAM to the program's path" % program)
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(program, [program] + sys.argv[1:])


if __name__ == "__main__":
    main()
