#!/usr/bin/python3
"""nocdyn from Python: the paper's robot along its trajectory 1, forces plotted to a PNG.

  PYTHONPATH=build/python /usr/bin/python3 examples/quickstart.py [--out quickstart.png]
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import nocdyn  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robot", default=str(ROOT / "robots" / "paper-3prr.yaml"), help="robot file (YAML)")
    parser.add_argument("--out", default="quickstart.png", help="PNG to write")
    args = parser.parse_args()

    robot = nocdyn.Robot.load(args.robot)
    trajectory = nocdyn.Trajectory.paper(1)  # eq. 33: 10 Hz in x, y and theta
    t = np.arange(2000) / 10000.0  # 0.2 s at 10 kHz
    P, dP, ddP = trajectory.evaluate(t)  # (N, 3) each: [x, y, theta] and derivatives
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)  # (N, n) each

    # units by joint type: a prismatic actuator moves in mm and pushes in N, a revolute one
    # turns in mrad and drives in N m (a robot mixing both is labelled with both)
    types = {a["type"] for a in robot.actuator_info()}
    u_unit = " or ".join(unit for kind, unit in (("P", "mm"), ("R", "mrad")) if kind in types)
    tau_unit = " or ".join(unit for kind, unit in (("P", "N"), ("R", "N m")) if kind in types)
    peak = robot.actuator_info()[0]["effort"]
    print(f"{robot!r}: peak |tau| per actuator [{tau_unit}]: {np.round(np.max(np.abs(tau), axis=0), 2)} "
          f"(limit {peak:g} {tau_unit})")
    # the check: these forces, played back through the forward dynamics from the first sample's
    # state, move the platform along trajectory 1 again (10 ms)
    columns = {"t": t, **{f"{name}{i + 1}": v[:, i] for name, v in (("u", u), ("du", du), ("tau", tau))
                          for i in range(robot.actuators)}}
    replayed = nocdyn.simulate(columns, robot=args.robot, duration=0.01)
    n = len(replayed)
    error = max(np.abs(replayed[axis] - P[:n, k]).max() for k, axis in enumerate(("x", "y", "theta")))
    print(f"forward dynamics of these forces: largest pose error {error:.2g} (m, rad) over {n} samples")
    if not error <= 1e-7:
        raise SystemExit(f"the forces do not reproduce trajectory 1: pose error {error:.3g}")

    fig, (ax_u, ax_tau) = plt.subplots(2, 1, sharex=True, figsize=(7.5, 5.5), constrained_layout=True)
    for i in range(robot.actuators):
        ax_u.plot(t * 1e3, u[:, i] * 1e3, label=f"u{i + 1}")
        ax_tau.plot(t * 1e3, tau[:, i], label=f"tau{i + 1}")
    ax_u.set_ylabel(f"actuator displacement [{u_unit}]")
    tau_name = " or ".join(name for kind, name in (("P", "force"), ("R", "torque")) if kind in types)
    ax_tau.set_ylabel(f"actuator {tau_name} [{tau_unit}]")
    ax_tau.set_xlabel("time [ms]")
    ax_u.set_title(f"{robot.name}, trajectory 1 of the paper (eq. 33): inverse dynamics")
    for ax in (ax_u, ax_tau):
        ax.grid(True, alpha=0.3)
        ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize="small")
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
