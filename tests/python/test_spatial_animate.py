"""nocdyn.animate on a spatial robot (the same job as the command line's `animate`): the 3-D page,
its forces those of nocdyn.inverse_dynamics, and the planar-only options refused."""

import json
import re

import numpy as np
import pytest

import nocdyn


def _data(html):
    found = re.search(r'<script type="application/json" id="nocdyn-data">(.*?)</script>', html, re.S)
    return json.loads(found.group(1))


def test_a_spatial_robots_page_is_drawn_in_3d_with_the_inverse_dynamics_forces(source_dir, tmp_path):
    robot = str(source_dir / "robots" / "delta.yaml")
    trajectory = str(source_dir / "trajectories" / "delta-pick.yaml")
    out = tmp_path / "delta.html"
    page = nocdyn.animate(trajectory, robot=robot, rate=200, duration=0.5, output=str(out))
    assert out.read_text(encoding="utf-8") == page.html
    assert "THREE" in page.html and "OrbitControls" in page.html
    data = _data(page.html)
    assert [limb["joints"] for limb in data["limbs"]] == ["RUU"] * 3
    table = nocdyn.inverse_dynamics(trajectory, robot=robot, rate=200, duration=0.5)
    rows = np.asarray(table.data)
    tau = rows[:, [table.columns.index(f"tau{a}") for a in (1, 2, 3)]]
    assert len(data["frames"]["t"]) == rows.shape[0] == 100
    assert np.allclose(np.asarray(data["frames"]["tau"]).reshape(-1, 3), tau, rtol=1e-12, atol=1e-12)
    assert np.ptp(tau) > 1.0  # the forces move


def test_planar_only_options_are_refused_for_a_spatial_robot(source_dir, tmp_path):
    robot = str(source_dir / "robots" / "stewart.yaml")
    trajectory = str(source_dir / "trajectories" / "stewart-sway.yaml")
    with pytest.raises(nocdyn.Error, match="frame.*planar"):
        nocdyn.animate(trajectory, robot=robot, frame=0.1, png=str(tmp_path / "f.png"))
    assert not (tmp_path / "f.png").exists()


def test_a_spatial_robot_object_is_refused_naming_the_path_it_takes(source_dir):
    robot = nocdyn.SpatialRobot.load(source_dir / "robots" / "delta.yaml")
    with pytest.raises(ValueError, match="spatial robot file's path"):
        nocdyn.animate(str(source_dir / "trajectories" / "delta-pick.yaml"), robot=robot)
