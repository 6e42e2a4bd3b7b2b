"""The Python regressor and payload identification: Y pi equals the inverse dynamics, per sample
and stacked; exact data identify a payload to 1e-9 (nocdyn.identify on a log given as columns,
its payload returned as numbers); a prior bounds the estimate; bad input raises nocdyn.Error."""

import numpy as np
import pytest

import nocdyn

PAYLOAD = dict(mass=0.5, com=(0.012, -0.007), inertia=8e-4)


def log(t, u, tau, du=None, ddu=None):
    """A log of arrays as the columns nocdyn.identify reads: t, u1..un, tau1..taun (du, ddu)."""
    columns = {"t": t}
    for name, values in (("u", u), ("tau", tau), ("du", du), ("ddu", ddu)):
        if values is not None:
            columns.update({f"{name}{a + 1}": values[:, a] for a in range(values.shape[1])})
    return columns


def identify_payload(robot, t, u, tau, du=None, ddu=None, **options):
    return nocdyn.identify(log(t, u, tau, du, ddu), robot=robot, progress=False, **options).payload_estimate


def motion(robot, samples, dt=0.004):
    """Samples of a two-frequency platform motion about the robot's home."""
    x, y, theta = robot.home
    traj = nocdyn.Trajectory.harmonic(theta=[(0.04, 3.0, 0.3), (0.02, 7.0, 1.0)],
                                      x=[(0.003, 2.0, 0.0), (0.001, 5.0, 1.2)],
                                      y=[(0.003, 4.0, 0.7), (0.001, 9.0, 0.2)], offset=(x, y, theta))
    t = np.arange(samples) * dt
    return (t, *traj.evaluate(t))


@pytest.mark.parametrize("name", ["paper-3prr-general", "3-rrr", "4-rrr"])
def test_regressor_times_the_standard_parameters_equals_inverse_dynamics(name):
    robot = nocdyn.Robot.example(name)
    _, P, dP, ddP = motion(robot, 40)
    pi = robot.standard_parameters()
    Y = robot.regressor(P, dP, ddP)
    n = robot.actuators
    assert Y.shape == (40 * n, len(pi)) == (40 * n, len(robot.parameter_names()))
    tau = robot.inverse_dynamics(P, dP, ddP).tau
    scale = np.max(np.abs(tau))
    assert np.max(np.abs((Y @ pi).reshape(40, n) - tau)) <= 1e-12 * scale
    # the stacked rows are the per-sample regressors
    for k in (0, 17, 39):
        Yk = robot.regressor(P[k], dP[k], ddP[k])
        assert Yk.shape == (n, len(pi))
        np.testing.assert_array_equal(Yk, Y[k * n:(k + 1) * n])
        assert np.max(np.abs(Yk @ pi - robot.inverse_dynamics(P[k], dP[k], ddP[k]).tau)) <= 1e-12 * scale
    assert robot.parameter_names()[-1].endswith(".friction")
    assert robot.parameter_units()[:4] == ["kg", "kg m", "kg m", "kg m^2"]


@pytest.mark.parametrize("name", ["paper-3prr-general", "4-rrr"])
def test_exact_data_identify_the_payload_to_1e_9(name):
    robot = nocdyn.Robot.example(name)
    loaded = robot.with_payload(**PAYLOAD)
    t, P, dP, ddP = motion(robot, 200)
    u, du, ddu, tau = loaded.inverse_dynamics(P, dP, ddP)
    est = identify_payload(robot, t, u, tau, du, ddu)
    assert isinstance(est, nocdyn.PayloadEstimate)
    # the deprecated wrapper over nocdyn.identify: the same numbers
    with pytest.warns(DeprecationWarning, match="nocdyn.identify"):
        assert robot.identify_payload(t, u, tau, du, ddu).as_dict()["mass"] == est.mass
    assert abs(est.mass - 0.5) <= 1e-9 * 0.5
    assert np.all(np.abs(est.com - np.array(PAYLOAD["com"])) <= 1e-9 * 0.012)
    assert abs(est.inertia - 8e-4) <= 1e-9 * 8e-4
    assert est.mass_sd < 1e-9 and est.inertia_sd < 1e-12
    assert est.active_bounds == [] and not est.inertia_constrained
    fit = est.fit
    assert fit["fit_samples"] + fit["holdout_samples"] == 200
    assert fit["measured"].shape == fit["predicted"].shape == (fit["holdout_samples"], robot.actuators)
    assert np.all(fit["rms_holdout"] <= 1e-9 * fit["rms_measured"])
    assert set(est.as_dict()) >= {"mass", "com", "inertia", "mass_sd", "com_sd", "inertia_sd", "covariance"}
    # the covariance of [mass, com_x, com_y, inertia]: its diagonal the standard deviations squared
    assert est.covariance.shape == (4, 4)
    np.testing.assert_allclose(np.sqrt(np.diag(est.covariance)),
                               [est.mass_sd, est.com_sd[0], est.com_sd[1], est.inertia_sd], rtol=1e-12, atol=0)
    assert fit["correlation_samples"] >= 1.0 and fit["effective_samples"] > 0.0


