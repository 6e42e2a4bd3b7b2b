#!/usr/bin/env python3
"""The optimiser against a grid on a 3-RRR workspace problem: the largest workspace area at
the home orientation over the proximal and distal link lengths l1, l2 in [0.07, 0.25] m within
a moving-mass budget of 4 kg (the links' masses grow with their lengths). Without the budget the
area grows with both lengths and the best design is a corner of the box; with it the best lies
on the budget's line, inside the box. A 20 x 20 grid (400 designs) against Optuna's TPE with
at most a quarter of the evaluations (100 trials), seeded. Prints both bests and whether the
optimiser's is at least as good.

usage: PYTHONPATH=build/python python3 examples/design_3rrr/optimise_vs_grid.py [--trials 100] [--seed 0]
"""

import argparse
import pathlib
import time

import numpy as np

from nocdyn import designs

HERE = pathlib.Path(__file__).resolve().parent
VARY = {"l1": (0.07, 0.25), "l2": (0.07, 0.25)}
BUDGET = 4.0  # moving mass [kg]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--seed", type=int, nargs="+", default=[0])
    parser.add_argument("--resolution", type=int, default=61)
    args = parser.parse_args()
    family = designs.Family(HERE / "family.yaml", vary=VARY)

    start = time.perf_counter()
    grid = designs.evaluate(family, designs.sample(family, 400, "grid"), ["workspace_area", "moving_mass"],
                           resolution=args.resolution)
    grid_time = time.perf_counter() - start
    g = int(np.nanargmax(np.where(grid.values[:, 1] <= BUDGET, grid.values[:, 0], np.nan)))
    print(f"grid 20 x 20: {len(grid)} evaluations, best area {grid.values[g, 0] * 1e6:.2f} mm^2 at "
          f"l1 = {grid.points[g, 0]:.4f} m, l2 = {grid.points[g, 1]:.4f} m ({grid_time:.1f} s)")

    for seed in args.seed:
        optimise(family, grid.values[g, 0], seed, args)


def optimise(family, grid_best, seed, args):
    start = time.perf_counter()
    study, table = designs.optimize(family, {"workspace_area": "maximize"}, n_trials=args.trials, seed=seed,
                                   constraints={"moving_mass": (None, BUDGET)}, resolution=args.resolution)
    opt_time = time.perf_counter() - start
    within = np.where(table.values[:, 1] <= BUDGET, table.values[:, 0], np.nan)
    o = int(np.nanargmax(within))
    first = int(np.argmax(np.nan_to_num(within, nan=-1.0) >= grid_best))
    reached = within[o] >= grid_best
    print(f"TPE (seed {seed}): {len(table)} evaluations, best area {table.values[o, 0] * 1e6:.2f} mm^2 at "
          f"l1 = {table.points[o, 0]:.4f} m, l2 = {table.points[o, 1]:.4f} m ({opt_time:.1f} s)")
    print(f"optimiser >= grid: {bool(reached)}" + (f" (first at evaluation {first + 1})" if reached else ""))


if __name__ == "__main__":
    main()
