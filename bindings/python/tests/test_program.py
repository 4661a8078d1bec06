"""`python -m dbrg` runs the dbrg program: the same output, files and exit codes."""

import os
import subprocess
import sys
import tempfile
import unittest

import dbrg
from dbrg.__main__ import program_path


def run_module(*arguments, **environment):
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(dbrg.__file__))))
    env.update(environment)
    return subprocess.run([sys.executable, "-m", "dbrg"] + list(arguments), env=env, capture_output=True, text=True,
                          timeout=120)


@unittest.skipUnless(os.access(program_path(), os.X_OK), "no dbrg program at %s (set DBRG_PROGRAM)" % program_path())
class ProgramThroughPython(unittest.TestCase):
    def test_version_is_the_librarys(self):
        run = run_module("--version")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stdout, "dbrg %s\n" % dbrg.library_version())

    def test_reconstructs_a_file(self):
        with tempfile.TemporaryDirectory() as scratch:
            output = os.path.join(scratch, "sphere.obj")
            run = run_module("reconstruct", "--demo", "--demo-shape", "sphere", "--demo-points", "400", "-o", output, "-q")
            self.assertEqual(run.returncode, 0, run.stderr)
            with open(output) as written:
                faces = [line for line in written if line.startswith("f ")]
            self.assertGreater(len(faces), 0)

    def test_usage_errors_keep_the_programs_exit_code(self):
        run = run_module("no-such-command")
        self.assertEqual(run.returncode, 2)
        self.assertIn("dbrg: unknown command", run.stderr)


class MissingProgram(unittest.TestCase):
    def test_says_where_it_looked(self):
        missing = os.path.join(os.path.dirname(os.path.abspath(dbrg.__file__)), "no-such-program")
        run = run_module("--version", DBRG_PROGRAM=missing)
        self.assertNotEqual(run.returncode, 0)
        self.assertIn(missing, run.stderr)


if __name__ == "__main__":
    unittest.main()
