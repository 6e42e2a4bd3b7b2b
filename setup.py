"""Builds the Python package with CMake for `pip install --no-build-isolation .`.

The module is built in NOCDYN_BUILD_DIR (default: build/, the README scripts' folder; only the
targets of the package are built there) with the interpreter running pip, and the package folder
CMake fills (<build>/python/nocdyn) becomes the wheel's `nocdyn` package.
"""

import os
import pathlib
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_py):
    def run(self):
        build_dir = pathlib.Path(os.environ.get("NOCDYN_BUILD_DIR", ROOT / "build")).resolve()
        jobs = os.environ.get("NOCDYN_BUILD_JOBS", str(os.cpu_count() or 1))
        # the interpreter itself, not a virtual environment's link to it (the same ABI)
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                        "-DNOCDYN_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={os.path.realpath(sys.executable)}"], check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "-j", jobs, "--target", "nocdyn_python"], check=True)
        package = build_dir / "python" / "nocdyn"
        target = pathlib.Path(self.build_lib) / "nocdyn"
        self.copy_tree(str(package), str(target))


class BinaryDistribution(Distribution):
    """A wheel for this platform and interpreter (it holds a compiled module)."""

    def has_ext_modules(self):
        return True


setup(packages=["nocdyn"], package_dir={"nocdyn": "python/nocdyn"}, cmdclass={"build_py": CMakeBuild},
      distclass=BinaryDistribution)
