"""The command line and the Python package agree: every command has a Python function, with the
same options (snake_case) and defaults, and on the same input both give the same numbers.

The options are compared by introspection: `nocdyn --help-json` (every command's options and
defaults, as the command line defines them) against inspect.signature of nocdyn.<command>, so
that an option added on one side fails here until the other side has it. The numbers are
compared bit for bit: both run the same compiled command (nocdyn.commands).
"""

import inspect
import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import nocdyn
from nocdyn.results import read_csv

from conftest import SOURCE_DIR, skip_or_fail_in_ci

# The documented exceptions (docs/python-parity.md), kept short:
# options of the command line with no Python argument: the output format of the printed answer, or
# none (Python always gets the structured answer, and the printed text in .text)
CLI_ONLY = {("pose", "json"), ("forward-kinematics", "json"), ("workspace", "json")}
# the options every command has on the command line only: --quiet (Python prints nothing)
CLI_ONLY_EVERYWHERE = {"quiet"}
# Python arguments with no option: the progress callback of the long commands
PYTHON_ONLY = {"progress"}
# a command's own: shake's records, the list of one record's component files under another name
PYTHON_ONLY_OF = {"shake": {"records"}}
# positional arguments of the command line (upper case) and their Python names
POSITIONAL = {("pose", "X"): "x", ("pose", "Y"): "y", ("pose", "THETA"): "theta",
              ("pose", "ANGLES"): "angles", ("forward-kinematics", "U"): "u", ("convert", "ROBOT"): "robot"}
# defaults that depend on the build: the plant is Simbody's when built in, else nocdyn's; Python
# leaves the choice to the command (None)
BUILD_DEPENDENT = {("control", "plant")}
# the files a command writes: Python returns the answer and writes a file only when asked (None),
# or where the command line would (reproduce's out_dir)
OUTPUTS = {"output", "out_dir", "figure", "log", "png", "svg"}
# defaults that mean "automatic" on the command line (its default text is a placeholder): the
# robot's home orientation; Python says so with None
AUTOMATIC = {("workspace", "theta"), ("design", "theta"), ("shake", "natural_frequency"), ("pose", "theta")}


def cli_path():
    path = os.environ.get("NOCDYN_CLI")
    if not path or not os.path.exists(path):
        skip_or_fail_in_ci("NOCDYN_CLI does not name the built nocdyn binary (ctest sets it)")
    return os.path.abspath(path)


def run_cli(*args, cwd=None):
    done = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True, timeout=120, cwd=cwd)
    assert done.returncode == 0, (args, done.stderr)
    return done.stdout


@pytest.fixture(scope="module")
def options():
    return json.loads(run_cli("--help-json"))


def test_the_options_json_is_the_packages_own(options):
    assert json.loads(nocdyn._nocdyn._options_json()) == options


def test_every_command_has_a_python_function_and_every_function_a_command(options):
    built = set(options)
    assert built - set(nocdyn.COMMANDS) == set(), "commands without a Python function"
    # validate exists only with both engines built in; every other function has its command
    assert set(nocdyn.COMMANDS) - built <= {"validate"}
    for name, function in nocdyn.COMMANDS.items():
        assert getattr(nocdyn, function.__name__) is function
        assert function.__name__ == name.replace("-", "_")
        assert function.__doc__ and f"nocdyn {name}" in function.__doc__, name


def cli_default(option):
    """The command line's default as a Python value (None for none)."""
    text = option["default"]
    if option["flag"]:
        return text in ("true", "1")
    if text in ("", "[]", "{}"):
        return None
    try:
        return float(text)
    except ValueError:
        return text


def python_default(value):
    if value is inspect.Parameter.empty:
        return None
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    if value in ((), [], ""):
        return None
    return value


