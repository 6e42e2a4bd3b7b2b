# %% [markdown]
# # The paper's Figs. 5 and 6 from Python
#
# The 3-PRR vibration generator of the paper along its trajectories 1 and 2 (eqs. 33-34),
# 0.2 s at 10 kHz: the motor displacements u and forces tau of the inverse dynamics (the NOC,
# eq. 20). `nocdyn.inverse_dynamics` runs `nocdyn inverse-dynamics` (same defaults, same
# numbers) and returns its CSV's columns as NumPy arrays.
#
# A jupytext-style script: open it as a notebook (`jupytext --to notebook`) or run it as it is
# (`PYTHONPATH=build/python /usr/bin/python3 examples/paper_figures.py`): it writes
# paper_fig5.png and paper_fig6.png into NOCDYN_EXAMPLE_OUT (default: the current folder).

# %%
import os
import pathlib

import matplotlib

if "ipykernel" not in __import__("sys").modules:
    matplotlib.use("Agg")  # files only when run as a script
import matplotlib.pyplot as plt
import numpy as np

import nocdyn

out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
robot = nocdyn.Robot.paper()
robot  # in Jupyter: the robot drawn at home (Robot._repr_svg_)

# %%
results = {}
for number in (1, 2):
    table = nocdyn.inverse_dynamics(f"paper{number}", duration=0.2, rate=10000.0)
    results[number] = table
    u, tau = table.group("u"), table.group("tau")
    print(f"trajectory {number}: {len(table)} samples, peak |u| {np.abs(u).max(axis=0) * 1e3} mm, "
          f"peak |tau| {np.abs(tau).max(axis=0)} N")

# %%
for number, figure in ((1, 5), (2, 6)):
    table = results[number]
    t = table["t"] * 1e3
    fig, (ax_u, ax_tau) = plt.subplots(2, 1, sharex=True, figsize=(7, 5), constrained_layout=True)
    for i in range(1, robot.actuators + 1):
        ax_u.plot(t, table[f"u{i}"] * 1e3, label=f"motor {i}")
        ax_tau.plot(t, table[f"tau{i}"], label=f"motor {i}")
    ax_u.set_ylabel("displacement [mm]")
    ax_tau.set_ylabel("force [N]")
    ax_tau.set_xlabel("time [ms]")
    ax_u.set_title(f"Fig. {figure}: trajectory {number} (eq. {32 + number})")
    for ax in (ax_u, ax_tau):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    fig.savefig(out / f"paper_fig{figure}.png", dpi=100)
    plt.close(fig)
    print(f"wrote {out / f'paper_fig{figure}.png'}")

# %% [markdown]
# The check: the forces of trajectory 1 played back through the forward dynamics (`nocdyn
# simulate`, an integrator of eq. 23 to 1e-10) move the platform along trajectory 1 again; the
# script fails (exit status 1) when they do not.

# %%
replayed = nocdyn.simulate(results[1], duration=0.05)
n = len(replayed)
error = max(np.abs(replayed[axis] - results[1][axis][:n]).max() for axis in ("x", "y", "theta"))
print(f"forward dynamics of trajectory 1's forces over {replayed['t'][-1]:.3g} s: largest pose error {error:.2g}")
if not error <= 1e-7:
    raise SystemExit(f"the forces do not reproduce trajectory 1: pose error {error:.3g} (m, rad)")

# %% [markdown]
# The same numbers as the command line (`nocdyn inverse-dynamics --trajectory paper1`), and as
# a pandas DataFrame with its columns:

# %%
results[1].to_pandas().head() if __import__("importlib").util.find_spec("pandas") else None
