"""A and B from one file: --a-cols and --b-cols on a log with a timestamp column, as pandas writes
it, against fitting the same columns split into two files (np.savetxt)."""
import json

import numpy as np
import pandas as pd
import pytest
import scipy.io

# The one file and the split files hold the same doubles (pandas writes the shortest round-trip
# decimal, savetxt 18 digits), and the same rows go through the same arithmetic: the estimates
# agree to the last bit; this bound only allows for a different summation order, should one arise.
SAME_DATA_TOL = 1e-13
# Streaming merges per-block QR factors instead of one QR: equal to rounding.
STREAM_TOL = 1e-12

N = 3
M = 40


def make_log():
    rng = np.random.default_rng(35)
    X = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])
    A0 = rng.uniform(-5, 5, (M, N))
    A = A0 + 0.05 * rng.standard_normal((M, N))
    B = A0 @ X + 0.05 * rng.standard_normal((M, N))
    return A, B


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("log")
    A, B = make_log()
    frame = pd.DataFrame({"time": pd.date_range("2026-11-27 02:00", periods=M, freq="10ms")})
    for j in range(N):
        frame[f"acc{j + 1}"] = A[:, j]
    for j in range(N):
        frame[f"F{j + 1}"] = B[:, j]
    frame["note"] = ["ok"] * M  # text, not selected: ignored
    frame.to_csv(folder / "log.csv", index=False)
    np.savetxt(folder / "A.csv", A, delimiter=",")
    np.savetxt(folder / "B.csv", B, delimiter=",")
    # pandas' header of a frame without names: digits, which are positions all the same.
    pd.DataFrame(np.hstack([A, B])).to_csv(folder / "digits.csv", index=False)
    np.savez(folder / "log.npz", log=np.hstack([A, B]))
    scipy.io.savemat(folder / "log.mat", {"log": np.hstack([A, B])})
    return folder


def X_of(result):
    assert result.returncode == 0, result.stderr
    return np.loadtxt(result.stdout.splitlines(), delimiter=",", ndmin=2)


def fit(spdfit, *args):
    return X_of(spdfit("fit", "--method", "spd-tls", *[str(a) for a in args]))


@pytest.fixture(scope="module")
def split_X(files, spdfit):
    return fit(spdfit, files / "A.csv", files / "B.csv")


@pytest.mark.parametrize("a_cols, b_cols", [
    ("acc1:acc3", "F1:F3"),      # name ranges
    ("2:4", "5:7"),              # position ranges
    ("2,3,4", "5,6,7"),          # lists
    ("acc1,3:4", "F1:F2,7"),     # mixed
])
def test_one_file_equals_the_split_files(files, spdfit, split_X, a_cols, b_cols):
    X = fit(spdfit, files / "log.csv", "--a-cols", a_cols, "--b-cols", b_cols)
    np.testing.assert_allclose(X, split_X, rtol=0, atol=SAME_DATA_TOL)


def test_digits_in_the_header_are_positions(files, spdfit, split_X):
    X = fit(spdfit, files / "digits.csv", "--a-cols", "1:3", "--b-cols", "4:6")
    np.testing.assert_allclose(X, split_X, rtol=0, atol=SAME_DATA_TOL)


def test_order_of_the_selection_is_kept(files, spdfit):
    # A P X' = B P (columns of A and B permuted by P) has X' = P' X P.
    X = fit(spdfit, files / "log.csv", "--a-cols", "acc1:acc3", "--b-cols", "F1:F3")
    permuted = fit(spdfit, files / "log.csv", "--a-cols", "acc2,acc1,acc3", "--b-cols", "F2,F1,F3")
    P = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 1]])
    np.testing.assert_allclose(permuted, P.T @ X @ P, rtol=0, atol=1e-12)


