"""The one guard of every Python entry, each case the exact input that once gave wrong numbers:
strided 1-D arrays read as contiguous, NaN options accepted, inf and NaN returned from finite
input, overlapping outputs, an absurd thread count."""

import numpy as np
import pytest

import nocdyn

PAYLOAD = dict(mass=0.5, com=(0.012, -0.007), inertia=8e-4)


def exact_log(robot, loaded, n=200):
    t = np.arange(n) * 0.004
    traj = nocdyn.Trajectory.harmonic(x=[(0.002, 5.0, 0.0)], y=[(0.002, 7.0, 0.5)], theta=[(0.05, 3.0, 0.0)],
                                      offset=robot.home)
    P, dP, ddP = traj.evaluate(t)
    u, du, ddu, tau = loaded.inverse_dynamics(P, dP, ddP)
    return t, u, du, ddu, tau


def test_identify_reads_columns_of_a_structured_csv_array_as_their_values():
    robot = nocdyn.Robot.example("paper-3prr-general")
    t, u, du, ddu, tau = exact_log(robot, robot.with_payload(**PAYLOAD))
    # numpy.genfromtxt(..., names=True) gives a structured array: A["t"] is a strided view
    names = ["t"] + [f"{q}{i}" for q in ("u", "du", "ddu", "tau") for i in (1, 2, 3)]
    A = np.zeros(len(t), dtype=[(name, float) for name in names])
    A["t"] = t
    for i in range(3):
        A[f"u{i + 1}"], A[f"du{i + 1}"], A[f"ddu{i + 1}"], A[f"tau{i + 1}"] = u[:, i], du[:, i], ddu[:, i], tau[:, i]
    assert A["t"].strides[0] == 8 * len(names)
    est = nocdyn.identify({name: A[name] for name in names}, robot=robot, progress=False).payload_estimate
    assert abs(est.mass - 0.5) <= 1e-9
    assert abs(est.inertia - 8e-4) <= 1e-12


def test_simulate_reads_a_strided_column_of_force_times_as_its_values():
    robot = nocdyn.Robot.example("paper-3prr-general")
    M = np.zeros((50, 4))
    M[:, 0] = np.arange(50) * 0.002
    M[:, 1:] = 1.0
    strided = nocdyn.simulate({"t": M[:, 0], "tau1": M[:, 1], "tau2": M[:, 2], "tau3": M[:, 3]}, robot=robot,
                              rate=200.0, duration=0.05, progress=False)
    contiguous = nocdyn.simulate({name: np.ascontiguousarray(M[:, k]) for k, name in
                                  enumerate(("t", "tau1", "tau2", "tau3"))}, robot=robot, rate=200.0, duration=0.05,
                                 progress=False)
    assert np.array_equal(strided.data, contiguous.data)
    assert np.all(np.isfinite(strided.data))


@pytest.mark.parametrize("option", ["rtol", "atol"])
def test_simulate_refuses_nan_options_as_the_command_line_does(option):
    forces = {"t": np.linspace(0.0, 0.01, 3), **{f"tau{a}": np.zeros(3) for a in (1, 2, 3)}}
    with pytest.raises(nocdyn.Error, match=option):
        nocdyn.simulate(forces, robot=nocdyn.Robot.example("paper-3prr-general"), **{option: float("nan")})


@pytest.mark.parametrize("which, value", [("dp", 1e155), ("ddp", 1e308)])
def test_huge_finite_rates_raise_instead_of_returning_nan_or_inf(which, value):
    robot = nocdyn.Robot.example("paper-3prr-general")
    p = np.tile(robot.home, (4, 1))
    args = {"p": p, "dp": np.zeros((4, 3)), "ddp": np.zeros((4, 3))}
    args[which][2, 1] = value
    with pytest.raises(nocdyn.Error, match="sample 3"):  # row 2, numbered from 1
        robot.inverse_dynamics(**args)
    one = {k: v[2] for k, v in args.items()}
    with pytest.raises(nocdyn.Error):
        robot.inverse_dynamics(**one)
    with pytest.raises(nocdyn.Error):
        robot.regressor(**args)


def test_overlapping_outputs_are_refused():
    robot = nocdyn.Robot.example("paper-3prr-general")
    p = np.tile(robot.home, (5, 1))
    z = np.zeros((5, 3))
    big = np.empty((5, 6))
    with pytest.raises(nocdyn.Error, match="overlap"):
        robot.inverse_dynamics(p, z, z, out=(big[:, 0:3], big[:, 1:4], np.empty((5, 3)), np.empty((5, 3))))
    same = np.empty((5, 3))
    with pytest.raises(nocdyn.Error, match="overlap"):
        robot.inverse_dynamics(p, z, z, out=(same, same, np.empty((5, 3)), np.empty((5, 3))))
    with pytest.raises(nocdyn.Error, match="overlap"):
        robot.inverse_dynamics(p, z, z, out=(np.lib.stride_tricks.as_strided(same, strides=(8, 8)), np.empty((5, 3)),
                                             np.empty((5, 3)), np.empty((5, 3))))
    inputs = p.copy()
    with pytest.raises(nocdyn.Error, match="overlaps the input p"):
        robot.inverse_dynamics(inputs, z, z, out=(inputs, np.empty((5, 3)), np.empty((5, 3)), np.empty((5, 3))))
    # side by side in one array, not overlapping: accepted, the same numbers
    ok = robot.inverse_dynamics(p, z, z, out=(big[:, 0:3], big[:, 3:6], np.empty((5, 3)), np.empty((5, 3))))
    ref = robot.inverse_dynamics(p, z, z)
    assert np.array_equal(ok.u, ref.u) and np.array_equal(ok.du, ref.du)


