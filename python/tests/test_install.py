"""`cmake --install` puts the module where Debian's python3 finds it: the
installed module imports from <prefix>/lib/python3.X/dist-packages alone
(a directory on Debian's sys.path for the default /usr/local prefix) and
computes what the built one does."""

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
    assert (site / "impactkit.pyi").is_file()
    code = ("import impactkit, sys; o = impactkit.find_orbit(impactkit.System.paper(0.6)); "
            "print(impactkit.__file__); print(*[x.hex() for x in o.eta])")
    run = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                         cwd=tmp_path, env={"PYTHONPATH": str(site), "PATH": os.environ["PATH"]})
    where, eta = run.stdout.splitlines()
    assert where.startswith(str(site))
    here = impactkit.find_orbit(impactkit.System.paper(0.6)).eta
    np.testing.assert_array_equal([float.fromhex(x) for x in eta.split()], here)
    # With the default prefix the same relative directory is on sys.path.
    assert f"/usr/local/lib/python{sys.version_info.major}.{sys.version_info.minor}/dist-packages" \
        in subprocess.run([sys.executable, "-c", "import sys; print(sys.path)"], check=True,
                          capture_output=True, text=True, env={}).stdout
