"""`cmake --install` puts the package where Debian's python3 finds it: the
installed package imports from <prefix>/lib/python3.X/dist-packages alone
(a directory on Debian's sys.path for the default /usr/local prefix),
computes what the built one does, and carries its metadata and license."""

import os
import subprocess
import sys

import numpy as np

import impactkit


def test_installed_module_imports_and_agrees(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run([os.environ["IMPACTKIT_CMAKE"], "--install", os.environ["IMPACTKIT_BUILD_DIR"],
                    "--prefix", str(prefix)], check=True, capture_output=True)
    site = prefix / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "dist-packages"
    for name in ("__init__.py", "_tables.py", "__init__.pyi", "py.typed"):
        assert (site / "impactkit" / name).is_file(), name
    code = ("import impactkit, sys; o = impactkit.find_orbit(impactkit.System.paper(0.6)); "
            "print(impactkit.__file__); print(*[x.hex() for x in o.eta])")
    run = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                         cwd=tmp_path, env={"PYTHONPATH": str(site), "PATH": os.environ["PATH"]})
    where, eta = run.stdout.splitlines()
    assert where.startswith(str(site))
    here = impactkit.find_orbit(impactkit.System.paper(0.6)).eta
    np.testing.assert_array_equal([float.fromhex(x) for x in eta.split()], here)
    # The distribution's metadata is installed beside it: pip and
    # importlib.metadata see its version and its license, whose text it carries.
    code = ("import importlib.metadata as m; d = m.distribution('impactkit'); "
            "print(d.version); print(d.metadata['License-Expression']); "
            "print(d.read_text('licenses/LICENSE').splitlines()[0])")
    run = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                         cwd=tmp_path, env={"PYTHONPATH": str(site), "PATH": os.environ["PATH"]})
    assert run.stdout.splitlines() == [impactkit.__version__, "BSD-3-Clause", "BSD 3-Clause License"]
    # With the default prefix the same relative directory is on sys.path.
    assert f"/usr/local/lib/python{sys.version_info.major}.{sys.version_info.minor}/dist-packages" \
        in subprocess.run([sys.executable, "-c", "import sys; print(sys.path)"], check=True,
                          capture_output=True, text=True, env={}).stdout
