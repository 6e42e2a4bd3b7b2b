"""Hostile input, fourth round, in Python: the same rules as the command line's
(tests/hostile_round4_cli_test.cpp). No output of a call replaces an input or another output;
an option that does not apply is refused, naming what it goes with; a payload is on the plant;
an unstable loop has no frequency response; the mode shapes have one layout."""
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
    plain = nocdyn.frequency_response(points=2, f_min=1.0, f_max=2.0, compliance="rigid")
    loaded = nocdyn.frequency_response(points=2, f_min=1.0, f_max=2.0, compliance="rigid", payload=5.0)
    drop = plain.data[:, 1] - loaded.data[:, 1]
    assert np.all(drop > 1.0), drop
    assert "payload 5 kg at C" in loaded.text


def test_an_unstable_closed_loop_has_no_frequency_response():
    with pytest.raises(ValueError, match="^closed_loop: unstable closed loop \\(spectral radius"):
        nocdyn.frequency_response(closed_loop=True, natural_frequency=10000.0, f_min=0.1, f_max=4000.0, points=50)
    # the rates shake refuses are refused here
    with pytest.raises(ValueError, match="^controller_rate: 50 is outside \\[100, 1000000\\] Hz"):
        nocdyn.frequency_response(closed_loop=True, controller_rate=50.0, f_max=10.0)


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
