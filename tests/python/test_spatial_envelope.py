"""nocdyn.envelope of a spatial robot goes through the same function as a planar robot's: the
pose coordinates as the axis words, the command line's numbers, the hexapod's velocity bound
A = v / (2 pi f n_z) along z in closed form, and the resonance bound refused."""

import csv
import math
import os
import subprocess

import pytest
from conftest import SOURCE_DIR

import nocdyn

STEWART = SOURCE_DIR / "robots" / "stewart.yaml"


def test_a_hexapod_envelope_has_six_axes_and_the_command_lines_numbers(tmp_path):
    table = nocdyn.envelope(robot=STEWART, min_frequency=1.0, max_frequency=100.0, points=2)
    assert list(table["axis"]) == ["x", "x", "y", "y", "z", "z", "roll", "roll", "pitch", "pitch", "yaw", "yaw"]
    assert table.first_natural_frequency is None
    assert "spatial" in table.resonance_reason
    out = tmp_path / "envelope.csv"
    subprocess.run([os.environ.get("NOCDYN_CLI", "nocdyn"), "envelope", "--robot", str(STEWART), "--points", "2",
                    "--min-frequency", "1", "--max-frequency", "100", "--output", str(out), "--quiet"], check=True)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["amplitude"]) for r in rows] == pytest.approx(list(table["amplitude"]), rel=1e-12)
    assert [r["limit"] for r in rows] == list(table["limit"])


def test_along_z_at_a_few_hertz_the_legs_rate_binds_in_closed_form():
    # moving along z the six legs lengthen alike at the rate n_z dz/dt (n_z = 0.8816 the legs'
    # vertical share at home, cos of their tilt): the 0.5 m/s limit at the period's peak rate,
    # at home, gives A = 0.5 / (2 pi f n_z)
    f = 3.0
    table = nocdyn.envelope(robot=STEWART, min_frequency=f, max_frequency=f, points=1, relative_tolerance=1e-10)
    z = [i for i, axis in enumerate(table["axis"]) if axis == "z"][0]
    assert table["limit"][z] == "velocity"
    assert table["amplitude"][z] == pytest.approx(0.5 / (2.0 * math.pi * f * 0.8816140833962374), rel=1e-6)


def test_the_resonance_bound_is_refused_for_a_spatial_robot():
    with pytest.raises(nocdyn.Error, match="amplification: applies to planar robots only"):
        nocdyn.envelope(robot=STEWART, points=1, amplification=2.0)
