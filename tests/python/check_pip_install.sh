#!/usr/bin/env bash
# `pip install .` as a Python user runs it (issue 18): into a fresh virtual environment of PYTHON
# that sees Debian's NumPy (--system-site-packages), without a package index or build isolation,
# packaging the _spdfit of the CMake build tree BUILD (SPDFIT_BUILD_DIR, see setup.py) rather than
# building it a second time. Then, from outside the source tree: the package imported is the one
# installed in the environment, its extension is BUILD's byte for byte, its version is VERSION
# (CMake's project version) as spdfit.__version__ and as the installed metadata, the type stubs
# are there, and spdfit.fit works. The environment is removed at the end, pass or fail.
# Usage: check_pip_install.sh BUILD VERSION [PYTHON]
set -euo pipefail
build=$(cd "$1" && pwd)
version=$2
python=${3:-/usr/bin/python3}
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
unset PYTHONPATH  # ctest's points at the build tree's package; this test is about the installed one

"$python" -m venv --system-site-packages "$scratch/venv"
if ! SPDFIT_BUILD_DIR="$build" "$scratch/venv/bin/python" -m pip install --no-index --no-build-isolation \
      --no-cache-dir "$source_dir" >"$scratch/pip.log" 2>&1; then
  cat "$scratch/pip.log" >&2
  echo "check_pip_install: pip install failed (its output above)" >&2
  exit 1
fi

cd "$scratch"
"$scratch/venv/bin/python" - "$build" "$version" "$source_dir" <<'PYTHON'
import importlib.metadata
import pathlib
import sys
import sysconfig

import numpy as np

import spdfit
import spdfit.experiment
import spdfit.hexapod
import spdfit.linkage

build, version, source = pathlib.Path(sys.argv[1]), sys.argv[2], pathlib.Path(sys.argv[3])
assert sys.prefix != sys.base_prefix, "not running in the virtual environment"

site = pathlib.Path(sysconfig.get_paths()["platlib"]).resolve()
package = pathlib.Path(spdfit.__file__).resolve().parent
assert package == site / "spdfit", f"spdfit was imported from {package}, not from the environment's {site}"
for module in (spdfit._spdfit, spdfit.experiment, spdfit.hexapod, spdfit.linkage):
    assert pathlib.Path(module.__file__).resolve().parent == package, module.__file__

extension = pathlib.Path(spdfit._spdfit.__file__).resolve()
built = build / "python" / "spdfit" / extension.name
assert extension.read_bytes() == built.read_bytes(), f"{extension} is not {built}: built again?"

assert spdfit.__version__ == version, f"spdfit.__version__ is {spdfit.__version__}, CMake's version {version}"
installed = importlib.metadata.version("spdfit")
assert installed == version, f"the installed metadata says {installed}, CMake's version is {version}"

expected = {p.name for p in (source / "python" / "spdfit").iterdir() if p.suffix in (".py", ".pyi") or p.name == "py.typed"}
present = {p.name for p in package.iterdir()}
assert expected <= present, f"not installed: {sorted(expected - present)}"

A = np.array([[5.0, 2.0], [-3.0, 1.0], [1.0, -2.0], [-1.0, 1.0]])
X = np.array([[3.0, 1.0], [1.0, 1.0]])
result = spdfit.fit(A, A @ X, method="spde")
assert result.ok and np.allclose(result.X, X, rtol=1e-12), result
print(f"check_pip_install: spdfit {version} installed in {site} and working")
PYTHON
