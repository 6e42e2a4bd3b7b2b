"""Sphinx extension of the nocdyn guide.

- The directive ``nocdyn-help`` puts the output of ``nocdyn COMMAND --help`` on the page, run at
  build time on the built program (environment variable NOCDYN_CLI): the option lists in the
  guide are the program's own. A missing program or a failing ``--help`` fails the build.
- Every command that ``nocdyn --help`` lists must have its page ``commands/COMMAND.md``: a new
  command without a page fails the build (a warning, and the build runs with -W).
"""

import os
import pathlib
import re
import subprocess

from docutils import nodes
from docutils.parsers.rst import Directive
from sphinx.util import logging

logger = logging.getLogger(__name__)


def _cli():
    path = os.environ.get("NOCDYN_CLI")
    if not path or not os.access(path, os.X_OK):
        return None
    return path


def _run(*args):
    cli = _cli()
    if cli is None:
        raise RuntimeError("NOCDYN_CLI does not name the built nocdyn program (e.g. NOCDYN_CLI=build/nocdyn)")
    done = subprocess.run([cli, *args], capture_output=True, text=True, timeout=60, env={**os.environ, "COLUMNS": "100"})
    if done.returncode != 0:
        raise RuntimeError(f"nocdyn {' '.join(args)} exited with {done.returncode}: {done.stderr.strip()}")
    return done.stdout


class NocdynHelp(Directive):
    """``nocdyn-help`` COMMAND: the command's --help text as a literal block."""

    required_arguments = 1
    has_content = False

    def run(self):
        try:
            text = _run(self.arguments[0], "--help")
        except RuntimeError as error:
            raise self.error(str(error))
        block = nodes.literal_block(text, text)
        block["language"] = "text"
        return [block]


def commands():
    """The commands `nocdyn --help` lists: the lines "  NAME   description" under each group's
    heading ("Model:", "Motion:", ...; not "Options:")."""
    listed, in_group = [], False
    for line in _run("--help").splitlines():
        heading = re.match(r"^([A-Z][A-Za-z ]+):$", line)
        if heading:
            in_group = heading.group(1) != "Options"
            continue
        match = re.match(r"^  ([a-z][a-z0-9-]*)\s", line)
        if in_group and match:
            listed.append(match.group(1))
    return listed


def check_command_pages(app):
    if _cli() is None:
        logger.warning("NOCDYN_CLI is not set: cannot check that every command has its page")
        return
    pages = pathlib.Path(app.srcdir) / "commands"
    listed = commands()
    if not listed:
        logger.warning("nocdyn --help lists no command (its format changed?)")
    for name in listed:
        if not (pages / f"{name}.md").exists():
            logger.warning(f"the command '{name}' has no page docs/commands/{name}.md")


def setup(app):
    app.add_directive("nocdyn-help", NocdynHelp)
    app.connect("builder-inited", check_command_pages)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
