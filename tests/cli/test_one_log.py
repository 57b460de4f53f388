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
    (["--rows", "a:b"], 2, "not a row number (nor a time, with --time-col)"),
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


# --time-col: the selections in the time column's units (t = 0.01 (row - 1) in this log).
def test_time_col_gives_the_selections_in_its_units(spdfit, log):
    want = run_json(spdfit, "fit", "--method", "spd-tls", "--rows", "701:900", "--rest-rows", "1:600", *COLS, log["log"])
    got = run_json(spdfit, "fit", "--method", "spd-tls", "--time-col", "t", "--rows", "6.995:8.995",
                   "--rest-rows", ":5.995", *COLS, log["log"])
    assert got["X"] == want["X"] and got["m"] == 200
    # By position, and on compare and hexapod identify.
    assert run_json(spdfit, "fit", "--method", "spd-tls", "--time-col", "1", "--rows", "6.995:8.995",
                    "--rest-rows", ":5.995", *COLS, log["log"])["X"] == want["X"]
    want = run_json(spdfit, "compare", "--rest-rows", "1:600", *COLS, log["log"])
    got = run_json(spdfit, "compare", "--time-col", "t", "--rest-rows", ":5.995", *COLS, log["log"])
    assert [r["X"] for r in got["results"]] == [r["X"] for r in want["results"]]
    want = run_json(spdfit, "hexapod", "identify", "--rest-rows", "1:600", *COLS, log["log"])
    got = run_json(spdfit, "hexapod", "identify", "--time-col", "t", "--rest-rows", ":5.995", *COLS, log["log"])
    assert {k: v["X"] for k, v in got["methods"].items()} == {k: v["X"] for k, v in want["methods"].items()}


@pytest.mark.parametrize("args,status,words", [
    (["--time-col", "t"], 2, "--time-col"),  # nothing to choose
    (["--time-col", "t", "--rows", "100:200"], 1, "no row's time"),
    (["--time-col", "t", "--rows", "2:1"], 2, "runs backwards"),
    (["--time-col", "t", "--rows", "1:x"], 2, "'x' in '1:x' is not a"),
    (["--time-col", "nope", "--rows", "1:2"], None, "nope"),
    (["--time-col", "a1:a2", "--rows", "1:2"], None, "give one"),
    (["--time-col", "t", "--rows", "1:2", "--stream"], 2, "--stream"),
    (["--rows", "1.5:3"], 2, "--time-col"),  # times without a time column
])
def test_bad_time_selections_are_errors_quoting_them(spdfit, log, args, status, words):
    r = spdfit("fit", "--method", "ls", *args, *COLS, log["log"])
    assert r.returncode == (status if status is not None else r.returncode) and r.returncode in (1, 2), r.stderr
    assert words in r.stderr, r.stderr


def test_time_col_needs_the_columns_of_one_log(spdfit, log):
    r = spdfit("fit", "--method", "ls", "--time-col", "t", "--rows", "1:2", log["A"], log["B"])
    assert r.returncode == 2 and "--a-cols" in r.stderr, r.stderr


def test_rest_files_take_the_logs_column_selections(spdfit, log):
    # The rest segment saved as a file of its own, with every column of the log: --a-cols chooses
    # A's columns of --rest-a and --b-cols B's of --rest-b, as they do of the data.
    table = np.loadtxt(log["log"], delimiter=",", skiprows=1)
    rest = write(log["dir"] / "rest_log.csv", table[:600], "t,a1,a2,a3,f1,f2,f3")
    want = run_json(spdfit, "fit", "--method", "spd-tls", "--rest-rows", "1:600", *COLS, log["log"])
    got = run_json(spdfit, "fit", "--method", "spd-tls", "--rest-a", rest, "--rest-b", rest, "--rows", "601:", *COLS,
                   log["log"])
    assert got["X"] == want["X"]
    assert got["diagnostics"]["noise_model"]["cov_a"] == want["diagnostics"]["noise_model"]["cov_a"]
    # Streamed, the rest files are read with the selections too.
    streamed = run_json(spdfit, "fit", "--method", "spd-tls", "--stream", "--rest-a", rest, "--rest-b", rest, *COLS,
                        write(log["dir"] / "moving.csv", table[600:], "t,a1,a2,a3,f1,f2,f3"))
    np.testing.assert_allclose(streamed["X"], want["X"], rtol=1e-12)


