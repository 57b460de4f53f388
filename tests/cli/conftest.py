"""Fixtures for the CLI tests: the spdfit binary (SPDFIT_CLI) and a runner."""
import os
import subprocess

import numpy as np
import pytest


# The sanitizer build (scripts/sanitize.sh sets SPDFIT_SANITIZED=1) runs the CLI about twenty
# times slower.
SLOWDOWN = 20 if os.environ.get("SPDFIT_SANITIZED") == "1" else 1


@pytest.fixture(scope="session")
def spdfit():
    path = os.environ.get("SPDFIT_CLI")
    if not path:
        pytest.skip("SPDFIT_CLI is not set (ctest sets it to the built spdfit)")
    assert os.access(path, os.X_OK), f"SPDFIT_CLI={path} is not an executable"

    def run(*args, input=None):
        return subprocess.run([path, *map(str, args)], capture_output=True, text=True, input=input, timeout=60 * SLOWDOWN)

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
