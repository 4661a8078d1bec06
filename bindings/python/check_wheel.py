#!/usr/bin/env python3
"""What `pip install .` gives a user: builds the wheel from the repository root offline (meson-python,
--no-build-isolation), installs it into a fresh virtual environment that sees the system's numpy, and
runs the binding's tests, `python -m dbrg` and the `dbrg` script against the installed package, from a
neutral directory with DBRG_LIBRARY, DBRG_PROGRAM and PYTHONPATH unset. Exits 77 (skipped) without
numpy, pip, venv or meson-python.

    python3 bindings/python/check_wheel.py SOURCE_ROOT BUILD_DIR

BUILD_DIR keeps meson-python's build between runs, so a second run only rebuilds what changed.
"""

import glob
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
MISSING = [
    ("numpy", "python3-numpy"), ("pip", "python3-pip"), ("venv", "python3-venv"), ("mesonpy", "python3-mesonpy"),
]


def missing_modules():
    missing = []
    for module, package in MISSING:
        probe = subprocess.run([sys.executable, "-c", "import " + module], capture_output=True)
        if probe.returncode != 0:
            missing.append("%s (Debian: %s)" % (module, package))
    return missing


def run(command, **kwargs):
    print("$", " ".join(command), flush=True)
    started = time.monotonic()
    subprocess.run(command, check=True, **kwargs)
    print("  (%.1f s)" % (time.monotonic() - started), flush=True)


def output_of(command, env, cwd):
    result = subprocess.run(command, env=env, cwd=cwd, capture_output=True, text=True, check=True)
    return result.stdout


def main(source_root, build_dir):
    missing = missing_modules()
    if missing:
        print("skipped: %s lacks %s" % (sys.executable, ", ".join(missing)))
        return 77
    clean_env = {key: value for key, value in os.environ.items()
                 if key not in ("DBRG_LIBRARY", "DBRG_PROGRAM", "PYTHONPATH", "PIP_REQUIRE_VIRTUALENV")}
    clean_env["PIP_ROOT_USER_ACTION"] = "ignore"
    clean_env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    # meson-python 0.12.0 reconfigures a given build directory whenever the native file it leaves in the
    # source tree exists, which fails on a directory that holds no build yet; without that file it sets up.
    if not os.path.exists(os.path.join(build_dir, "meson-private", "coredata.dat")):
        native_file = os.path.join(source_root, ".mesonpy-native-file.ini")
        if os.path.exists(native_file):
            os.remove(native_file)
    with tempfile.TemporaryDirectory(prefix="dbrg-wheel-") as scratch:
        wheels = os.path.join(scratch, "wheels")
        run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-build-isolation", "--no-deps", "--no-index",
             "--wheel-dir", wheels, "--config-settings", "builddir=" + os.path.abspath(build_dir),
             "--config-settings", "compile-args=-j2", os.path.abspath(source_root)], env=clean_env, cwd=scratch)
        (wheel,) = glob.glob(os.path.join(wheels, "dbrg-*.whl"))
        # Without pip of its own: the system's pip, visible through --system-site-packages, installs into it.
        venv = os.path.join(scratch, "venv")
        run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", venv], env=clean_env)
        python = os.path.join(venv, "bin", "python")
        run([python, "-m", "pip", "install", "--quiet", "--no-index", "--no-deps", wheel], env=clean_env, cwd=scratch)

        where = output_of([python, "-c", "import dbrg; print(dbrg.__file__); print(dbrg.library_path())"],
                          clean_env, scratch).split()
        package = os.path.dirname(where[0])
        if not package.startswith(venv + os.sep) or os.path.dirname(where[1]) != package:
            print("the installed package or its library is not in the virtual environment: %s" % where)
            return 1
        version = "dbrg %s\n" % output_of([python, "-c", "import dbrg; print(dbrg.library_version())"], clean_env, scratch).strip()
        for program in ([python, "-m", "dbrg", "--version"], [os.path.join(venv, "bin", "dbrg"), "--version"]):
            printed = output_of(program, clean_env, scratch)
            if printed != version:
                print("%s printed %r, expected %r" % (" ".join(program), printed, version))
                return 1
        print("installed %s: %s" % (version.strip(), package), flush=True)
        tests = subprocess.run([python, os.path.join(HERE, "run_tests.py"), "--installed"], env=clean_env, cwd=scratch)
        return tests.returncode


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
