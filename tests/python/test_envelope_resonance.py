"""The operating envelope's third bound, the first natural frequency, where the rigid model stops
holding: Robot.envelope gives it as nocdyn.envelope does, and `loads --envelope` leaves out the
envelope's motions at and above it (their limit is 'resonance') and says so."""

import numpy as np
import pytest
from conftest import SOURCE_DIR

import nocdyn

COMPLIANT = SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml"
RIGID = SOURCE_DIR / "robots" / "paper-3prr.yaml"
GENERAL = SOURCE_DIR / "robots" / "paper-3prr-general.yaml"  # the compliant one without its compliance


@pytest.fixture(scope="module")
def compliant():
    return nocdyn.Robot.load(COMPLIANT)


def test_robot_envelope_gives_the_first_natural_frequency_of_nocdyn_envelope(compliant):
    points = compliant.envelope(min_frequency=10.0, max_frequency=100.0, points=3)
    table = nocdyn.envelope(robot=COMPLIANT, min_frequency=10.0, max_frequency=100.0, points=3)
    f1 = points.first_natural_frequency
    assert f1 == table.first_natural_frequency
    assert f1 == pytest.approx(compliant.natural_frequencies(compliant.home)[0], rel=1e-12)
    assert 30.0 < f1 < 100.0  # the paper robot with its drive loops: near 41 Hz
    assert isinstance(points, list) and len(points) == 9
    for p in points:  # the limit is resonance exactly at and above it
        assert (p["limit"] == "resonance") == (p["frequency"] >= f1), p
    rigid = nocdyn.Robot.load(RIGID).envelope(min_frequency=10.0, max_frequency=100.0, points=3)
    assert rigid.first_natural_frequency is None and "compliance" in rigid.resonance_reason
    assert all(p["limit"] != "resonance" for p in rigid)


def test_envelope_loads_leave_out_the_motions_at_and_above_the_first_natural_frequency(compliant):
    f1 = compliant.envelope(min_frequency=10.0, max_frequency=10.0, points=1).first_natural_frequency
    # 10, 31.6 and 100 Hz per axis: 100 Hz is above f1 on each of the three axes
    table = nocdyn.loads(robot=COMPLIANT, envelope=True, min_frequency=10.0, max_frequency=100.0, points=3)
    assert f"left out: 3 envelope motions at or above the first natural frequency {f1:.6g} Hz" in table.text
    assert np.all(table["peak_force_frequency"] < f1)
    # the same loads as the envelope below f1 alone
    below = nocdyn.loads(robot=COMPLIANT, envelope=True, min_frequency=10.0, max_frequency=np.sqrt(1000.0), points=2)
    assert "left out" not in below.text
    np.testing.assert_allclose(table["peak_force"], below["peak_force"], rtol=1e-5)
    np.testing.assert_allclose(table["peak_force_frequency"], below["peak_force_frequency"], rtol=1e-9)
    # the rigid model's loads at 100 Hz (the same bodies without compliance) are larger than any
    # below f1: they were not merged
    above = nocdyn.loads(robot=GENERAL, envelope=True, min_frequency=100.0, max_frequency=100.0, points=1)
    assert above["peak_force"].max() > table["peak_force"].max()


def test_envelope_loads_entirely_above_the_first_natural_frequency_are_an_error(cli, tmp_path):
    with pytest.raises(nocdyn.Error, match="every envelope frequency is at or above the first natural frequency"):
        nocdyn.loads(robot=COMPLIANT, envelope=True, min_frequency=60.0, max_frequency=100.0, points=2)
    out = tmp_path / "loads.csv"
    code, stdout, stderr = cli("loads", "--envelope", "--robot", COMPLIANT, "--min-frequency", 60, "--max-frequency",
                               100, "--points", 2, "-o", out)
    assert code != 0 and "--min-frequency: " in stderr and "first natural frequency" in stderr, stderr
    assert len(stderr.strip().splitlines()) == 1
    assert not out.exists()
    code, stdout, stderr = cli("loads", "--envelope", "--robot", COMPLIANT, "--min-frequency", 10, "--max-frequency",
                               100, "--points", 3, "-o", out)
    assert code == 0, stderr
    assert "left out: 3 envelope motions" in stdout
