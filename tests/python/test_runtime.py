"""The batch releases the GIL; calls leak neither references nor memory."""

import gc
import os
import sys
import threading
import time
import tracemalloc

import numpy as np

import nocdyn


def test_another_python_thread_runs_while_a_batch_computes(paper_robot):
    """Thread B counts in Python while thread A is inside a long batch. With the GIL held for the
    whole batch B could not run at all between A's entry and exit; on a loaded machine B still
    gets the core now and then, so only a few of its iterations are required inside the window."""
    n = 400_000  # ~0.1-0.2 s of batch
    rng = np.random.default_rng(0)
    P = np.tile(paper_robot.home, (n, 1)) + rng.uniform(-1e-3, 1e-3, (n, 3))
    dP = rng.uniform(-0.1, 0.1, (n, 3))
    ddP = rng.uniform(-1, 1, (n, 3))
    out = tuple(np.empty((n, 3)) for _ in range(4))
    stamps = []
    stop = threading.Event()
    started = threading.Event()

    def counter():
        started.set()
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0)  # a Python-level yield, nothing that could run without the GIL

    b = threading.Thread(target=counter)
    b.start()
    started.wait()
    inside = 0
    for _ in range(3):  # a few attempts: the scheduler of a loaded machine may starve B once
        t0 = time.perf_counter()
        paper_robot.inverse_dynamics(P, dP, ddP, out=out)
        t1 = time.perf_counter()
        window = (t1 - t0) * 0.1  # B's iterations well inside the batch, not at its edges
        inside = sum(1 for s in list(stamps) if t0 + window < s < t1 - window)
        if inside >= 20:
            break
    stop.set()
    b.join()
    assert inside >= 20, f"only {inside} iterations of the other thread ran during the batch"


def test_two_threads_run_batches_concurrently_with_the_right_numbers(paper_robot):
    n = 50_000
    rngs = [np.random.default_rng(seed) for seed in (5, 6)]
    inputs = [(paper_robot.home + r.uniform(-2e-3, 2e-3, (n, 3)), r.uniform(-0.1, 0.1, (n, 3)),
               r.uniform(-1.0, 1.0, (n, 3))) for r in rngs]
    refs = [paper_robot.inverse_dynamics(*x) for x in inputs]
    results = [None, None]

    def work(i):
        results[i] = paper_robot.inverse_dynamics(*inputs[i])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r, ref in zip(results, refs):
        for a, b in zip(r, ref):
            np.testing.assert_array_equal(a, b)


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_100000_calls_leak_no_references_and_no_memory(paper_robot):
    """10^5 per-sample calls, 10^4 small batches and 10^3 failing calls: every reference count is
    unchanged, no Python object is left, the resident size does not grow (one leaked array per
    call would be > 10 MB), and tracemalloc sees nothing kept over a further 10^4 calls."""
    p = np.array([0.01, 0.001, -0.002])
    dp = np.array([0.1, 0.02, 0.01])
    ddp = np.array([1.0, 0.5, -0.5])
    P, dP, ddP = (np.tile(x, (8, 1)) for x in (p, dp, ddp))
    out = tuple(np.empty((8, 3)) for _ in range(4))
    far = np.array([0.0, 1.0, 0.0])
    watched = [paper_robot, p, dp, ddp, P, dP, ddP, far, *out, nocdyn.Error, nocdyn.InverseDynamics]

    def calls(samples, batches, failures):
        for _ in range(samples):
            paper_robot.inverse_dynamics(p, dp, ddp)
        for _ in range(batches):
            paper_robot.inverse_dynamics(P, dP, ddP, out=out)
        for _ in range(failures):
            try:
                paper_robot.inverse_dynamics(far, dp, ddp)
            except nocdyn.Error:
                pass

    calls(2000, 200, 200)  # warm up (pybind11's type caches, the allocator's pools)
    gc.collect()
    refs_before = [sys.getrefcount(x) for x in watched]
    objects_before = len(gc.get_objects())
    rss_before = resident_bytes()
    calls(100_000, 10_000, 1_000)
    gc.collect()
    rss_growth = resident_bytes() - rss_before
    assert [sys.getrefcount(x) for x in watched] == refs_before
    assert len(gc.get_objects()) - objects_before < 50
    assert rss_growth < 2_000_000, f"resident size grew by {rss_growth} bytes over 111 000 calls"
    tracemalloc.start()
    try:
        before, _ = tracemalloc.get_traced_memory()
        calls(10_000, 1_000, 100)
        gc.collect()
        after, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert after - before < 20_000, f"{after - before} bytes kept after 11 100 calls"
