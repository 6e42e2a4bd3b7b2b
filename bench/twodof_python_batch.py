#!/usr/bin/python3
"""Python batch inverse dynamics of a two-DOF robot (the five-bar, arrays of shape (N, 2)) against
a three-DOF one (the 3-RRR, (N, 3)), in ns per sample: best of R calls of
`robot.inverse_dynamics(P, dP, ddP)` on C-ordered inputs, with new outputs and into preallocated
ones (`out=`), CPU time of the calling thread (the machine may be shared).

  PYTHONPATH=build/python /usr/bin/python3 bench/twodof_python_batch.py [--samples 200000] [--repeat 7]
"""

import argparse
import os
import time

import numpy as np

import nocdyn


def motion(home, n, amplitude, columns):
    """A smooth motion about home over `columns` pose coordinates: p, dp, ddp of shape (n, columns)."""
    t = np.arange(n) / 10000.0
    w = np.array([9.0, 13.0, 7.0])[:columns]
    a = np.array(amplitude)[:columns]
    P = np.asarray(home)[:columns] + a * np.sin(np.outer(t, w))
    dP = a * w * np.cos(np.outer(t, w))
    ddP = -a * w * w * np.sin(np.outer(t, w))
    return np.ascontiguousarray(P), np.ascontiguousarray(dP), np.ascontiguousarray(ddP)


def best(fn, repeat):
    """Least CPU time of the calling thread over `repeat` calls of fn [s]."""
    times = []
    for _ in range(repeat):
        start = time.clock_gettime(time.CLOCK_THREAD_CPUTIME_ID)
        fn()
        times.append(time.clock_gettime(time.CLOCK_THREAD_CPUTIME_ID) - start)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=int, default=200000)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "robots")
    n = args.samples
    cases = []
    five_bar = nocdyn.Robot.load(os.path.join(root, "five-bar.yaml"))
    cases.append(("five-bar (N, 2)", five_bar, motion([0.01, 0.32], n, [0.03, 0.04], 2)))
    rrr = nocdyn.Robot.load(os.path.join(root, "3-rrr.yaml"))
    cases.append(("3-rrr (N, 3)", rrr, motion(rrr.home, n, [0.004, 0.004, 0.05], 3)))
    print(f"{n} samples, best of {args.repeat}, ns per sample (CPU time of the calling thread)")
    for name, robot, (P, dP, ddP) in cases:
        out = tuple(np.empty((n, robot.actuators)) for _ in range(4))
        robot.inverse_dynamics(P, dP, ddP, out=out)  # warm: pages of the outputs mapped
        new = best(lambda: robot.inverse_dynamics(P, dP, ddP), args.repeat)
        into = best(lambda: robot.inverse_dynamics(P, dP, ddP, out=out), args.repeat)
        print(f"  {name:16s} new outputs {1e9 * new / n:7.1f}   out= {1e9 * into / n:7.1f}")


if __name__ == "__main__":
    main()
