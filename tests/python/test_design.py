"""nocdyn.designs: parametric families, Sobol and Latin-hypercube sweeps, a Dask cluster of
worker processes giving the serial table row for row, and the seeded optimiser."""

import numpy as np
import pytest

import nocdyn
from nocdyn import designs

# small workspace grids keep each design to a few milliseconds
OPTIONS = dict(resolution=21)
METRICS = ["workspace_area", "envelope_x@50", "moving_mass"]


@pytest.fixture(scope="module")
def family(source_dir):
    return designs.Family(source_dir / "examples" / "design_3rrr" / "family.yaml",
                         vary={"r_b": (0.15, 0.25), "l1": (0.08, 0.14)}, fixed={"l2": 0.11})


def same_rows(a, b):
    assert a.names == b.names and a.metrics == b.metrics
    assert np.array_equal(a.points, b.points)
    assert np.array_equal(a.values, b.values, equal_nan=True)
    assert np.array_equal(a.feasible, b.feasible)
    assert a.reason == b.reason


def test_a_family_at_its_values_is_the_example_robot(source_dir):
    fam = designs.Family(source_dir / "examples" / "design_3rrr" / "family.yaml", vary={"r_b": (0.1, 0.3)})
    robot = fam.robot([0.2])
    assert (robot.limbs, robot.actuators) == (3, 3)
    assert dict(fam.parameters([0.25]))["rho"] == pytest.approx(0.25 - (0.25 - 0.0635) / 2)


def test_convert_is_the_command_lines_convert_set(family, source_dir, cli):
    code, out, err = cli("convert", source_dir / "examples" / "design_3rrr" / "family.yaml", "--set", "r_b=0.21",
                         "--set", "l1=0.1", "--set", "l2=0.11")
    assert code == 0, err
    assert out.split("\n", 1)[1] == family.convert([0.21, 0.1])


def test_an_undeclared_parameter_is_named(source_dir):
    with pytest.raises(nocdyn.Error, match="varied parameter 'nope' is not declared"):
        designs.Family(source_dir / "examples" / "design_3rrr" / "family.yaml", vary={"nope": (0, 1)})


def test_sobol_and_latin_hypercube_samples_are_seeded_and_in_range(family):
    for method in ("sobol", "lhs", "random", "grid"):
        a = designs.sample(family, 16, method, seed=4)
        assert a.shape == (16, 2)
        assert np.array_equal(a, designs.sample(family, 16, method, seed=4))
        assert (a[:, 0] >= 0.15).all() and (a[:, 0] <= 0.25).all()
    lhs = designs.sample(family, 8, "lhs", seed=1)
    # one point in each eighth of every range
    assert sorted(np.floor((lhs[:, 1] - 0.08) / 0.06 * 8).astype(int)) == list(range(8))
    with pytest.raises(nocdyn.Error, match="samples"):
        designs.sample(family, 2_000_000, "random")


def test_a_dask_cluster_of_two_worker_processes_gives_the_serial_table_row_for_row(family):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        table = designs.sweep(family, METRICS, samples=8, method="sobol", seed=2, client=client, chunk=3, **OPTIONS)
    serial = designs.evaluate(family, designs.sample(family, 8, "sobol", seed=2), METRICS, threads=1, **OPTIONS)
    assert len(table) == 8 and table.feasible.sum() >= 6
    same_rows(table, serial)


def test_the_optimiser_is_seeded_and_keeps_every_trial(family):
    runs = [designs.optimize(family, {"workspace_area": "maximize"}, n_trials=6, seed=5,
                            constraints={"moving_mass": (None, 10.0)}, **OPTIONS) for _ in range(2)]
    (study, table), (_, again) = runs
    same_rows(table, again)
    assert len(table) == 6 and table.metrics == ["workspace_area", "moving_mass"]
    assert study.best_value == pytest.approx(np.nanmax(table.column("workspace_area")))


def test_the_table_is_written_in_the_command_lines_layout(family, tmp_path):
    table = designs.evaluate(family, [[0.2, 0.105], [0.2, 0.02]], ["workspace_area"], **OPTIONS)
    table.to_csv(tmp_path / "designs.csv")
    lines = (tmp_path / "designs.csv").read_text().splitlines()
    assert lines[0] == "design,r_b,l1,workspace_area,feasible,reason"
    assert lines[1].endswith(",true,")
    assert ",false," in lines[2] and "not finite" in lines[2]
    assert designs.pareto_front(table) == [0]


def test_designs_are_numbered_from_1_where_a_person_reads_them(tmp_path):
    """designs.csv's design column and Designs.rows() count from 1 (row k of the arrays is design
    k + 1), as `nocdyn design` writes it."""
    table = designs.Designs(["r_b"], ["moving_mass"], [[0.15], [0.2]], [[1.0], [2.0]], [True, False], ["", "x"])
    assert [row["design"] for row in table.rows()] == [1, 2]
    table.to_csv(tmp_path / "designs.csv")
    lines = (tmp_path / "designs.csv").read_text().splitlines()
    assert lines[0].startswith("design,r_b,moving_mass") and lines[1].startswith("1,0.15,1.0,true")
    assert lines[2].startswith("2,0.2,2.0,false")


def test_the_front_is_the_one_the_command_line_writes_to_pareto_csv(source_dir, cli, tmp_path):
    """pareto_front is the library's, so a table read back from designs.csv has the command
    line's pareto.csv as its front, design for design."""
    import csv
    metrics = ["workspace_area", "condition_median", "moving_mass"]
    args = ["design", "--robot", source_dir / "examples" / "design_3rrr" / "family.yaml", "--vary", "r_b=0.15:0.25",
            "--vary", "l1=0.08:0.14", "--set", "l2=0.11", "--samples", "40", "--seed", "2", "--resolution", "21",
            "--no-figures", "--out-dir", tmp_path / "o"]
    for m in metrics:
        args += ["--metric", m]
    code, _, err = cli(*args)
    assert code == 0, err
    rows = list(csv.DictReader((tmp_path / "o" / "designs.csv").open()))
    points = np.array([[float(r[k]) for k in ("r_b", "l1")] for r in rows])
    values = np.array([[float(r[m]) if r[m] else np.nan for m in metrics] for r in rows])
    table = designs.Designs(["r_b", "l1"], metrics, points, values, [r["feasible"] == "true" for r in rows],
                            [r["reason"] for r in rows])
    written = [int(r["design"]) - 1 for r in csv.DictReader((tmp_path / "o" / "pareto.csv").open())]
    assert 2 <= len(written) < table.feasible.sum()
    assert designs.pareto_front(table) == written
    # two metrics: the first two's front, from every design compared with every other
    two = designs.Designs(table.names, metrics[:2], points, values[:, :2], table.feasible, table.reason)
    s = values[:, :2] * [1.0, -1.0]
    brute = [i for i in np.flatnonzero(table.feasible)
             if not any(np.all(s[j] >= s[i]) and np.any(s[j] > s[i]) for j in np.flatnonzero(table.feasible))]
    assert designs.pareto_front(two) == brute


def test_the_design_of_the_largest_first_metric_is_on_the_front_whatever_its_second():
    # an infinite mass is the worst mass, but no design has as large a workspace: undominated
    table = designs.Designs(["r_b"], ["workspace_area", "moving_mass"], [[0.1], [0.2], [0.3]],
                            [[2.0, np.inf], [1.0, 1.0], [0.5, 1.0]], [True] * 3, [""] * 3)
    assert designs.pareto_front(table) == [0, 1]
    assert designs.pareto_front(table, {"moving_mass": "maximize"}) == [0]
