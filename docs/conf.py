# The nocdyn user guide (Sphinx, Markdown pages through MyST). Built by the test `docs.sphinx`
# (ctest -L docs) with warnings as errors:
#   NOCDYN_CLI=build/nocdyn NOCDYN_PYTHONPATH=build/python \
#     sphinx-build -W --keep-going -b html docs build/docs/html
# NOCDYN_CLI: the built `nocdyn`, whose `--help` pages are the option lists of docs/commands/
# (read at build time, so they cannot drift from the program). NOCDYN_PYTHONPATH: the folder
# holding the built Python package, whose docstrings make the Python API page.
import os
import pathlib
import sys

here = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(here / "_ext"))
if os.environ.get("NOCDYN_PYTHONPATH"):
    sys.path.insert(0, os.environ["NOCDYN_PYTHONPATH"])

project = "nocdyn"
author = "the nocdyn authors"
copyright = "the nocdyn authors"
extensions = ["myst_parser", "sphinx.ext.autodoc", "nocdyn_docs"]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
html_theme = "alabaster"
html_static_path = []
autodoc_member_order = "bysource"
nitpicky = False
