"""pathlib.Path (any os.PathLike) is accepted wherever the module takes a file name, and result
arrays are writable copies (issue 18)."""
import pathlib

import numpy as np
import pytest

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


def test_result_arrays_are_writable_copies():
    """Arrays in results are the caller's, as NumPy's are: writable, and writing to one leaves the
    result unchanged (issue 18)."""
    A = spdfit.read_matrix(ROOT / "examples" / "paper_2x2" / "A.csv")
    B = spdfit.read_matrix(ROOT / "examples" / "paper_2x2" / "B.csv")
    r = spdfit.fit(A, B, "spde")
    X = r.X
    assert X.flags.writeable and r.diagnostics.singular_values_a.flags.writeable
    before = X[0, 0]
    X[0, 0] = before + 1.0
    assert r.X[0, 0] == before
    assert spdfit.solve(A, B).solution.flags.writeable
    assert spdfit.nearest_spd(np.eye(2), full_output=True).X.flags.writeable


@pytest.mark.parametrize("dtype", ["float32", "int8", "int64", "uint16", "uint64", "bool", ">f4", ">i8"])
def test_read_matrix_converts_numeric_npy_as_numpy_does(tmp_path, dtype):
    # Issue 18: float32, integer and boolean .npy files read as numpy's astype(float) gives them.
    rng = np.random.default_rng(8)
    normal = rng.standard_normal((7, 3))
    values = (normal > 0) if dtype == "bool" else (normal * 1000).astype(dtype)
    np.save(tmp_path / "v.npy", values)
    np.testing.assert_array_equal(spdfit.read_matrix(tmp_path / "v.npy"), values.astype(float))
    np.save(tmp_path / "f.npy", np.asfortranarray(values))
    np.testing.assert_array_equal(spdfit.read_matrix(tmp_path / "f.npy"), values.astype(float))


def test_fit_files_names_x_by_the_files_columns(tmp_path):
    # Issue 18: rows of X named by A's columns, columns by B's; kept through pickling.
    import pickle
    rng = np.random.default_rng(9)
    A = rng.standard_normal((12, 2))
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", header="ax,ay", comments="")
    np.savetxt(tmp_path / "B.csv", A @ [[1.0, 2.0, 0.0], [0.0, 1.0, 1.0]], delimiter=",", header="f1,f2,f3",
               comments="")
    for stream in (False, True):
        r = spdfit.fit_files(tmp_path / "A.csv", tmp_path / "B.csv", "ls") if stream else \
            spdfit.fit_files(tmp_path / "A.csv", tmp_path / "B.csv", "ls", block_rows=5)
        assert (r.row_names, r.column_names) == (["ax", "ay"], ["f1", "f2", "f3"])
        back = pickle.loads(pickle.dumps(r))
        assert (back.row_names, back.column_names) == (r.row_names, r.column_names)
    assert spdfit.fit(A, A, "ls").row_names == []


def test_read_table_takes_pandas_unnamed_header_as_names(tmp_path):
    # pd.DataFrame(M).to_csv(path, index=False) writes 0,1,2 over the rows: names, with a warning.
    M = np.array([[1.5, 2.0, -3.0], [0.25, 4.0, 5.0]])
    path = tmp_path / "M.csv"
    path.write_text("0,1,2\n" + "".join(",".join(repr(v) for v in row) + "\n" for row in M))
    with pytest.warns(spdfit.SpdfitWarning, match=r"M.csv:1: the first line, '0,1,2', is read as a header row"):
        values, names = spdfit.read_table(path)
    assert names == ["0", "1", "2"]
    np.testing.assert_array_equal(values, M)
    # header=False: the first line is data; header=True: it is names whatever it holds.
    np.testing.assert_array_equal(spdfit.read_matrix(path, header=False), np.vstack([[0.0, 1.0, 2.0], M]))
    values, names = spdfit.read_table(path, header=True)
    assert names == ["0", "1", "2"] and values.shape == (2, 3)
    (tmp_path / "N.csv").write_text("7,8\n1,2\n")
    assert spdfit.read_table(tmp_path / "N.csv", header=True)[1] == ["7", "8"]
    with pytest.raises(TypeError, match="header must be True, False or None, not str"):
        spdfit.read_matrix(path, header="yes")


