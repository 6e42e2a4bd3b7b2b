# %% [markdown]
# # El Centro on the vibration generator
#
# The 1940 El Centro record (N-S, PEER AT2, in g; `data/`) played on the paper's robot as a
# shake table plays it: high-passed, integrated, compressed in time by similitude until every
# actuator fits within its range, velocity and effort less a margin, then tracked in closed loop
# on a plant that carries 0.5 kg the controller does not know. The controller (`--controller
# table`, the default) reads only the sensors a table has: actuator encoders and platform
# accelerometers, with their noise, fused by a Kalman estimator; it drives the inverse dynamics
# of its model as feed-forward with a low-gain pose feedback (6 Hz). The plant is nocdyn's
# forward dynamics, one Runge-Kutta 4 step per tick (the default; `plant="simbody"` replays on
# the independent Simbody model, about 70 times slower). The score: how well the achieved
# acceleration and its response spectrum follow the target. The last cell checks the score
# against the CSV the replay wrote and fails (exit status 1) when the replay is off.

# %%
import os
import pathlib
import sys

import numpy as np

import nocdyn

root = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path.cwd()))
record = root / "data" / "elcentro_1940_ns.AT2"
out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
quick = os.environ.get("NOCDYN_EXAMPLE_QUICK") == "1"  # the tests: the first seconds only

# %%
replay = nocdyn.shake(record, window=1.0 if quick else 0.0, rate=2000.0 if quick else 10000.0,
                      out_dir=out / "el-centro")
print(replay.text)
metrics = replay.metrics
print("time scale L =", metrics["time_scale"], " amplitude scale =", metrics["amplitude_scale"])

# %% [markdown]
# The check: the RMS error of the achieved acceleration along x, computed here from the written
# samples, against the one the replay reports and against the goal of 5 %; and every actuator
# within its limits.

# %%
error = replay["ax_achieved"] - replay["ax"]
rms = 100 * np.sqrt(np.mean(error ** 2)) / np.sqrt(np.mean(replay["ax"] ** 2))  # [%]
reported = metrics["metrics"]["ax"]["rms_error_percent"]  # every error in shake.json is in percent
goal = 5.0  # [%]
print(f"{len(replay)} samples; RMS acceleration error in x: {rms:.3g} % (reported {reported:.3g} %, "
      f"goal {goal:.3g} %); limit use {100 * metrics['achieved_limit_use']['ratio']:.3g} %")
off = []
if not rms <= goal:
    off.append(f"RMS error {rms:.3g} % above the goal {goal:.3g} %")
if not abs(rms - reported) <= 0.1 * reported:
    off.append(f"RMS error from the samples {rms:.4g} % differs from the reported {reported:.4g} %")
if not metrics["achieved_limit_use"]["ratio"] <= 1.0:
    off.append(f"a limit was exceeded: {metrics['achieved_limit_use']}")
if off:
    sys.exit("the replay is off:\n" + "\n".join(off))
print("the replay meets its goal")
