# %% [markdown]
# # Identifying a payload on the simulated experiment
#
# The paper's robot tracks its trajectory 2 by computed torque on the plant (the Simbody model
# when built in, else nocdyn's forward dynamics) while carrying a payload the controller does
# not know (0.5 kg off the centre). The sensors' log (encoders and force sensors, with noise)
# is all `identify` gets; it recovers the payload's mass, centre of mass and inertia.

# %%
import os
import pathlib

import nocdyn

out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
quick = os.environ.get("NOCDYN_EXAMPLE_QUICK") == "1"  # the tests: a shorter experiment
duration = 0.2 if quick else 1.0
payload = dict(payload_mass=0.5, payload_com=(0.012, -0.007), payload_inertia=2e-4)

# %%
log = out / "experiment-log.csv"
run = nocdyn.control("paper2", duration=duration, plant="nocdyn" if quick else None, log=log,
                     noise_u=1e-7, noise_tau=0.05, seed=3, **payload)
print(run.text)
print(f"{len(run)} controller ticks; peak |e_x| {abs(run['e_x']).max() * 1e6:.2f} um")

# %%
estimate = nocdyn.identify(log)
print(estimate.text)
print("true payload:", payload)
estimate.payload
