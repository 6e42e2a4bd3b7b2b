"""Hostile input, fourth round, in Python: the same rules as the command line's
(tests/hostile_round4_cli_test.cpp). No output of a call replaces an input or another output;
an option that does not apply is refused, naming what it goes with; a payload is on the plant;
an unstable loop has no frequency response; the mode shapes have one layout."""
import inspect
import json

import numpy as np
import pytest

import nocdyn


@pytest.fixture
def compliant(source_dir, tmp_path):
    path = tmp_path / "r.yaml"
    path.write_text((source_dir / "robots" / "paper-3prr-compliant.yaml").read_text())
    return path


def test_no_output_replaces_an_input_or_another_output(compliant, tmp_path):
    original = compliant.read_text()
    with pytest.raises(ValueError, match="summary '.*r.yaml' is an input file \\(robot"):
        nocdyn.frequency_response(robot=compliant, points=3, summary=compliant)
    assert compliant.read_text() == original
    with pytest.raises(ValueError, match="summary '.*p.csv' is also written by output"):
        nocdyn.frequency_response(points=3, output=tmp_path / "p.csv", summary=tmp_path / "p.csv")
    with pytest.raises(ValueError, match="frequency_map '.*m.csv' is also written by output"):
        nocdyn.workspace(robot=compliant, resolution=11, output=tmp_path / "m.csv", frequency_map=tmp_path / "m")
    with pytest.raises(ValueError, match="frequency_map '.*f.png' is also written by figure"):
        nocdyn.workspace(robot=compliant, resolution=11, figure=tmp_path / "f", frequency_map=tmp_path / "f")
    with pytest.raises(ValueError, match="log '.*c.csv' is also written by output"):
        nocdyn.control("paper1", duration=0.002, plant="nocdyn-rk4", output=tmp_path / "c.csv",
                       log=tmp_path / "c.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.yaml"]


def test_controller_options_without_the_closed_loop_are_refused_and_the_payload_applies():
    with pytest.raises(ValueError, match="^controller_rate: does not apply to the plant: it goes with closed_loop$"):
        nocdyn.frequency_response(points=3, controller_rate=50000.0)
    with pytest.raises(ValueError, match="^natural_frequency: does not apply to the plant"):
        nocdyn.frequency_response(points=3, natural_frequency=100.0)
    with pytest.raises(ValueError, match="^output_kind: does not apply to the closed loop"):
        nocdyn.frequency_response(points=3, closed_loop=True, output_kind="actuators")
    # the rigid 3-PRR at rest: |ddx/tau1| scales as 1 / (platform and carried mass) along x
    plain = nocdyn.frequency_response(points=2, min_frequency=1.0, max_frequency=2.0, compliance="rigid")
    loaded = nocdyn.frequency_response(points=2, min_frequency=1.0, max_frequency=2.0, compliance="rigid",
                                       payload_mass=5.0)
    drop = plain.data[:, 1] - loaded.data[:, 1]
    assert np.all(drop > 1.0), drop
    assert "payload 5 kg at C" in loaded.text


def test_an_unstable_closed_loop_has_no_frequency_response():
    with pytest.raises(ValueError, match="^closed_loop: unstable closed loop \\(spectral radius"):
        nocdyn.frequency_response(closed_loop=True, natural_frequency=10000.0, min_frequency=0.1,
                                  max_frequency=4000.0, points=50)
    # the rates shake refuses are refused here
    with pytest.raises(ValueError, match="^controller_rate: 50 is outside \\[100, 1000000\\] Hz"):
        nocdyn.frequency_response(closed_loop=True, controller_rate=50.0, max_frequency=10.0)


def test_old_keyword_spellings_warn_and_mean_the_new_ones():
    # one name per concept across the commands (as on the command line): f_min, f_max and
    # frequency_response's payload, shake's encoder_noise and jobs go in the next release
    current = nocdyn.frequency_response(points=3, min_frequency=2.0, max_frequency=20.0, compliance="rigid",
                                        payload_mass=1.0)
    with pytest.warns(DeprecationWarning) as caught:
        old = nocdyn.frequency_response(points=3, f_min=2.0, f_max=20.0, compliance="rigid", payload=1.0)
    assert sorted(str(w.message) for w in caught) == [
        f"{old} is deprecated and will be removed in the next release: use {new}"
        for old, new in (("f_max", "max_frequency"), ("f_min", "min_frequency"), ("payload", "payload_mass"))]
    assert all(w.filename == __file__ for w in caught), [w.filename for w in caught]  # the caller's line
    np.testing.assert_array_equal(old.data, current.data)
    with pytest.raises(TypeError, match="^f_min is the old spelling of min_frequency: give min_frequency only$"):
        nocdyn.frequency_response(points=3, f_min=2.0, min_frequency=2.0)
    # shake's: the value is checked and refused under the new name
    with pytest.warns(DeprecationWarning, match="^jobs is deprecated"):
        with pytest.raises(ValueError, match="^threads: -1 is out of range"):
            nocdyn.shake("x.AT2", jobs=-1)
    with pytest.warns(DeprecationWarning, match="^encoder_noise is deprecated.*use noise_u$"):
        with pytest.raises(ValueError, match="^noise_u: 2 is outside"):
            nocdyn.shake("x.AT2", encoder_noise=2.0)
    assert "f_min" not in inspect.signature(nocdyn.frequency_response).parameters


def test_shake_options_that_do_not_apply_are_refused_naming_what_they_go_with(source_dir, tmp_path):
    record = str(source_dir / "data" / "elcentro_1940_ns.AT2")
    for option, message in [(dict(drive_model="exact"), "^drive_model: does not apply here: it goes with iterations"),
                            (dict(iteration_gain=0.5), "^iteration_gain: does not apply here"),
                            (dict(accuracy=1e-8), "^accuracy: does not apply here: it goes with plant simbody"),
                            (dict(noise_pose=1e-5), "^noise_pose: does not apply here: it goes with controller pose")]:
        with pytest.raises(ValueError, match=message):
            nocdyn.shake(record, plant="nocdyn-rk4", window=0.5, rate=1000.0, out_dir=tmp_path / "out", **option)
    assert not (tmp_path / "out").exists()


def test_pose_json_mode_shapes_are_the_columns_python_gives(compliant, cli):
    pose = [0.004, -0.003, 0.03]
    code, out, err = cli("pose", *pose, "--robot", compliant, "--json")
    assert code == 0, err
    report = json.loads(out)
    _, shapes = nocdyn.Robot.load(str(compliant)).natural_frequencies(pose, modes=True)
    np.testing.assert_allclose(np.array(report["mode_shapes"]), shapes, rtol=1e-9, atol=1e-12)
