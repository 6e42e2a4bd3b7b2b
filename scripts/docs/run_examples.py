#!/usr/bin/python3
"""Runs every example of the README and the user guide that is marked runnable, so that the
documentation cannot drift from the program.

A runnable example is a fenced code block whose info string is `bash runnable` or
`python runnable`. The blocks of one page run in order in one fresh temporary folder laid out
like the top of the source tree (robots/, trajectories/, data/, examples/, bench/ linked from
the sources; build/nocdyn and build/python linked to the build), so an example reads as a user
types it there. A bash block runs with `bash -euo pipefail`; a python block with the given
interpreter and PYTHONPATH=build/python. Any non-zero exit fails the run, naming the page, the
block's line and its output.

    scripts/docs/run_examples.py --cli build/nocdyn --python-dir build/python [FILES...]

Without FILES: README.md and every docs/**/*.md. Time per block is printed.
"""

import argparse
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
FENCE = re.compile(r"^(`{3,})(\S*)\s*(.*)$")
LINKED = ["robots", "trajectories", "data", "examples", "bench"]


def blocks(path):
    """(line, language, code) of each runnable block of a Markdown file."""
    found, lines = [], path.read_text(encoding="utf-8").splitlines()
    k = 0
    while k < len(lines):
        match = FENCE.match(lines[k])
        if not match:
            k += 1
            continue
        fence, language, rest = match.groups()
        start, body = k + 1, []
        k += 1
        while k < len(lines) and not lines[k].startswith(fence):
            body.append(lines[k])
            k += 1
        k += 1
        if "runnable" in rest.split():
            if language not in ("bash", "python"):
                raise SystemExit(f"{path}:{start}: a runnable block must be bash or python, not '{language}'")
            found.append((start, language, "\n".join(body) + "\n"))
    return found


def workspace(folder, cli, python_dir):
    for name in LINKED:
        (folder / name).symlink_to(ROOT / name)
    build = folder / "build"
    build.mkdir()
    (build / "nocdyn").symlink_to(cli)
    (build / "python").symlink_to(python_dir)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", required=True, type=pathlib.Path, help="the built nocdyn program")
    parser.add_argument("--python-dir", required=True, type=pathlib.Path, help="the folder holding the built package")
    parser.add_argument("--python", default="/usr/bin/python3", help="interpreter of the python blocks")
    parser.add_argument("--timeout", type=float, default=120.0, help="seconds per block")
    parser.add_argument("files", nargs="*", type=pathlib.Path)
    args = parser.parse_args()
    cli, python_dir = args.cli.resolve(), args.python_dir.resolve()
    if not os.access(cli, os.X_OK):
        raise SystemExit(f"run_examples: {cli} is not an executable nocdyn")
    if not (python_dir / "nocdyn").is_dir():
        raise SystemExit(f"run_examples: {python_dir} holds no nocdyn package (build nocdyn_python)")
    files = args.files or [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    env = {**os.environ, "PYTHONPATH": "build/python", "MPLBACKEND": "Agg", "PYTHONDONTWRITEBYTECODE": "1"}
    env.pop("NOCDYN_CLI", None)
    failures, count, started = 0, 0, time.monotonic()
    for path in files:
        found = blocks(path)
        if not found:
            continue
        shown = path.resolve().relative_to(ROOT) if path.resolve().is_relative_to(ROOT) else path
        with tempfile.TemporaryDirectory(prefix="nocdyn-docs-") as temporary:
            folder = pathlib.Path(temporary)
            workspace(folder, cli, python_dir)
            for line, language, code in found:
                count += 1
                command = ["bash", "-euo", "pipefail", "-c", code] if language == "bash" else [args.python, "-c", code]
                begin = time.monotonic()
                try:
                    done = subprocess.run(command, cwd=folder, env=env, capture_output=True, text=True,
                                          timeout=args.timeout)
                    status, output = done.returncode, done.stdout + done.stderr
                except subprocess.TimeoutExpired as expired:
                    status, output = "timeout", f"no end after {expired.timeout} s"
                seconds = time.monotonic() - begin
                if status == 0:
                    print(f"ok      {shown}:{line} ({language}, {seconds:.1f} s)")
                else:
                    failures += 1
                    print(f"FAILED  {shown}:{line} ({language}, exit {status}, {seconds:.1f} s)\n{code}--- output:\n"
                          f"{output}---")
    print(f"run_examples: {count - failures} of {count} examples ran, {time.monotonic() - started:.1f} s")
    if count == 0:
        print("run_examples: no runnable example found")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
