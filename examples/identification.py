# %% [markdown]
# # Identifying a payload on the simulated experiment
#
# The paper's robot tracks its trajectory 2 by computed torque on the plant (the Simbody model
# when built in, else nocdyn's forward dynamics) while carrying a payload the controller does
# not know (0.5 kg off the centre). The sensors' log (encoders and force sensors, with noise)
# is all `identify` gets; it recovers the payload's mass, centre of mass and inertia. The log
# names its forces `tau1_held..`: they are the controller's commands, each held until the next
# tick, and `identify` takes them so with its default options. The last cell checks the estimate
# against the payload put on the plant and fails (exit status 1) when it is off.

# %%
import os
import pathlib
import re
import sys

import nocdyn

out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
quick = os.environ.get("NOCDYN_EXAMPLE_QUICK") == "1"  # the tests: a shorter experiment
duration = 0.5 if quick else 1.0
payload = dict(payload_mass=0.5, payload_com=(0.012, -0.007), payload_inertia=2e-4)

# %%
log = out / "experiment-log.csv"
run = nocdyn.control("paper2", duration=duration, plant="nocdyn-rk4" if quick else None, log=log,
                     noise_u=1e-7, noise_tau=0.05, seed=3, **payload)
print(run.text)
print(f"{len(run)} controller ticks; peak |e_x| {abs(run['e_x']).max() * 1e6:.2f} um")

# %%
estimate = nocdyn.identify(log)  # the default options: the log says its forces are held commands
print(estimate.text)
print("true payload:", payload)

# %% [markdown]
# The check: each identified parameter against the truth the plant carried, within a tolerance
# (mass 1 %, c.o.m. 0.2 mm, inertia 2 %).

# %%
found = re.search(r"payload: \{mass: (\S+), com: \[(\S+), (\S+)\], inertia: (\S+)\}", estimate.text)
mass, com_x, com_y, inertia = (float(v) for v in found.groups())
checks = [("mass [kg]", mass, payload["payload_mass"], 0.01 * payload["payload_mass"]),
          ("c.o.m. x [m]", com_x, payload["payload_com"][0], 2e-4),
          ("c.o.m. y [m]", com_y, payload["payload_com"][1], 2e-4),
          ("inertia [kg m^2]", inertia, payload["payload_inertia"], 0.02 * payload["payload_inertia"])]
off = [f"{name}: identified {value:.6g}, true {truth:.6g}, allowed +-{allowed:.3g}"
       for name, value, truth, allowed in checks if not abs(value - truth) <= allowed]
for name, value, truth, allowed in checks:
    print(f"{name}: {value:.6g} (true {truth:.6g}, error {value - truth:+.3g}, allowed +-{allowed:.3g})")
if off:
    sys.exit("identification is off:\n" + "\n".join(off))
print("every parameter within its tolerance")
