"""The Python inverse dynamics against the C++ CLI, the golden values and the NOC identities;
array layouts, dtypes and shapes."""

import csv
import tracemalloc

import numpy as np
import pytest

import nocdyn


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    data = np.array([[float(v) for v in row] for row in rows[1:]])
    return {name: data[:, i] for i, name in enumerate(header)}


def columns(table, prefix, n):
    return np.column_stack([table[f"{prefix}{i + 1}"] for i in range(n)])


def assert_close_to_peak(ours, theirs, rel, what):
    """|ours - theirs| <= rel * (peak of |theirs| in the column), for every entry."""
    peak = np.max(np.abs(theirs), axis=0)
    err = np.abs(ours - theirs)
    assert np.all(err <= rel * peak), f"{what}: largest error {np.max(err / peak):.3g} of the column peak"


@pytest.mark.parametrize("robot_file", ["paper-3prr.yaml", "3-rrr.yaml", "4-rrr.yaml"])
def test_the_inverse_dynamics_job_on_a_trajectory_object_equals_the_cli_csv_exactly_and_the_batch_to_rounding(
        tmp_path, cli, source_dir, robot_file):
    """nocdyn.inverse_dynamics on a nocdyn.Trajectory runs the CLI's code: every number equal. The batch runs the lean
    kernel (FMA, a branch-free atan2 within 2 ulp of libm's): u within 1e-15 (m or rad, a few ulp
    of joint angles of order 1), du, ddu and tau within 5e-15 of their column's peak."""
    robot_path = source_dir / "robots" / robot_file
    out = tmp_path / "id.csv"
    code, _, err = cli("inverse-dynamics", "--robot", robot_path, "--trajectory", "paper1", "--rate", 10000,
                       "--duration", 0.01, "--allow-limits", "--output", out)
    assert code == 0, err
    table = read_csv(out)
    robot = nocdyn.Robot.load(robot_path)
    n = robot.actuators
    t = table["t"]
    P, dP, ddP = nocdyn.Trajectory.paper(1).evaluate(t)
    np.testing.assert_array_equal(P, np.column_stack([table["x"], table["y"], table["theta"]]))
    batch = robot.inverse_dynamics(P, dP, ddP, check_limits=False)  # as --allow-limits
    sampled = nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, rate=10000, duration=0.01,
                                      allow_limits=True, progress=False)
    assert sampled.columns == list(table.keys())
    for column in table:
        np.testing.assert_array_equal(sampled[column], table[column])
    # the deprecated wrapper: the same Table, and a DeprecationWarning
    with pytest.warns(DeprecationWarning, match="nocdyn.inverse_dynamics"):
        wrapped = robot.trajectory_dynamics(nocdyn.Trajectory.paper(1), rate=10000, duration=0.01, allow_limits=True)
    np.testing.assert_array_equal(wrapped.data, sampled.data)
    for name in ("u", "du", "ddu", "tau"):
        theirs = columns(table, name, n)
        if name == "u":
            np.testing.assert_allclose(batch.u, theirs, rtol=0, atol=1e-15)
        else:
            assert_close_to_peak(getattr(batch, name), theirs, 5e-15, f"batch {name}")


@pytest.mark.parametrize("number", [1, 2])
def test_paper_trajectories_reproduce_the_golden_values_to_1e9(golden_dir, paper_robot, number):
    golden = read_csv(golden_dir / f"paper_trajectory{number}.csv")
    P, dP, ddP = nocdyn.Trajectory.paper(number).evaluate(golden["t"])
    np.testing.assert_allclose(P, np.column_stack([golden["x"], golden["y"], golden["theta"]]), rtol=0, atol=1e-15)
    result = paper_robot.inverse_dynamics(P, dP, ddP)
    for name in ("u", "du", "ddu", "tau"):
        theirs = columns(golden, name, 3)
        peak = np.max(np.abs(theirs), axis=0)
        # relative 1e-9, with a floor of 1e-12 of the column peak (u passes through ~1e-19 m)
        assert np.all(np.abs(getattr(result, name) - theirs) <= np.maximum(1e-9 * np.abs(theirs), 1e-12 * peak)), name


