#!/usr/bin/python3
"""Checks a built user guide (scripts/docs.sh) for pages that built but came out empty: every
command page's option list (the program's --help, read at build time) and the Python API page
(the built package's docstrings). A site built without the program or the package would have
them empty; this fails it, naming each empty page.

    scripts/docs/check_site.py SITE          # SITE: the html folder, e.g. build/docs/html
    scripts/docs/check_site.py --self-test   # shows that an empty option list fails the check
"""

import html
import pathlib
import re
import sys
import tempfile

# the Python API page documents at least this many objects (nocdyn.Robot, its methods, the
# command functions ...); the package has about 80
MIN_PYTHON_OBJECTS = 20


def text_of(page):
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8")))


def problems(site):
    site = pathlib.Path(site)
    found = []
    pages = sorted((site / "commands").glob("*.html"))
    commands = [p for p in pages if p.stem not in ("index", "genindex", "search")]
    if not commands:
        found.append(f"{site / 'commands'}: no command page")
    for page in commands:
        text = text_of(page)
        # CLI11's help: "Options:" then one line per option, each with a "--name"
        options = text.split("Options:", 1)
        if len(options) < 2 or not re.search(r"^\s+(-\w,\s*)?--[a-z]", options[1], re.M):
            found.append(f"{page}: the option list is empty (was NOCDYN_CLI set? use scripts/docs.sh)")
    python = site / "python.html"
    if not python.exists():
        found.append(f"{python}: missing")
    else:
        documented = set(re.findall(r'id="(nocdyn\.[A-Za-z0-9_.]+)"', python.read_text(encoding="utf-8")))
        if len(documented) < MIN_PYTHON_OBJECTS:
            found.append(f"{python}: the Python API documents {len(documented)} objects, expected at least "
                         f"{MIN_PYTHON_OBJECTS} (was NOCDYN_PYTHONPATH set? use scripts/docs.sh)")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as folder:
        site = pathlib.Path(folder)
        (site / "commands").mkdir()
        (site / "commands" / "pose.html").write_text("<pre>Usage: nocdyn pose\nOptions:\n</pre>")
        (site / "python.html").write_text("<dl id=\"nocdyn.Robot\"></dl>")
        empty = problems(site)
        assert len(empty) == 2, empty
        full = "".join(f'<dt id="nocdyn.f{k}"></dt>' for k in range(MIN_PYTHON_OBJECTS))
        (site / "commands" / "pose.html").write_text("<pre>Options:\n  -h,--help  Print this help\n</pre>")
        (site / "python.html").write_text(full)
        assert problems(site) == [], problems(site)
    print("check_site: an empty option list and an empty Python API fail the check; full pages pass")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return 0
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = problems(sys.argv[1])
    for line in found:
        print(f"check_site: {line}", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
