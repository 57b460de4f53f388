"""Fixtures for the hexapod suite: the spdfit CLI named by SPDFIT_CLI, run in a scratch directory."""
import json
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))
from spdfit_testing import SANITIZED, SLOWDOWN, SOURCE_DIR, cli_path, run_cli  # noqa: E402

# The independent NumPy implementations of the thesis' algorithms and generator.
sys.path.insert(0, str(SOURCE_DIR / "tests" / "reference"))
# The docs' full-size runs (thousands of Monte Carlo trials per command, the demo's tables) check
# the published numbers, which the plain build does. Under the sanitizers they took over 15 of
# CI's minutes; the same code runs there at small trial counts in test_cli_contract.py.
full_size = pytest.mark.skipif(SANITIZED, reason="full-size doc runs are checked in the plain build")
CLI_TIMEOUT_S = 120 * SLOWDOWN  # the slowest call here (the demo) takes a few seconds


@pytest.fixture(scope="session")
def spdfit_cli():
    return cli_path()


@pytest.fixture
def cli(spdfit_cli, tmp_path):
    """cli(*args, expect=0, cwd=tmp_path) -> CompletedProcess of `spdfit args...`, asserting its exit status."""
    def run(*args, expect=0, cwd=None):
        proc = run_cli(spdfit_cli, *args, timeout_s=120, cwd=cwd or tmp_path)
        assert proc.returncode == expect, (
            f"spdfit {' '.join(map(str, args))} exited {proc.returncode}, expected {expect}\n"
            f"stdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
        return proc
    return run


@pytest.fixture
def cli_json(cli):
    """cli_json(*args) -> the parsed JSON that `spdfit args... --json` prints."""
    def run(*args):
        return json.loads(cli(*args, "--json").stdout)
    return run


def read_csv(path):
    return np.loadtxt(path, delimiter=",", ndmin=2)
