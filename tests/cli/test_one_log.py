"""One log (issue 42 item 4): --rows chooses the rows fitted and --rest-rows takes the rest segment
from the data files themselves, with --a-cols/--b-cols applying, on fit, compare and hexapod
identify.

Reference: the same fit of the rows cut out by NumPy and written to files of their own (the data
rows as A and B, the rest segment as --rest-a and --rest-b): the same numbers to the last bit, since
the arithmetic is the same."""
import json

import numpy as np
import pytest


def write(path, M, header=None):
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g", header=header or "", comments="")
    return str(path)


@pytest.fixture(scope="module")
def log(tmp_path_factory):
    """One log as a logger writes it: a time column, 600 rows at rest, then 400 moving, A's and
    B's columns side by side with a header."""
    d = tmp_path_factory.mktemp("log")
    rng = np.random.default_rng(8)
    X = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
    sd_a, sd_b = np.array([0.05, 0.1, 0.2]), np.array([3.0, 1.0, 0.3])
    rest_A = rng.standard_normal((600, 3)) * sd_a
    rest_B = np.array([20.0, -5.0, 2.0]) + rng.standard_normal((600, 3)) * sd_b
    A0 = rng.uniform(-5, 5, (400, 3))
    A = A0 + rng.standard_normal(A0.shape) * sd_a
    B = A0 @ X + rng.standard_normal(A0.shape) * sd_b
    t = 0.01 * np.arange(1000)
    table = np.column_stack([t, np.vstack([rest_A, A]), np.vstack([rest_B, B])])
    return {"log": write(d / "log.csv", table, "t,a1,a2,a3,f1,f2,f3"),
            "A": write(d / "A.csv", A), "B": write(d / "B.csv", B),
            "A_part": write(d / "A_part.csv", A[100:300]), "B_part": write(d / "B_part.csv", B[100:300]),
            "rest_A": write(d / "rest_A.csv", rest_A), "rest_B": write(d / "rest_B.csv", rest_B), "dir": d}


COLS = ["--a-cols", "a1:a3", "--b-cols", "f1:f3"]


def run_json(spdfit, *args):
    r = spdfit(*args, "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


@pytest.mark.parametrize("method", ["spd-tls", "auto", "psd-ls"])
def test_rest_rows_from_the_log_are_the_rest_files(spdfit, log, method):
    want = run_json(spdfit, "fit", "--method", method, "--rest-a", log["rest_A"], "--rest-b", log["rest_B"], log["A"],
                    log["B"])
    got = run_json(spdfit, "fit", "--method", method, "--rest-rows", "1:600", *COLS, log["log"])
    assert got["X"] == want["X"]
    assert got["m"] == 400 and got["diagnostics"]["noise_model"]["rest_rows"] == 600
    np.testing.assert_array_equal(got["diagnostics"]["noise_model"]["cov_b"], want["diagnostics"]["noise_model"]["cov_b"])


def test_rows_choose_the_rows_fitted(spdfit, log):
    want = run_json(spdfit, "fit", "--method", "ls", log["A_part"], log["B_part"])
    for spec in ("701:900", "701:800,801:900", "701:750, 751:900"):
        assert run_json(spdfit, "fit", "--method", "ls", "--rows", spec, *COLS, log["log"])["X"] == want["X"], spec
    # With a rest segment: the rows given, and the model of the rest rows.
    both = run_json(spdfit, "fit", "--method", "spd-tls", "--rows", "701:900", "--rest-rows", ":600", *COLS, log["log"])
    ref = run_json(spdfit, "fit", "--method", "spd-tls", "--rest-a", log["rest_A"], "--rest-b", log["rest_B"],
                   log["A_part"], log["B_part"])
    assert both["X"] == ref["X"]


def test_compare_and_identify_take_one_log(spdfit, log):
    want = run_json(spdfit, "compare", "--rest-a", log["rest_A"], "--rest-b", log["rest_B"], log["A"], log["B"])
    got = run_json(spdfit, "compare", "--rest-rows", "1:600", *COLS, log["log"])
    assert [r["X"] for r in got["results"]] == [r["X"] for r in want["results"]]
    want = run_json(spdfit, "hexapod", "identify", "--rest-a", log["rest_A"], "--rest-b", log["rest_B"], log["A"],
                    log["B"])
    got = run_json(spdfit, "hexapod", "identify", "--rest-rows", "1:600", *COLS, log["log"])
    assert {k: v["X"] for k, v in got["methods"].items()} == {k: v["X"] for k, v in want["methods"].items()}


@pytest.mark.parametrize("args,status,words", [
    (["--rows", "0:10"], 2, "no row 0"),
    (["--rows", "20:10"], 2, "runs backwards"),
    (["--rows", "1,,5"], 2, "empty item"),
    (["--rows", "a:b"], 2, "not a row number"),
    (["--rows", "900:1200"], 1, "row 1200 is beyond the 1000 data rows"),
    (["--rest-rows", "1:1000"], 1, "none is left to fit"),
    (["--rest-rows", "5"], 1, "--rest-rows '5'"),
    (["--rest-rows", "1:600", "--stream"], 2, "--stream"),
    (["--rest-rows", "1:600", "--noise-std-a", "1", "--noise-std-b", "1"], 2, "--rest-rows"),
])
def test_bad_row_selections_are_errors_quoting_them(spdfit, log, args, status, words):
    r = spdfit("fit", "--method", "spd-tls", *args, *COLS, log["log"])
    assert r.returncode == status, r.stderr
    assert words in r.stderr, r.stderr


def test_rows_with_spde_and_a_rest_segment(spdfit, log):
    # spde takes no noise model: --rest-rows with it is refused as --rest-a is.
    r = spdfit("fit", "--method", "spde", "--rest-rows", "1:600", *COLS, log["log"])
    assert r.returncode == 2 and "--rest-rows" in r.stderr, r.stderr
    assert spdfit("fit", "--method", "spde", "--rows", "601:", *COLS, log["log"]).returncode == 0
