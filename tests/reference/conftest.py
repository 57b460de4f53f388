"""Fixtures for running the spdfit CLI named by the SPDFIT_CLI environment variable."""
import os
import subprocess

import numpy as np
import pytest

# The sanitizer build (scripts/sanitize.sh sets SPDFIT_SANITIZED=1) runs the CLI about twenty
# times slower.
SLOWDOWN = 20 if os.environ.get("SPDFIT_SANITIZED") == "1" else 1
CLI_TIMEOUT_S = 60 * SLOWDOWN  # generous: every call here is a tiny dense problem


@pytest.fixture(scope="session")
def spdfit_cli():
    """Path of the spdfit executable; skips the CLI comparison tests when SPDFIT_CLI is unset."""
    path = os.environ.get("SPDFIT_CLI")
    if not path:
        pytest.skip("SPDFIT_CLI is not set; export SPDFIT_CLI=/path/to/spdfit to compare "
                    "the CLI with the NumPy reference")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        pytest.fail(f"SPDFIT_CLI={path!r} is not an executable file")
    return path


@pytest.fixture(scope="session")
def run_cli(spdfit_cli):
    """run_cli(*args) -> stdout of `spdfit args...`; fails the test unless it exits 0."""
    def run(*args):
        cmd = [spdfit_cli, *map(str, args)]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=CLI_TIMEOUT_S)
        assert proc.returncode == 0, (
            f"{' '.join(cmd)} exited {proc.returncode}\nstdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
        return proc.stdout
    return run


@pytest.fixture(scope="session")
def write_csv(tmp_path_factory):
    """write_csv(name, M) -> path of M saved with round-trip precision."""
    root = tmp_path_factory.mktemp("spdfit_inputs")

    def write(name, M):
        path = root / f"{name}.csv"
        np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g")
        return path
    return write
