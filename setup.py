"""The build behind `pip install .` (pyproject.toml): setuptools packages the pure-Python files of
python/spdfit and the compiled spdfit._spdfit, which the project's own CMake build makes.

Where _spdfit comes from:

  SPDFIT_BUILD_DIR=DIR  an existing CMake build tree of this source tree (CI's build/): its target
                        _spdfit is brought up to date (`cmake --build DIR --target _spdfit`, which
                        does nothing when it is) and packaged, so that nothing is built twice;
  otherwise             build-pip/ in the source tree, configured for the library and the module
                        only (Release; CMAKE_ARGS adds options, e.g.
                        CMAKE_ARGS=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache) and kept, so that the next
                        `pip install .` rebuilds only what changed.

The module is built for the interpreter that runs this build (pip's; SPDFIT_PYTHON in CMake).
setuptools' own staging goes into that CMake build tree too, not into build/ beside it.
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version in CMakeLists.txt's `project(spdfit VERSION x.y.z ...)`, its one home (the C++
    headers, the CLI and spdfit.__version__ get it from there too)."""
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*spdfit\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", text)
    if not match:
        raise SystemExit("setup.py: CMakeLists.txt has no `project(spdfit VERSION ...)`")
    return match.group(1)


def cache_entry(build_dir, name):
    """The value of `name` in build_dir's CMakeCache.txt, or None."""
    for line in (build_dir / "CMakeCache.txt").read_text().splitlines():
        key, _, value = line.partition("=")
        if key.split(":", 1)[0] == name:
            return value
    return None


def given_build_dir():
    """SPDFIT_BUILD_DIR, checked: a configured build tree of this source tree, with the module, not
    sanitized (a sanitized module only loads with the sanitizer runtime preloaded)."""
    build_dir = pathlib.Path(os.environ["SPDFIT_BUILD_DIR"]).resolve()
    if not (build_dir / "CMakeCache.txt").is_file():
        raise SystemExit(f"setup.py: SPDFIT_BUILD_DIR={build_dir} is not a configured CMake build tree")
    source = cache_entry(build_dir, "CMAKE_HOME_DIRECTORY")
    if source is None or pathlib.Path(source).resolve() != ROOT:
        raise SystemExit(f"setup.py: SPDFIT_BUILD_DIR={build_dir} was configured for the sources in {source}, "
                         f"not {ROOT}")
    if cache_entry(build_dir, "SPDFIT_BUILD_PYTHON") not in ("ON", "TRUE", "1"):
        raise SystemExit(f"setup.py: SPDFIT_BUILD_DIR={build_dir} does not build the Python module "
                         "(configure it with -DSPDFIT_BUILD_PYTHON=ON)")
    if cache_entry(build_dir, "SPDFIT_SANITIZE") in ("ON", "TRUE", "1"):
        raise SystemExit(f"setup.py: SPDFIT_BUILD_DIR={build_dir} is a sanitizer build; give a plain one")
    return build_dir


# The CMake build tree that makes _spdfit (see the module's docstring).
GIVEN = "SPDFIT_BUILD_DIR" in os.environ
CMAKE_BUILD_DIR = given_build_dir() if GIVEN else ROOT / "build-pip"


class CMakeBuild(build_ext):
    """build_ext that gets spdfit._spdfit from the CMake build instead of compiling sources."""

    def build_extension(self, ext):
        if not GIVEN:
            configure = ["cmake", "-S", str(ROOT), "-B", str(CMAKE_BUILD_DIR), "-DCMAKE_BUILD_TYPE=Release",
                         "-DSPDFIT_BUILD_PYTHON=ON", "-DSPDFIT_BUILD_APPS=OFF", "-DSPDFIT_BUILD_TESTS=OFF",
                         "-DSPDFIT_BUILD_BENCHMARKS=OFF", f"-DSPDFIT_PYTHON={sys.executable}",
                         *shlex.split(os.environ.get("CMAKE_ARGS", ""))]
            subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(CMAKE_BUILD_DIR), "--target", "_spdfit"], check=True)

        # The module for this interpreter's ABI (e.g. _spdfit.cpython-311-x86_64-linux-gnu.so).
        package_dir = CMAKE_BUILD_DIR / "python" / "spdfit"
        built = package_dir / ("_spdfit" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            found = ", ".join(p.name for p in package_dir.glob("_spdfit*.so")) or "none"
            raise SystemExit(f"setup.py: {CMAKE_BUILD_DIR} has no {built.name} for {sys.executable} (found: "
                             f"{found}); configure it with -DSPDFIT_PYTHON={sys.executable}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)
        # The type stubs as the build wrote them (their option keywords come from the library's
        # tables), in place of the sources that build_py copied.
        for stub in package_dir.glob("*.pyi"):
            shutil.copyfile(stub, target.parent / stub.name)


setup(
    version=project_version(),
    ext_modules=[Extension("spdfit._spdfit", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(CMAKE_BUILD_DIR / "setuptools")},
             "egg_info": {"egg_base": str(CMAKE_BUILD_DIR / "setuptools")}},
)
