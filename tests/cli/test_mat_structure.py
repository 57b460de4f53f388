"""spdfit checks a level-5 .mat file's structure the way libmatio reads it (tests/errors/
test_mat_hostile.py: the damaged files it refuses, within bounded memory): its messages name the
variable, fuzz/regressions/mat keeps the crafted files' bytes for the fuzz target (which the
sanitizer build replays under libFuzzer's 2 GB allocation limit), and every kind of array MATLAB
and scipy write still passes."""
import json
import pathlib
import sys

import numpy as np
import pytest
import scipy.io
import scipy.sparse

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

import level5_mat  # noqa: E402
from spdfit_testing import SOURCE_DIR  # noqa: E402

REGRESSIONS = SOURCE_DIR / "fuzz" / "regressions" / "mat"


def test_the_message_names_the_variable_once_its_name_is_read(spdfit, tmp_path):
    path = tmp_path / "s.mat"
    path.write_bytes(level5_mat.CRAFTED["field_with_a_name.mat"][0])
    assert "(variable 's': a struct field with a name of its own)" in spdfit("fit", "--method", "ls", path, path).stderr
    # Before the name: its number in the file.
    path.write_bytes(level5_mat.CRAFTED["flags_of_16_bytes.mat"][0])
    assert "(variable number 1: an array's flags" in spdfit("fit", "--method", "ls", path, path).stderr


@pytest.mark.parametrize("file", sorted(level5_mat.CRAFTED))
def test_the_fuzz_regressions_are_the_crafted_files(file):
    # The sanitizer build replays fuzz/regressions/mat through fuzz_mat: the same bytes.
    assert (REGRESSIONS / file).read_bytes() == level5_mat.CRAFTED[file][0]


def test_an_opaque_object_as_matlab_writes_it_does_not_stop_the_file(spdfit, tmp_path):
    # A MATLAB string (an opaque object: no dimensions after its flags) next to the matrix.
    path = tmp_path / "string.mat"
    path.write_bytes(level5_mat.MATLAB_STRING_AND_MATRIX)
    result = spdfit("fit", "--method", "ls", "--json", path, path)
    assert result.returncode == 0, result.stderr
    # A = B = [2 .5; .5 1]: least squares gives the identity.
    np.testing.assert_allclose(json.loads(result.stdout)["X"], np.eye(2), atol=1e-12)


@pytest.mark.parametrize("compressed", [False, True])
def test_every_kind_of_array_scipy_writes_passes_the_check(spdfit, tmp_path, compressed):
    rng = np.random.default_rng(12)
    A = rng.standard_normal((12, 3))
    X = np.array([[2.0, 0.3, 0.0], [0.3, 1.0, 0.1], [0.0, 0.1, 1.5]])
    cells = np.empty((1, 3), dtype=object)
    cells[0, 0], cells[0, 1], cells[0, 2] = "text", scipy.sparse.eye(3, format="csc"), np.arange(4.0)
    path = tmp_path / "all.mat"
    scipy.io.savemat(path, {
        "A": A, "B": A @ X,
        "s": {"name": "rig", "gain": 2.5, "mask": np.array([True, False]), "inner": {"k": np.int16(3)}},
        "cells": cells,
        "sp": scipy.sparse.random(5, 4, density=0.4, random_state=3, format="csc"),
        "spc": scipy.sparse.csc_matrix(np.array([[1 + 2j, 0], [0, 3 - 1j]])),
        "z": np.array([[1 + 1j, 2]]), "words": np.array(["ab", "cd"]), "empty": np.zeros((0, 3)),
        "structs": np.array([({"a": 1.0},), ({"a": 2.0},)], dtype=[("f", object)]),
    }, do_compression=compressed)
    result = spdfit("fit", "--method", "ls", "--json", f"{path}:A", f"{path}:B")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(json.loads(result.stdout)["X"], X, atol=1e-10)
