"""Batch calls release the interpreter lock: another Python thread keeps
running while one classifies."""

import threading
import time

import numpy as np

import wingedge


def test_a_batch_call_does_not_block_other_python_threads():
    solid = wingedge.sphere(64)
    pts = np.random.default_rng(3).uniform(-1.2, 1.2, size=(1_500_000, 3))
    started = threading.Event()
    done = []

    def work():
        started.set()
        t0 = time.perf_counter()
        done.append(solid.classify(pts))
        done.append(time.perf_counter() - t0)

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    ticks = []
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    call_seconds = done[1]
    gaps = np.diff(ticks) if len(ticks) > 1 else np.array([call_seconds])
    # Holding the lock would stall this thread for the whole call: one gap
    # as long as the call. Released, it ticks all along.
    assert len(ticks) > 10, (len(ticks), call_seconds)
    assert gaps.max() < 0.5 * call_seconds, (gaps.max(), call_seconds)
    assert len(done[0]) == len(pts)
