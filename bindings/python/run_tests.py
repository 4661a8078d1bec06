#!/usr/bin/env python3
"""Runs the Python binding's tests: pytest when it is installed, unittest otherwise. Exits 77 (meson's
"skipped") when this interpreter has no numpy. The package tested is the source tree's, unless
--installed asks for the one this interpreter imports from its own site-packages.

    DBRG_LIBRARY=build/src/libdbrg.so python3 bindings/python/run_tests.py [-k pattern | test names]
    venv/bin/python bindings/python/run_tests.py --installed
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TESTS = os.path.join(HERE, "tests")


def main(arguments):
    try:
        import numpy  # noqa: F401
    except ImportError:
        print("skipped: %s has no numpy (Debian: apt-get install python3-numpy)" % sys.executable)
        return 77
    use_unittest = "--unittest" in arguments
    installed = "--installed" in arguments
    arguments = [a for a in arguments if a not in ("--unittest", "--installed")]
    if installed:
        # The script's own folder holds the source package; it must not shadow the installed one.
        sys.path[:] = [TESTS] + [entry for entry in sys.path if os.path.abspath(entry or ".") != HERE]
        import dbrg
        if os.path.abspath(dbrg.__file__).startswith(HERE + os.sep):
            print("--installed: %s imports the source tree's package (%s)" % (sys.executable, dbrg.__file__))
            return 1
    else:
        sys.path[:0] = [HERE, TESTS]
        os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [HERE, os.environ.get("PYTHONPATH")]))
        import dbrg
    print("python %s, numpy %s, dbrg from %s, DBRG_LIBRARY=%s" % (
        sys.version.split()[0], numpy.__version__, os.path.dirname(dbrg.__file__),
        os.environ.get("DBRG_LIBRARY", "(unset)")))
    if not use_unittest:
        try:
            import pytest
        except ImportError:
            use_unittest = True
    if not use_unittest:
        return pytest.main(["-q", "-p", "no:cacheprovider", "--rootdir", HERE, TESTS] + arguments)
    import unittest
    if arguments:
        suite = unittest.defaultTestLoader.loadTestsFromNames(arguments)
    else:
        suite = unittest.defaultTestLoader.discover(TESTS, top_level_dir=TESTS)
    result = unittest.TextTestRunner(verbosity=2).run(suite)
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
