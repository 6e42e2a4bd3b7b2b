"""shake (and the other purpose commands moved onto the application layer) from Python: the
options struct takes every argument, set= reaches the robot, a bad value is refused naming its
argument, Ctrl-C (a KeyboardInterrupt from the progress callback) stops the replay and leaves no
file or folder behind, and two threads replay at once."""

import os
import pathlib
import tempfile
import threading

import numpy as np
import pytest

import nocdyn

from conftest import SOURCE_DIR

RECORD = SOURCE_DIR / "data" / "elcentro_1940_ns.AT2"
FAMILY = SOURCE_DIR / "examples" / "design_vibration_generator" / "family.yaml"
QUICK = dict(window=0.5, plant="nocdyn-rk4", rate=1000.0, progress=False)


def nocdyn_temporary_folders():
    return {p.name for p in pathlib.Path(tempfile.gettempdir()).glob("nocdyn-*")}


def test_shake_scores_are_percent_with_the_unit_in_their_name():
    r = nocdyn.shake(RECORD, **QUICK)
    ax = r.metrics["metrics"]["ax"]
    assert "rms_error" not in ax and "peak_error" not in ax
    # the score recomputed from the samples, in percent (the text prints the same number)
    error = r["ax_achieved"] - r["ax"]
    rms = 100 * np.sqrt(np.mean(error ** 2)) / np.sqrt(np.mean(r["ax"] ** 2))
    assert ax["rms_error_percent"] == pytest.approx(rms, rel=0.1)
    assert f"RMS error {ax['rms_error_percent']:.2f} %" in r.text
    assert r.metrics["pass_rms_error_percent"] == [ax["rms_error_percent"]]
    assert r.folder is None


def test_shake_set_reaches_the_robot_file():
    prototype = nocdyn.shake(RECORD, robot=FAMILY, **QUICK)
    tilted = nocdyn.shake(RECORD, robot=FAMILY, set={"psi": 0.2}, **QUICK)
    assert prototype.metrics["fitted_limit_use"] != tilted.metrics["fitted_limit_use"]
    with pytest.raises(ValueError, match="set"):
        nocdyn.shake(RECORD, set={"psi": 0.2}, **QUICK)  # the built-in prototype has no parameters


@pytest.mark.parametrize("option, message", [(dict(margin=2.0), "^margin: 2 is outside"),
                                             (dict(rate=float("nan")), "^rate: expected a finite"),
                                             (dict(controller="bang-bang"), "^controller: expected table or pose"),
                                             (dict(time_scale="0x10"), "^time_scale: expected auto"),
                                             (dict(iterations=21), "^iterations: 21 is outside"),
                                             (dict(threads=-1), "^threads: -1 is out of range: expected a non-negative integer"),
                                             (dict(max_peak_percent=-1.0), "^max_peak_percent: -1 is outside")])
def test_shake_refuses_a_bad_value_naming_its_argument(option, message, tmp_path):
    arguments = {**QUICK, **option}
    with pytest.raises(ValueError, match=message):
        nocdyn.shake(RECORD, out_dir=tmp_path / "out", **arguments)
    assert not (tmp_path / "out").exists()


def test_a_keyboard_interrupt_from_the_progress_callback_stops_shake_and_leaves_nothing(tmp_path):
    before = nocdyn_temporary_folders()
    calls = []

    def interrupt(done, total):
        calls.append(done)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nocdyn.shake(RECORD, window=2.0, plant="nocdyn-rk4", rate=10000.0, out_dir=tmp_path / "out",
                     progress=interrupt)
    assert len(calls) == 1, "the replay went on after the interrupt"
    assert 0.0 < calls[0] < 2.0
    assert not (tmp_path / "out").exists(), "a stopped replay wrote its folder"
    assert nocdyn_temporary_folders() <= before, "a temporary folder was left behind"


