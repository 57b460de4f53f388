"""`spdfit nearest --corr`: Higham's (2002) example, the JSON report, weights and alpha, and
the options' and weights file's checks."""
import json

import numpy as np
import pytest

HIGHAM = np.array([[2, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]], dtype=float)
HIGHAM_ANSWER = np.array([[1, -0.8084, 0.1916, 0.1068], [-0.8084, 1, -0.6562, 0.1916],
                          [0.1916, -0.6562, 1, -0.8084], [0.1068, 0.1916, -0.8084, 1]])


@pytest.fixture
def higham(tmp_path):
    path = tmp_path / "C.csv"
    np.savetxt(path, HIGHAM, delimiter=",")
    return path


def test_highams_example(spdfit, higham):
    out = spdfit("nearest", "--corr", higham)
    assert out.returncode == 0, out.stderr
    X = np.array([[float(v) for v in line.split(",")] for line in out.stdout.splitlines()])
    np.testing.assert_allclose(X, HIGHAM_ANSWER, atol=6e-5)
    assert np.all(np.diag(X) == 1.0)


def test_json_report(spdfit, higham):
    j = json.loads(spdfit("nearest", "--corr", "--json", "--alpha", "0.05", higham).stdout)
    for key in ("X", "n", "alpha", "distance", "iterations", "gradient_norm", "converged", "clipped",
                "cholesky", "warnings"):
        assert key in j, key
    assert j["converged"] and j["cholesky"] and j["alpha"] == 0.05
    # Higham's example has 2 on the diagonal: repairing it as a correlation says so.
    assert len(j["warnings"]) == 1 and "the diagonal is not 1" in j["warnings"][0]
    assert j["warning_codes"] == ["diagonal_changed"]
    assert np.linalg.eigvalsh(np.array(j["X"]))[0] >= 0.05 - 1e-12


def test_weights(spdfit, higham, tmp_path):
    (tmp_path / "w.csv").write_text("1\n2\n3\n4\n")
    weighted = spdfit("nearest", "--corr", "--weights", tmp_path / "w.csv", higham)
    plain = spdfit("nearest", "--corr", higham)
    assert weighted.returncode == 0 and weighted.stdout != plain.stdout
    (tmp_path / "row.csv").write_text("1,2,3,4\n")
    assert spdfit("nearest", "--corr", "--weights", tmp_path / "row.csv", higham).stdout == weighted.stdout


@pytest.mark.parametrize("text, message", [("1\n2\n3\n", "give 4 numbers"), ("1\n0\n1\n1\n", "weight 2 is 0"),
                                           ("1,2\n3,4\n", "give 4 numbers")])
def test_bad_weights_are_data_errors(spdfit, higham, tmp_path, text, message):
    (tmp_path / "w.csv").write_text(text)
    out = spdfit("nearest", "--corr", "--weights", tmp_path / "w.csv", higham)
    assert out.returncode == 1 and message in out.stderr and "w.csv" in out.stderr


@pytest.mark.parametrize("args", [["--corr", "--alpha", "0.1", "--min-eig", "0.1"], ["--alpha", "0.1"],
                                  ["--corr", "--alpha", "1"], ["--corr", "--tol", "0"], ["--corr", "--max-iter", "0"],
                                  ["--weights", "w.csv"], ["--min-eig", "0.1", "--min-eig-rel", "1e-6"],
                                  ["--min-eig-rel", "1"], ["--keep-diag", "--alpha", "0.1"],
                                  ["--keep-diag", "--via-corr"], ["--corr", "--via-corr"], ["--max-iter", "5"]])
def test_usage_errors(spdfit, higham, args):
    out = spdfit("nearest", *args, higham)
    assert out.returncode == 2, out.stdout


def test_not_converged_and_asymmetric_input_warn(spdfit, tmp_path):
    rng = np.random.default_rng(1)
    M = rng.uniform(-1, 1, (30, 30))
    C = M + M.T
    np.fill_diagonal(C, 1)
    np.savetxt(tmp_path / "C.csv", C, delimiter=",")
    out = spdfit("nearest", "--corr", "--max-iter", "1", "--json", tmp_path / "C.csv")
    assert out.returncode == 0 and "not converged" in out.stderr
    assert json.loads(out.stdout)["converged"] is False
    C[0, 1] += 0.5
    np.savetxt(tmp_path / "A.csv", C, delimiter=",")
    assert "not symmetric" in spdfit("nearest", "--corr", tmp_path / "A.csv").stderr


def test_r_matrix_symw_converges(spdfit):
    """R Matrix's nearPD test matrix symW (tests/data/r_matrix), entries up to 1.8e8, as a
    correlation: the Newton method stops at its gradient's rounding level and says converged
    (tests/python/test_nearest_correlation.py checks the answer's optimality)."""
    from spdfit_testing import SOURCE_DIR
    out = spdfit("nearest", "--corr", "--min-eig", "0", "--json", SOURCE_DIR / "tests" / "data" / "r_matrix" / "symW.csv")
    assert out.returncode == 0, out.stderr
    assert "the diagonal is not 1" in out.stderr
    j = json.loads(out.stdout)
    assert j["converged"] and j["iterations"] < 200
    assert np.all(np.diag(np.array(j["X"])) == 1.0)
