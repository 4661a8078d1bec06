"""Installs the build into a staging directory (meson install --destdir) and builds and runs consumer.c
against it the way a user would: with CMake's find_package, or with the commands docs/install.md gives
for pkg-config (shared, or with libdbrg.a).

Usage: check_install.py MODE --meson CMD --build-root DIR --work-dir DIR --prefix P --libdir L
       --includedir I --version X.Y.Z [--fully-static] -- CC [CC ARGS...]
MODE: cmake, pkg-config-shared or pkg-config-static. --fully-static also links a program with -static
(only when every library dbrg needs has an archive: not in builds with TetGen).
"""
import argparse
import contextlib
import fcntl
import os
import shlex
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CONSUMER = os.path.join(HERE, "consumer.c")


def run(command, **kwargs):
    print("+", shlex.join(command), flush=True)
    return subprocess.run(command, check=True, **kwargs)


def fail(message):
    print("FAILED: " + message, flush=True)
    sys.exit(1)


@contextlib.contextmanager
def install_log_kept(build_root):
    """meson install rewrites meson-logs/install-log.txt, which `ninja uninstall` reads: keep the user's own
    install's log, and let one test at a time install."""
    log = os.path.join(build_root, "meson-logs", "install-log.txt")
    with open(os.path.join(build_root, "meson-private", "dbrg-install-test.lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        saved = None
        if os.path.exists(log):
            with open(log, "rb") as f:
                saved = f.read()
        try:
            yield
        finally:
            if saved is None:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(log)
            else:
                with open(log, "wb") as f:
                    f.write(saved)


class Stage:
    """A `meson install --destdir` of the build: where each installed directory ended up."""

    def __init__(self, args):
        self.destdir = os.path.join(args.work_dir, "stage")
        self.prefix = self.staged(args.prefix, args.prefix)
        self.libdir = self.staged(args.libdir, args.prefix)
        self.includedir = self.staged(args.includedir, args.prefix)

    def staged(self, path, prefix):
        absolute = path if os.path.isabs(path) else os.path.join(prefix, path)
        return os.path.join(self.destdir, absolute.lstrip(os.sep))


def needed_libraries(program):
    dynamic = subprocess.run(["readelf", "-d", program], check=True, capture_output=True, text=True).stdout
    return [line.split("[", 1)[1].rstrip("]") for line in dynamic.splitlines() if "(NEEDED)" in line]


def check_program(program, links_libdbrg, stage, args=()):
    """Runs the consumer; a program that links libdbrg.so finds it through the staged libdir only."""
    needed = needed_libraries(program)
    uses_shared = any(name.startswith("libdbrg.so") for name in needed)
    if uses_shared != links_libdbrg:
        fail("{} {} libdbrg.so (needs {})".format(program, "does not link" if links_libdbrg else "links",
                                                 ", ".join(needed) or "nothing"))
    env = dict(os.environ)
    if links_libdbrg:
        env["LD_LIBRARY_PATH"] = stage.libdir
    else:
        env.pop("LD_LIBRARY_PATH", None)
    run([program] + list(args), env=env)


def check_cmake(args, stage, cc):
    build = os.path.join(args.work_dir, "cmake-build")
    compiler = ["-DCMAKE_C_COMPILER=" + cc[-1]]
    if len(cc) > 1:
        compiler.append("-DCMAKE_C_COMPILER_LAUNCHER=" + ";".join(cc[:-1]))
    run(["cmake", "-S", HERE, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
         "-DCMAKE_PREFIX_PATH=" + stage.prefix, "-DDBRG_VERSION=" + args.version] + compiler)
    # find_package searched the usual places below the prefix; the package it took must be the staged one.
    with open(os.path.join(build, "CMakeCache.txt")) as cache:
        found_at = [line.split("=", 1)[1].strip() for line in cache if line.startswith("dbrg_DIR:")]
    if not found_at or not found_at[0].startswith(stage.destdir):
        fail("find_package(dbrg) took {} instead of the staged install".format(found_at))
    run(["cmake", "--build", build])
    check_program(os.path.join(build, "consumer_shared"), True, stage)
    check_program(os.path.join(build, "consumer_static"), False, stage)
    mesh = os.path.join(build, "sphere.ply")
    check_program(os.path.join(build, "consumer_io"), True, stage, [mesh])
    with open(mesh, "rb") as f:
        header = f.read(400)
    if not header.startswith(b"ply\n") or b"property float nx" not in header:
        fail("consumer_io wrote no PLY file with normals to " + mesh)


def pkg_config(stage, *arguments):
    """pkg-config's answer for the staged install, as it would be for one in the prefix itself."""
    env = dict(os.environ, PKG_CONFIG_LIBDIR=os.path.join(stage.libdir, "pkgconfig"))
    env.pop("PKG_CONFIG_PATH", None)
    command = ["pkg-config", "--define-variable=prefix=" + stage.prefix, "--define-variable=libdir=" + stage.libdir,
               "--define-variable=includedir=" + stage.includedir] + list(arguments)
    print("+", shlex.join(command), flush=True)
    return shlex.split(subprocess.run(command, check=True, capture_output=True, text=True, env=env).stdout)


def compile_consumer(cc, program, flags, before=()):
    run(cc + list(before) + ["-std=c99", "-o", program, CONSUMER] + flags + ["-lm"])


def check_pkg_config_shared(args, stage, cc):
    program = os.path.join(args.work_dir, "consumer_shared")
    compile_consumer(cc, program, pkg_config(stage, "--cflags", "--libs", "dbrg"))
    check_program(program, True, stage)


def check_pkg_config_static(args, stage, cc):
    program = os.path.join(args.work_dir, "consumer_static")
    compile_consumer(cc, program, pkg_config(stage, "--cflags", "--libs", "dbrg-static"))
    check_program(program, False, stage)
    if args.fully_static:
        program = os.path.join(args.work_dir, "consumer_fully_static")
        compile_consumer(cc, program, pkg_config(stage, "--cflags", "--static", "--libs", "dbrg"), ["-static"])
        check_program(program, False, stage)
        if needed_libraries(program):
            fail(program + " is not fully static")


CHECKS = {"cmake": check_cmake, "pkg-config-shared": check_pkg_config_shared,
          "pkg-config-static": check_pkg_config_static}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=sorted(CHECKS))
    parser.add_argument("--meson", required=True, help="the meson command, as one shell word list")
    parser.add_argument("--build-root", required=True)
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--prefix", required=True)
    parser.add_argument("--libdir", required=True)
    parser.add_argument("--includedir", required=True)
    parser.add_argument("--version", required=True)
    parser.add_argument("--fully-static", action="store_true")
    parser.add_argument("cc", nargs="+", help="the C compiler command")
    args = parser.parse_args()

    shutil.rmtree(args.work_dir, ignore_errors=True)
    os.makedirs(args.work_dir)
    stage = Stage(args)
    with install_log_kept(args.build_root):
        run(shlex.split(args.meson) + ["install", "-C", args.build_root, "--no-rebuild", "--quiet",
                                       "--destdir", stage.destdir])
    CHECKS[args.mode](args, stage, args.cc)
    print("ok: {} consumer built and run against {}".format(args.mode, stage.destdir))


if __name__ == "__main__":
    main()
