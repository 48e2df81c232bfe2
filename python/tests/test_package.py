"""pip installs the package as a user would (docs/python.md, "Install with
pip"): from a clean copy of the checkout, into a fresh virtual environment
that sees Debian's numpy, pandas and pytest, offline, building only the
library and the module. The installed package carries its stubs, py.typed,
license and the CMake project's version, passes the Python tests run
against it (not build/python), and pip uninstall removes it.

Slow (the library is compiled from scratch: minutes on 2 cores)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(os.environ["IMPACTKIT_SOURCE_DIR"])
TESTS = Path(__file__).resolve().parent
# Not run against the installed package: the build tree's install, this
# test, and the notebook tests (which run on their own).
SKIPPED = {"test_install.py", "test_package.py", "test_notebook.py"}


def clean_copy(destination):
    """The checkout's files, as git sees them (tracked, and new ones not
    ignored), without any build directory."""
    listed = subprocess.run(["git", "-C", str(SOURCE), "ls-files", "-z", "--cached", "--others",
                             "--exclude-standard"], capture_output=True)
    if listed.returncode == 0:
        for name in listed.stdout.decode().split("\0"):
            if name and (SOURCE / name).is_file():
                (destination / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(SOURCE / name, destination / name)
    else:  # not a git checkout (a release tarball)
        shutil.copytree(SOURCE, destination, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("build*", ".venv", "__pycache__", ".git"))


def test_pip_installs_tests_and_uninstalls(tmp_path):
    source, venv = tmp_path / "impactkit", tmp_path / "venv"
    clean_copy(source)
    assert not (source / "build").exists() and (source / "pyproject.toml").is_file()
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python, pip = venv / "bin" / "python", venv / "bin" / "pip"
    # Offline: pip must find nothing to download (PIP_NO_INDEX); the build
    # uses two jobs, as CI has two cores.
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    env.update(PIP_NO_INDEX="1", CMAKE_BUILD_PARALLEL_LEVEL="2")
    subprocess.run([str(pip), "install", "--no-build-isolation", str(source)], check=True,
                   env=env, cwd=tmp_path, capture_output=True)

    site = Path(subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        check=True, capture_output=True, text=True, env=env).stdout.strip())
    assert site.is_relative_to(venv)
    code = """
import importlib.metadata as metadata, impactkit
distribution = metadata.distribution("impactkit")
print(impactkit.__file__)
print(impactkit.__version__, distribution.version, distribution.metadata["License"])
print(sorted(str(f) for f in distribution.files if not str(f).endswith(".pyc")))
print(distribution.read_text("LICENSE").splitlines()[0])
"""
    where, versions, files, license_line = subprocess.run(
        [str(python), "-c", code], check=True, capture_output=True, text=True, env=env,
        cwd=tmp_path).stdout.splitlines()
    assert Path(where) == site / "impactkit" / "__init__.py"
    cmake = (SOURCE / "CMakeLists.txt").read_text()
    version = versions.split()[0]
    assert f"project(impactkit VERSION {version} " in cmake
    assert versions.split()[1:] == [version, "BSD-3-Clause"]
    for name in ("impactkit/__init__.py", "impactkit/_tables.py", "impactkit/__init__.pyi",
                 "impactkit/py.typed", "impactkit-%s.dist-info/LICENSE" % version):
        assert f"'{name}'" in files, name
    assert "impactkit/_impactkit.cpython-" in files
    assert license_line == "BSD 3-Clause License"
    assert (site / "impactkit" / "__init__.pyi").read_text() == \
        (SOURCE / "python" / "impactkit.pyi").read_text()

    # The Python tests against the installed package, from outside the
    # checkout (IMPACTKIT_CLI and the rest as ctest gives them).
    tests = sorted(str(path) for path in TESTS.glob("test_*.py") if path.name not in SKIPPED)
    run = subprocess.run([str(python), "-m", "pytest", "-q", "-p", "no:cacheprovider", *tests],
                         env=env, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout[-5000:] + run.stderr[-2000:]

    subprocess.run([str(pip), "uninstall", "-y", "impactkit"], check=True, env=env,
                   capture_output=True)
    assert not any(site.glob("impactkit*")), list(site.glob("impactkit*"))
    where = subprocess.run([str(python), "-c", "import impactkit; print(impactkit.__file__)"],
                           env=env, cwd=tmp_path, capture_output=True, text=True)
    assert where.returncode != 0 or not Path(where.stdout.strip()).is_relative_to(venv)
