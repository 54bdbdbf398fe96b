"""pip's build of the Python package (pyproject.toml): the native module bouncer._core is the
bouncer_python target of the CMake project, built here with cmake, and the pure-Python
package is python/bouncer.

Environment:
  BOUNCER_BUILD_DIR   an existing, configured CMake build tree of this source (e.g. build):
                      its bouncer_python target is brought up to date and used, instead of
                      configuring and building a tree of its own (which builds the library,
                      about 20 minutes on 2 cores).
  BOUNCER_BUILD_JOBS  parallel jobs of that build (default: the number of CPUs).
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    """The CMake project's version (CMakeLists.txt: project(bouncer VERSION x.y.z)), which the
    CLI prints with --version and the module has as bouncer.__version__."""
    text = (ROOT / "CMakeLists.txt").read_text()
    m = re.search(r"project\(\s*bouncer\s+VERSION\s+([0-9][0-9.]*)", text)
    if not m:
        raise RuntimeError("CMakeLists.txt: no project(bouncer VERSION x.y.z)")
    return m.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        jobs = os.environ.get("BOUNCER_BUILD_JOBS") or str(os.cpu_count() or 1)
        given = os.environ.get("BOUNCER_BUILD_DIR")
        if given:
            tree = Path(given).resolve()
            if not (tree / "CMakeCache.txt").is_file():
                raise RuntimeError(f"BOUNCER_BUILD_DIR={given}: not a configured CMake build tree (no CMakeCache.txt)")
        else:
            tree = Path(self.build_temp).resolve() / "cmake"
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release",
                            "-DBOUNCER_BUILD_TESTS=OFF", "-DBOUNCER_BUILD_BENCHMARKS=OFF", "-DBOUNCER_WITH_MPI=OFF",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(tree), "--target", "bouncer_python", "-j", jobs], check=True)
        built = tree / "python" / "bouncer" / ("_core" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            found = sorted(p.name for p in (tree / "python" / "bouncer").glob("_core*"))
            raise RuntimeError(f"{built} was not built (found: {found or 'nothing'}): the build tree's Python is not "
                               f"{sys.executable}, or it lacks pybind11-dev / python3-dev / python3-numpy")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


# setuptools' own scratch space, away from the CMake build tree build/: its build_base and the
# egg-info (which must exist beforehand). pip runs this file in the source directory.
SCRATCH = "build-pip"
os.makedirs(SCRATCH, exist_ok=True)

setup(
    version=project_version(),
    packages=["bouncer"],
    package_dir={"bouncer": "python/bouncer"},
    package_data={"bouncer": ["py.typed", "*.pyi"]},
    ext_modules=[Extension("bouncer._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": SCRATCH}, "egg_info": {"egg_base": SCRATCH}},
    zip_safe=False,
)