# Measured: Lagrange's equations by central differences (h = 1e-6) hold to 4.8e-12 of the terms'
# scale on the paper's robot.
LAGRANGE_TOLERANCE = 5e-11


def random_motion(robot, n, seed=1):
    rng = np.random.default_rng(seed)
    # [x, y, theta] and its rates
    P = robot.home + rng.uniform(-1, 1, (n, 3)) * [0.003, 0.003, 0.02]
    dP = rng.uniform(-1, 1, (n, 3)) * [0.1, 0.1, 0.5]
    ddP = rng.uniform(-1, 1, (n, 3)) * [10.0, 10.0, 50.0]
    return P, dP, ddP


@pytest.mark.parametrize("name", ["paper-3prr", "3-rpr", "4-rrr"])
def test_one_sample_equals_its_batch_row_and_the_full_path(name):
    robot = nocdyn.Robot.example(name)
    P, dP, ddP = random_motion(robot, 50)
    batch = robot.inverse_dynamics(P, dP, ddP)
    for k in range(0, 50, 7):
        one = robot.inverse_dynamics(P[k], dP[k], ddP[k])
        full = robot.inverse_dynamics(P[k], dP[k], ddP[k], matrices=True)
        for field in ("u", "du", "ddu", "tau"):
            ref = getattr(one, field)
            # the same kernel, on packets of four samples in the batch (with its own FMA
            # contractions): equal to rounding
            np.testing.assert_allclose(getattr(batch, field)[k], ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))
            assert np.all(np.abs(getattr(full, field) - ref) <= 1e-12 * max(1.0, np.max(np.abs(ref)))), field


def test_forces_satisfy_lagranges_equations_with_the_inertia_by_finite_differences(paper_robot):
    """Three actuators, no gravity or friction. With the kinetic energy du^T I(u) du / 2, Lagrange's
    equations give tau = I ddu + (dI/dt) du - [du^T (dI/du_k) du / 2]_k: dI/dt by central
    differences of I along the motion, dI/du_k along dp/du e_k (dp/du the inverse of A_p = du/dp,
    itself by central differences of u). tau is computed as I ddu + C du (eq. 20): this sees every
    component of C du, where C and C^T differ. I is symmetric positive-definite."""
    P, dP, ddP = random_motion(paper_robot, 5, seed=3)
    h = 1e-6
    zero = np.zeros(3)

    def inertia(p):
        return paper_robot.inverse_dynamics(p, zero, zero, matrices=True).I

    def actuators(p):
        return paper_robot.inverse_dynamics(p, zero, zero).u

    worst = 0.0
    for k in range(5):
        p, dp, ddp = P[k], dP[k], ddP[k]
        r = paper_robot.inverse_dynamics(p, dp, ddp, matrices=True)
        assert r.I.shape == (3, 3) and r.C.shape == (3, 3) and r.T.shape == (paper_robot.bodies, 3, 3)
        np.testing.assert_allclose(r.I, r.I.T, rtol=0, atol=1e-14 * np.max(np.abs(r.I)))
        assert np.all(np.linalg.eigvalsh(r.I) > 0)
        I_dot = (inertia(p + h * dp + 0.5 * h * h * ddp) - inertia(p - h * dp + 0.5 * h * h * ddp)) / (2 * h)
        A_p = np.column_stack([(actuators(p + h * e) - actuators(p - h * e)) / (2 * h) for e in np.eye(3)])
        dp_du = np.linalg.inv(A_p)
        centrifugal = np.array(
            [r.du @ (inertia(p + h * dp_du[:, j]) - inertia(p - h * dp_du[:, j])) @ r.du / (4 * h) for j in range(3)]
        )
        velocity_terms = I_dot @ r.du - centrifugal
        lagrange = r.I @ r.ddu + velocity_terms
        scale = np.max(np.abs(r.I @ r.ddu)) + np.max(np.abs(velocity_terms))
        worst = max(worst, np.max(np.abs(lagrange - r.tau)) / scale)
        # the velocity terms matter here: C in place of C^T would change tau by more than the bound
        assert np.max(np.abs((r.C - r.C.T) @ r.du)) > 1e3 * LAGRANGE_TOLERANCE * scale
        assert np.all(np.abs(lagrange - r.tau) <= LAGRANGE_TOLERANCE * scale), f"sample {k}: {lagrange} vs {r.tau}"
    print(f"Lagrange's equations: largest error {worst:.3g} of the terms' scale")


