"""Batch calls and booleans release the interpreter lock: another Python
thread keeps running while one classifies or computes a boolean."""

import threading
import time

import numpy as np

import wingedge


def _run_while_ticking(call):
    """Runs `call` in a worker thread while this one ticks every
    millisecond: `(result, seconds the call took, tick times)`."""
    started = threading.Event()
    done = []

    def work():
        started.set()
        t0 = time.perf_counter()
        done.append(call())
        done.append(time.perf_counter() - t0)

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    ticks = []
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    return done[0], done[1], ticks


def _assert_never_blocked(call_seconds, ticks):
    gaps = np.diff(ticks) if len(ticks) > 1 else np.array([call_seconds])
    # Holding the lock would stall this thread for the whole call: one gap
    # as long as the call. Released, it ticks all along.
    assert len(ticks) > 10, (len(ticks), call_seconds)
    assert gaps.max() < 0.5 * call_seconds, (gaps.max(), call_seconds)


def test_a_batch_call_does_not_block_other_python_threads():
    solid = wingedge.sphere(64)
    pts = np.random.default_rng(3).uniform(-1.2, 1.2, size=(1_500_000, 3))
    codes, seconds, ticks = _run_while_ticking(lambda: solid.classify(pts))
    _assert_never_blocked(seconds, ticks)
    assert len(codes) == len(pts)


def test_a_boolean_does_not_block_other_python_threads():
    a = wingedge.sphere(96)
    vertices, faces = a.to_arrays()
    b = wingedge.Solid.from_arrays(vertices + [0.3, 0.2, 0.1], faces)
    result, seconds, ticks = _run_while_ticking(lambda: wingedge.combine([a, b], ("difference", 0, 1)))
    _assert_never_blocked(seconds, ticks)
    assert 0 < result.volume < a.volume
