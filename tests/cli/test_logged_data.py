"""Data as it is logged (issue 42): the command line's answers to a logger's code for an invalid
reading (9.9e37) and to one entry of 1e160, and to a CSV export that quotes every cell. Each gives
the truth, a warning naming the rows and the fix, or a clear error; references are NumPy's least
squares and the fit of the rows the warning says to keep."""
import json

import numpy as np

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
# Agreement of two ways to the same arithmetic (different QR orders): rounding.
ROUNDING = 1e-10


def write_csv(path, M, quoted=False):
    rows = []
    for row in np.atleast_2d(M):
        cells = [repr(float(v)) for v in row]
        rows.append(",".join(f'"{c}"' for c in cells) if quoted else ",".join(cells))
    path.write_text("\n".join(rows) + "\n")
    return str(path)


def problem(m=50, seed=1, noise=0.01):
    rng = np.random.default_rng(seed)
    A = rng.uniform(-1, 1, (m, 3))
    B = A @ X_TRUE + noise * rng.standard_normal((m, 3))
    return A, B


def fit_json(spdfit, *args):
    result = spdfit("fit", "--json", *args)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout), result.stderr


def test_a_sentinel_is_named_with_the_rows_to_keep(spdfit, tmp_path):
    A, B = problem()
    A[16, 1] = 9.9e37
    a, b = write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B)
    result = spdfit("fit", "--method", "spde", "--json", a, b)
    assert "row 17 (9.9e+37 in A's column 2) holds a value of magnitude 1e30 or more" in result.stderr
    assert "(the rows 1:16,18:50, as --rows takes them without --time-col)" in result.stderr
    if result.returncode == 0:
        doc = json.loads(result.stdout)
        assert "logger" in " ".join(doc["warnings"]) and "outliers" in doc["warning_codes"]
    # The fix it names gives the truth (to the noise), and no warning.
    keep = np.r_[0:16, 17:50]
    out, err = fit_json(spdfit, "--method", "spde", write_csv(tmp_path / "A2.csv", A[keep]),
                        write_csv(tmp_path / "B2.csv", B[keep]))
    assert out["m"] == 49 and "1e30" not in err
    np.testing.assert_allclose(np.array(out["X"]), X_TRUE, atol=0.05)


def test_one_huge_entry_is_named_and_a_failure_points_at_it(spdfit, tmp_path):
    A, B = problem()
    A[4, 0] = 1e160
    a, b = write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B)
    result = spdfit("fit", "--method", "spde", "--json", a, b)
    assert "row 5 (1e+160 in A's column 1)" in result.stderr
    assert "(the rows 1:4,6:50, as --rows takes them without --time-col)" in result.stderr
    if result.returncode != 0:
        assert "values of magnitude 1e30 or more, which decide this" in result.stderr
    # compare says it once, not once per method.
    compared = spdfit("compare", a, b)
    assert compared.stderr.count("row 5 (1e+160") == 1, compared.stderr


def test_a_sentinel_in_b_is_named_too(spdfit, tmp_path):
    A, B = problem(seed=2)
    B[[3, 9], 2] = -9.9e37
    out, err = fit_json(spdfit, "--method", "ls", write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B))
    assert "rows 4 (-9.9e+37 in B's column 3), 10 (-9.9e+37 in B's column 3) hold" in err


def test_a_streamed_fit_says_a_sentinel_is_there(spdfit, tmp_path):
    # Streamed (and under the streaming bootstrap) no rows are kept to name: the warning says a code
    # is there and names the in-memory route; a fit the code breaks says why, not "B has rank 3 < 3".
    A, B = problem(m=200, seed=4)
    A[50, 1] = 9.9e37
    a, b = write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B)
    r = spdfit("fit", "--method", "ls", "--stream", "--block-rows", "16", a, b)
    assert r.returncode == 0, r.stderr
    assert "A holds a value of magnitude about 1e30 or more" in r.stderr and "without --stream" in r.stderr
    # (With a bootstrap of so few rows they are resampled in memory, and the row is named.)
    r = spdfit("fit", "--method", "ls", "--stream", "--bootstrap", "20", a, b)
    assert r.returncode == 0 and "row 51 (9.9e+37 in A's column 2)" in r.stderr, r.stderr
    r = spdfit("fit", "--method", "spd-tls", "--stream", a, b)
    assert "1e30" in r.stderr and "B has rank 3 < n = 3" not in r.stderr, r.stderr
    clean = write_csv(tmp_path / "A_clean.csv", problem(m=200, seed=4)[0])
    assert "1e30" not in spdfit("fit", "--method", "ls", "--stream", clean, b).stderr


