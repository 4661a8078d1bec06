"""Progress callbacks: stage names, cancelling by returning False, exceptions passed through."""

import os
import signal
import subprocess
import sys
import time
import traceback
import unittest

import dbrg
from _support import fibonacci_sphere

SPHERE = fibonacci_sphere(600)


class Boom(Exception):
    pass


class Progress(unittest.TestCase):
    def test_stages_arrive_in_pipeline_order_with_fractions_in_range(self):
        reports = []
        dbrg.reconstruct(SPHERE, progress=lambda stage, fraction: reports.append((stage, fraction)))
        self.assertTrue(reports)
        # The pipeline's order: cleaning (a later enum value) runs between validation and Delaunay.
        order = [name for name in dbrg.STAGES.values() if name != "clean"]
        order.insert(order.index("validate") + 1, "clean")
        positions = [order.index(stage) for stage, _ in reports]
        self.assertEqual(positions, sorted(positions), "stages never go back")
        self.assertTrue(all(0.0 <= fraction <= 1.0 for _, fraction in reports))
        stages = {stage for stage, _ in reports}
        self.assertTrue({"validate", "delaunay", "output"} <= stages, stages)
        self.assertEqual(reports[-1], ("output", 1.0))

    def test_returning_false_cancels(self):
        calls_after_cancel = []

        def cancel_in_delaunay(stage, fraction):
            if calls_after_cancel:
                calls_after_cancel.append(stage)
            if stage == "delaunay":
                calls_after_cancel.append("cancelled")
                return False
            return True

        with self.assertRaises(dbrg.CancelledError) as caught:
            dbrg.reconstruct(SPHERE, progress=cancel_in_delaunay)
        self.assertEqual(caught.exception.status, "DBRG_ERR_CANCELLED")
        self.assertEqual(calls_after_cancel, ["cancelled"], "no report after the cancel")

    def test_none_continues_and_other_false_values_cancel(self):
        self.assertGreater(len(dbrg.reconstruct(SPHERE, progress=lambda s, f: None).triangles), 0)
        with self.assertRaises(dbrg.CancelledError):
            dbrg.reconstruct(SPHERE, progress=lambda s, f: 0)

    def test_an_exception_inside_comes_out_of_reconstruct(self):
        seen_after = []
        raised = Boom("stop here")

        def explode(stage, fraction):
            if seen_after or stage == "delaunay":
                seen_after.append(stage)
                raise raised

        try:
            dbrg.reconstruct(SPHERE, progress=explode)
        except Boom as error:  # not assertRaises: it drops the traceback
            self.assertIs(error, raised)
            frames = [frame.name for frame in traceback.extract_tb(error.__traceback__)]
        else:
            self.fail("Boom was swallowed")
        self.assertEqual(len(seen_after), 1, "the callback is not called again once it raised")
        self.assertIn("explode", frames, "the traceback reaches into the callback")

    def test_a_keyboard_interrupt_inside_is_not_swallowed(self):
        def interrupt(stage, fraction):
            raise KeyboardInterrupt

        with self.assertRaises(KeyboardInterrupt):
            dbrg.reconstruct(SPHERE, progress=interrupt)

    def test_a_callback_result_that_is_neither_true_nor_false_raises(self):
        import numpy as np
        with self.assertRaises(ValueError):  # bool() of a two-element array
            dbrg.reconstruct(SPHERE, progress=lambda s, f: np.array([True, False]))

    def test_the_call_after_an_exception_works_normally(self):
        with self.assertRaises(Boom):
            dbrg.reconstruct(SPHERE, progress=lambda s, f: (_ for _ in ()).throw(Boom()))
        self.assertGreater(len(dbrg.reconstruct(SPHERE, progress=lambda s, f: True).triangles), 0)

    def test_delaunay_reports_and_cancels_too(self):
        stages = []
        dbrg.delaunay(SPHERE, progress=lambda stage, fraction: stages.append(stage))
        self.assertIn("delaunay", stages)
        with self.assertRaises(dbrg.CancelledError):
            dbrg.delaunay(SPHERE, progress=lambda stage, fraction: stage != "delaunay")
        with self.assertRaises(Boom):
            dbrg.delaunay(SPHERE, progress=lambda s, f: (_ for _ in ()).throw(Boom()))


LONG_RECONSTRUCTION = r"""
import sys, time
import dbrg
from _support import fibonacci_sphere
points = fibonacci_sphere(1000000)  # several seconds of work
print("started", flush=True)
start = time.perf_counter()
reports = []
try:
    dbrg.reconstruct(points, progress=(lambda stage, fraction: reports.append(stage)) if sys.argv[1] == "callback" else None)
except KeyboardInterrupt:
    print("interrupted after %.2f s" % (time.perf_counter() - start), flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


class CtrlC(unittest.TestCase):
    def interrupt(self, mode):
        here = os.path.dirname(os.path.abspath(__file__))
        package = os.path.dirname(os.path.dirname(os.path.abspath(dbrg.__file__)))
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([package, here]))
        child = subprocess.Popen([sys.executable, "-c", LONG_RECONSTRUCTION, mode], env=env, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
        try:
            self.assertEqual(child.stdout.readline().strip(), "started")
            time.sleep(0.5)
            child.send_signal(signal.SIGINT)
            out, err = child.communicate(timeout=60)
        finally:
            if child.poll() is None:
                child.kill()
                child.wait()
        self.assertEqual(child.returncode, 3, out + err)
        self.assertIn("interrupted", out)
        self.assertNotIn("Exception ignored", err)

    @unittest.skipUnless(os.name == "posix", "sends SIGINT")
    def test_ctrl_c_cancels_a_long_reconstruction(self):
        self.interrupt("plain")

    @unittest.skipUnless(os.name == "posix", "sends SIGINT")
    def test_ctrl_c_cancels_a_long_reconstruction_with_a_progress_callback(self):
        self.interrupt("callback")

    def test_the_sigint_handler_is_restored(self):
        before = signal.getsignal(signal.SIGINT)
        dbrg.reconstruct(SPHERE, progress=lambda s, f: True)
        with self.assertRaises(dbrg.CancelledError):
            dbrg.reconstruct(SPHERE, progress=lambda s, f: False)
        self.assertIs(signal.getsignal(signal.SIGINT), before)


if __name__ == "__main__":
    unittest.main()
