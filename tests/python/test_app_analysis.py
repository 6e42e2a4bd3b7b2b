"""The analysis commands on the application layer (envelope, workspace, loads, regressor, convert,
design): options from the struct (set= applies, a bad value names its argument), two threads at
once, 1-based integer numbering of limbs, joints and actuators, and a design sweep that a
KeyboardInterrupt (from the progress callback or Ctrl-C) stops with no temporary folder left."""

import os
import signal
import tempfile
import threading
import time

import numpy as np
import pytest

import nocdyn

from conftest import SOURCE_DIR

ROBOT = str(SOURCE_DIR / "robots" / "3-rrr.yaml")
FAMILY = str(SOURCE_DIR / "examples" / "design_3rrr" / "family.yaml")
SMALL_ENVELOPE = dict(points=2, min_frequency=5.0, max_frequency=50.0)
COMPLIANT = str(SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml")


def temporary_folders():
    return {p for p in os.listdir(tempfile.gettempdir()) if p.startswith("nocdyn-")}


def in_two_threads(function):
    """function() in two threads at once: both answers, or the first exception."""
    answers, errors = [None, None], []

    def run(k):
        try:
            answers[k] = function()
        except Exception as error:  # noqa: BLE001 - handed to the test
            errors.append(error)
    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise errors[0]
    return answers


def test_envelope_numbers_limbs_joints_and_actuators_from_one_as_integers():
    table = nocdyn.envelope(robot=ROBOT, **SMALL_ENVELOPE)
    assert len(table) == 6 and list(table["axis"]) == ["x"] * 2 + ["y"] * 2 + ["theta"] * 2
    for column in ("limb", "joint", "actuator"):
        assert table[column].dtype == np.int64 and table[column].min() >= 0
        assert str(table.to_pandas()[column].dtype) == "int64"
    bound = table["limit"] != "none"
    assert np.all(table["limb"][bound] >= 1) and np.all(table["limb"][bound] <= 3)
    assert np.all(table["amplitude"] > 0.0)


def test_envelope_returns_the_first_natural_frequency_at_home_and_resonance_from_it():
    f1 = float(nocdyn.pose(0.0, 0.0, 0.0, robot=COMPLIANT).natural_frequencies[0])  # the lumped model at home
    assert f1 > 0.0
    # with amplification 1.5 the band of each axis ends between f_1 / 2 (|H| = 1.33 along x) and f_1
    table = nocdyn.envelope(robot=COMPLIANT, points=3, min_frequency=0.5 * f1, max_frequency=2.0 * f1,
                            amplification=1.5)
    assert isinstance(table, nocdyn.Envelope)
    assert table.first_natural_frequency == f1
    assert f"first natural frequency {f1:.6g} Hz" in table.text
    np.testing.assert_array_equal(table["first_natural_frequency"], np.full(9, f1))
    assert list(table["axis"]) == ["x"] * 3 + ["y"] * 3 + ["theta"] * 3
    beyond = table["frequency"] >= f1
    assert list(beyond) == [False, True, True] * 3
    assert np.all((table["limit"] == "resonance") == beyond)
    assert np.all(table["actuator"][beyond] == 0) and np.all(table["actuator"][~beyond] >= 1)


def test_envelope_without_compliance_has_no_third_bound_and_says_why():
    table = nocdyn.envelope(robot=ROBOT, **SMALL_ENVELOPE)
    assert table.first_natural_frequency is None
    assert "first_natural_frequency" not in table
    assert "resonance" not in set(table["limit"])
    assert table.text.startswith("third bound (first natural frequency): unknown, the robot file declares no "
                                 "compliance") and "docs/robot-files.md" in table.text


def test_envelope_set_bad_values_and_two_threads():
    family = nocdyn.envelope(robot=FAMILY, points=1, min_frequency=50.0, max_frequency=50.0)
    wider = nocdyn.envelope(robot=FAMILY, set={"r_b": 0.25}, points=1, min_frequency=50.0, max_frequency=50.0)
    assert not np.array_equal(family["amplitude"], wider["amplitude"])
    with pytest.raises(ValueError, match="^max_frequency: "):
        nocdyn.envelope(min_frequency=50.0, max_frequency=10.0)
    with pytest.raises(ValueError, match="^points: "):
        nocdyn.envelope(points=0)
    with pytest.raises(ValueError, match="^min_frequency: "):
        nocdyn.envelope(min_frequency=float("nan"))
    a, b = in_two_threads(lambda: nocdyn.envelope(robot=ROBOT, **SMALL_ENVELOPE))
    np.testing.assert_array_equal(a.data, b.data)


def test_workspace_set_bad_values_and_two_threads(tmp_path):
    ws = nocdyn.workspace(robot=FAMILY, resolution=21)
    larger = nocdyn.workspace(robot=FAMILY, set={"l1": 0.13}, resolution=21)
    assert larger.area > ws.area > 0.0
    with pytest.raises(ValueError, match="^resolution: "):
        nocdyn.workspace(resolution=5)
    with pytest.raises(ValueError, match="^theta: "):
        nocdyn.workspace(theta=1e4)
    with pytest.raises(ValueError, match="^set: "):
        nocdyn.workspace(set={"l1": 0.1})  # the built-in prototype has no parameters
    a, b = in_two_threads(lambda: nocdyn.workspace(robot=ROBOT, resolution=21))
    np.testing.assert_array_equal(a.data, b.data)
    assert a.text == b.text and a.cells.shape == (21, 21)
    # files only where asked, and then the command line's
    nocdyn.workspace(robot=ROBOT, resolution=21, output=tmp_path / "w.csv", figure=tmp_path / "w")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["w.csv", "w.png", "w.svg"]


def test_loads_integers_set_bad_values_and_two_threads():
    table = nocdyn.loads("paper1", duration=0.005, rate=2000.0)
    assert list(table["limb"]) == [1, 1, 1, 2, 2, 2, 3, 3, 3] and table["limb"].dtype == np.int64
    assert list(table["joint"]) == [1, 2, 3] * 3 and table["joint"].dtype == np.int64
    assert "largest: limb" in table.text
    heavier = nocdyn.loads("paper1", robot=FAMILY, set={"r_b": 0.25}, duration=0.005, rate=2000.0)
    lighter = nocdyn.loads("paper1", robot=FAMILY, duration=0.005, rate=2000.0)
    assert not np.array_equal(heavier["peak_force"], lighter["peak_force"])
    with pytest.raises(ValueError, match="^trajectory: "):
        nocdyn.loads()
    with pytest.raises(ValueError, match="^rate: "):
        nocdyn.loads("paper1", rate=0.0)
    with pytest.raises(ValueError, match="^trajectory: "):
        nocdyn.loads("paper1", envelope=True)
    a, b = in_two_threads(lambda: nocdyn.loads("paper1", duration=0.005, rate=2000.0))
    np.testing.assert_array_equal(a.data, b.data)


def test_regressor_set_bad_values_and_two_threads():
    assert nocdyn.regressor(robot=FAMILY, set={"l1": 0.12}, samples=40) != nocdyn.regressor(robot=FAMILY, samples=40)
    with pytest.raises(ValueError, match="^samples: "):
        nocdyn.regressor(samples=5)
    a, b = in_two_threads(lambda: nocdyn.regressor(robot=ROBOT, samples=40))
    assert a == b and a.startswith("# standard parameters")


def test_convert_set_bad_values_and_two_threads(tmp_path):
    assert nocdyn.convert(FAMILY, set={"l1": 0.12}) != nocdyn.convert(FAMILY)
    with pytest.raises(ValueError, match="^robot: "):
        nocdyn.convert(None)
    with pytest.raises(nocdyn.Error, match="parameter 'l1' is set but the file declares no parameters"):
        nocdyn.convert(ROBOT, set={"l1": 0.12})
    a, b = in_two_threads(lambda: nocdyn.convert(ROBOT))
    assert a == b and a.startswith("# ")
    nocdyn.convert(ROBOT, output=tmp_path / "robot.yaml")
    assert (tmp_path / "robot.yaml").read_text() == a


SWEEP = dict(robot=FAMILY, set={"l2": 0.11}, resolution=11, threads=2)


def test_design_without_out_dir_writes_nothing_and_equals_the_command_line(tmp_path):
    before = temporary_folders()
    designs = nocdyn.design(["r_b=0.15:0.25", "l1=0.08:0.14"], ["workspace_area", "moving_mass"], samples=6, seed=3,
                            no_figures=True, **SWEEP)
    assert len(designs) == 6 and designs.names == ["r_b", "l1"] and temporary_folders() == before
    kept = nocdyn.design(["r_b=0.15:0.25", "l1=0.08:0.14"], ["workspace_area", "moving_mass"], samples=6, seed=3,
                         no_figures=True, out_dir=tmp_path / "run", **SWEEP)
    np.testing.assert_array_equal(kept.values, designs.values)
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == ["designs.csv", "journal.csv", "pareto.csv"]
    with pytest.raises(ValueError, match="^vary: "):
        nocdyn.design("r_b=0.3:0.2", "moving_mass", **SWEEP)
    with pytest.raises(ValueError, match="^metric: "):
        nocdyn.design("r_b=0.1:0.2", "envelope_q@50", **SWEEP)
    with pytest.raises(ValueError, match="^threads: "):
        nocdyn.design("r_b=0.1:0.2", "moving_mass", robot=FAMILY, threads=-1)
    with pytest.raises(ValueError, match="^robot: "):
        nocdyn.design("r_b=0.1:0.2", "moving_mass")


def test_a_keyboard_interrupt_from_the_progress_callback_stops_a_design_sweep(tmp_path):
    before = temporary_folders()
    calls = []

    def progress(done, total):
        calls.append((done, total))
        if done >= 2:
            raise KeyboardInterrupt
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        nocdyn.design("r_b=0.15:0.25", "workspace_area", samples=400, out_dir=tmp_path / "run", progress=progress,
                      **SWEEP)
    # stopped once the designs under way finished: far from the 400
    assert calls[-1][0] < 10 and calls[-1][1] == 400 and time.monotonic() - started < 60
    assert temporary_folders() == before
    # the journal keeps what was done; no table of a sweep that did not finish
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == ["journal.csv"]
    lines = (tmp_path / "run" / "journal.csv").read_text().splitlines()
    assert 2 <= len(lines) - 2 < 10
    # and the same sweep resumes from it, with a warning saying so
    with pytest.warns(RuntimeWarning, match="resuming: "):
        nocdyn.design("r_b=0.15:0.25", "workspace_area", samples=6, out_dir=tmp_path / "other", **SWEEP)
        nocdyn.design("r_b=0.15:0.25", "workspace_area", samples=6, out_dir=tmp_path / "other", **SWEEP)


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals reach the main thread")
def test_ctrl_c_stops_a_design_sweep_and_leaves_no_temporary_folder():
    before = temporary_folders()
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            nocdyn.design("r_b=0.15:0.25", "workspace_area", samples=100000, **SWEEP)
    finally:
        timer.cancel()
    assert time.monotonic() - started < 30
    assert temporary_folders() == before
