"""pathlib.Path (any os.PathLike) is accepted wherever the module takes a file name (issue 18)."""
import pathlib

import numpy as np

import spdfit

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readers_and_writer_take_paths(tmp_path):
    a = ROOT / "examples" / "paper_2x2" / "A.csv"
    A = spdfit.read_matrix(a)
    assert np.array_equal(A, spdfit.read_matrix(str(a)))
    values, names = spdfit.read_table(a)
    assert np.array_equal(values, A) and isinstance(names, list)
    out = tmp_path / "X.csv"
    spdfit.write_csv(out, A)
    assert np.array_equal(spdfit.read_matrix(out), A)


def test_fit_files_takes_paths():
    a, b = ROOT / "examples" / "paper_2x2" / "A.csv", ROOT / "examples" / "paper_2x2" / "B.csv"
    assert np.array_equal(spdfit.fit_files(a, b, "spde").X, spdfit.fit_files(str(a), str(b), "spde").X)
