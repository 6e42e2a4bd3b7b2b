"""nocdyn.shake(records=[...], iterations=...) on a six-DOF table (robots/stewart.yaml): the
drive iterated on x, y, z, the pass kept lowering every axis's RMS error below the first pass's,
its samples' error the kept pass's; the tolerance taken; a planar drive model refused naming it."""

import numpy as np
import pytest

import nocdyn

from conftest import SOURCE_DIR

ROBOT = SOURCE_DIR / "robots" / "stewart.yaml"
STEM = SOURCE_DIR / "data" / "records3" / "RSN6_IMPVALL.I_I-ELC"
COMPONENTS = [f"{STEM}180-hor1.AT2", f"{STEM}270-hor2.AT2", f"{STEM}-UP.AT2"]
QUICK = dict(window=2.0, progress=False)


def test_the_iterated_drive_lowers_every_axiss_error():
    r = nocdyn.shake(records=COMPONENTS, robot=ROBOT, iterations=2, **QUICK)
    m = r.metrics
    kept = m["pass_kept"]
    assert kept >= 1
    assert len(m["pass_rms_error_percent"]) >= 2
    assert m["iteration_stop"]
    for axis in ("ax", "ay", "az"):
        passes = m["pass_rms_error_percent_axes"][axis]
        assert passes[kept] < passes[0]
        assert m["metrics"][axis]["rms_error_percent"] == pytest.approx(passes[kept], rel=1e-12)
        # the samples returned are the kept pass's
        error = r[f"{axis}_achieved"] - r[axis]
        rms = 100 * np.sqrt(np.mean(error ** 2)) / np.sqrt(np.mean(r[axis] ** 2))
        assert rms == pytest.approx(passes[kept], rel=0.1)
    assert f"pass {kept} kept" in r.text


def test_the_tolerance_stops_the_iteration_and_a_planar_drive_model_is_refused():
    r = nocdyn.shake(records=COMPONENTS, robot=ROBOT, iterations=3, iteration_tolerance=0.9, **QUICK)
    assert len(r.metrics["pass_rms_error_percent"]) == 2
    assert r.metrics["iteration_stop"] == "pass 1 improved the RMS error by less than 90 %"
    with pytest.raises(ValueError, match="drive_model"):
        nocdyn.shake(records=COMPONENTS, robot=ROBOT, iterations=2, drive_model="exact", **QUICK)
