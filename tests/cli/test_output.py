"""The output contract: CSV that reads back exactly, JSON keys, --output, warnings, version."""
import json

import numpy as np

from conftest import write_text

METHODS = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls"]


def save(tmp_path, A, B):
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", fmt="%.17g")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    return tmp_path / "A.csv", tmp_path / "B.csv"


def test_csv_output_reads_back_bitwise_equal_to_json(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    for method in METHODS:
        csv = spdfit("fit", "--method", method, a, b)
        js = spdfit("fit", "--method", method, "--json", a, b)
        assert csv.returncode == 0 and js.returncode == 0, csv.stderr + js.stderr
        X_csv = np.array([[float(v) for v in line.split(",")] for line in csv.stdout.splitlines()])
        assert X_csv.shape == (3, 3)
        assert np.array_equal(X_csv, np.array(json.loads(js.stdout)["X"]))


def test_json_has_the_contract_keys(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    for method in METHODS:
        out = json.loads(spdfit("fit", "--method", method, "--json", a, b).stdout)
        assert {"method", "m", "n", "X", "diagnostics", "warnings"} <= set(out)
        assert out["method"] == method and out["m"] == 9 and out["n"] == 3
        d = out["diagnostics"]
        assert {"rank_a", "rank_b", "cond_a", "cond_b", "residual_norm"} <= set(d)
        if method == "spde":
            assert {"area_criterion", "area_criterion_minimum"} <= set(d)
        if method == "procrustes":
            assert isinstance(d["cross_term_positive_definite"], bool)
        if method.startswith("tls"):
            assert "tls_correction_norm" in d


def test_output_option_writes_the_file(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    out = tmp_path / "X.csv"
    result = spdfit("fit", "--method", "spde", "--output", out, a, b)
    assert result.returncode == 0 and result.stdout == ""
    assert np.loadtxt(out, delimiter=",").shape == (3, 3)


def test_output_to_unwritable_place_fails(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    result = spdfit("fit", "--method", "spde", "--output", tmp_path / "no" / "such" / "dir.csv", a, b)
    assert result.returncode == 1 and "spdfit: error:" in result.stderr


def test_warnings_go_to_stderr_and_json(spdfit, tmp_path):
    A = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])  # rank 1
    B = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    a, b = save(tmp_path, A, B)
    result = spdfit("fit", "--method", "ls", "--json", a, b)
    assert result.returncode == 0
    assert "spdfit: warning: " in result.stderr and "rank-deficient" in result.stderr
    assert any("rank-deficient" in w for w in json.loads(result.stdout)["warnings"])
    quiet = spdfit("--quiet", "fit", "--method", "ls", a, b)
    assert quiet.returncode == 0 and quiet.stderr == ""


def test_nearest_gives_a_definite_matrix(spdfit, tmp_path):
    C = np.array([[1.0, 0.9, 0.7], [0.9, 1.0, -0.4], [0.7, -0.4, 1.0]])  # indefinite
    path = tmp_path / "C.csv"
    np.savetxt(path, C, delimiter=",", fmt="%.17g")
    out = json.loads(spdfit("nearest", "--min-eig", "0.01", "--json", path).stdout)
    X = np.array(out["X"])
    assert np.array_equal(X, X.T)
    assert np.linalg.eigvalsh(X)[0] >= 0.01 * (1 - 1e-10)
    assert out["clipped"] >= 1 and out["distance"] > 0


def test_help_and_version(spdfit):
    for args in (["--help"], ["fit", "--help"], ["nearest", "--help"], ["compare", "--help"]):
        result = spdfit(*args)
        assert result.returncode == 0 and "Usage" in result.stdout
    version = spdfit("--version")
    assert version.returncode == 0 and version.stdout.startswith("spdfit ")


def test_compare_reports_every_method(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    truth = write_text(tmp_path / "truth.csv", "3,1,0.5\n1,2,0.2\n0.5,0.2,1.5\n")
    text = spdfit("compare", "--truth", truth, a, b)
    assert text.returncode == 0
    for method in METHODS:
        assert method in text.stdout
    out = json.loads(spdfit("compare", "--json", "--truth", truth, a, b).stdout)
    assert [r["method"] for r in out["results"]] == METHODS
    assert all(r["error_vs_truth"] < 1.0 for r in out["results"])