def test_two_threads_replay_at_once_with_the_numbers_of_one():
    alone = nocdyn.shake(RECORD, **QUICK)
    results = [None, None]

    def replay(k):
        results[k] = nocdyn.shake(RECORD, **QUICK)

    threads = [threading.Thread(target=replay, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        np.testing.assert_array_equal(r.data, alone.data)
        assert r.metrics == alone.metrics


# --- identify, excite, animate -------------------------------------------------------------------

SMALL = dict(evaluations=12, random_shapes=6, samples=48, check_samples=300, duration=0.4)


@pytest.fixture(scope="module")
def log(tmp_path_factory):
    path = tmp_path_factory.mktemp("identify") / "log.csv"
    nocdyn.control("paper1", duration=0.01, rate=2000.0, payload_mass=0.5, plant="nocdyn-rk4", log=path)
    return path


def test_identify_set_reaches_the_robot_and_bad_values_name_their_argument(log, tmp_path):
    own = nocdyn.identify(log, robot=FAMILY, holdout=0.0)
    # the family at its own values is the prototype: the same estimate
    assert own.payload["mass"] == pytest.approx(nocdyn.identify(log, holdout=0.0).payload["mass"], rel=1e-6)
    heavier_links = nocdyn.identify(log, robot=FAMILY, set={"l": 0.16}, holdout=0.0)
    assert heavier_links.payload != own.payload
    with pytest.raises(ValueError, match="^holdout: 2 is outside"):
        nocdyn.identify(log, holdout=2.0)
    with pytest.raises(ValueError, match="^base: give payload or base"):
        nocdyn.identify(log, payload=True, base=True, output=tmp_path / "x.yaml")
    assert not (tmp_path / "x.yaml").exists()


def test_identify_writes_only_where_asked(log, tmp_path):
    r = nocdyn.identify(log, holdout=0.0, output=tmp_path / "identified.yaml")
    assert (tmp_path / "identified.yaml").read_text() == r.robot_yaml
    assert sorted(p.name for p in tmp_path.iterdir()) == ["identified.yaml"]


def test_excite_set_applies_and_bad_values_name_their_argument():
    own = nocdyn.excite(robot=FAMILY, **SMALL)
    tilted = nocdyn.excite(robot=FAMILY, set={"psi": 0.2}, **SMALL)
    assert own.yaml != tilted.yaml
    with pytest.raises(ValueError, match="^harmonics: 2 is outside"):
        nocdyn.excite(harmonics=2, **SMALL)
    with pytest.raises(ValueError, match="^payload_guess: expected 4 numbers"):
        nocdyn.excite(payload_guess=(0.5, 0.0), **SMALL)


def test_a_keyboard_interrupt_from_the_progress_callback_stops_excite(tmp_path):
    calls = []

    def interrupt(done, total):
        calls.append((done, total))
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nocdyn.excite(output=tmp_path / "x.yaml", progress=interrupt, **SMALL)
    assert calls == [(0.0, 12.0)]
    assert not (tmp_path / "x.yaml").exists()


def test_two_threads_design_and_animate_at_once():
    alone = nocdyn.excite(**SMALL)
    page = nocdyn.animate("paper1", duration=0.005, rate=2000.0).html
    results = [None] * 4

    def run(k):
        results[k] = nocdyn.excite(**SMALL).yaml if k < 2 else nocdyn.animate("paper1", duration=0.005,
                                                                              rate=2000.0).html

    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [alone.yaml, alone.yaml, page, page]


def test_animate_set_applies_a_table_motion_plays_and_bad_values_name_their_argument(tmp_path):
    own = nocdyn.animate("paper1", robot=FAMILY, duration=0.005, rate=2000.0)
    tilted = nocdyn.animate("paper1", robot=FAMILY, set={"psi": 0.2}, duration=0.005, rate=2000.0)
    assert own.html != tilted.html and own.path is None
    samples = nocdyn.inverse_dynamics("paper1", duration=0.005, rate=2000.0, progress=False)
    from_table = nocdyn.animate(motion=samples)
    assert "<canvas" in from_table.html
    with pytest.raises(ValueError, match="^magnify: -1 is outside"):
        nocdyn.animate("paper1", magnify=-1.0)
    with pytest.raises(ValueError, match="^frame: needs png or svg"):
        nocdyn.animate("paper1", frame=0.0, duration=0.005)
    with pytest.raises(ValueError, match="^trajectory: give a trajectory or a motion"):
        nocdyn.animate()
    assert list(tmp_path.iterdir()) == []
