"""The GIL is released while the library computes, and concurrent calls do not disturb each other."""

import threading
import time
import unittest

import dbrg
from _support import canonical_triangles, fibonacci_sphere


def longest_pause(ticks, start, end):
    """The longest stretch of [start, end] in which the ticking thread made no progress."""
    inside = [start] + [t for t in ticks if start < t < end] + [end]
    return max(b - a for a, b in zip(inside, inside[1:]))


class GilRelease(unittest.TestCase):
    def test_another_thread_runs_python_during_a_long_reconstruction(self):
        # Find a size that keeps the library busy for a while on this machine.
        count, mesh = 1000, None
        while True:
            points = fibonacci_sphere(count)
            ticks = []
            stop = threading.Event()

            def tick():
                # Pure Python work: it can only progress while this thread holds the GIL.
                while not stop.is_set():
                    ticks.append(time.perf_counter())
                    sum(range(100))

            ticker = threading.Thread(target=tick)
            ticker.start()
            try:
                while not ticks:
                    time.sleep(0.001)
                start = time.perf_counter()
                mesh = dbrg.reconstruct(points)
                end = time.perf_counter()
            finally:
                stop.set()
                ticker.join()
            busy = mesh.stats["seconds_total"]
            if busy >= 0.3 or count >= 64000:
                break
            count *= 2
        self.assertGreater(busy, 0.05, "the reconstruction was too quick to tell")
        # Holding the GIL through the foreign call would stall the ticker for the whole of it.
        self.assertLess(longest_pause(ticks, start, end), 0.5 * busy,
                        "the ticking thread stalled while the library computed: the GIL was held")

    def test_concurrent_calls_give_the_serial_answers(self):
        inputs = [fibonacci_sphere(300 + 50 * k) for k in range(4)]
        expected = [canonical_triangles(dbrg.reconstruct(points).triangles) for points in inputs]
        results = [None] * len(inputs)
        errors = []

        def run(k):
            try:
                reports = []
                mesh = dbrg.reconstruct(inputs[k], progress=lambda s, f: reports.append(s))
                results[k] = canonical_triangles(mesh.triangles)
            except BaseException as error:  # reported by the main thread
                errors.append(error)

        threads = [threading.Thread(target=run, args=(k,)) for k in range(len(inputs))]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        self.assertEqual(errors, [])
        self.assertEqual(results, expected)


if __name__ == "__main__":
    unittest.main()
