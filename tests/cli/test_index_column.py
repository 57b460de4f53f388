"""Issue 18: a pandas or R index column is never fitted as data. A header whose first cell is
empty drops it with a warning; row numbers 0, 1, 2, ... under another header are refused with a
message naming --index-col; --index-col and --no-index-col say it explicitly (also after the
command, and with --stream); Python's read_matrix(index_col=...) does the same."""
import json

import numpy as np
import pytest

X_TRUE = np.array([[2.0, 0.5], [0.5, 1.0]])


@pytest.fixture
def pandas_files(tmp_path):
    rng = np.random.default_rng(18)
    A = rng.standard_normal((30, 2))
    B = A @ X_TRUE + 1e-3 * rng.standard_normal((30, 2))

    def write(name, M, header, index=True):
        lines = [header] + [(f"{i}," if index else "") + ",".join(repr(v) for v in row) for i, row in enumerate(M)]
        (tmp_path / name).write_text("\n".join(lines) + "\n")
        return str(tmp_path / name)

    return {
        "A": write("A.csv", A, ",Fx,Fy"),            # df.to_csv()
        "B": write("B.csv", B, ",ax,ay"),
        "A_numbered": write("A0.csv", A, ",0,1"),    # pd.DataFrame(A).to_csv()
        "A_labelled": write("Ai.csv", A, "i,Fx,Fy"),  # df.to_csv(index_label="i")
        "B_plain": write("Bp.csv", B, "ax,ay", index=False),
        "B_labelled": write("Bi.csv", B, "i,ax,ay"),
        "A_plain": write("Ap.csv", A, "Fx,Fy", index=False),
        "expected": np.linalg.lstsq(A, B, rcond=None)[0],
    }


def test_an_empty_first_header_cell_drops_the_index_with_a_warning(spdfit, pandas_files):
    for a in (pandas_files["A"], pandas_files["A_numbered"]):
        result = spdfit("fit", "--method", "ls", a, pandas_files["B"])
        assert result.returncode == 0, result.stderr
        X = np.loadtxt(result.stdout.splitlines(), delimiter=",")
        assert X.shape == (2, 2)
        np.testing.assert_allclose(X, pandas_files["expected"], rtol=1e-12)
        assert "the first column holds row labels" in result.stderr
        streamed = spdfit("fit", "--stream", "--method", "ls", a, pandas_files["B"])
        assert streamed.returncode == 0 and "the first column holds row labels" in streamed.stderr
        np.testing.assert_allclose(np.loadtxt(streamed.stdout.splitlines(), delimiter=","), X, rtol=1e-12)


def test_row_numbers_under_another_header_are_refused(spdfit, pandas_files):
    result = spdfit("fit", "--method", "ls", pandas_files["A_labelled"], pandas_files["B_plain"])
    assert result.returncode == 1
    assert "Ai.csv:2:1: the first column is 0, 1, 2, ..." in result.stderr and "--index-col" in result.stderr
    streamed = spdfit("fit", "--stream", "--method", "ls", pandas_files["A_labelled"], pandas_files["B_plain"])
    assert streamed.returncode == 1 and "--index-col" in streamed.stderr
    # --index-col applies to every file of the command.
    for args in (["--index-col", "fit"], ["fit", "--index-col"]):
        ok = spdfit(*args, "--method", "ls", pandas_files["A_labelled"], pandas_files["B_labelled"])
        assert ok.returncode == 0, ok.stderr
        np.testing.assert_allclose(np.loadtxt(ok.stdout.splitlines(), delimiter=","), pandas_files["expected"],
                                   rtol=1e-12)


def test_no_index_col_keeps_the_first_column_as_data(spdfit, pandas_files):
    # Asked for, the index is data: a 3-column A against 3 columns of B is what the user gets.
    result = spdfit("solve", "--no-index-col", "--json", pandas_files["A_labelled"], pandas_files["B_plain"])
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["n"] == 3 and "row labels" not in result.stderr
    both = spdfit("--index-col", "--no-index-col", "fit", pandas_files["A"], pandas_files["B"])
    assert both.returncode == 2


def test_covariance_from_pandas_cov(spdfit, tmp_path):
    # df.cov().to_csv(): row labels that are the column names are a labelled matrix, which nearest
    # reads as such without a word; other row labels are still dropped with the notice.
    path = tmp_path / "C.csv"
    path.write_text(",x1,x2\nx1,2.0,0.5\nx2,0.5,-1.0\n")
    result = spdfit("nearest", "--min-eig", "0", str(path))
    assert result.returncode == 0, result.stderr
    assert np.loadtxt(result.stdout.splitlines(), delimiter=",").shape == (2, 2)
    assert "the first column holds row labels" not in result.stderr
    other = tmp_path / "D.csv"
    other.write_text(",x1,x2\na,2.0,0.5\nb,0.5,-1.0\n")
    result = spdfit("nearest", "--min-eig", "0", str(other))
    assert result.returncode == 0, result.stderr
    assert "the first column holds row labels" in result.stderr


def test_python_read_matrix(pandas_files):
    spdfit = pytest.importorskip("spdfit")
    with pytest.warns(spdfit.SpdfitWarning, match="row labels"):
        assert spdfit.read_matrix(pandas_files["A"]).shape == (30, 2)
    with pytest.raises(spdfit.DataError, match="--index-col"):
        spdfit.read_matrix(pandas_files["A_labelled"])
    assert spdfit.read_matrix(pandas_files["A_labelled"], index_col=True).shape == (30, 2)
    assert spdfit.read_matrix(pandas_files["A_labelled"], index_col=False).shape == (30, 3)
    values, names = spdfit.read_table(pandas_files["A_plain"])
    assert names == ["Fx", "Fy"] and values.shape == (30, 2)