def test_a_one_column_file_starting_with_0_is_data(tmp_path):
    path = tmp_path / "v.csv"
    path.write_text("0\n1\n2\n")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        np.testing.assert_array_equal(spdfit.read_matrix(path), [[0.0], [1.0], [2.0]])


def test_warnings_point_at_the_callers_line(tmp_path):
    import inspect
    import warnings
    path = tmp_path / "M.csv"
    path.write_text("0,1\n1.5,2\n3,4\n5,7\n")
    A = np.array([[1.0, 0.0], [0.0, 0.0], [2.0, 0.0]])  # rank-deficient: ls warns
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        spdfit.read_matrix(path)
        spdfit.least_squares(A, A)
    assert len(caught) >= 2
    for w in caught:
        assert w.filename == __file__, (w.filename, str(w.message))
    assert caught[0].lineno == line and caught[-1].lineno == line + 1


def test_a_nan_is_named_by_its_row_and_column():
    A = np.arange(12.0).reshape(6, 2)
    A[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"A contains NaN or Inf: NaN in row 3, column 2 \(counting from 1; "
                       r"A\[2, 1\] in NumPy\)"):
        spdfit.fit(A, np.ones((6, 2)), "spde")


def test_boolean_arrays_are_read_as_0_and_1():
    A = np.array([[True, False], [False, True], [True, True], [True, False], [False, True], [True, True]])
    B = A.astype(float) @ np.array([[2.0, 0.5], [0.5, 1.0]])
    np.testing.assert_allclose(spdfit.fit(A, B, "ls").X, np.linalg.lstsq(A.astype(float), B, rcond=None)[0],
                               rtol=1e-12)


def test_python_refuses_what_the_command_line_refuses():
    A = np.random.default_rng(1).standard_normal((20, 2))
    with pytest.raises(TypeError, match="method must be a str"):
        spdfit.fit(A, A, method=None)
    for name in ("bootstrap", "threads"):
        with pytest.raises(TypeError, match=f"{name} must be an int, got NoneType"):
            spdfit.fit(A, A, "ls", **{name: None})
    with pytest.raises(TypeError, match="not NoneType"):
        spdfit.read_matrix(None)
    for name, value in (("confidence", 0.9), ("seed", 3)):
        with pytest.raises(ValueError, match=f"{name} applies to the bootstrap"):
            spdfit.fit(A, A, "ls", **{name: value})
    with pytest.raises(TypeError, match="keep_diag must be a bool, got str"):
        spdfit.nearest_spd(np.eye(2), keep_diag="yes")
    with pytest.raises(ValueError, match=r"max_iter must be an integer in \[1, 1000000\], got 0"):
        spdfit.fit(A, A, "spd-tls", max_iter=0)


def test_fit_files_reader_warnings_are_not_prefixed_with_the_method(tmp_path):
    import warnings
    rng = np.random.default_rng(2)
    A = rng.uniform(-5, 5, (30, 2))
    B = A @ np.array([[2.0, 0.5], [0.5, 1.0]]) + 1e-3 * rng.standard_normal((30, 2))
    a = tmp_path / "A.csv"
    a.write_text("0,1\n" + "".join(f"{x!r},{y!r}\n" for x, y in A))
    np.save(tmp_path / "B.npy", B)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spdfit.fit_files(a, tmp_path / "B.npy", "spde")
    messages = [str(w.message) for w in caught]
    assert any(m.startswith(f"{a}:1: the first line, '0,1', is read as a header row") for m in messages), messages
