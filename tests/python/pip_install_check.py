"""`pip install .` gives both `import nocdyn` and the `nocdyn` command, from one build.

A copy of the source tree (nothing is written into the real one) is installed with Debian's pip
into a fresh virtual environment made with --system-site-packages (no download: no build
isolation, no dependencies fetched), reusing the configured build folder given (only
out-of-date targets of the package are built). Then, from another folder, with no PYTHONPATH:
`nocdyn --version` prints the CMake project version (and the commit), `nocdyn pose` runs, and `import nocdyn`
gives the same __version__ from the installed package.

Usage: python3 pip_install_check.py SOURCE_DIR BUILD_DIR
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile


def main():
    source, build = (pathlib.Path(a).resolve() for a in sys.argv[1:3])
    version = re.search(r"project\(nocdyn\s+VERSION\s+([0-9.]+)", (source / "CMakeLists.txt").read_text()).group(1)
    with tempfile.TemporaryDirectory(prefix="nocdyn-pip-") as folder:
        folder = pathlib.Path(folder)
        copy = folder / "source"
        skip = shutil.ignore_patterns(".git", "build*", "results", "node_modules", "*.egg-info", "__pycache__")
        shutil.copytree(source, copy, ignore=skip, symlinks=True)
        venv = folder / "venv"
        subprocess.run([sys.executable, "-m", "venv", "--without-pip", "--system-site-packages", str(venv)], check=True)
        python = venv / "bin" / "python"
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NOCDYN_CLI")}
        env["NOCDYN_BUILD_DIR"] = str(build)
        env["NOCDYN_BUILD_JOBS"] = "2"
        env["PIP_NO_INDEX"] = "1"
        env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
        subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-build-isolation", "--no-deps", str(copy)],
                       check=True, env=env, cwd=folder)
        command = venv / "bin" / "nocdyn"
        assert command.exists(), "pip did not install the nocdyn command"
        run = subprocess.run([str(command), "--version"], capture_output=True, text=True, env=env, cwd=folder)
        # the version, then the commit the build was configured from ("unknown" outside a checkout)
        printed = re.fullmatch(rf"nocdyn {re.escape(version)} \(commit ([0-9a-f]+|unknown)\)\n", run.stdout)
        assert run.returncode == 0 and printed, (run.returncode, run.stdout, run.stderr)
        run = subprocess.run([str(command), "pose", "0", "0", "0", "--json"], capture_output=True, text=True, env=env,
                             cwd=folder)
        assert run.returncode == 0 and '"cond_A"' in run.stdout, (run.returncode, run.stderr)
        run = subprocess.run([str(command), "pose", "0", "0", "0", "--bogus"], capture_output=True, text=True,
                             env=env, cwd=folder)
        assert run.returncode == 2 and "--bogus" in run.stderr, (run.returncode, run.stderr)
        code = ("import nocdyn, pathlib; print(nocdyn.__version__); "
                "print(pathlib.Path(nocdyn.__file__).resolve().is_relative_to(pathlib.Path(%r).resolve()))" % str(venv))
        run = subprocess.run([str(python), "-c", code], capture_output=True, text=True, env=env, cwd=folder)
        assert run.returncode == 0 and run.stdout.split() == [version, "True"], (run.stdout, run.stderr)
    print(f"pip install: nocdyn {version}, the command and the package")


if __name__ == "__main__":
    main()
