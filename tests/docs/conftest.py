"""Fixtures shared by the documentation tests."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def cli():
    """The spdfit executable under test (ctest sets SPDFIT_CLI)."""
    path = os.environ.get("SPDFIT_CLI")
    if not path:
        pytest.skip("SPDFIT_CLI is not set (ctest sets it)")
    return path
