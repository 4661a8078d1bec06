"""Finding the shared library: clear errors when it is missing, foreign, or of another version.
Each case runs in a fresh interpreter, because a process loads the library only once."""

import ctypes.util
import os
import subprocess
import sys
import unittest

import dbrg

PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(dbrg.__file__)))


def run_python(code, **environment):
    env = dict(os.environ)
    env["PYTHONPATH"] = PACKAGE_ROOT + os.pathsep + env.get("PYTHONPATH", "")
    env.update(environment)
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)


class LibraryLookup(unittest.TestCase):
    def test_a_missing_file_named_by_dbrg_library(self):
        missing = os.path.join(PACKAGE_ROOT, "no-such-dir", "libdbrg.so")
        run = run_python("import dbrg; dbrg.library_version()", DBRG_LIBRARY=missing)
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("dbrg.LibraryError", run.stderr)
        self.assertIn(missing, run.stderr)
        self.assertIn("DBRG_LIBRARY", run.stderr)

    def test_import_does_not_need_the_library(self):
        run = run_python("import dbrg; print(dbrg.__version__)", DBRG_LIBRARY="/nonexistent/libdbrg.so")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stdout.strip(), dbrg.__version__)

    @unittest.skipUnless(ctypes.util.find_library("m"), "no libm to stand in for a foreign library")
    def test_a_library_that_is_not_dbrg(self):
        run = run_python("import dbrg; dbrg.reconstruct([[0, 0, 0]] * 4)", DBRG_LIBRARY=ctypes.util.find_library("m"))
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("not a usable dbrg library", run.stderr)

    def test_a_library_of_another_minor_version(self):
        # Pretend the package was written for 0.7: the 0.2 library must be refused, naming both versions.
        code = ("import dbrg._capi as c; c.DBRG_VERSION_MINOR = 7; c.DBRG_VERSION_STRING = '0.7.0'\n"
                "import dbrg; dbrg.library_version()")
        run = run_python(code, DBRG_LIBRARY=dbrg.library_path())
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("needs the library version 0.7", run.stderr)
        self.assertIn(dbrg.library_version(), run.stderr)

    def test_a_newer_minor_library_is_refused_too(self):
        # A package written for the previous minor version calls EXPERIMENTAL functions that may have changed.
        older = int(dbrg.library_version().split(".")[1]) - 1
        if older < 0:
            self.skipTest("no earlier minor version to pretend")
        code = ("import dbrg._capi as c; c.DBRG_VERSION_MINOR = %d; c.DBRG_VERSION_STRING = '0.%d.0'\n"
                "import dbrg; dbrg.library_version()" % (older, older))
        run = run_python(code, DBRG_LIBRARY=dbrg.library_path())
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("needs the library version 0.%d" % older, run.stderr)

    def test_nothing_found_explains_how_to_point_at_the_library(self):
        env = {"DBRG_LIBRARY": "", "LD_LIBRARY_PATH": ""}
        code = ("import dbrg._library as l\n"
                "l._file_names = lambda base='dbrg': ['libdbrg-does-not-exist.so']\n"
                "l.ctypes.util.find_library = lambda name: None\n"
                "import dbrg; dbrg.library_version()")
        run = run_python(code, **env)
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("cannot find the dbrg shared library", run.stderr)
        self.assertIn("DBRG_LIBRARY=", run.stderr)


if __name__ == "__main__":
    unittest.main()