def test_outputs_have_the_documented_shapes_and_dtype():
    robot = nocdyn.Robot.example("4-rrr")
    assert robot.actuators == 4 and robot.limbs == 4 and robot.redundant
    P, dP, ddP = random_motion(robot, 17)
    result = robot.inverse_dynamics(P, dP, ddP)
    for a in result:
        assert a.shape == (17, 4) and a.dtype == np.float64 and a.flags.c_contiguous
    one = robot.inverse_dynamics(list(P[0]), tuple(dP[0]), ddP[0])
    for a in one:
        assert a.shape == (4,) and a.dtype == np.float64
    empty = robot.inverse_dynamics(P[:0], dP[:0], ddP[:0])
    assert all(a.shape == (0, 4) for a in empty)


def test_fortran_ordered_and_strided_inputs_give_the_same_numbers(paper_robot):
    P, dP, ddP = random_motion(paper_robot, 200)
    ref = paper_robot.inverse_dynamics(P, dP, ddP)
    fortran = paper_robot.inverse_dynamics(np.asfortranarray(P), np.asfortranarray(dP), np.asfortranarray(ddP))
    for a, b in zip(fortran, ref):
        np.testing.assert_array_equal(a, b)
    # every second row of a wider array: non-contiguous in both dimensions' sense
    wide = [np.zeros((400, 5)) for _ in range(3)]
    for w, x in zip(wide, (P, dP, ddP)):
        w[::2, 1:4] = x
    strided = paper_robot.inverse_dynamics(*(w[::2, 1:4] for w in wide))
    assert not wide[0][::2, 1:4].flags.c_contiguous and not wide[0][::2, 1:4].flags.f_contiguous
    for a, b in zip(strided, ref):
        np.testing.assert_array_equal(a, b)
    # Fortran-ordered and strided outputs
    out_f = tuple(np.empty((200, 3), order="F") for _ in range(4))
    got = paper_robot.inverse_dynamics(P, dP, ddP, out=out_f)
    big = [np.full((200, 6), np.inf) for _ in range(4)]
    out_s = tuple(b[:, ::2] for b in big)
    paper_robot.inverse_dynamics(P, dP, ddP, out=out_s)
    for g, o, s, b in zip(got, out_f, out_s, ref):
        assert g is o
        np.testing.assert_array_equal(o, b)
        np.testing.assert_array_equal(s, b)
    assert np.all(np.isinf(big[0][:, 1::2])), "a strided output wrote outside its view"


def test_batch_reads_inputs_and_writes_out_in_place_without_copies(paper_robot):
    n = 100_000
    P, dP, ddP = (np.asfortranarray(a) for a in random_motion(paper_robot, n))
    out = tuple(np.empty((n, 3)) for _ in range(4))
    paper_robot.inverse_dynamics(P[:10], dP[:10], ddP[:10])  # warm up
    tracemalloc.start()
    try:
        result = paper_robot.inverse_dynamics(P, dP, ddP, out=out)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert all(r is o for r, o in zip(result, out))
    # one input copied would be 2.4 MB
    assert peak < 200_000, f"{peak} bytes allocated during a batch with preallocated outputs"


def test_wrong_dtypes_raise_type_error_naming_the_array(paper_robot):
    P, dP, ddP = random_motion(paper_robot, 4)
    with pytest.raises(TypeError, match=r"^p: expected an array of float64, got dtype float32"):
        paper_robot.inverse_dynamics(P.astype(np.float32), dP, ddP)
    with pytest.raises(TypeError, match=r"^ddp: expected an array of float64, got dtype int64"):
        paper_robot.inverse_dynamics(P, dP, np.zeros((4, 3), dtype=np.int64))
    with pytest.raises(TypeError, match=r"^dp: .*object"):
        paper_robot.inverse_dynamics(P, np.array([[None] * 3] * 4, dtype=object), ddP)
    out = (np.empty((4, 3), dtype=np.float32),) + tuple(np.empty((4, 3)) for _ in range(3))
    with pytest.raises(TypeError, match=r"^u: expected an array of float64"):
        paper_robot.inverse_dynamics(P, dP, ddP, out=out)


