"""Issue 17: `fit --method ls/tls` and `compare` with B of d != n columns print the n x d X; the
other methods exit 1 naming B's file and ls/tls, streamed or not."""
import json

import numpy as np
import pytest


@pytest.fixture
def files(tmp_path):
    rng = np.random.default_rng(17)
    A0 = rng.standard_normal((60, 4))
    X = rng.standard_normal((4, 2))
    A = A0 + 0.01 * rng.standard_normal(A0.shape)
    B = A0 @ X + 0.01 * rng.standard_normal((60, 2))
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", header="a1,a2,a3,a4", comments="")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", header="b1,b2", comments="")
    np.save(tmp_path / "A.npy", A)
    np.save(tmp_path / "B.npy", B)
    return tmp_path, A, B


@pytest.mark.parametrize("method", ["ls", "tls"])
@pytest.mark.parametrize("stream", [[], ["--stream", "--block-rows", "7"]])
def test_fit_prints_the_n_by_d_x(spdfit, files, method, stream):
    path, A, B = files
    result = spdfit("fit", "--method", method, *stream, path / "A.csv", path / "B.csv")
    assert result.returncode == 0, result.stderr
    X = np.array([[float(v) for v in line.split(",")] for line in result.stdout.splitlines()])
    if method == "ls":
        reference = np.linalg.lstsq(A, B, rcond=None)[0]
    else:
        V = np.linalg.svd(np.hstack([A, B]))[2].T
        reference = -V[:4, 4:] @ np.linalg.inv(V[4:, 4:])
    np.testing.assert_allclose(X, reference, rtol=1e-10)


def test_json_report_and_npy_output(spdfit, files):
    path, A, B = files
    j = json.loads(spdfit("fit", "--method", "tls", "--json", path / "A.npy", path / "B.npy").stdout)
    assert (j["m"], j["n"], j["d"]) == (60, 4, 2)
    assert np.shape(j["X"]) == (4, 2) and j["diagnostics"]["symmetric"] is False
    report = spdfit("fit", "--method", "ls", "--report", path / "A.npy", path / "B.npy")
    assert report.returncode == 0 and report.stdout.startswith("ls estimate of X (4 x 2) from m = 60 rows")
    result = spdfit("fit", "--method", "ls", "-o", path / "X.npy", path / "A.npy", path / "B.npy")
    assert result.returncode == 0, result.stderr
    assert np.load(path / "X.npy").shape == (4, 2)


@pytest.mark.parametrize("stream", [[], ["--stream"]])
def test_symmetric_methods_name_b_and_ls_tls(spdfit, files, stream):
    path, _, _ = files
    result = spdfit("fit", "--method", "auto", *stream, path / "A.csv", path / "B.csv")
    assert result.returncode == 1 and result.stdout == ""
    assert "B.csv: auto estimates a symmetric X" in result.stderr
    assert "A has 4 and B 2: for the 4x2 X of A X ~= B use ls or tls" in result.stderr


def test_compare_runs_ls_and_tls(spdfit, files):
    path, _, _ = files
    result = spdfit("compare", path / "A.csv", path / "B.csv")
    assert result.returncode == 0, result.stderr
    assert "n = 4, d = 2" in result.stdout and "only ls and tls fit a non-square X" in result.stdout
    j = json.loads(spdfit("compare", "--json", path / "A.csv", path / "B.csv").stdout)
    assert j["d"] == 2 and [r["method"] for r in j["results"]] == ["ls", "tls"]


def test_hexapod_identify_needs_a_square_matrix(spdfit, files):
    path, _, _ = files
    result = spdfit("hexapod", "identify", path / "A.csv", path / "B.csv")
    assert result.returncode == 1 and "B.csv" in result.stderr and "square" in result.stderr