def test_stream_equals_in_memory(files, spdfit):
    memory = fit(spdfit, files / "log.csv", "--a-cols", "acc1:acc3", "--b-cols", "F1:F3")
    for rows in ("7", "1000"):
        streamed = fit(spdfit, "--stream", "--block-rows", rows, files / "log.csv", "--a-cols", "acc1:acc3",
                       "--b-cols", "F1:F3")
        np.testing.assert_allclose(streamed, memory, rtol=0, atol=STREAM_TOL)


def test_standard_input_streamed(files, spdfit):
    memory = fit(spdfit, files / "log.csv", "--a-cols", "acc1:acc3", "--b-cols", "F1:F3")
    r = spdfit("fit", "--method", "spd-tls", "--stream", "-", "--a-cols", "acc1:acc3", "--b-cols", "F1:F3",
               input=(files / "log.csv").read_text())
    np.testing.assert_allclose(X_of(r), memory, rtol=0, atol=STREAM_TOL)


@pytest.mark.parametrize("name, variable", [("log.npz", []), ("log.mat", ["--var-a", "log"])])
def test_npz_and_mat_by_position(files, spdfit, split_X, name, variable):
    X = fit(spdfit, files / name, *variable, "--a-cols", "1:3", "--b-cols", "4:6")
    np.testing.assert_allclose(X, split_X, rtol=0, atol=SAME_DATA_TOL)
    streamed = fit(spdfit, "--stream", files / name, *variable, "--a-cols", "1:3", "--b-cols", "4:6")
    np.testing.assert_allclose(streamed, split_X, rtol=0, atol=STREAM_TOL)
    r = spdfit("fit", "--method", "spd-tls", str(files / name), *variable, "--a-cols", "acc1:acc3", "--b-cols", "4:6")
    assert r.returncode == 2
    assert "--a-cols 'acc1:acc3'" in r.stderr and "no column names" in r.stderr


def test_npy_by_position(files, spdfit, split_X, tmp_path):
    A, B = make_log()
    np.save(tmp_path / "log.npy", np.hstack([B, A]))
    X = fit(spdfit, "--stream", tmp_path / "log.npy", "--a-cols", "4:6", "--b-cols", "1:3")
    np.testing.assert_allclose(X, split_X, rtol=0, atol=STREAM_TOL)


def test_report_and_json_say_which_columns(files, spdfit):
    r = spdfit("fit", "--method", "spd-tls", "--report", str(files / "log.csv"), "--a-cols", "acc1:acc3",
               "--b-cols", "F1,F2,F3")
    assert r.returncode == 0, r.stderr
    assert f"A: {files / 'log.csv'} columns acc1..acc3 (2-4)" in r.stdout
    assert f"B: {files / 'log.csv'} columns F1..F3 (5-7)" in r.stdout
    r = spdfit("fit", "--method", "spd-tls", "--json", "--stream", str(files / "log.csv"), "--a-cols", "2,4",
               "--b-cols", "5,7")
    assert r.returncode == 0, r.stderr
    document = json.loads(r.stdout)
    assert document["a_columns"] == f"{files / 'log.csv'} columns acc1, acc3 (2, 4)"
    assert document["row_names"] == ["acc1", "acc3"] and document["column_names"] == ["F1", "F3"]


def test_compare_and_hexapod_identify(files, spdfit):
    split = spdfit("compare", "--json", str(files / "A.csv"), str(files / "B.csv"))
    one = spdfit("compare", "--json", str(files / "log.csv"), "--a-cols", "acc1:acc3", "--b-cols", "F1:F3")
    assert split.returncode == 0 and one.returncode == 0, one.stderr
    for s, o in zip(json.loads(split.stdout)["results"], json.loads(one.stdout)["results"]):
        assert s["method"] == o["method"]
        np.testing.assert_allclose(np.array(o["X"]), np.array(s["X"]), rtol=0, atol=SAME_DATA_TOL)
    split = spdfit("hexapod", "identify", "--json", str(files / "A.csv"), str(files / "B.csv"))
    one = spdfit("hexapod", "identify", "--json", str(files / "log.csv"), "--a-cols", "2:4", "--b-cols", "F1:F3")
    assert split.returncode == 0 and one.returncode == 0, one.stderr
    assert json.loads(one.stdout) == json.loads(split.stdout)


