"""Fixtures for the linear-system and linkage tests: the spdfit binary (SPDFIT_CLI), the source
tree (SPDFIT_SOURCE_DIR), a runner and a CSV writer."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

# The sanitizer build (scripts/sanitize.sh sets SPDFIT_SANITIZED=1) runs the CLI about twenty
# times slower.
SLOWDOWN = 20 if os.environ.get("SPDFIT_SANITIZED") == "1" else 1

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def spdfit():
    """spdfit(*args) -> CompletedProcess of the CLI run in the source tree."""
    path = os.environ.get("SPDFIT_CLI")
    if not path:
        pytest.skip("SPDFIT_CLI is not set (ctest sets it to the built spdfit)")
    assert os.access(path, os.X_OK), f"SPDFIT_CLI={path} is not an executable"

    def run(*args):
        return subprocess.run([path, *map(str, args)], capture_output=True, text=True, timeout=120 * SLOWDOWN, cwd=ROOT)

    return run


@pytest.fixture(scope="session")
def spdfit_json(spdfit):
    """spdfit_json(*args) -> the parsed JSON of a run that must succeed (--json is added)."""
    def run(*args):
        result = spdfit(*args, "--json")
        assert result.returncode == 0, (args, result.stderr)
        return json.loads(result.stdout)

    return run


@pytest.fixture
def write_csv(tmp_path):
    """write_csv(name, M, header=None) -> path of M saved with round-trip precision."""
    def write(name, M, header=None):
        path = tmp_path / name
        np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g",
                   header=header or "", comments="")
        return path

    return write


def fails(result, status, *fragments):
    """The run failed with `status`, printed nothing on stdout, and named every fragment."""
    assert result.returncode == status, (result.returncode, result.stdout, result.stderr)
    assert result.stdout == ""
    assert result.stderr.startswith("spdfit: error: "), result.stderr
    for fragment in fragments:
        assert str(fragment) in result.stderr, (fragment, result.stderr)
