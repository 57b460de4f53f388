"""Fixtures for the linear-system and linkage tests: the spdfit binary (SPDFIT_CLI), the source
tree (SPDFIT_SOURCE_DIR), a runner and a CSV writer."""
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

import pytest

from spdfit_testing import SOURCE_DIR, cli_path, run_cli, save_csv

ROOT = SOURCE_DIR


@pytest.fixture(scope="session")
def spdfit():
    """spdfit(*args) -> CompletedProcess of the CLI run in the source tree."""
    path = cli_path()

    def run(*args):
        return run_cli(path, *args, timeout_s=120, cwd=ROOT)

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
        return save_csv(tmp_path / name, M, header)

    return write


def fails(result, status, *fragments):
    """The run failed with `status`, printed nothing on stdout, and named every fragment."""
    assert result.returncode == status, (result.returncode, result.stdout, result.stderr)
    assert result.stdout == ""
    assert result.stderr.startswith("spdfit: error: "), result.stderr
    for fragment in fragments:
        assert str(fragment) in result.stderr, (fragment, result.stderr)
