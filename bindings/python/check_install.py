#!/usr/bin/env python3
"""Installs the Python package offline with pip, with the shared library bundled next to it, and uses
the installed copy from a neutral directory with DBRG_LIBRARY unset. Works on a copy of the package in a
temporary directory so the source tree stays clean. Exits 77 (skipped) without numpy or pip.

    python3 bindings/python/check_install.py build/src/libdbrg.so
"""

import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

USE_INSTALLED = r"""
import os, sys
import numpy as np
import dbrg
assert dbrg.__file__.startswith(sys.argv[1]), dbrg.__file__
assert os.path.dirname(dbrg.library_path()) == os.path.dirname(dbrg.__file__), dbrg.library_path()
i = np.arange(300) + 0.5
polar, azimuth = np.arccos(1 - 2 * i / 300), np.pi * (1 + 5 ** 0.5) * i
points = np.stack([np.cos(azimuth) * np.sin(polar), np.sin(azimuth) * np.sin(polar), np.cos(polar)], axis=1)
mesh = dbrg.reconstruct(points)
assert mesh.triangles.shape == (596, 3) and mesh.stats["boundary_edges"] == 0, mesh
print("installed", dbrg.__version__, "at", dbrg.__file__, "with", dbrg.library_path(), ":", mesh)
"""


def main(library):
    try:
        import numpy  # noqa: F401
    except ImportError:
        print("skipped: %s has no numpy" % sys.executable)
        return 77
    if subprocess.run([sys.executable, "-m", "pip", "--version"], capture_output=True).returncode != 0:
        print("skipped: %s has no pip (Debian: apt-get install python3-pip)" % sys.executable)
        return 77
    with tempfile.TemporaryDirectory(prefix="dbrg-install-") as scratch:
        source = os.path.join(scratch, "source")
        target = os.path.join(scratch, "site")
        shutil.copytree(HERE, source, ignore=shutil.ignore_patterns("tests", "build", "*.egg-info", "__pycache__"))
        shutil.copy(os.path.realpath(library), os.path.join(source, "dbrg", "libdbrg.so"))
        install = [sys.executable, "-m", "pip", "install", "--quiet", "--no-index", "--no-build-isolation",
                   "--no-deps", "--disable-pip-version-check", "--target", target, source]
        print("$", " ".join(install), flush=True)
        subprocess.run(install, check=True, env=dict(os.environ, PIP_ROOT_USER_ACTION="ignore"))
        env = {key: value for key, value in os.environ.items() if key not in ("DBRG_LIBRARY", "PYTHONPATH")}
        env["PYTHONPATH"] = target
        run = subprocess.run([sys.executable, "-c", USE_INSTALLED, target], cwd=scratch, env=env)
        return run.returncode


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