@pytest.mark.parametrize("command", sorted(nocdyn.COMMANDS))
def test_options_and_defaults_agree(options, command):
    if command not in options:
        skip_or_fail_in_ci(f"{command}: not built into this nocdyn (needs the engines)")
    signature = inspect.signature(nocdyn.COMMANDS[command]).parameters
    seen = set()
    for option in options[command]:
        if option["hidden"] and not option["positional"]:
            continue  # an old spelling of a shown option
        if option["positional"]:
            name = POSITIONAL[(command, option["name"])]
        else:
            assert option["long"], option
            name = option["long"][0].replace("-", "_")
        if (command, name) in CLI_ONLY or name in CLI_ONLY_EVERYWHERE:
            continue
        seen.add(name)
        assert name in signature, f"{command}: option {option['name']} has no Python argument {name}"
        parameter = signature[name]
        # positionals the command line lets go: convert's ROBOT, pose's THETA (a two-DOF robot has none)
        optional = {("convert", "ROBOT"), ("pose", "THETA")}
        if option["required"] or (option["positional"] and (command, option["name"]) not in optional):
            assert parameter.default is inspect.Parameter.empty, f"{command}: {name} is required on the command line"
            continue
        if (command, name) in BUILD_DEPENDENT or (command, name) in AUTOMATIC:
            assert parameter.default is None
            continue
        if name in OUTPUTS and parameter.default is None:
            continue
        expected, got = cli_default(option), python_default(parameter.default)
        if isinstance(expected, float) and isinstance(got, float):
            assert math.isclose(expected, got, rel_tol=0, abs_tol=0) or expected == got, (command, name, expected, got)
        else:
            assert expected == got, f"{command} {name}: the command line's default {option['default']!r}, " \
                                    f"Python's {parameter.default!r}"
    extra = set(signature) - seen - PYTHON_ONLY - PYTHON_ONLY_OF.get(command, set())
    assert extra == set(), f"{command}: Python arguments the command line does not have: {extra}"


# --- the numbers -------------------------------------------------------------------------------

ROBOT = str(SOURCE_DIR / "robots" / "3-rrr.yaml")
PAPER = str(SOURCE_DIR / "robots" / "paper-3prr.yaml")


def same_table(path, table):
    columns, data, labels = read_csv(path)
    assert columns == table.columns
    np.testing.assert_array_equal(data, table.data)  # bit for bit: the same code ran (NaN: words)
    assert labels.keys() == table.labels.keys()
    for column, words in labels.items():
        np.testing.assert_array_equal(words, table[column])
    df = table.to_pandas()
    assert list(df.columns) == columns and df.shape == data.shape


def test_pose(tmp_path):
    # the pose in the order of every table: x, y, theta, on the command line and in Python
    cli = json.loads(run_cli("pose", 0.001, -0.002, 0.01, "--robot", ROBOT, "--json"))
    py = nocdyn.pose(0.001, -0.002, 0.01, robot=ROBOT)
    assert cli["pose"] == {"x": 0.001, "y": -0.002, "theta": 0.01}
    np.testing.assert_array_equal(py.pose, [0.001, -0.002, 0.01])
    # bit for bit: the same typed result rendered twice
    np.testing.assert_array_equal(py.u, [a["u"] for a in cli["actuators"]])
    np.testing.assert_array_equal(py.range_used, [a["range_used"] for a in cli["actuators"]])
    np.testing.assert_array_equal(py.q, [limb["q"] for limb in cli["limbs"]])
    np.testing.assert_array_equal(py.cond_J, [limb["cond_J"] for limb in cli["limbs"]])
    np.testing.assert_array_equal(py.A, cli["A"])
    np.testing.assert_array_equal(py.I, cli["I"])
    np.testing.assert_array_equal(py.tau, cli["tau"])
    assert py.cond_A == cli["cond_A"] > 1.0 and py.coordinates == cli["coordinates"] and py.within_limits
    assert list(py.to_pandas()["joint"]) == [a["joint"] for a in cli["actuators"]] == [1, 1, 1]
    # A's columns are x, y, theta: du = A dp/dt against a finite difference of u along each
    h = 1e-7
    for k, step in enumerate(np.eye(3) * h):
        ahead = nocdyn.pose(*(py.pose + step), robot=ROBOT).u
        behind = nocdyn.pose(*(py.pose - step), robot=ROBOT).u
        np.testing.assert_allclose((ahead - behind) / (2 * h), py.A[:, k], rtol=1e-6, atol=1e-9)
    # the static reactions: the JSON's list in (limb, joint, [fx, fy, m]) order, as Robot.reactions
    robot = nocdyn.Robot.load(ROBOT)
    np.testing.assert_array_equal(py.reactions[1, 2], [cli["reactions"][5][k] for k in ("fx", "fy", "m")])
    np.testing.assert_allclose(py.reactions, robot.reactions(py.pose, np.zeros(3), np.zeros(3)), rtol=0,
                               atol=1e-12)
    with pytest.raises(ValueError, match="theta"):
        nocdyn.pose(0.0, 0.0, float("nan"))
    with pytest.raises(ValueError, match="^x: "):
        nocdyn.pose(5e3, 0.0, 0.0)


