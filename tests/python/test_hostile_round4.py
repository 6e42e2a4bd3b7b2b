"""Hostile input in the Python package, compliance and long calls: each test holds one finding
with its exact input. Ctrl-C in the jobs and Robot's batches, a stiffness
contrast, tiny stiffness values, stiff beams, the frequency response at very low frequency, the
lumped model next to a limb singularity, and the typed layer's messages."""

import os
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import nocdyn


@pytest.fixture(scope="module")
def compliant(source_dir):
    return nocdyn.Robot.load(source_dir / "robots" / "paper-3prr-compliant.yaml")


@pytest.fixture(scope="module")
def compliant_text(source_dir):
    return (source_dir / "robots" / "paper-3prr-compliant.yaml").read_text()


def interrupted_after(seconds, call):
    """Runs call() with a SIGINT sent to this process after `seconds`; the time from the signal
    to the KeyboardInterrupt, which must arrive."""
    sent = []
    timer = threading.Timer(seconds, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
            time.sleep(5.0)  # the call ended before the signal: wait for it, the test then fails below
    finally:
        timer.cancel()
    assert sent, "the call returned before the signal was sent"
    return time.monotonic() - sent[0]


def test_ctrl_c_stops_a_long_simulation_at_once(source_dir):
    forces = {"t": [0.0, 1000.0], **{f"tau{a}": [0.0, 0.0] for a in (1, 2, 3)}}
    compliant = source_dir / "robots" / "paper-3prr-compliant.yaml"
    late = interrupted_after(0.5, lambda: nocdyn.simulate(forces, robot=compliant, rate=1000.0, progress=False))
    assert late < 2.0


def test_ctrl_c_stops_the_envelope_within_a_point(source_dir):
    compliant = source_dir / "robots" / "paper-3prr-compliant.yaml"
    late = interrupted_after(1.0, lambda: nocdyn.envelope(robot=compliant, points=1000, max_frequency=1e4,
                                                          progress=False))
    assert late < 2.0


def test_ctrl_c_stops_the_inverse_dynamics_of_a_trajectory(paper_robot):
    late = interrupted_after(0.5, lambda: nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=paper_robot,
                                                                  rate=1e7, duration=0.1, progress=False))
    assert late < 2.0


