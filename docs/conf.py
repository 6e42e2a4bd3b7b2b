# The nocdyn user guide (Sphinx, Markdown pages through MyST). Build it with
#   bash scripts/docs.sh
# which builds what the guide reads, sets the variables below and checks the site; the test
# `docs.sphinx` (ctest -L docs) does the same with warnings as errors.
# NOCDYN_CLI: the built `nocdyn`, whose `--help` pages are the option lists of docs/commands/
# (read at build time, so they cannot drift from the program). NOCDYN_PYTHONPATH: the folder
# holding the built Python package, whose docstrings make the Python API page. Unset, both are
# taken from build/ when it holds them; else the build stops here and says how to build.
import os
import pathlib
import subprocess
import sys

here = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(here / "_ext"))
for variable, default in (("NOCDYN_CLI", here.parent / "build" / "nocdyn"),
                          ("NOCDYN_PYTHONPATH", here.parent / "build" / "python")):
    if not os.environ.get(variable):
        if not default.exists():
            raise RuntimeError(f"{variable} is not set and {default} does not exist: build the guide with "
                               "`bash scripts/docs.sh` (it builds the program and the Python package first)")
        os.environ[variable] = str(default)
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