def test_inverse_dynamics_simulate_and_animate(tmp_path):
    cli_id = tmp_path / "id.csv"
    run_cli("inverse-dynamics", "--trajectory", "paper1", "--duration", 0.005, "--rate", 2000, "-o", cli_id)
    py_id = nocdyn.inverse_dynamics("paper1", duration=0.005, rate=2000.0, progress=False)
    same_table(cli_id, py_id)
    assert len(py_id) == 10 and np.max(np.abs(py_id["tau1"])) > 1.0
    # the forces back through the forward dynamics (cubic interpolation on both sides)
    cli_sim = tmp_path / "sim.csv"
    run_cli("simulate", "--forces", cli_id, "--rate", 2000, "-o", cli_sim)
    py_sim = nocdyn.simulate(str(cli_id), rate=2000.0, progress=False)
    same_table(cli_sim, py_sim)
    py_from_table = nocdyn.simulate(py_id, rate=2000.0, progress=False)
    np.testing.assert_array_equal(py_from_table.data, py_sim.data)
    np.testing.assert_allclose(py_sim["x"], py_id["x"][: len(py_sim)], atol=1e-9)
    # the joint reactions: the same columns from both, after the others
    cli_rid = tmp_path / "rid.csv"
    run_cli("inverse-dynamics", "--trajectory", "paper1", "--duration", 0.005, "--rate", 2000, "--reactions", "-o",
            cli_rid)
    py_rid = nocdyn.inverse_dynamics("paper1", duration=0.005, rate=2000.0, reactions=True, progress=False)
    same_table(cli_rid, py_rid)
    cli_rsim = tmp_path / "rsim.csv"
    run_cli("simulate", "--forces", cli_id, "--rate", 2000, "--reactions", "-o", cli_rsim)
    py_rsim = nocdyn.simulate(str(cli_id), rate=2000.0, reactions=True, progress=False)
    same_table(cli_rsim, py_rsim)
    assert py_rsim.columns[-1] == "limb3_j3_m" and len(py_rsim.columns) == len(py_sim.columns) + 27
    # limb 1's rail (a P joint along x) takes no force along itself; its pivot does
    assert np.all(py_rsim["limb1_j1_fx"] == 0.0) and np.max(np.abs(py_rsim["limb1_j2_fx"])) > 0.1
    page = tmp_path / "robot.html"
    run_cli("animate", "--trajectory", "paper1", "--duration", 0.005, "--rate", 2000, "--output", page)
    animation = nocdyn.animate("paper1", duration=0.005, rate=2000.0)
    assert animation.html == page.read_text() and "<canvas" in animation._repr_html_()