@pytest.fixture(scope="module")
def spiked(log):
    """The log with a gross error in B (file data row 750) and a logger's code in A (row 800)."""
    table = np.loadtxt(log["log"], delimiter=",", skiprows=1)
    table[749, 4] += 500.0
    spike = write(log["dir"] / "spike.csv", table, "t,a1,a2,a3,f1,f2,f3")
    table[799, 1] = 9.9e37
    return {"spike": spike, "sentinel": write(log["dir"] / "sentinel.csv", table, "t,a1,a2,a3,f1,f2,f3")}


def test_rows_are_named_as_numbered_in_the_file(spdfit, log, spiked):
    # Under --rows the warnings and the robust report number rows as the file does, not among the
    # rows fitted (row 750 of the file is the 150th fitted).
    for args in (["--rows", "601:"], ["--time-col", "t", "--rows", "5.995:"], ["--rest-rows", ":600"]):
        r = spdfit("fit", "--method", "ls", *args, *COLS, spiked["spike"])
        assert r.returncode == 0, r.stderr
        assert "row 750 (z = " in r.stderr and "dominates the fit" in r.stderr, (args, r.stderr)
    # The robust fit's report: the rows of the moving segment cut out by NumPy, numbered 600 lower.
    table = np.loadtxt(spiked["spike"], delimiter=",", skiprows=1)
    cut = write(log["dir"] / "spike_moving.csv", table[600:], "t,a1,a2,a3,f1,f2,f3")
    robust = run_json(spdfit, "fit", "--method", "ls", "--robust", "huber", "--rows", "601:", *COLS, spiked["spike"])
    alone = run_json(spdfit, "fit", "--method", "ls", "--robust", "huber", *COLS, cut)
    assert robust["X"] == alone["X"] and 750 in robust["robust"]["rows_downweighted"]
    assert robust["robust"]["rows_downweighted"] == [r + 600 for r in alone["robust"]["rows_downweighted"]]
    r = spdfit("fit", "--method", "ls", "--rows", "601:", *COLS, spiked["sentinel"])
    assert "row 800 (9.9e+37 in A's column 1)" in r.stderr and "the rows 601:799,801:1000, as --rows takes them" in r.stderr, r.stderr


def test_compare_and_identify_name_dominant_rows_once(spdfit, log, spiked):
    for command in (["compare"], ["hexapod", "identify"]):
        r = spdfit(*command, "--rest-rows", ":600", *COLS, spiked["spike"])
        assert r.returncode == 0, r.stderr
        assert r.stderr.count("dominates the fit") == 1 and "row 750 (z = " in r.stderr, (command, r.stderr)
        r = spdfit(*command, "--rest-rows", ":600", *COLS, log["log"])
        assert "dominate" not in r.stderr, (command, r.stderr)


@pytest.mark.parametrize("loss", ["huber", "tukey"])
def test_compare_robust_is_each_methods_robust_fit(spdfit, log, spiked, loss):
    # compare --robust: every method but spde as `fit --method M --robust` fits it, spde as it is.
    got = run_json(spdfit, "compare", "--robust", loss, "--rest-rows", ":600", *COLS, spiked["spike"])
    for r in got["results"]:
        # (spde takes no noise model: compare runs it on the rows fitted without one.)
        how = ["--robust", loss, "--rest-rows", ":600"] if r["method"] != "spde" else ["--rows", "601:"]
        want = run_json(spdfit, "fit", "--method", r["method"], *how, *COLS, spiked["spike"])
        assert r["X"] == want["X"], r["method"]
        assert ("robust" in r) == (r["method"] != "spde")
        if "robust" in r:  # rows numbered as in the file, as fit numbers them
            assert r["robust"]["rows_downweighted"] == want["robust"]["rows_downweighted"], r["method"]
