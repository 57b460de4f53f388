"""Fixtures for the CLI tests: the spdfit binary (SPDFIT_CLI) and a runner."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

import numpy as np
import pytest

from spdfit_testing import cli_path, run_cli


@pytest.fixture(scope="session")
def spdfit():
    """spdfit(*args, input=None) -> CompletedProcess of the CLI."""
    path = cli_path()

    def run(*args, input=None):
        return run_cli(path, *args, input=input)

    return run


@pytest.fixture(scope="session")
def data():
    """A well-conditioned noisy problem (m = 9, n = 3) as arrays."""
    rng = np.random.default_rng(5)
    X = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])
    A0 = rng.uniform(-5, 5, (9, 3))
    return A0 + 0.1 * rng.standard_normal((9, 3)), A0 @ X + 0.1 * rng.standard_normal((9, 3))


def write_text(path, text, encoding="utf-8"):
    path.write_bytes(text.encode(encoding))
    return path
