#!/bin/bash
# The user guide, in one command from a fresh clone (after scripts/install-deps.sh):
#
#   bash scripts/docs.sh [BUILD_DIR]        # default BUILD_DIR: build
#
# Builds what the guide reads (the `nocdyn` program, whose --help pages are the option lists of
# docs/commands/, and the Python package, whose docstrings are the Python API page; a fresh build
# folder is configured Release without tests), then runs Sphinx from scratch with warnings as
# errors into BUILD_DIR/docs/html, then checks the site: it fails when a command's option list
# or the Python API would be empty. Open BUILD_DIR/docs/html/index.html in a browser.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(realpath -m "${1:-$root/build}")
cd "$root"
if ! command -v sphinx-build >/dev/null; then
    echo "docs.sh: sphinx-build is missing (bash scripts/install-deps.sh installs it)" >&2
    exit 1
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DNOCDYN_BUILD_TESTS=OFF -DNOCDYN_BUILD_BENCHMARKS=OFF \
        -DNOCDYN_BUILD_PYTHON=ON
else
    cmake -S . -B "$build" -DNOCDYN_BUILD_PYTHON=ON >/dev/null   # an existing build: add the package
fi
cmake --build "$build" -j"$(nproc)" --target nocdyn_cli nocdyn_python
# what docs/conf.py reads: the program, the package, Doxygen's output folder
export NOCDYN_CLI="$build/nocdyn" NOCDYN_PYTHONPATH="$build/python" NOCDYN_DOXYGEN_OUT="$build/docs/doxygen"
export PYTHONDONTWRITEBYTECODE=1
sphinx-build -E -W --keep-going -q -b html -d "$build/docs/doctrees" docs "$build/docs/html"
/usr/bin/python3 scripts/docs/check_site.py "$build/docs/html"
echo "docs.sh: the guide is $build/docs/html/index.html (open it in a browser)"