def test_reversed_and_strided_inputs_give_the_contiguous_answer():
    robot = nocdyn.Robot.example("paper-3prr-general")
    traj = nocdyn.Trajectory.paper(1)
    P, dP, ddP = traj.evaluate(np.arange(20) * 1e-3)
    P = P + robot.home
    ref = robot.inverse_dynamics(P, dP, ddP)
    got = robot.inverse_dynamics(P[::-1], dP[::-1], ddP[::-1])
    assert np.array_equal(got.tau, ref.tau[::-1])
    wide = np.zeros((20, 6))
    wide[:, ::2] = P
    got = robot.inverse_dynamics(wide[:, ::2], np.asfortranarray(dP), ddP)
    assert np.array_equal(got.tau, ref.tau)


def test_threads_are_checked_and_capped():
    robot = nocdyn.Robot.example("paper-3prr-general")
    p = np.tile(robot.home, (8, 1))
    z = np.zeros((8, 3))
    ref = robot.inverse_dynamics(p, z, z)
    for many in (1000, 100000, 10**9):
        assert np.array_equal(robot.inverse_dynamics(p, z, z, threads=many).tau, ref.tau)
    with pytest.raises(nocdyn.Error, match="threads"):
        robot.inverse_dynamics(p, z, z, threads=-1)
    with pytest.raises(TypeError):
        robot.inverse_dynamics(p, z, z, threads=2.5)


def test_trajectory_evaluate_refuses_nan_and_overflowing_times():
    traj = nocdyn.Trajectory.paper(1)
    with pytest.raises(nocdyn.Error, match="t"):
        traj.evaluate([0.0, float("nan")])
    with pytest.raises(nocdyn.Error, match="not finite"):
        traj.evaluate([1e308])


def test_identify_on_a_translation_along_x_alone_names_what_it_cannot_identify():
    robot = nocdyn.Robot.example("paper-3prr-general")
    loaded = robot.with_payload(**PAYLOAD)
    t = np.arange(1000) * 0.001
    P, dP, ddP = nocdyn.Trajectory.harmonic(x=[(0.002, 5.0, 0.0)], offset=robot.home).evaluate(t)
    u, du, ddu, tau = loaded.inverse_dynamics(P, dP, ddP)
    with pytest.raises(nocdyn.Error, match="payload inertia") as info:
        columns = {"t": t, **{f"{q}{a + 1}": values[:, a] for q, values in (("u", u), ("tau", tau), ("du", du),
                                                                            ("ddu", ddu)) for a in range(3)}}
        nocdyn.identify(columns, robot=robot, progress=False)
    assert "payload c.o.m. x" in str(info.value) and "payload mass 0.5 kg" in str(info.value)


def test_the_inverse_dynamics_job_refuses_more_samples_than_memory_holds_before_computing_any():
    robot = nocdyn.Robot.example("paper-3prr-general")
    with pytest.raises(nocdyn.Error, match="more than the 800 MB allowed"):
        nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, rate=1e8, duration=1.0)
    with pytest.raises(nocdyn.Error, match="rate"):
        nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, rate=float("nan"))
    out = nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, rate=10000.0, duration=0.01)
    assert len(out) == 100 and np.all(np.isfinite(out["tau3"]))


def test_one_sample_whose_results_overflow_raises_unless_check_is_false():
    robot = nocdyn.Robot.example("paper-3prr-general")
    p, z = np.asarray(robot.home, dtype=float), np.zeros(3)
    huge = np.array([0.0, 0.0, 1e155])  # a rate whose square is beyond the doubles
    with pytest.raises(nocdyn.Error, match="the inverse dynamics is not finite"):
        robot.inverse_dynamics(p, huge, z, check_limits=False)
    with pytest.raises(nocdyn.Error, match="the inverse dynamics is not finite"):
        robot.inverse_dynamics(p, huge, z, matrices=True, check_limits=False)
    result = robot.inverse_dynamics(p, huge, z, check_limits=False, check=False)
    assert not np.all(np.isfinite(result.tau))
    # a finite sample is unchanged
    assert np.all(np.isfinite(robot.inverse_dynamics(p, z, z).tau))
