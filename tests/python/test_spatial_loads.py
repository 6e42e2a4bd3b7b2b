"""nocdyn.loads on a spatial robot (the same job as the command line's `loads`): the table of
the command line's CSV, each joint's type as a word, the envelope and a figure refused."""

import csv

import numpy as np
import pytest

import nocdyn


def test_a_spatial_robots_loads_are_the_command_lines_table(source_dir, tmp_path, cli):
    robot = str(source_dir / "robots" / "stewart.yaml")
    sway = str(source_dir / "trajectories" / "stewart-sway.yaml")
    table = nocdyn.loads(sway, robot=robot, duration=0.25, rate=200.0)
    coordinates = ["x", "y", "z", "roll", "pitch", "yaw"]
    assert table.columns == ["limb", "joint", "type", "peak_force", "peak_force_t",
                             *[f"peak_force_{c}" for c in coordinates], "rms_force", "peak_moment", "peak_moment_t"]
    assert list(table["limb"]) == [j for j in range(1, 7) for _ in range(3)]
    assert list(table["joint"]) == [1, 2, 3] * 6
    assert list(table["type"]) == ["U", "P", "S"] * 6
    assert "largest: limb " in table.text
    # the command line's CSV, number for number
    path = tmp_path / "loads.csv"
    code, _, err = cli("loads", "--robot", robot, "--trajectory", sway, "--duration", "0.25", "--rate", "200",
                       "--output", path)
    assert code == 0, err
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == table.columns
    numbers = [i for i, c in enumerate(table.columns) if c != "type"]
    written = np.array([[float(row[i]) for i in numbers] for row in rows[1:]])
    np.testing.assert_array_equal(written, table.data[:, numbers])
    assert [row[2] for row in rows[1:]] == list(table["type"])
    # the legs' S joints carry the table: every one at least a sixth of its 300 kg weight
    s = table.data[2::3, table.columns.index("peak_force")]
    assert np.all(s > 300.0 * 9.81 / 6.0) and np.all(np.isfinite(table.data[:, numbers]))


def test_a_still_pose_gives_each_joint_a_constant_load_and_the_envelope_is_refused(source_dir, tmp_path):
    robot = str(source_dir / "robots" / "stewart.yaml")
    still = tmp_path / "still.yaml"
    still.write_text("name: still\nx: {offset: 0.0}\ny: {offset: 0.0}\nz: {offset: 1.06}\n"
                     "roll: {offset: 0.01}\npitch: {offset: 0.0}\nyaw: {offset: 0.0}\n")
    table = nocdyn.loads(str(still), robot=robot, duration=0.05, rate=100.0)
    peak, rms = table["peak_force"], table["rms_force"]
    np.testing.assert_allclose(rms, peak, rtol=1e-12)
    assert np.all(peak[2::3] > 0.0)
    with pytest.raises(ValueError, match="^envelope: .*spatial"):
        nocdyn.loads(robot=robot, envelope=True)
    with pytest.raises(ValueError, match="^figure: .*planar robots only"):
        nocdyn.loads(str(still), robot=robot, duration=0.05, rate=100.0, figure=str(tmp_path / "f"))
    assert not (tmp_path / "f.png").exists()
