# The nocdyn user guide (Sphinx, Markdown pages through MyST). Built by the test `docs.sphinx`
# (ctest -L docs) with warnings as errors:
#   NOCDYN_CLI=build/nocdyn NOCDYN_PYTHONPATH=build/python \
#     sphinx-build -W --keep-going -b html docs build/docs/html
# NOCDYN_CLI: the built `nocdyn`, whose `--help` pages are the option lists of docs/commands/
# (read at build time, so they cannot drift from the program). NOCDYN_PYTHONPATH: the folder
# holding the built Python package, whose docstrings make the Python API page.
import os
import pathlib
import subprocess
import sys

here = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(here / "_ext"))
if os.environ.get("NOCDYN_PYTHONPATH"):
    sys.path.insert(0, os.environ["NOCDYN_PYTHONPATH"])

project = "nocdyn"
author = "the nocdyn authors"
copyright = "the nocdyn authors"
extensions = ["myst_parser", "sphinx.ext.autodoc", "breathe", "nocdyn_docs"]

# The C++ API page (cpp-api.md): Doxygen's XML of the public headers (docs/Doxyfile), made here at
# every build into NOCDYN_DOXYGEN_OUT (the test sets a folder of the build tree), read by Breathe.
doxygen_out = pathlib.Path(os.environ.get("NOCDYN_DOXYGEN_OUT") or here.parent / "build" / "docs" / "doxygen")
doxygen_out.mkdir(parents=True, exist_ok=True)
subprocess.run(["doxygen", "Doxyfile"], cwd=here, check=True, timeout=300,
               env={**os.environ, "NOCDYN_DOXYGEN_OUT": str(doxygen_out)},
               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
breathe_projects = {"nocdyn": str(doxygen_out / "xml")}
breathe_default_project = "nocdyn"
breathe_domain_by_extension = {"hpp": "cpp"}
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
html_theme = "alabaster"
html_static_path = []
autodoc_member_order = "bysource"
nitpicky = False