@pytest.mark.parametrize("args, status, pieces", [
    (["--a-cols", "acc1:acc9", "--b-cols", "F1:F3"], 2,
     ["--a-cols 'acc1:acc9'", "no column named acc9", "its columns: time, acc1, acc2, acc3, F1, F2, F3, note"]),
    (["--a-cols", "acc1:acc3", "--b-cols", "acc3:F2"], 2,
     ["--a-cols 'acc1:acc3' and --b-cols 'acc3:F2' both select column 4 (acc3)"]),
    (["--a-cols", "4:2", "--b-cols", "F1:F3"], 2, ["--a-cols '4:2'", "runs backwards (write 2:4)"]),
    (["--a-cols", "acc3:acc1", "--b-cols", "F1:F3"], 2, ["--a-cols 'acc3:acc1'", "runs backwards"]),
    (["--a-cols", "2:4", "--b-cols", "5:9"], 2, ["--b-cols '5:9'", "column 9 is beyond the 8 columns"]),
    (["--a-cols", "0:2", "--b-cols", "5:7"], 2, ["--a-cols '0:2'", "count from 1"]),
    (["--a-cols", "2,,4", "--b-cols", "5:7"], 2, ["--a-cols '2,,4'", "empty item"]),
    (["--a-cols", "2:4"], 2, ["--a-cols and --b-cols come together"]),
    (["--b-cols", "2:4"], 2, ["--a-cols and --b-cols come together"]),
    ([], 2, ["B's file is missing"]),
    (["--a-cols", "time,acc1,acc2", "--b-cols", "F1:F3"], 1, ["log.csv:2:1:", "is not a number",
                                                               "column 1 is selected by --a-cols"]),
])
def test_errors(files, spdfit, args, status, pieces):
    r = spdfit("fit", "--method", "spd-tls", str(files / "log.csv"), *args)
    assert r.returncode == status, r.stderr
    for piece in pieces:
        assert piece in r.stderr, r.stderr


def test_two_files_with_columns_is_a_usage_error(files, spdfit):
    r = spdfit("fit", "--method", "spd-tls", str(files / "A.csv"), str(files / "B.csv"), "--a-cols", "1:3",
               "--b-cols", "4:6")
    assert r.returncode == 2
    assert "two files were given" in r.stderr and "B.csv" in r.stderr


def test_errors_streaming_too(files, spdfit):
    r = spdfit("fit", "--method", "spd-tls", "--stream", str(files / "log.csv"), "--a-cols", "acc1:acc9",
               "--b-cols", "F1:F3")
    assert r.returncode == 2 and "no column named acc9" in r.stderr


def test_unselected_timestamp_needs_no_index_col(files, spdfit):
    # Without a selection the timestamp column is an error that names both ways out.
    r = spdfit("fit", "--method", "spd-tls", str(files / "log.csv"), str(files / "B.csv"))
    assert r.returncode == 1
    assert "--a-cols" in r.stderr


def test_streaming_bootstrap_from_standard_input(files, spdfit):
    """Too few rows for the streaming bootstrap: one file on standard input is resampled in memory
    from its kept text, as the file itself is."""
    args = ["fit", "--method", "spd-tls", "--json", "--stream", "--bootstrap", "20", "--a-cols", "acc1:acc3",
            "--b-cols", "F1:F3"]
    from_file = spdfit(*args, str(files / "log.csv"))
    from_stdin = spdfit(*args, "-", input=(files / "log.csv").read_text())
    assert from_file.returncode == 0 and from_stdin.returncode == 0, from_stdin.stderr
    a, b = json.loads(from_file.stdout), json.loads(from_stdin.stdout)
    assert a["X"] == b["X"] and a["standard_errors"] == b["standard_errors"]
