"""pandas' header of a frame without column names: pd.DataFrame(A).to_csv(index=False) writes the
first line 0,1,...,k-1, which is read as column names (with a warning naming the line), never as a
row of data; --no-header reads the first line as data. A one-column file starting with 0 is data.
nearest on a matrix with one row too many points at the line that looks like a header."""
import json

import numpy as np
import pytest

X_TRUE = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])
# The fits below solve exact systems of a few rows: agreement to rounding.
EXACT_RTOL = 1e-10


def to_csv_unnamed(path, M):
    """What pandas' DataFrame(M).to_csv(path, index=False) writes: the header 0,1,... then the rows."""
    header = ",".join(str(j) for j in range(M.shape[1]))
    path.write_text(header + "\n" + "".join(",".join(repr(float(v)) for v in row) + "\n" for row in M))
    return str(path)


@pytest.fixture
def unnamed(tmp_path):
    rng = np.random.default_rng(35)
    A = rng.uniform(-5, 5, (20, 3))
    B = A @ X_TRUE + 1e-3 * rng.standard_normal((20, 3))
    return {"A": to_csv_unnamed(tmp_path / "A.csv", A), "B": to_csv_unnamed(tmp_path / "B.csv", B),
            "arrays": (A, B)}


def test_the_header_0_to_k_minus_1_is_not_a_sample(spdfit, unnamed):
    A, B = unnamed["arrays"]
    result = spdfit("fit", "--method", "ls", "--json", unnamed["A"], unnamed["B"])
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["m"] == 20
    np.testing.assert_allclose(np.array(out["X"]), np.linalg.lstsq(A, B, rcond=None)[0], rtol=EXACT_RTOL)
    assert "A.csv:1: the first line, '0,1,2', is read as a header row" in result.stderr
    assert "--no-header" in result.stderr
    # The same through the streaming reader.
    streamed = spdfit("fit", "--stream", "--method", "ls", unnamed["A"], unnamed["B"])
    assert streamed.returncode == 0, streamed.stderr
    assert "A.csv:1: the first line" in streamed.stderr
    np.testing.assert_allclose(np.loadtxt(streamed.stdout.splitlines(), delimiter=","),
                               np.linalg.lstsq(A, B, rcond=None)[0], rtol=EXACT_RTOL)


def test_no_header_reads_the_first_line_as_data(spdfit, unnamed):
    A, B = unnamed["arrays"]
    for args in (["--no-header", "fit"], ["fit", "--no-header"]):
        result = spdfit(*args, "--method", "ls", "--json", unnamed["A"], unnamed["B"])
        assert result.returncode == 0, result.stderr
        X = np.array(json.loads(result.stdout)["X"])
        A1 = np.vstack([np.arange(3.0), A])
        B1 = np.vstack([np.arange(3.0), B])
        np.testing.assert_allclose(X, np.linalg.lstsq(A1, B1, rcond=None)[0], rtol=EXACT_RTOL)
        assert "header" not in result.stderr


def test_a_single_column_starting_with_0_is_data(spdfit, tmp_path):
    a = tmp_path / "a.csv"
    a.write_text("0\n1\n2\n4\n")
    b = tmp_path / "b.csv"
    b.write_text("1\n3\n5\n9\n")
    result = spdfit("fit", "--method", "ls", "--json", str(a), str(b))
    assert result.returncode == 0, result.stderr
    assert "header" not in result.stderr
    x = np.array(json.loads(result.stdout)["X"])
    np.testing.assert_allclose(x, np.linalg.lstsq(np.array([[0.0], [1], [2], [4]]),
                                                  np.array([[1.0], [3], [5], [9]]), rcond=None)[0],
                               rtol=EXACT_RTOL)


def test_other_number_rows_stay_data(spdfit, tmp_path):
    # 1,2,3 (not pandas' 0-based names) and 0,2,1 (not in order) are data, with no warning.
    for first in ("1,2,3", "0,2,1"):
        path = tmp_path / "C.csv"
        path.write_text(first + "\n4,5,6\n7,8,10\n")
        result = spdfit("solve", str(path), str(path))
        assert result.returncode == 0, result.stderr
        assert "header" not in result.stderr


def test_nearest_on_pandas_corr_without_names(spdfit, tmp_path):
    # df.corr().to_csv(index=False) for a frame made from an array: an 8x8 matrix under 0,...,7.
    rng = np.random.default_rng(8)
    C = np.corrcoef(rng.standard_normal((8, 40)))
    path = to_csv_unnamed(tmp_path / "corr.csv", C)
    result = spdfit("nearest", "--corr", path)
    assert result.returncode == 0, result.stderr
    assert np.loadtxt(result.stdout.splitlines(), delimiter=",").shape == (8, 8)
    assert "corr.csv:1: the first line, 0, 1, ..., 7, is read as a header row" in result.stderr
    # With --no-header the first line is a row: 9x8, and the message says which line to look at.
    refused = spdfit("--no-header", "nearest", "--corr", path)
    assert refused.returncode == 1
    assert "X is 9x8: a square matrix is needed; line 1, its first row, looks like a header" in refused.stderr
    # A header of other numbers (1-based names) is data: the same pointer, without the option.
    other = tmp_path / "corr1.csv"
    other.write_text(",".join(str(j + 1) for j in range(8)) + "\n" + "\n".join(
        ",".join(repr(float(v)) for v in row) for row in C) + "\n")
    result = spdfit("nearest", "--corr", str(other))
    assert result.returncode == 1
    assert "line 1, its first row, looks like a header of column names: delete it" in result.stderr
