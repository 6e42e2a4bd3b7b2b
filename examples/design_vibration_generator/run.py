#!/usr/bin/env python3
"""The paper's 3-PRR vibration generator as a design problem: base side b, platform side a,
link length l and rail angle psi; maximise the x, y and theta envelopes at 50 Hz under the
paper's actuators (24.9 mm stroke, 262 N) with NSGA-II, keeping the workspace area at theta = 0
at least the prototype's. Writes OUT/designs.csv (every trial), OUT/pareto.csv and
OUT/pareto.png (the front against the prototype's own point). Checks what it claims: every
design on the front is feasible, keeps at least the prototype's workspace and is dominated by
no other candidate, and the front holds a design whose envelopes are all at least the
prototype's (exits non-zero when one fails). NOCDYN_EXAMPLE_QUICK=1 (the tests): fewer trials on
a coarser workspace grid, into NOCDYN_EXAMPLE_OUT.

usage: PYTHONPATH=build/python python3 examples/design_vibration_generator/run.py [--trials 200] [--out DIR]
"""

import argparse
import os
import pathlib
import sys

import numpy as np

from nocdyn import designs

HERE = pathlib.Path(__file__).resolve().parent
OBJECTIVES = {"envelope_x@50": "maximize", "envelope_y@50": "maximize", "envelope_theta@50": "maximize"}
VARY = {"b": (0.30, 0.50), "a": (0.08, 0.16), "l": (0.12, 0.22), "psi": (-0.4, 0.4)}
PROTOTYPE = [0.400, 0.110, 0.15915, 0.0]
QUICK = os.environ.get("NOCDYN_EXAMPLE_QUICK") == "1"
QUICK_TRIALS, QUICK_RESOLUTION = 100, 41  # the tests: 1 design on the front reaches the prototype (5 of 200)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=QUICK_TRIALS if QUICK else 200)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--resolution", type=int, default=QUICK_RESOLUTION if QUICK else 101,
                        help="workspace grid points per side")
    parser.add_argument("--out", default=str(pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
                                             / "design_vibration_generator"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    family = designs.Family(HERE / "family.yaml", vary=VARY)
    metrics = list(OBJECTIVES) + ["workspace_area"]
    prototype = designs.evaluate(family, [PROTOTYPE], metrics, resolution=args.resolution)
    area = prototype.values[0, -1]
    print(f"prototype: envelope x {prototype.values[0, 0] * 1e3:.3f} mm, y {prototype.values[0, 1] * 1e3:.3f} mm, "
          f"theta {np.degrees(prototype.values[0, 2]):.3f} deg at 50 Hz; workspace {area * 1e6:.1f} mm^2")

    study, table = designs.optimize(family, OBJECTIVES, n_trials=args.trials, seed=args.seed,
                                   constraints={"workspace_area": (area, None)}, resolution=args.resolution)
    table.to_csv(out / "designs.csv")
    keep = table.feasible & (np.nan_to_num(table.column("workspace_area")) >= area)
    candidates = designs.Designs(table.names, table.metrics, table.points[keep], table.values[keep],
                                table.feasible[keep], [r for r, k in zip(table.reason, keep) if k])
    envelopes = designs.Designs(table.names, list(OBJECTIVES), candidates.points, candidates.values[:, :3],
                               candidates.feasible, candidates.reason)
    front = designs.pareto_front(envelopes)  # over the three envelopes
    pareto = designs.Designs(table.names, table.metrics, candidates.points[front], candidates.values[front],
                            candidates.feasible[front], [candidates.reason[i] for i in front])
    pareto.to_csv(out / "pareto.csv")
    print(f"{len(table)} trials, {int(keep.sum())} feasible with the prototype's workspace, {len(front)} on the front")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    for panel, other in zip(ax, ("envelope_y@50", "envelope_theta@50")):
        scale = 180 / np.pi if other.startswith("envelope_theta") else 1e3
        panel.scatter(candidates.column("envelope_x@50") * 1e3, candidates.column(other) * scale, s=8, c="#999999",
                      label="designs (workspace >= prototype's)")
        panel.scatter(pareto.column("envelope_x@50") * 1e3, pareto.column(other) * scale, s=18, c="#c0392b",
                      label="Pareto front")
        panel.scatter([prototype.values[0, 0] * 1e3], [prototype.column(other)[0] * scale], marker="*", s=160,
                      c="k", label="the paper's prototype")
        panel.set_xlabel("x amplitude at 50 Hz [mm]")
        panel.set_ylabel("theta amplitude at 50 Hz [deg]" if scale != 1e3 else "y amplitude at 50 Hz [mm]")
        panel.grid(True, alpha=0.3)
    ax[0].legend(fontsize=8)
    fig.suptitle("3-PRR vibration generator: envelopes at 50 Hz under the paper's actuators")
    fig.tight_layout()
    fig.savefig(out / "pareto.png", dpi=120)
    print(f"wrote {out / 'designs.csv'}, {out / 'pareto.csv'}, {out / 'pareto.png'}")

    off = []
    if len(front) == 0:
        off.append("the front is empty: no design keeps the prototype's workspace")
    if not (np.all(pareto.feasible) and np.all(pareto.column("workspace_area") >= area)):
        off.append("a design on the front is infeasible or has less workspace than the prototype")
    # no candidate is at least as large in every envelope and larger in one than a front design
    for i in front:
        better = np.all(envelopes.values >= envelopes.values[i], axis=1) & np.any(envelopes.values > envelopes.values[i],
                                                                                  axis=1)
        if better.any():
            off.append(f"the front design {candidates.points[i]} is dominated by {candidates.points[better][0]}")
    reach = np.all(pareto.values[:, :3] >= prototype.values[0, :3], axis=1)
    if not reach.any():
        off.append("no design on the front reaches the prototype's envelope along x, y and theta together")
    if off:
        sys.exit("the design study is off:\n" + "\n".join(off))
    print(f"{int(reach.sum())} design(s) on the front reach at least the prototype's three envelopes")


if __name__ == "__main__":
    main()