def test_clean_data_have_no_sentinel_warning(spdfit, tmp_path):
    A, B = problem(seed=3)
    A[7] *= 1e6  # a large row (leverage), not a code
    _, err = fit_json(spdfit, "--method", "ls", write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B))
    assert "1e30" not in err


def test_a_quoted_export_keeps_its_first_row(spdfit, tmp_path):
    A, B = problem()
    a = write_csv(tmp_path / "A.csv", A, quoted=True)
    b = write_csv(tmp_path / "B.csv", B, quoted=True)
    out, err = fit_json(spdfit, "--method", "ls", a, b)
    assert out["m"] == 50
    assert "header" not in err
    np.testing.assert_allclose(np.array(out["X"]), np.linalg.lstsq(A, B, rcond=None)[0], rtol=ROUNDING)


def test_quoted_numbered_names_are_data_with_a_warning(spdfit, tmp_path):
    A, B = problem(m=20)
    a = tmp_path / "A.csv"
    a.write_text('"1","2","3"\n' + "\n".join(",".join(repr(float(v)) for v in row) for row in A) + "\n")
    b = write_csv(tmp_path / "B.csv", np.vstack([np.ones((1, 3)), B]))
    out, err = fit_json(spdfit, "--method", "ls", str(a), b)
    assert out["m"] == 21
    assert "is read as data" in err and "--header" in err


def test_the_rows_a_sentinel_warning_names_are_what_rows_takes(spdfit, tmp_path):
    A, B = problem()
    A[16, 1] = 9.9e37
    a, b = write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B)
    # typed as the warning gives it: the fit of the other rows, against NumPy's least squares
    out, err = fit_json(spdfit, "--method", "ls", "--rows", "1:16,18:50", a, b)
    keep = np.r_[0:16, 17:50]
    assert out["m"] == 49 and "1e30" not in err
    ref = np.linalg.lstsq(A[keep], B[keep], rcond=None)[0]
    np.testing.assert_allclose(np.array(out["X"]), ref, rtol=ROUNDING, atol=ROUNDING)


def test_a_sentinel_among_the_rest_rows_is_named(spdfit, tmp_path):
    A, B = problem(m=200)
    rng = np.random.default_rng(5)
    rest_a, rest_b = 0.01 * rng.standard_normal((100, 3)), 0.01 * rng.standard_normal((100, 3))
    rest_b[4, 1] = 9.9e37
    files = [write_csv(tmp_path / n, M) for n, M in (("A.csv", A), ("B.csv", B), ("ra.csv", rest_a),
                                                      ("rb.csv", rest_b))]
    result = spdfit("fit", "--method", "auto", "--json", "--rest-a", files[2], "--rest-b", files[3], *files[:2])
    assert result.returncode == 0, result.stderr
    assert (f"the rest rows of B ({files[3]}) hold a value of magnitude 1e30 or more "
            "in row 5 (9.9e+37 in column 2)") in result.stderr, result.stderr
    assert "leave that row out of the rest rows" in result.stderr
    # one log: the rest segment first, then the data; the rest rows counted from the segment's first
    log = np.vstack([np.hstack([rest_a, rest_b]), np.hstack([A, B])])
    path = write_csv(tmp_path / "log.csv", log)
    result = spdfit("fit", "--method", "auto", "--json", "--rest-rows", ":100", "--a-cols", "1:3", "--b-cols",
                    "4:6", path)
    assert result.returncode == 0, result.stderr
    assert ("the rest rows of B hold a value of magnitude 1e30 or more in rest row 5 (9.9e+37 in column 2)"
            in result.stderr), result.stderr
    # without it, no such warning
    rest_b[4, 1] = 0.0
    write_csv(tmp_path / "rb.csv", rest_b)
    result = spdfit("fit", "--method", "auto", "--json", "--rest-a", files[2], "--rest-b", files[3], *files[:2])
    assert result.returncode == 0 and "1e30" not in result.stderr, result.stderr


