"""python3 -m dbrg: the dbrg program installed inside this package, with the same arguments, output and
exit code. The Python process is replaced by the program, so signals and Ctrl-C behave as for the
program itself, and there is one implementation of the command line, not two.

The program is looked up as the environment variable DBRG_PROGRAM names it (e.g. build/src/cli/dbrg
in a build tree), else in dbrg/bin/ beside this file, where `pip install .` puts it.
"""

import os
import sys


def program_path():
    """The dbrg program this package runs (it may not exist: the package can be used without it)."""
    explicit = os.environ.get("DBRG_PROGRAM")
    if explicit:
        return explicit
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "dbrg")


def main():
    program = program_path()
    if not os.access(program, os.X_OK):
        sys.exit("dbrg: the dbrg program is not at %s; install the package with `pip install .` from the "
                 "repository, or set DBRG_PROGRAM to the program's path" % program)
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(program, [program] + sys.argv[1:])


if __name__ == "__main__":
    main()