def test_a_prior_excluding_the_payload_puts_the_estimate_on_its_bound(tmp_path):
    robot = nocdyn.Robot.example("paper-3prr-general")
    t, P, dP, ddP = motion(robot, 120)
    u, du, ddu, tau = robot.with_payload(**PAYLOAD).inverse_dynamics(P, dP, ddP)
    est = identify_payload(robot, t, u, tau, du, ddu, prior={"mass": (0.3, 0.45), "com_x": (None, 0.05)})
    assert est.mass == 0.45
    assert [(b["parameter"], b["side"]) for b in est.active_bounds] == [("mass", "upper")]
    assert abs(est.active_bounds[0]["unbounded"] - 0.5) <= 1e-9
    # the same from a prior file
    path = tmp_path / "prior.yaml"
    path.write_text("payload:\n  mass: [0.3, 0.45]\n  com_x: [~, 0.05]\n")
    assert nocdyn.load_prior(path) == {"mass": (0.3, 0.45), "com_x": (None, 0.05)}
    assert identify_payload(robot, t, u, tau, du, ddu, prior=path).mass == 0.45
    path.write_text("payload:\n  mass: [0.6, 0.45]\n")
    with pytest.raises(nocdyn.Error, match=r"prior.yaml:2: payload.mass: lower bound 0.6 is above upper bound 0.45"):
        identify_payload(robot, t, u, tau, du, ddu, prior=path)
    with pytest.raises(nocdyn.Error, match="unknown key 'density'"):
        identify_payload(robot, t, u, tau, du, ddu, prior={"density": (1, 2)})


def test_bad_logs_raise_nocdyn_errors():
    robot = nocdyn.Robot.example("paper-3prr-general")
    t, P, dP, ddP = motion(robot, 60)
    u, du, ddu, tau = robot.with_payload(**PAYLOAD).inverse_dynamics(P, dP, ddP)
    with pytest.raises(nocdyn.Error, match=r"^data: no column 'tau3'"):
        identify_payload(robot, t, u, tau[:, :2], du, ddu)
    with pytest.raises(nocdyn.Error, match="give both du1..du3 and ddu1..ddu3, or neither"):
        identify_payload(robot, t, u, tau, du)
    bad = u.copy()
    bad[7, 1] = np.nan  # row 8 of the log, numbered from 1
    with pytest.raises(nocdyn.Error, match=r"^data: row 8: column 'u2': not a finite number$"):
        identify_payload(robot, t, bad, tau, du, ddu)
    back = t.copy()
    back[5] = back[4]
    with pytest.raises(nocdyn.Error, match=r"^data: row 6: column 't': .* \(time must increase\)$"):
        identify_payload(robot, back, u, tau, du, ddu)
    with pytest.raises(nocdyn.Error, match="^sample 2: "):  # row 1, numbered from 1
        far = P.copy()
        far[1, 1] += 10.0
        robot.regressor(far, dP, ddP)


def test_identify_returns_the_payload_as_numbers_without_pyyaml(tmp_path):
    """The identified payload is the job's typed result, not its YAML read back: with PyYAML made
    unimportable (sys.modules["yaml"] = None) in a fresh interpreter, the payload is still there."""
    import os
    import subprocess
    import sys
    script = tmp_path / "no_yaml.py"
    script.write_text(
        "import sys\n"
        "sys.modules['yaml'] = None  # import yaml now raises ImportError\n"
        "import numpy as np, nocdyn\n"
        "robot = nocdyn.Robot.example('paper-3prr-general')\n"
        "t = np.arange(200) * 0.004\n"
        "traj = nocdyn.Trajectory.harmonic(theta=[(0.04, 3.0, 0.3), (0.02, 7.0, 1.0)], x=[(0.003, 2.0, 0.0),\n"
        "    (0.001, 5.0, 1.2)], y=[(0.003, 4.0, 0.7), (0.001, 9.0, 0.2)], offset=tuple(robot.home))\n"
        "u, du, ddu, tau = robot.with_payload(0.5, (0.012, -0.007), 8e-4).inverse_dynamics(*traj.evaluate(t))\n"
        "log = {'t': t, **{f'{q}{a + 1}': x[:, a] for q, x in (('u', u), ('tau', tau), ('du', du), ('ddu', ddu))\n"
        "                  for a in range(3)}}\n"
        "r = nocdyn.identify(log, robot=robot, progress=False)\n"
        "try:\n"
        "    import yaml\n"
        "    print('yaml importable')\n"
        "except ImportError:\n"
        "    pass\n"
        "assert r.report is None, r.report\n"
        "print(repr(r.payload['mass']), repr(r.payload_estimate.inertia))\n")
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120,
                          env={**os.environ})
    assert done.returncode == 0, done.stderr
    assert "yaml importable" not in done.stdout
    mass, inertia = (float(v) for v in done.stdout.split()[:2])
    assert abs(mass - 0.5) <= 1e-9 * 0.5 and abs(inertia - 8e-4) <= 1e-9 * 8e-4
