"""Builds the Python package with CMake for `pip install --no-build-isolation .`.

The module is built in NOCDYN_BUILD_DIR (default: build/, the README scripts' folder; only the
targets of the package are built there) with the interpreter running pip, and the package folder
CMake fills (<build>/python/nocdyn) becomes the wheel's `nocdyn` package. A build folder that is
already configured for this interpreter is used as it is (its options kept, nothing rebuilt that
is up to date). The compiled module holds the command line too: the `nocdyn` command pip
installs (pyproject.toml) runs it (nocdyn/__main__.py). The version is the CMake project's.
"""

import os
import pathlib
import re
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version in CMakeLists.txt's project() (the one `nocdyn --version` prints)."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    return re.search(r"project\(nocdyn\s+VERSION\s+([0-9.]+)", text).group(1)


def configured_python(build_dir):
    """The interpreter a configured build folder builds the module for, or None."""
    cache = build_dir / "CMakeCache.txt"
    if not cache.exists():
        return None
    match = re.search(r"^Python3_EXECUTABLE:[A-Z]+=(.*)$", cache.read_text(encoding="utf-8"), re.MULTILINE)
    return os.path.realpath(match.group(1)) if match else None


class CMakeBuild(build_py):
    def run(self):
        build_dir = pathlib.Path(os.environ.get("NOCDYN_BUILD_DIR", ROOT / "build")).resolve()
        jobs = os.environ.get("NOCDYN_BUILD_JOBS", str(os.cpu_count() or 1))
        # the interpreter itself, not a virtual environment's link to it (the same ABI)
        python = os.path.realpath(sys.executable)
        if configured_python(build_dir) != python:
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                            "-DNOCDYN_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={python}"], check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "-j", jobs, "--target", "nocdyn_python"], check=True)
        package = build_dir / "python" / "nocdyn"
        target = pathlib.Path(self.build_lib) / "nocdyn"
        self.copy_tree(str(package), str(target))


class BinaryDistribution(Distribution):
    """A wheel for this platform and interpreter (it holds a compiled module)."""

    def has_ext_modules(self):
        return True


setup(version=project_version(), packages=["nocdyn"], package_dir={"nocdyn": "python/nocdyn"}, cmdclass={"build_py": CMakeBuild},
      distclass=BinaryDistribution)