def test_header_row_reads_rs_numbered_names_as_a_header(spdfit, tmp_path):
    # R's write.csv(row.names = FALSE) of a matrix without names: "1","2","3" over the rows
    A, B = problem()
    for name, M in (("A.csv", A), ("B.csv", B)):
        lines = ['"1","2","3"'] + [",".join(f'"{v!r}"' for v in row) for row in M]
        (tmp_path / name).write_text("\n".join(lines) + "\n")
    a, b = str(tmp_path / "A.csv"), str(tmp_path / "B.csv")
    result = spdfit("fit", "--method", "ls", "--json", a, b)
    assert result.returncode == 0 and "the global option --header-row reads it as a header row" in result.stderr
    assert json.loads(result.stdout)["m"] == 51  # the names read as data, as the warning says
    result = spdfit("--header-row", "fit", "--method", "ls", "--json", a, b)
    assert result.returncode == 0 and "header" not in result.stderr, result.stderr
    out = json.loads(result.stdout)
    assert out["m"] == 50
    np.testing.assert_allclose(np.array(out["X"]), np.linalg.lstsq(A, B, rcond=None)[0], rtol=ROUNDING,
                               atol=ROUNDING)
    usage = spdfit("--header-row", "--no-header", "fit", "--method", "ls", a, b)
    assert usage.returncode == 2 and "--no-header" in usage.stderr and "--header-row" in usage.stderr


def test_an_option_given_twice_is_named_plainly(spdfit, tmp_path):
    A, B = problem()
    a, b = write_csv(tmp_path / "A.csv", A), write_csv(tmp_path / "B.csv", B)
    result = spdfit("fit", "--scale-b", "1000", "--scale-b", "1", a, b)
    assert result.returncode == 2
    assert "--scale-b is given 2 times: give it once" in result.stderr and "At Most" not in result.stderr


def test_a_spreadsheet_export_with_units_and_empty_rows_is_read(spdfit, tmp_path):
    """A logger's CSV as Excel saves it: a units row under the names, empty rows (",,,,,") between
    the data rows and many after them. Read as the data rows alone, with a notice for each kind of
    line skipped that sits among the data; in memory and streamed, against NumPy's least squares."""
    A, B = problem()
    lines = ["t,a1,a2,a3,f1,f2,f3", "s,m/s^2,m/s^2,m/s^2,N,N,N"]
    for i, row in enumerate(np.hstack([A, B])):
        if i == 20:
            lines.append(",,,,,,")
        lines.append(",".join([repr(0.01 * i)] + [repr(float(v)) for v in row]))
    lines += [",,,,,,"] * 30
    path = tmp_path / "log.csv"
    path.write_text("\r\n".join(lines) + "\r\n")
    ref = np.linalg.lstsq(A, B, rcond=None)[0]
    for extra in ([], ["--stream"]):
        out, err = fit_json(spdfit, "--method", "ls", "--a-cols", "a1:a3", "--b-cols", "f1:f3", *extra, str(path))
        assert out["m"] == 50
        np.testing.assert_allclose(np.array(out["X"]), ref, rtol=ROUNDING, atol=ROUNDING)
        assert "2: the line under the header, 's,m/s^2,m/s^2,m/s^2,N,N,N', is read as a units row" in err, err
        assert "line 23 holds only separators (a spreadsheet's empty row) between data rows" in err, err
    # --rows counts data rows: 21:50 are the rows after the empty one
    out, _ = fit_json(spdfit, "--method", "ls", "--a-cols", "a1:a3", "--b-cols", "f1:f3", "--rows", "21:50",
                      str(path))
    np.testing.assert_allclose(np.array(out["X"]), np.linalg.lstsq(A[20:], B[20:], rcond=None)[0],
                               rtol=ROUNDING, atol=ROUNDING)


def test_a_sentinel_in_the_time_column_is_a_data_error(spdfit, tmp_path):
    A, B = problem()
    t = 0.01 * np.arange(50)
    t[30] = 9.9e37
    path = write_csv(tmp_path / "log.csv", np.column_stack([t, A, B]))
    result = spdfit("fit", "--method", "ls", "--a-cols", "2:4", "--b-cols", "5:7", "--time-col", "1", "--rows",
                    "0.1:", path)
    assert result.returncode == 1, result.stderr
    assert ("the time column (--time-col '1') holds 9.9e+37 in data row 31: a logger's code for an invalid "
            "reading, not a time") in result.stderr, result.stderr