def test_a_stiffness_contrast_above_a_billion_keeps_the_held_modes(compliant_text):
    text = compliant_text.replace("EA: 1.4e7", "EA: 1e15").replace("stiffness: 2.0e5", "stiffness: 5e14", 1)
    robot = nocdyn.Robot.from_yaml(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the contrast costs digits: said, not an error
        f = robot.natural_frequencies([0.0, 0.0, 0.0])
    assert f[0] == pytest.approx(41.3, abs=0.5) and f[1] == pytest.approx(43.8, abs=0.5)
    assert nocdyn.envelope(robot=robot, points=2).first_natural_frequency == pytest.approx(f[0], rel=1e-12)


def test_a_contrast_beyond_double_precision_is_refused_by_name(compliant_text):
    text = compliant_text.replace("EA: 1.4e7", "EA: 1e15")
    for _ in range(2):
        text = text.replace("stiffness: 2.0e5,", "stiffness: 1e15,", 1)
    text = text.replace("stiffness: 2.0e5,", "stiffness: 1e-3,", 1)
    robot = nocdyn.Robot.from_yaml(text)
    with pytest.raises(nocdyn.Error, match="stiffness contrast"):
        robot.natural_frequencies([0.0, 0.0, 0.0])


@pytest.mark.parametrize("old, new, field", [("stiffness: 2.0e5", "stiffness: 1e-320", "stiffness"),
                                             ("EI: 466.7", "EI: 1e-300", "EI"),
                                             ("EA: 1.4e7", "EA: 1e-10", "EA")])
def test_a_stiffness_too_small_to_invert_is_refused_naming_the_field(compliant_text, old, new, field):
    with pytest.raises(nocdyn.Error, match=rf"\.{field}: must be .*\[1e-09, 1e\+15\]"):
        nocdyn.Robot.from_yaml(compliant_text.replace(old, new, 1))


def test_stiff_beams_give_the_rigid_links_frequencies(source_dir):
    text = (source_dir / "robots" / "3-rrr-elastic.yaml").read_text()
    import re
    rigid = nocdyn.Robot.from_yaml(re.sub(r", elastic: \{[^}]*\}", "", text)).natural_frequencies([0, 0, 0])
    for X in ("1e10", "1e13", "1e15"):
        stiff = nocdyn.Robot.from_yaml(re.sub(r"EA: [0-9.e]+, EI: [0-9.e]+", f"EA: {X}, EI: {X}", text))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            f = stiff.natural_frequencies([0, 0, 0], model="elastodynamic")
        assert np.all(np.isfinite(f))
        np.testing.assert_allclose(f[:3], rigid, rtol=1e-6, err_msg=X)


def test_the_frequency_response_keeps_its_digits_at_very_low_frequency(compliant, source_dir):
    A, B, C, D = compliant.linearize(np.zeros(3), np.zeros(3), np.zeros(3), output="acceleration")
    Q, P = -A[3:, :3], B[3:]
    t = nocdyn.frequency_response(robot=source_dir / "robots" / "paper-3prr-compliant.yaml", min_frequency=1e-9,
                                  max_frequency=1e-1, points=9)
    for row in t.data:
        w = 2 * np.pi * row[0]
        H = -w ** 2 * np.linalg.solve(Q - w ** 2 * np.eye(3), P)
        for k, axis in enumerate("x y theta".split()):
            for a in range(3):
                got = row[t.columns.index(f"dd{axis}_uc{a + 1}_db")]
                assert abs(got - 20 * np.log10(abs(H[k, a]))) < 1e-6, (row[0], axis, a)


def test_a_frequency_below_the_response_range_is_refused_naming_min_frequency(source_dir):
    with pytest.raises(ValueError, match="^min_frequency: "):
        nocdyn.frequency_response(robot=source_dir / "robots" / "paper-3prr-compliant.yaml", min_frequency=1e-300)


def limitless_3rrr_elastic(source_dir):
    import re
    text = (source_dir / "robots" / "3-rrr-elastic.yaml").read_text()
    return re.sub(r"limits: \{[^}]*\}", "limits: {}", text).replace(",\n         limits: {}}", "}")


def next_to_the_reach_below_home(robot):
    """1e-9 m inside the reach boundary below home (bisection on y)."""
    lo, hi = 0.0, 0.2
    for _ in range(60):
        mid = (lo + hi) / 2
        try:
            robot.stiffness([0.0, -mid, 0.0])
            lo = mid
        except nocdyn.Error:
            hi = mid
    return [0.0, -(lo - 1e-9), 0.0]


def test_next_to_a_limb_singularity_the_lumped_model_warns_that_it_does_not_hold(source_dir):
    robot = nocdyn.Robot.from_yaml(limitless_3rrr_elastic(source_dir))
    with pytest.warns(RuntimeWarning, match="lumped model does not hold at this pose"):
        robot.natural_frequencies(next_to_the_reach_below_home(robot))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        robot.natural_frequencies([0.0, 0.0, 0.0])  # at home the two agree: no warning


def test_where_the_lumped_model_does_not_hold_the_default_is_the_elastodynamic_model(source_dir, tmp_path):
    text = limitless_3rrr_elastic(source_dir)
    robot = nocdyn.Robot.from_yaml(text)
    p = next_to_the_reach_below_home(robot)
    with pytest.warns(RuntimeWarning, match="the elastodynamic frequencies are used here"):
        elastic = robot.natural_frequencies(p, model="elastodynamic")
    with pytest.warns(RuntimeWarning, match="the elastodynamic frequencies are the ones to use here"):
        lumped = robot.natural_frequencies(p, model="lumped")
    with pytest.warns(RuntimeWarning, match=r"does not hold at this pose: its first natural frequency 9\.80\d Hz "
                                            r"against the elastodynamic model's 29\.9\d* Hz .* the elastodynamic "
                                            r"frequencies are used here"):
        default, shapes = robot.natural_frequencies(p, modes=True)
    # the lumped f_1 collapses to a third of the elastodynamic one (documented numbers)
    assert lumped[0] == pytest.approx(9.805, rel=1e-3)
    assert elastic[0] == pytest.approx(29.905, rel=1e-3)
    assert lumped[0] / elastic[0] == pytest.approx(0.328, abs=1e-3)
    # the default answer is the elastodynamic model's, as many as the lumped model gives: its
    # 3 lowest frequencies and their platform shapes
    assert len(elastic) > 3
    assert len(default) == len(lumped) == 3
    np.testing.assert_array_equal(default, elastic[:3])
    assert shapes.shape == (3, 3)
    with pytest.warns(RuntimeWarning):
        _, elastic_shapes = robot.natural_frequencies(p, model="elastodynamic", modes=True)
    np.testing.assert_array_equal(shapes, elastic_shapes[:, :3])
    assert abs(default[0] / elastic[0] - 1) < 0.05
    # `nocdyn pose` names the first frequency it uses and its model, beside the lumped three
    path = tmp_path / "3-rrr-elastic-limitless.yaml"
    path.write_text(text)
    with pytest.warns(RuntimeWarning, match="the elastodynamic frequencies are used here"):
        report = nocdyn.pose(*p, robot=path)
    assert report.first_frequency_model == "elastodynamic"
    assert report.first_frequency == pytest.approx(elastic[0], rel=1e-12)
    assert report.natural_frequencies[0] == pytest.approx(lumped[0], rel=1e-12)
    # at home the lumped model holds (0.01 % from the elastodynamic one) and stays the default
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        home = robot.natural_frequencies([0.0, 0.0, 0.0])
        home_elastic = robot.natural_frequencies([0.0, 0.0, 0.0], model="elastodynamic")
        np.testing.assert_array_equal(home, robot.natural_frequencies([0.0, 0.0, 0.0], model="lumped"))
        report = nocdyn.pose(0.0, 0.0, 0.0, robot=path)
    assert len(home) == 3
    assert abs(home[0] / home_elastic[0] - 1) < 0.05
    assert report.first_frequency_model == "lumped"
    assert report.first_frequency == pytest.approx(home[0], rel=1e-12)


@pytest.mark.parametrize("call, name", [
    (lambda: nocdyn.shake("x.AT2", threads=-1), "threads"),
    (lambda: nocdyn.frequency_response(points=2 ** 31), "points"),
    (lambda: nocdyn.frequency_response(pose="abc"), "pose"),
    (lambda: nocdyn.frequency_response(pose=0.0), "pose"),
    (lambda: nocdyn.frequency_response(pose=[0.0, "a", 0.0]), r"pose\[1\]"),
    (lambda: nocdyn.frequency_response(rate=np.zeros((1, 3))), "rate"),
    (lambda: nocdyn.frequency_response(min_frequency="abc"), "min_frequency"),
])
def test_a_wrong_argument_is_named_with_what_it_takes(call, name):
    with pytest.raises(ValueError, match=f"^{name}: ") as e:
        call()
    assert "got int" not in str(e.value) and "could not convert" not in str(e.value)


def test_design_refuses_the_dict_form_of_vary_with_the_strings_it_means(compliant_text, tmp_path):
    family = tmp_path / "fam.yaml"
    family.write_text(compliant_text.replace("max_condition: 10000", "parameters:\n  k: 2.0e5\nmax_condition: 10000")
                      .replace("stiffness: 2.0e5", "stiffness: k"))
    with pytest.raises(ValueError, match=r"^vary: a dict .*\['k=100000.0:200000.0'\]") as e:
        nocdyn.design({"k": (1e5, 2e5)}, ["moving_mass"], robot=family, samples=2)
    designs = nocdyn.design(eval(str(e.value).split("vary=")[1]), ["moving_mass"], robot=family, samples=2)
    assert len(designs) == 2
    with pytest.raises(ValueError, match=r"^vary\['k'\]"):
        nocdyn.design({"k": (1e5, "x")}, ["moving_mass"], robot=family, samples=2)


def test_a_byte_swapped_batch_is_copied_and_gives_the_native_numbers(compliant):
    P = np.zeros((2, 3))
    P[:, 1] = [0.001, -0.002]
    native = compliant.inverse_dynamics_derivatives(P, P, P)
    swapped = compliant.inverse_dynamics_derivatives(*(P.astype(">f8"),) * 3)
    for a, b in zip(native, swapped):
        np.testing.assert_array_equal(a, b)


def test_the_closed_loop_refuses_frequencies_where_its_reference_swamps_it_and_holds_above():
    with pytest.raises(ValueError, match=r"^min_frequency: .*6e-05 Hz"):
        nocdyn.frequency_response(closed_loop=True, min_frequency=1e-7, max_frequency=1.0)
    t = nocdyn.frequency_response(closed_loop=True, min_frequency=1e-4, max_frequency=1e-2, points=7)
    for axis in ("x", "y", "theta"):
        # the loop follows a slow reference exactly: 0 dB
        assert np.max(np.abs(t.data[:, t.columns.index(f"{axis}_db")])) < 1e-4, axis


@pytest.mark.parametrize("method", ["inverse_dynamics", "inverse_dynamics_derivatives", "reactions"])
def test_ctrl_c_stops_a_long_batch_within_a_slice(paper_robot, method):
    N = 4_000_000  # seconds of work: the batch runs in slices of 65536 rows, Ctrl-C looked for between
    P = np.zeros((N, 3))
    P[:, 0] = 1e-3 * np.sin(np.arange(N) * 1e-5)
    late = interrupted_after(0.3, lambda: getattr(paper_robot, method)(P, P, P))
    assert late < 1.0


def test_a_batch_in_slices_names_its_first_failed_sample_in_the_whole_batch(paper_robot):
    N = 200_000
    P = np.zeros((N, 3))
    P[150_000, 0] = 10.0  # out of reach, in the third slice
    with pytest.raises(nocdyn.Error, match="^sample 150001: "):  # numbered from 1: row 150000
        paper_robot.inverse_dynamics(P, P, P)
    with pytest.raises(nocdyn.Error, match="^sample 150001: "):
        paper_robot.reactions(P, P, P)


def test_harmonics_and_family_values_that_are_not_numbers_are_named():
    with pytest.raises(nocdyn.Error, match=r"^x: a harmonic is"):
        nocdyn.Trajectory.harmonic(x=[("a", 1.0, 0.0)])
    with pytest.raises(nocdyn.Error, match=r"^offset: expected 3 numbers"):
        nocdyn.Trajectory.harmonic(offset=(0.0, "b", 0.0))
    from nocdyn import designs
    with pytest.raises(ValueError, match=r"^vary\['k'\] upper: expected a number"):
        designs.Family(text="name: x\n", vary={"k": (1.0, "z")})
    with pytest.raises(ValueError, match=r"^vary\['k'\]: expected \(LOWER, UPPER\)"):
        designs.Family(text="name: x\n", vary={"k": 1.0})
