"""nocdyn.shake on a six-DOF table (robots/stewart.yaml) with a three-component record: the
same samples and metrics as `nocdyn shake`, the components given as records=[...] in any order,
the metrics keyed ax, ay, az, and the table's x azimuth turned by 90 degrees giving x' = -y,
y' = x."""

import json

import numpy as np
import pytest

import nocdyn
from nocdyn.results import read_csv

from conftest import SOURCE_DIR

ROBOT = SOURCE_DIR / "robots" / "stewart.yaml"
STEM = SOURCE_DIR / "data" / "records3" / "RSN6_IMPVALL.I_I-ELC"
COMPONENTS = [f"{STEM}180-hor1.AT2", f"{STEM}270-hor2.AT2", f"{STEM}-UP.AT2"]
QUICK = dict(window=1.0, time_scale="1", rate=1000.0, progress=False)


def test_the_three_components_replay_as_the_command_does(cli, tmp_path):
    code, out, err = cli("shake", "--robot", ROBOT, "--record", COMPONENTS[2], "--record", COMPONENTS[0], "--record",
                         COMPONENTS[1], "--window", 1.0, "--time-scale", 1, "--rate", 1000, "--out-dir",
                         tmp_path / "cli")
    assert code == 0, err
    py = nocdyn.shake(records=COMPONENTS, robot=ROBOT, out_dir=tmp_path / "py", **QUICK)
    columns, data, _ = read_csv(tmp_path / "cli" / "shake.csv")
    assert columns == py.columns
    np.testing.assert_array_equal(data, py.data)
    assert py.metrics == json.loads((tmp_path / "cli" / "shake.json").read_text())
    assert set(py.metrics["metrics"]) == {"ax", "ay", "az"}
    for axis in ("ax", "ay", "az"):
        error = py[f"{axis}_achieved"] - py[axis]
        rms = 100 * np.sqrt(np.mean(error ** 2)) / np.sqrt(np.mean(py[axis] ** 2))
        assert py.metrics["metrics"][axis]["rms_error_percent"] == pytest.approx(rms, rel=0.1)
        assert rms < 5.0
    assert (tmp_path / "py" / "shake_spectrum.svg").exists()


def test_turning_the_tables_x_azimuth_by_90_degrees(tmp_path):
    base = nocdyn.shake(records=COMPONENTS, robot=ROBOT, **QUICK)
    turned = nocdyn.shake(records=COMPONENTS, robot=ROBOT, x_azimuth=270.0, **QUICK)
    assert turned.metrics["x_azimuth"] == 270.0
    np.testing.assert_allclose(turned["ax"], -base["ay"], atol=1e-12)
    np.testing.assert_allclose(turned["ay"], base["ax"], atol=1e-12)
    np.testing.assert_array_equal(turned["az"], base["az"])
    with pytest.raises(ValueError, match="record"):
        nocdyn.shake(COMPONENTS, records=COMPONENTS, robot=ROBOT, **QUICK)


def test_the_specimen_identified_first_comes_back_as_numbers():
    # a 40 kg specimen, a point mass at the platform origin: the 10 parameters and the mass,
    # c.o.m. and inertia with their standard deviations, the true values beside them
    run = nocdyn.shake(records=COMPONENTS, robot=ROBOT, identify_payload=True, payload_mass=40.0,
                       excitation_duration=1.0, **QUICK)
    e = run.metrics["payload_estimate"]
    assert e["true"]["mass"] == 40.0
    assert e["true"]["parameters"] == [40.0] + [0.0] * 9
    assert 0.0 < e["mass_sd"] < 1.0
    assert abs(e["mass"] - 40.0) < 5 * e["mass_sd"]
    for c, sd in zip(e["com"], e["com_sd"]):
        assert abs(c) < 5 * sd
    assert np.shape(e["inertia"]) == (3, 3) and np.shape(e["inertia_sd"]) == (3, 3)
    assert len(e["parameters"]) == len(e["parameters_sd"]) == len(e["parameter_names"]) == 10
    assert e["samples"] == 1000
    assert e["excitation_limit_use"]["ratio"] <= 1.0
    for axis in ("ax", "ay", "az"):
        assert run.metrics["metrics"][axis]["rms_error_percent"] < 5.0
