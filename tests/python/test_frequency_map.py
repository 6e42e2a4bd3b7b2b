"""The first natural frequency over the workspace in Python: nocdyn.workspace(first_frequency=True)
as a NumPy array, the command line's --frequency-map bit for bit, and the design metric
first_frequency_min (an Optuna objective) equal to the map's lowest value."""

import json
import threading

import numpy as np
import pytest

import nocdyn
from nocdyn import designs
from nocdyn.results import read_csv

RESOLUTION = 41


@pytest.fixture(scope="module")
def compliant(source_dir):
    return str(source_dir / "robots" / "paper-3prr-compliant.yaml")


@pytest.fixture(scope="module")
def compliant_family(source_dir, tmp_path_factory):
    """The 3-RRR family with a stiffness of 20 N m/rad at every actuated joint."""
    text = (source_dir / "examples" / "design_3rrr" / "family.yaml").read_text()
    assert text.count("actuated: true,") == 3
    path = tmp_path_factory.mktemp("family") / "family.yaml"
    path.write_text(text.replace("actuated: true,", "actuated: true, stiffness: 20.0,"))
    return path


def test_the_array_holds_every_feasible_point_and_its_minimum_is_reported(compliant):
    ws = nocdyn.workspace(robot=compliant, resolution=RESOLUTION, first_frequency=True)
    f = ws.first_frequency
    assert isinstance(f, np.ndarray) and f.shape == (RESOLUTION, RESOLUTION) and f.dtype == np.float64
    feasible = ws.cells == 0
    assert np.isfinite(f[feasible]).all() and np.isnan(f[~feasible]).all()
    assert ws.first_frequency_min == np.nanmin(f) and ws.first_frequency_max == np.nanmax(f)
    assert 35.0 < ws.first_frequency_min < ws.first_frequency_max < 45.0
    # where: the grid point (x, y) of the lowest value, at the map's theta (x, y, theta)
    ix, iy = np.unravel_index(np.nanargmin(f), f.shape)
    x, y, theta = ws.first_frequency_at
    grid_x = np.asarray(ws["x"]).reshape(RESOLUTION, RESOLUTION)
    grid_y = np.asarray(ws["y"]).reshape(RESOLUTION, RESOLUTION)
    assert (x, y, theta) == (grid_x[ix, iy], grid_y[ix, iy], 0.0)
    # the pose command at that point gives the same lowest natural frequency
    assert nocdyn.pose(x, y, theta, robot=compliant).natural_frequencies[0] == pytest.approx(
        ws.first_frequency_min, rel=1e-12)
    assert list(ws.frequency_table.columns) == ["x", "y", "first_frequency"]
    np.testing.assert_array_equal(ws.frequency_table["first_frequency"], f[feasible])
    assert "lowest" in ws.text and "Hz at (x, y)" in ws.text
    # without the option, no map
    assert nocdyn.workspace(robot=compliant, resolution=21).first_frequency is None


def test_the_command_lines_frequency_map_bit_for_bit(compliant, cli, tmp_path):
    code, out, err = cli("workspace", "--robot", compliant, "--resolution", RESOLUTION, "--frequency-map",
                         tmp_path / "cli", "--json")
    assert code == 0, err
    ws = nocdyn.workspace(robot=compliant, resolution=RESOLUTION, frequency_map=tmp_path / "py")
    for stem in ("cli", "py"):
        columns, data, _ = read_csv(tmp_path / f"{stem}.csv")
        assert columns == ["x", "y", "first_frequency"]
        np.testing.assert_array_equal(data, ws.frequency_table.data)
        assert (tmp_path / f"{stem}.png").stat().st_size > 1000 and (tmp_path / f"{stem}.svg").exists()
    summary = json.loads(out)["first_frequency"]
    assert summary["lowest"] == ws.first_frequency_min
    assert [summary["lowest_at"][k] for k in ("x", "y", "theta")] == list(ws.first_frequency_at)


def test_a_robot_without_compliance_is_refused(source_dir):
    with pytest.raises(nocdyn.Error, match="robot '3-rrr' .* declares no compliance"):
        nocdyn.workspace(robot=str(source_dir / "robots" / "3-rrr.yaml"), resolution=21, first_frequency=True)


def test_bad_values_name_the_argument(compliant):
    with pytest.raises(ValueError, match="^first_frequency: "):
        nocdyn.workspace(robot=compliant, resolution=21, first_frequency="yes")
    with pytest.raises(ValueError, match="^frequency_map: "):
        nocdyn.workspace(robot=compliant, resolution=21, frequency_map="")


def test_two_threads_map_at_once(compliant):
    results = [None, None]

    def run(k):
        results[k] = nocdyn.workspace(robot=compliant, resolution=31, first_frequency=True).first_frequency

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    np.testing.assert_array_equal(results[0], results[1])


def test_the_design_metric_is_the_maps_lowest(compliant_family, tmp_path):
    family = designs.Family(compliant_family, vary={"r_b": (0.18, 0.22)})
    points = [[0.19], [0.21]]
    table = designs.evaluate(family, points, ["first_frequency_min", "workspace_area"], resolution=RESOLUTION,
                             threads=1)
    assert table.feasible.all(), table.reason
    for k, point in enumerate(points):
        robot = tmp_path / f"design{k}.yaml"
        robot.write_text(family.convert(point))
        ws = nocdyn.workspace(robot=str(robot), resolution=RESOLUTION, first_frequency=True)
        assert table.values[k, 0] == ws.first_frequency_min > 0.0
        assert table.values[k, 1] == pytest.approx(ws.area, rel=1e-12)
        # set= applies: the family file with the parameter overridden is the same design
        by_set = nocdyn.workspace(robot=str(compliant_family), set={"r_b": point[0]}, resolution=RESOLUTION,
                                  first_frequency=True)
        assert by_set.first_frequency_min == ws.first_frequency_min
    assert table.values[0, 0] != table.values[1, 0]


def test_a_family_without_compliance_is_infeasible_with_the_reason(source_dir):
    family = designs.Family(source_dir / "examples" / "design_3rrr" / "family.yaml", vary={"r_b": (0.18, 0.22)})
    table = designs.evaluate(family, [[0.2]], ["first_frequency_min"], resolution=21, threads=1)
    assert not table.feasible[0] and np.isnan(table.values[0, 0])
    assert "declares no compliance" in table.reason[0] and "first_frequency_min" in table.reason[0]


def test_first_frequency_min_is_an_optuna_objective(compliant_family):
    pytest.importorskip("optuna")
    family = designs.Family(compliant_family, vary={"r_b": (0.18, 0.22)})
    study, table = designs.optimize(family, {"first_frequency_min": "maximize"}, n_trials=4, seed=2,
                                    resolution=21)
    assert len(table) == 4 and table.feasible.all()
    assert study.best_value == np.max(table.column("first_frequency_min")) > 0.0