def test_forward_kinematics_every_assembly_mode():
    u = nocdyn.pose(0.001, -0.002, 0.01, robot=ROBOT).u
    args = [repr(float(v)) for v in u]
    cli = json.loads(run_cli("forward-kinematics", *args, "--robot", ROBOT, "--json", "--all-branches"))
    py = nocdyn.forward_kinematics(u, robot=ROBOT, all_branches=True)
    assert py.solutions == cli["solutions"] and len(py) == cli["solutions_all_branches"] > 1
    working = nocdyn.forward_kinematics(u, robot=ROBOT)
    assert any(np.allclose(p, [0.001, -0.002, 0.01], atol=1e-9) for p in working.poses)  # x, y, theta
    # as a table the pose is in the order of every file: x, y, theta, last
    assert list(working.to_pandas().columns)[-3:] == ["x", "y", "theta"]


def test_frequency_response_open_and_closed_loop(tmp_path):
    compliant = str(SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml")
    for args, kwargs in (([], {}), (["--pose", 0.002, -0.001, 0.01, "--output-kind", "actuators"],
                                    {"pose": [0.002, -0.001, 0.01], "output_kind": "actuators"}),
                         (["--robot", compliant], {"robot": compliant}),
                         (["--robot", compliant, "--compliance", "rigid"], {"robot": compliant, "compliance": "rigid"}),
                         (["--closed-loop", "--payload-mass", 2, "--max-frequency", 2000],
                          {"closed_loop": True, "payload_mass": 2.0, "max_frequency": 2000.0})):
        out, summary = tmp_path / "fr.csv", tmp_path / "fr.txt"
        printed = run_cli("frequency-response", "--points", 7, *args, "-o", out)
        run_cli("frequency-response", "--points", 7, *args, "-o", out, "--summary", summary)
        py = nocdyn.frequency_response(points=7, **kwargs)
        same_table(out, py)
        assert py.text == printed == summary.read_text()
    # the compliant file's plant is from the commanded drive positions, its lumped modes in the summary
    lumped = nocdyn.frequency_response(robot=compliant, points=7)
    assert lumped.columns[1] == "ddx_uc1_db" and "lumped natural frequencies at the pose [Hz]: 41.0384" in lumped.text
    assert nocdyn.frequency_response(robot=compliant, points=7, compliance="rigid").columns[1] == "ddx_tau1_db"


def test_tables_take_their_columns_from_the_registry():
    run = nocdyn.control("paper1", duration=0.005, rate=2000.0, plant="nocdyn")
    assert run.columns == nocdyn._nocdyn._column_names("closed_loop", actuators=3)
    assert run.columns[:10] == ["t", "x_d", "y_d", "theta_d", "x", "y", "theta", "e_x", "e_y", "e_theta"]
    np.testing.assert_array_equal(run["e_x"], run["x_d"] - run["x"])
    with pytest.raises(nocdyn.Error, match="no CSV layout named 'nope'"):
        nocdyn._nocdyn._column_names("nope")


def test_control_on_every_plant_and_identify(tmp_path):
    common = ["--trajectory", "paper1", "--duration", 0.01, "--rate", 2000, "--payload-mass", 0.5]
    for plant in ("nocdyn", "nocdyn-rk4"):
        out, log = tmp_path / f"{plant}.csv", tmp_path / f"{plant}-log.csv"
        run_cli("control", *common, "--plant", plant, "-o", out, "--log", log)
        py = nocdyn.control("paper1", duration=0.01, rate=2000.0, payload_mass=0.5, plant=plant,
                            log=tmp_path / "py-log.csv")
        same_table(out, py)
        assert (tmp_path / "py-log.csv").read_bytes() == log.read_bytes()
        assert "rms" in py.text.lower()
    cli = run_cli("identify", "--data", log, "--holdout", 0)
    py = nocdyn.identify(log, holdout=0.0)
    assert py.text == cli and py.payload["mass"] > 0.0
    assert list(py.to_pandas()["parameter"])[:4] == ["mass", "com_x", "com_y", "inertia"]


def test_envelope_workspace_loads_regressor_convert(tmp_path):
    run_cli("envelope", "--points", 2, "--min-frequency", 5, "--max-frequency", 50, "-o", tmp_path / "e.csv")
    same_table(tmp_path / "e.csv", nocdyn.envelope(points=2, min_frequency=5.0, max_frequency=50.0))
    compliant = str(SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml")
    text = run_cli("envelope", "--robot", compliant, "--points", 3, "--min-frequency", 5, "--max-frequency", 500,
                   "-o", tmp_path / "c.csv")
    band = nocdyn.envelope(robot=compliant, points=3, min_frequency=5.0, max_frequency=500.0)
    same_table(tmp_path / "c.csv", band)
    assert band.text == text.strip() and "resonance" in set(band["limit"])
    (tmp_path / "c.csv").unlink()
    text = run_cli("workspace", "--robot", ROBOT, "--resolution", 21, "-o", tmp_path / "w.csv", cwd=tmp_path)
    ws = nocdyn.workspace(robot=ROBOT, resolution=21)
    same_table(tmp_path / "w.csv", ws)
    assert ws.text == text.strip() and ws.cells.shape == (21, 21) and ws.area > 0.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["e.csv", "w.csv"]  # no figure unless asked for
    run_cli("loads", "--trajectory", "paper1", "--duration", 0.005, "--rate", 2000, "-o", tmp_path / "l.csv")
    same_table(tmp_path / "l.csv", nocdyn.loads("paper1", duration=0.005, rate=2000.0))
    assert nocdyn.regressor(robot=ROBOT, samples=40) == run_cli("regressor", "--robot", ROBOT, "--samples", 40)
    assert nocdyn.convert(ROBOT) == run_cli("convert", "--robot", ROBOT) == run_cli("convert", ROBOT)


def test_design_and_loads_over_the_envelope(tmp_path):
    family = str(SOURCE_DIR / "examples" / "design_3rrr" / "family.yaml")
    run_cli("design", "--robot", family, "--set", "l2=0.11", "--vary", "r_b=0.15:0.25", "--samples", 4, "--metric",
            "workspace_area", "--metric", "moving_mass", "--resolution", 11, "--no-figures", "--out-dir",
            tmp_path / "cli")
    py = nocdyn.design("r_b=0.15:0.25", ["workspace_area", "moving_mass"], robot=family, set={"l2": 0.11}, samples=4,
                       resolution=11, no_figures=True, out_dir=tmp_path / "py")
    for name in ("designs.csv", "pareto.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    columns, data, labels = read_csv(tmp_path / "cli" / "designs.csv")
    np.testing.assert_array_equal(py.values, data[:, 2:4])
    assert list(py.feasible) == [w == "true" for w in labels["feasible"]]
    run_cli("loads", "--envelope", "--points", 1, "--min-frequency", 20, "--max-frequency", 20, "-o", tmp_path / "l.csv")
    table = nocdyn.loads(envelope=True, points=1, min_frequency=20.0, max_frequency=20.0)
    same_table(tmp_path / "l.csv", table)
    assert table["limb"].dtype == np.int64 and "over the operating envelope" in table.text


def test_excite(tmp_path):
    small = dict(evaluations=12, random_shapes=6, samples=48, check_samples=300, duration=0.4)
    args = [a for k, v in small.items() for a in ("--" + k.replace("_", "-"), v)]
    text = run_cli("excite", "--robot", ROBOT, *args, "-o", tmp_path / "x.yaml")
    py = nocdyn.excite(robot=ROBOT, **small)
    assert py.yaml == (tmp_path / "x.yaml").read_text()
    # the same report; the command line then names the file written
    assert py.text.splitlines() == text.splitlines()[:-1] and "wrote" in text.splitlines()[-1]
    assert py.trajectory.duration == pytest.approx(0.4)


def test_shake(tmp_path):
    record = SOURCE_DIR / "data" / "elcentro_1940_ns.AT2"
    args = dict(window=0.5, plant="nocdyn-rk4", rate=1000.0)
    run_cli("shake", "--record", record, "--window", 0.5, "--plant", "nocdyn-rk4", "--rate", 1000, "--out-dir",
            tmp_path / "cli")
    py = nocdyn.shake(record, out_dir=tmp_path / "py", **args)
    same_table(tmp_path / "cli" / "shake.csv", py)
    assert py.metrics == json.loads((tmp_path / "cli" / "shake.json").read_text())
    assert (tmp_path / "py" / "shake_acceleration.svg").exists()


def test_validate_when_built(options, tmp_path):
    if "validate" not in options:
        skip_or_fail_in_ci("validate is not built in (needs Simbody and MuJoCo)")
    run_cli("validate", "--trajectory", "paper1", "--duration", 0.005, "-o", tmp_path / "v.csv")
    py = nocdyn.validate("paper1", duration=0.005)
    same_table(tmp_path / "v.csv", py)
    assert np.max(np.abs(py.group("simbody_dtau"))) < 1e-6


def test_bad_arguments_name_the_python_argument():
    with pytest.raises(ValueError, match="rate"):
        nocdyn.inverse_dynamics("paper1", rate=-1.0, progress=False)
    with pytest.raises(ValueError, match="plant"):
        nocdyn.control("paper1", plant="adams")
    with pytest.raises(nocdyn.Error, match="nope"):
        nocdyn.inverse_dynamics("nope", progress=False)


def test_progress_callback_and_version():
    calls = []
    nocdyn.inverse_dynamics("paper1", duration=0.2, rate=20000.0, progress=lambda done, total: calls.append(
        (done, total)))
    assert calls and all(total == pytest.approx(0.2) and 0.0 <= done <= total for done, total in calls)
    assert run_cli("--version").startswith(f"nocdyn {nocdyn.__version__} (commit ")


def test_robot_draws_itself_and_help_shows_the_docstrings():
    for name in ("paper-3prr", "3-rrr", "4-rrr"):
        robot = nocdyn.Robot.example(name)
        svg = robot._repr_svg_()
        assert svg.startswith("<svg") and svg.rstrip().endswith("</svg>")
        # every limb drawn, every actuator marked and labelled
        assert svg.count('stroke="#1f77b4"') == robot.limbs
        assert all(f">u{a + 1}<" in svg for a in range(robot.actuators))
    assert nocdyn.Robot.paper().svg([0.02, 0.001, 0.0]) != nocdyn.Robot.paper().svg()
    with pytest.raises(nocdyn.Error):
        nocdyn.Robot.paper().svg([0.0, 1.0, 0.0])  # out of reach
    # help() shows the docstrings; the type stub (_nocdyn.pyi) describes the compiled module
    import pydoc
    text = pydoc.render_doc(nocdyn.shake, renderer=pydoc.plaintext)
    assert "shake(record" in text and "nocdyn shake" in text
    package = pathlib.Path(nocdyn.__file__).parent
    assert (package / "py.typed").exists() and "def _run_pose" in (package / "_nocdyn.pyi").read_text()


def test_reproduce(tmp_path):
    quick = ["--closed-loop-duration", 0.001, "--identification-duration", 0.01]
    run_cli("reproduce", "--out-dir", tmp_path / "cli", *quick)
    report = nocdyn.reproduce(out_dir=tmp_path / "py", closed_loop_duration=0.001, identification_duration=0.01)
    cli_files = sorted(p.relative_to(tmp_path / "cli") for p in (tmp_path / "cli").rglob("*.csv"))
    assert cli_files == sorted(p.relative_to(tmp_path / "py") for p in report.files if p.suffix == ".csv")
    assert len(cli_files) >= 10
    for name in cli_files:  # every table bit for bit (the timings in summary.md differ)
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert report.summary.startswith("# nocdyn reproduce") and report._repr_markdown_() == report.summary
    same_table(tmp_path / "cli" / "paper1.csv", report.table("paper1.csv"))
