#!/usr/bin/env python3
"""Runs the Python binding's tests from the source tree: pytest when it is installed, unittest
otherwise. Exits 77 (meson's "skipped") when this interpreter has no numpy.

    DBRG_LIBRARY=build/src/libdbrg.so python3 bindings/python/run_tests.py [-k pattern | test names]
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
    sys.path[:0] = [HERE, TESTS]
    os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [HERE, os.environ.get("PYTHONPATH")]))
    print("python %s, numpy %s, DBRG_LIBRARY=%s" % (sys.version.split()[0], numpy.__version__,
                                                    os.environ.get("DBRG_LIBRARY", "(unset)")))
    use_unittest = "--unittest" in arguments
    arguments = [a for a in arguments if a != "--unittest"]
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
