#!/usr/bin/python3
"""Speed of the Python package against the C++ library, measured in one run (one process).

  PYTHONPATH=build/python /usr/bin/python3 bench/python_batch.py [--samples 1000000] [--robot paper-3prr ...]

1. Batch: inverse dynamics of N samples (trajectory 1 of the paper plus a second harmonic per
   axis) through `robot.inverse_dynamics(P, dP, ddP)` from Python, with C-ordered inputs and new
   outputs, with F-ordered inputs, and into preallocated outputs (`out=`), against the C++
   batch `nocdyn::inverseDynamicsBatch` over Eigen's own column-major arrays, timed inside C++
   (`Robot._core._time_cpp_batch`, the same kernel on one thread, its outputs allocated and
   written once before it is timed). CPU time of the calling
   thread (CLOCK_THREAD_CPUTIME_ID on both sides), best of R interleaved repetitions of each
   (the machine may be shared: interleaving gives each the same load). The memory floor: the
   same bytes read and written by one thread without computing (the 9 inputs of a sample read
   into the first of its 4 n output values, the rest written), what no batch can beat.
2. Per-sample call: `robot.inverse_dynamics(p, dp, ddp)` on (3,) arrays, and the compiled entry
   alone, against the C++ per-sample time of the batch; the difference is the call overhead.
"""

import argparse
import os
import time

import numpy as np

import nocdyn


def motion(robot, n):
    t = np.arange(n) / 10000.0
    base = nocdyn.Trajectory.paper(1)
    second = nocdyn.Trajectory.harmonic(theta=[(0.01, 20.0, 0.3)], x=[(0.0005, 20.0, 0.1)], y=[(0.0005, 30.0, 0.2)])
    P, dP, ddP = base.evaluate(t)
    P2, dP2, ddP2 = second.evaluate(t)
    return P + P2 + robot.home, dP + dP2, ddP + ddP2


def best(fn, repeat):
    """Least CPU time of the calling thread over `repeat` calls of fn [s]: the batch runs on the
    calling thread, and CPU time does not count the other processes of a shared machine."""
    times = []
    for _ in range(repeat):
        t0 = time.thread_time()
        fn()
        times.append(time.thread_time() - t0)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=int, default=1_000_000)
    parser.add_argument("--robot", nargs="+", default=["paper-3prr"],
                        help="example robot names (nocdyn.Robot.examples()), measured one after the other")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--calls", type=int, default=200_000, help="per-sample calls timed")
    args = parser.parse_args()
    for name in args.robot:
        measure(name, args)
        print()


def measure(name, args):
    robot = nocdyn.Robot.example(name)
    n = args.samples
    P, dP, ddP = motion(robot, n)
    Pf, dPf, ddPf = (np.asfortranarray(a) for a in (P, dP, ddP))
    out = tuple(np.empty((n, robot.actuators)) for _ in range(4))
    core = robot._core

    # interleaved repetitions: each variant sees the same machine load
    results = {"cpp": [], "py_c": [], "py_unchecked": [], "py_f": [], "py_out": [], "floor": []}
    # the floor: 9 n doubles read, 4 n m written (m actuators), in one pass each
    source = np.concatenate([P.ravel(), dP.ravel(), ddP.ravel()])
    target = np.empty(4 * n * robot.actuators)

    def floor():
        np.copyto(target[:source.size], source)
        target[source.size:].fill(0.0)

    floor()
    for _ in range(args.repeat):
        results["floor"].append(best(floor, 1))
        results["cpp"].append(core._time_cpp_batch(P, dP, ddP, 1))
        results["py_c"].append(best(lambda: robot.inverse_dynamics(P, dP, ddP), 1))
        results["py_unchecked"].append(best(lambda: robot.inverse_dynamics(P, dP, ddP, check_limits=False), 1))
        results["py_f"].append(best(lambda: robot.inverse_dynamics(Pf, dPf, ddPf), 1))
        results["py_out"].append(best(lambda: robot.inverse_dynamics(P, dP, ddP, out=out), 1))
    cpp = min(results["cpp"])

    p, dp, ddp = P[123].copy(), dP[123].copy(), ddP[123].copy()
    calls = args.calls

    def per_sample():
        f = robot.inverse_dynamics
        for _ in range(calls):
            f(p, dp, ddp)

    def per_sample_core():
        f = core._inverse_dynamics_sample
        for _ in range(calls):
            f(p, dp, ddp, False)

    call = best(per_sample, 3) / calls
    call_core = best(per_sample_core, 3) / calls
    cpp_sample = cpp / n

    print(f"robot {robot.name}, {n} samples, thread CPU time, best of {args.repeat} interleaved runs; "
          f"load average {os.getloadavg()[0]:.1f} at the end")
    print()
    names = {"cpp": "C++ `inverseDynamicsBatch` (Eigen arrays, timed in C++)",
             "py_c": "Python, C-ordered inputs, new outputs (limits checked, the default)",
             "py_unchecked": "Python, C-ordered inputs, new outputs, `check_limits=False`",
             "py_f": "Python, F-ordered inputs, new outputs",
             "py_out": "Python, C-ordered inputs, `out=` preallocated"}
    names["floor"] = "memory floor (the same bytes copied, NumPy)"
    floor_time = min(results["floor"])
    print("| batch of %d samples | time (ms) | ns/sample | / C++ batch | / memory floor |" % n)
    print("|---|---|---|---|---|")
    for key, label in names.items():
        t = min(results[key])
        print(f"| {label} | {t * 1e3:.1f} | {t / n * 1e9:.1f} | {t / cpp:.3f} | {t / floor_time:.2f} |")
    print()
    print("| per-sample call (CPU time) | us/call | overhead over the C++ per-sample time |")
    print("|---|---|---|")
    print(f"| C++ (batch time / N) | {cpp_sample * 1e6:.3f} | - |")
    print(f"| `robot.inverse_dynamics(p, dp, ddp)` | {call * 1e6:.3f} | {(call - cpp_sample) * 1e6:.3f} us |")
    print(f"| compiled entry alone (`robot._core._inverse_dynamics_sample`) | {call_core * 1e6:.3f} | "
          f"{(call_core - cpp_sample) * 1e6:.3f} us |")


if __name__ == "__main__":
    main()
