"""Fixtures for running the spdfit CLI named by the SPDFIT_CLI environment variable."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

import pytest

import spdfit_testing
from spdfit_testing import cli_path, save_csv

CLI_TIMEOUT_S = 60  # generous: every call here is a tiny dense problem (scaled for the sanitizers)


@pytest.fixture(scope="session")
def spdfit_cli():
    """Path of the spdfit executable; skips the CLI comparison tests when SPDFIT_CLI is unset."""
    return cli_path()


@pytest.fixture(scope="session")
def run_cli(spdfit_cli):
    """run_cli(*args) -> stdout of `spdfit args...`; fails the test unless it exits 0."""
    def run(*args):
        proc = spdfit_testing.run_cli(spdfit_cli, *args, timeout_s=CLI_TIMEOUT_S)
        assert proc.returncode == 0, (
            f"spdfit {' '.join(map(str, args))} exited {proc.returncode}\nstdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
        return proc.stdout
    return run


@pytest.fixture(scope="session")
def write_csv(tmp_path_factory):
    """write_csv(name, M) -> path of M saved with round-trip precision."""
    root = tmp_path_factory.mktemp("spdfit_inputs")

    def write(name, M):
        return save_csv(root / f"{name}.csv", M)
    return write
