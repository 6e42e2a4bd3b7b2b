"""The operating envelope's third bound, where the rigid model stops holding (per axis, where the
damped lumped model's dynamic amplification leaves [1/A, A], below the first natural frequency):
Robot.envelope gives it as nocdyn.envelope does, and `loads --envelope` leaves out the envelope's
motions beyond it (their limit is 'resonance') and says so."""

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


def test_the_envelope_gives_the_first_natural_frequency_and_each_axis_band_end(compliant):
    table = nocdyn.envelope(robot=COMPLIANT, min_frequency=10.0, max_frequency=100.0, points=3)
    f1 = table.first_natural_frequency
    assert f1 == nocdyn.envelope(robot=compliant, min_frequency=10.0, max_frequency=100.0,
                                 points=3).first_natural_frequency
    assert f1 == pytest.approx(compliant.natural_frequencies(compliant.home)[0], rel=1e-12)
    assert 30.0 < f1 < 100.0  # the paper robot with its drive loops: near 41 Hz
    assert len(table) == 9
    # the band ends at f_1 / sqrt(11) along x and y (|H| = 1 / (1 - r^2) = 1.1), at 13.6 Hz about
    # theta (its mode is at 45.2 Hz), and the limit is resonance exactly at and above it
    assert table.band_end["x"] == pytest.approx(f1 / np.sqrt(11.0), rel=1e-3)
    assert 13.0 < table.band_end["theta"] < 14.0
    for axis, limit, frequency in zip(table["axis"], table["limit"], table["frequency"]):
        assert (limit == "resonance") == (frequency >= table.band_end[axis]), (axis, limit, frequency)
    wide = nocdyn.envelope(robot=COMPLIANT, min_frequency=10.0, max_frequency=100.0, points=3, amplification=3.0)
    assert f1 / np.sqrt(3.0) < wide.band_end["x"] < f1  # 1 / (1 - r^2) = 3 at r^2 = 2/3, 2 % damped
    rigid = nocdyn.envelope(robot=RIGID, min_frequency=10.0, max_frequency=100.0, points=3)
    assert rigid.first_natural_frequency is None and rigid.band_end is None
    assert "compliance" in rigid.resonance_reason
    assert all(limit != "resonance" for limit in rigid["limit"])


def test_envelope_loads_leave_out_the_motions_at_and_above_the_first_natural_frequency(compliant):
    f1 = nocdyn.envelope(robot=compliant, min_frequency=10.0, max_frequency=10.0, points=1).first_natural_frequency
    # 10, 31.6 and 100 Hz per axis: 31.6 and 100 Hz are beyond the band (12.4 Hz along x and y,
    # 13.6 Hz about theta) on each of the three axes
    table = nocdyn.loads(robot=COMPLIANT, envelope=True, min_frequency=10.0, max_frequency=100.0, points=3)
    assert ("left out: 6 envelope motions beyond the band's third bound (limit resonance: the dynamic amplification "
            f"leaves [1/1.1, 1.1]; first natural frequency {f1:.6g} Hz)") in table.text
    assert np.all(table["peak_force_frequency"] < f1)
    # the same loads as the envelope within the band alone
    below = nocdyn.loads(robot=COMPLIANT, envelope=True, min_frequency=10.0, max_frequency=10.0, points=1)
    assert "left out" not in below.text
    np.testing.assert_allclose(table["peak_force"], below["peak_force"], rtol=1e-5)
    np.testing.assert_allclose(table["peak_force_frequency"], below["peak_force_frequency"], rtol=1e-9)
    # the rigid model's loads at 100 Hz (the same bodies without compliance) are larger than any
    # within the band: they were not merged
    above = nocdyn.loads(robot=GENERAL, envelope=True, min_frequency=100.0, max_frequency=100.0, points=1)
    assert above["peak_force"].max() > table["peak_force"].max()


def test_envelope_loads_entirely_above_the_first_natural_frequency_are_an_error(cli, tmp_path):
    with pytest.raises(nocdyn.Error, match="every envelope frequency is beyond the band's third bound"):
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
    assert "left out: 6 envelope motions" in stdout
