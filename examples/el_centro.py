# %% [markdown]
# # El Centro on the vibration generator
#
# The 1940 El Centro record (N-S, PEER AT2, in g) played on the paper's robot: high-passed,
# integrated, compressed in time by similitude until every actuator fits, and tracked by
# computed torque with an unknown payload and sensor noise. The score: how well the achieved
# acceleration and its response spectrum follow the target.

# %%
import os
import pathlib

import numpy as np

import nocdyn

root = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path.cwd()))
record = root / "data" / "elcentro_1940_ns.AT2"
out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
quick = os.environ.get("NOCDYN_EXAMPLE_QUICK") == "1"  # the tests: the first seconds only

# %%
replay = nocdyn.shake(record, window=1.0 if quick else 0.0, plant="nocdyn-rk4" if quick else None,
                      rate=2000.0 if quick else 10000.0, out_dir=out / "el-centro")
print(replay.text)
metrics = replay.metrics
print("time scale L =", metrics["time_scale"], " amplitude scale =", metrics["amplitude_scale"])

# %%
error = replay["ax_achieved"] - replay["ax"]
print(f"{len(replay)} samples; RMS acceleration error in x: {np.sqrt(np.mean(error ** 2)):.4g} m/s^2")
replay.to_pandas().describe() if __import__("importlib").util.find_spec("pandas") else None
