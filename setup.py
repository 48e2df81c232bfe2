"""pip's build of the impactkit package (pyproject.toml): setuptools, with
the compiled module built by the project's own CMake.

build_ext configures the checkout in build-pip/ (Release) without the
command-line tool, tests, benchmarks, examples and the peers they compare
against, builds the target impactkit_python alone (the library, its io and
the module; CMAKE_BUILD_PARALLEL_LEVEL jobs, by default one per core) and
puts the module into the package. build_py adds the type stubs
(python/impactkit.pyi, as impactkit/__init__.pyi) beside py.typed. The
version is project()'s in CMakeLists.txt, the one the CLI reports.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent


def project_version():
    match = re.search(r"^project\(impactkit VERSION ([0-9.]+)",
                      (ROOT / "CMakeLists.txt").read_text(), flags=re.M)
    if not match:
        raise RuntimeError("CMakeLists.txt: no project(impactkit VERSION ...)")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds impactkit._impactkit with CMake."""

    def build_extension(self, ext):
        cmake = os.environ.get("CMAKE", "cmake")
        build = Path(self.build_temp).resolve() / "cmake"
        subprocess.run([
            cmake, "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DIMPACTKIT_BUILD_APPS=OFF", "-DIMPACTKIT_BUILD_TESTS=OFF",
            "-DIMPACTKIT_BUILD_EXAMPLES=OFF", "-DIMPACTKIT_BUILD_BENCHMARKS=OFF",
            "-DIMPACTKIT_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}",
        ], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run([cmake, "--build", str(build), "--target", "impactkit_python", "-j", jobs],
                       check=True)
        built = sorted((build / "python" / "impactkit").glob("_impactkit*.so"))
        if not built:
            raise RuntimeError(f"CMake built no _impactkit module in {build}/python/impactkit "
                               "(is pybind11-dev installed? see its configure output above)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


class BuildPy(build_py):
    """The package's Python files and py.typed, and its stubs."""

    def run(self):
        super().run()
        self.copy_file(str(ROOT / "python" / "impactkit.pyi"),
                       str(Path(self.build_lib) / "impactkit" / "__init__.pyi"))


setup(
    version=project_version(),
    packages=["impactkit"],
    package_dir={"impactkit": "python/impactkit"},
    package_data={"impactkit": ["py.typed"]},
    ext_modules=[Extension("impactkit._impactkit", sources=[])],
    cmdclass={"build_ext": CMakeBuild, "build_py": BuildPy},
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)
