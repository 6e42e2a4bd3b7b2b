"""Python's defaults and ranges are the C++ job structs' (app/*.hpp), read through the binding,
never written again in Python: every command function's keyword defaults equal its options
struct's fields, the design sweeps' (nocdyn.designs) defaults and ranges are app::DesignOptions'
and app/options.hpp's, and Robot's deprecated job wrappers define no option of their own."""

import inspect

import pytest

import nocdyn
from nocdyn import _nocdyn, designs

# Python's None for "the build's choice", "the robot's own" or "not given" (pose's theta, which a
# two-DOF robot has none of): said in the functions' docstrings
AUTOMATIC = {("control", "plant"), ("loads", "trajectory"), ("animate", "trajectory"), ("pose", "theta")}


def options_type(command):
    name = "".join(word.capitalize() for word in command.split("-")) + "Options"
    return getattr(_nocdyn, name, None)


@pytest.mark.parametrize("command", sorted(nocdyn.COMMANDS))
def test_every_keyword_default_of_a_command_is_its_options_structs(command):
    kind = options_type(command)
    if kind is None:
        pytest.skip(f"{command}: not built in")
    defaults = kind()
    parameters = inspect.signature(nocdyn.COMMANDS[command]).parameters
    compared = 0
    for name in kind._fields:
        if name not in parameters or parameters[name].default is inspect.Parameter.empty:
            continue
        if (command, name) in AUTOMATIC:
            assert parameters[name].default is None
            continue
        assert parameters[name].default == getattr(defaults, name), f"{command}: {name}"
        compared += 1
    # every field is compared, except the required ones (pose's x, y, theta) and the automatic
    required = [n for n in kind._fields if n in parameters and parameters[n].default is inspect.Parameter.empty]
    automatic = [n for n in kind._fields if (command, n) in AUTOMATIC]
    assert compared + len(required) + len(automatic) == len([n for n in kind._fields if n in parameters])


def test_the_design_sweeps_defaults_and_ranges_are_the_design_commands(source_dir):
    struct = _nocdyn.DesignOptions()
    signature = inspect.signature(designs._options).parameters
    assert signature["resolution"].default == struct.resolution == 201
    assert signature["rate"].default == struct.rate == 10000.0
    ranges = _nocdyn._ranges()
    low, high = (int(v) for v in ranges["design_resolution"][:2])
    assert (low, high) == (11, 2001)
    with pytest.raises(ValueError, match=f"from {low} to {high}"):
        designs._options(resolution=low - 1)
    with pytest.raises(ValueError, match="rate"):
        designs._options(rate=ranges["rate"][1] * 10)
    with pytest.raises(ValueError, match="duration"):
        designs._options(duration=ranges["duration"][0] / 10)
    # the command itself refuses the same values, in the same words' range
    with pytest.raises(ValueError, match="resolution"):
        nocdyn.design("r_b=0.15:0.25", "moving_mass", robot=source_dir / "examples" / "design_3rrr" / "family.yaml",
                      resolution=low - 1)


@pytest.mark.parametrize("method", ["trajectory_dynamics", "simulate", "envelope", "identify_payload"])
def test_robots_deprecated_job_wrappers_hold_no_option_of_their_own(method):
    parameters = inspect.signature(getattr(nocdyn.Robot, method)).parameters
    assert all(p.default is inspect.Parameter.empty or p.default is None for p in parameters.values()), method
    assert any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values())
    assert "Deprecated" in getattr(nocdyn.Robot, method).__doc__


def test_the_type_stub_names_only_what_the_compiled_module_has_with_its_arguments():
    """_nocdyn.pyi (hand-written) matches the module: every function and method it declares
    exists, with the same argument names in the same order as pybind11's signature."""
    import ast
    import pathlib
    import re
    stub = ast.parse((pathlib.Path(_nocdyn.__file__).parent / "_nocdyn.pyi").read_text())

    def check(owner, function, where):
        if function.name.startswith("__"):
            return
        bound = getattr(owner, function.name, None)
        assert bound is not None, f"{where}.{function.name} is in the stub, not in the module"
        declared = [a.arg for a in function.args.posonlyargs + function.args.args if a.arg != "self"]
        # pybind11's docstring starts with name(arg: type, ...) -> result
        lines = (bound.__doc__ or "").splitlines()
        assert lines, f"{where}.{function.name} has no pybind11 signature to compare"
        first = lines[0]
        actual = [name for name in re.findall(r"(\w+): ", first.split("->")[0]) if name != "self"]
        assert declared == actual, f"{where}.{function.name}: stub {declared}, module {actual}"

    checked = 0
    for node in stub.body:
        if isinstance(node, ast.FunctionDef):
            check(_nocdyn, node, "_nocdyn")
            checked += 1
        elif isinstance(node, ast.ClassDef):
            cls = getattr(_nocdyn, node.name, None)
            assert cls is not None, f"class {node.name} is in the stub, not in the module"
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not any(
                        isinstance(d, ast.Name) and d.id == "staticmethod" for d in item.decorator_list):
                    check(cls, item, node.name)
                    checked += 1
    assert checked >= 15


def test_every_choice_takes_the_command_lines_words_and_refuses_another(cli):
    """A choice (an enum with one name table) accepts in Python exactly the words its command-line
    option lists (`nocdyn --help-json`, type TEXT:{a,b}), its default is the option's, and another
    word is refused naming them all in the table's order."""
    import json
    import re
    code, out, err = cli("--help-json")
    assert code == 0, err
    checked = []
    for command, options in json.loads(out).items():
        kind = options_type(command)
        for option in options:
            words = re.fullmatch(r"TEXT:\{([a-z0-9,-]+)\}", option["type"])
            field = option["name"].replace("-", "_")
            if kind is None or words is None or field not in kind._fields:
                continue
            words = words.group(1).split(",")
            struct = kind()
            assert getattr(struct, field) == option["default"], f"{command} --{option['name']}"
            for word in words:
                setattr(struct, field, word)
                assert getattr(struct, field) == word
            listed = ", ".join(words[:-1]) + " or " + words[-1]
            with pytest.raises(ValueError, match=f"^{field}: expected {re.escape(listed)}, got 'bogus'$"):
                setattr(struct, field, "bogus")
            checked.append(f"{command} {field}")
    for converted in ["control controller", "control measure", "design sweep", "excite optimizer",
                      "frequency-response output_kind", "frequency-response compliance", "shake axis",
                      "simulate interpolation", "validate engine", "shake plant", "shake drive_model"]:
        assert converted in checked