def test_bad_shapes_layouts_and_outputs_raise_nocdyn_error(paper_robot):
    P, dP, ddP = random_motion(paper_robot, 4)
    cases = [
        ((P, dP[:3], ddP), {}, r"^dp: expected shape \(4, 3\), got \(3, 3\)"),
        ((P[:, :2], dP, ddP), {}, r"^p: expected shape \(N, 3\), got \(4, 2\)"),
        ((P, dP, ddP), {"out": tuple(np.empty((4, 2)) for _ in range(4))}, r"^u: expected shape \(4, 3\)"),
        ((P, dP, ddP), {"out": (np.empty((4, 3), order="F"),) + tuple(np.empty((4, 3)) for _ in range(3))},
         r"^out: u, du, ddu and tau must have the same memory order"),
        ((P, dP, ddP), {"out": (np.empty((4, 3)),) * 3}, r"^out: expected a tuple of four arrays"),
        ((P[0], dP[0], ddP[0][:2]), {}, r"^ddp: expected 3 values"),
        ((P[0], dP[0], ddP[0]), {"out": 1}, r"^out: only for a batch"),
        ((P, dP, ddP), {"matrices": True}, r"^matrices: only for one sample"),
    ]
    for args, kwargs, message in cases:
        with pytest.raises(nocdyn.Error, match=message):
            paper_robot.inverse_dynamics(*args, **kwargs)
    readonly = tuple(np.empty((4, 3)) for _ in range(4))
    readonly[2].flags.writeable = False
    with pytest.raises(nocdyn.Error, match=r"^ddu: the output array is read-only"):
        paper_robot.inverse_dynamics(P, dP, ddP, out=readonly)
    assert issubclass(nocdyn.Error, ValueError)
    # a reversed view is read as it is (copied, its strides being negative)
    reversed_rows = paper_robot.inverse_dynamics(P[::-1], dP[::-1], ddP[::-1])
    assert np.array_equal(reversed_rows.tau, paper_robot.inverse_dynamics(P, dP, ddP).tau[::-1])


def test_a_sample_out_of_reach_names_it_and_leaves_nan_rows(paper_robot):
    P, dP, ddP = random_motion(paper_robot, 6)
    P[3, 0] = 0.5  # x 0.5 m off: far out of reach
    with pytest.raises(nocdyn.Error, match=r"^sample 4: .*\(1 of 6 samples failed\)$"):
        paper_robot.inverse_dynamics(P, dP, ddP)
    result = paper_robot.inverse_dynamics(P, dP, ddP, check=False)
    assert np.all(np.isnan(result.tau[3])) and np.all(np.isfinite(np.delete(result.tau, 3, axis=0)))
    with pytest.raises(nocdyn.Error) as one:
        paper_robot.inverse_dynamics(P[3], dP[3], ddP[3])
    assert str(one.value) in str(pytest.raises(nocdyn.Error, paper_robot.inverse_dynamics, P, dP, ddP).value)
    P[2, 0] = np.nan
    with pytest.raises(nocdyn.Error, match=r"^sample 3: .*\(2 of 6 samples failed\)$"):
        paper_robot.inverse_dynamics(P, dP, ddP)


def test_threads_split_the_batch_with_the_same_numbers(paper_robot):
    P, dP, ddP = random_motion(paper_robot, 1001)
    ref = paper_robot.inverse_dynamics(P, dP, ddP)
    for a, b in zip(paper_robot.inverse_dynamics(P, dP, ddP, threads=2), ref):
        np.testing.assert_array_equal(a, b)


def test_an_absurd_thread_count_is_capped_and_gives_the_one_thread_numbers(paper_robot):
    """threads=100000 once aborted the interpreter (a thread that could not start): the count is
    capped at the hardware and at one chunk per 8 samples."""
    P, dP, ddP = random_motion(paper_robot, 50)
    ref = paper_robot.inverse_dynamics(P, dP, ddP, threads=1)
    for a, b in zip(paper_robot.inverse_dynamics(P, dP, ddP, threads=100000), ref):
        np.testing.assert_array_equal(a, b)
