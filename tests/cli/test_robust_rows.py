"""Rows that dominate a fit and the robust fit on the command line (issue 42 item 3): the outlier
warning names gross errors and wrong rows of A with NumPy's robust z-scores, --robust huber|tukey
reweighs them (JSON `robust`), and each misuse is a usage error naming the option.

References: NumPy's studentized residuals of least squares (hat matrix by QR) and their median/MAD
z-scores; the robust fit of NumPy-centred data for --offsets estimate; the plain fit of the clean rows."""
import json

import numpy as np
import pytest

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
SIGMA = 0.05


def write(path, M):
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g")
    return str(path)


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    d = tmp_path_factory.mktemp("robust")
    rng = np.random.default_rng(8)
    A = rng.standard_normal((400, 3))
    B = A @ X_TRUE + SIGMA * rng.standard_normal((400, 3))
    Bbad = B.copy()
    bad = [11, 150, 299]
    Bbad[bad] += 60 * SIGMA
    return {"A": write(d / "A.csv", A), "B": write(d / "B.csv", B), "Bbad": write(d / "Bbad.csv", Bbad),
            "As": write(d / "As.csv", A + 1e3), "Bs": write(d / "Bs.csv", Bbad - 2e3),
            "Ac": write(d / "Ac.csv", A - A.mean(0)), "Bc": write(d / "Bc.csv", Bbad - Bbad.mean(0)),
            "bad": bad, "arrays": (A, B, Bbad)}


def fit(spdfit, *args, expect=0):
    r = spdfit("fit", *args)
    assert r.returncode == expect, r.stderr
    return r


def test_the_warning_names_gross_errors_with_numpys_z_scores(spdfit, logs):
    r = fit(spdfit, "--method", "ls", "--json", logs["A"], logs["Bbad"])
    out = json.loads(r.stdout)
    assert "outliers" in out["warning_codes"]
    text = out["warnings"][out["warning_codes"].index("outliers")]
    A, _, Bbad = logs["arrays"]
    X = np.array(out["X"])
    Q, _ = np.linalg.qr(A)
    score = np.linalg.norm(A @ X - Bbad, axis=1) / np.sqrt(1 - (Q * Q).sum(1))
    z = (score - np.median(score)) / (1.482602218505602 * np.median(np.abs(score - np.median(score))))
    for row in logs["bad"]:
        printed = float(text.split(f"{row + 1} (z = ")[1].split(")")[0])
        assert abs(printed - z[row]) <= 0.006 * z[row]
    assert "--rows" in r.stderr  # the CLI's spelling of the option it names
    # Clean rows: no such warning.
    assert "dominate" not in fit(spdfit, "--method", "ls", logs["A"], logs["B"]).stderr


@pytest.mark.parametrize("loss", ["huber", "tukey"])
def test_robust_fits_the_clean_rows_answer_and_reports_the_rows(spdfit, logs, loss):
    clean = np.array(json.loads(fit(spdfit, "--method", "spd-tls", "--json", logs["A"], logs["B"]).stdout)["X"])
    plain = np.array(json.loads(fit(spdfit, "--method", "spd-tls", "--json", logs["A"], logs["Bbad"]).stdout)["X"])
    r = fit(spdfit, "--method", "spd-tls", "--robust", loss, "--json", logs["A"], logs["Bbad"])
    out = json.loads(r.stdout)
    rob = out["robust"]
    assert rob["method"] == loss and rob["converged"] and rob["iterations"] >= 1
    assert set(rob["rows_downweighted"]) >= {b + 1 for b in logs["bad"]}
    assert rob["rows_downweighted_count"] == len(rob["rows_downweighted"]) and rob["weights_min"] < 0.5
    X = np.array(out["X"])
    assert np.linalg.norm(X - clean) < 0.2 * np.linalg.norm(plain - clean)
    assert "dominate" not in r.stderr  # the robust fit reports its rows instead
    report = fit(spdfit, "--method", "spd-tls", "--robust", loss, "--report", logs["A"], logs["Bbad"]).stdout
    assert f"robust: {loss} (k = " in report


def test_robust_with_offsets_estimate_is_the_fit_of_the_centred_rows(spdfit, logs):
    # Constants added to A and B do not move a robust fit with --offsets estimate; the centred rows'
    # robust fit is the same to the accuracy the reweighting settles to.
    shifted = json.loads(fit(spdfit, "--method", "ls", "--robust", "huber", "--offsets", "estimate", "--json",
                             logs["As"], logs["Bs"]).stdout)
    centred = json.loads(fit(spdfit, "--method", "ls", "--robust", "huber", "--offsets", "estimate", "--json",
                             logs["Ac"], logs["Bc"]).stdout)
    X, Y = np.array(shifted["X"]), np.array(centred["X"])
    assert np.linalg.norm(X - Y) <= 1e-7 * np.linalg.norm(Y)
    assert shifted["offsets"]["mode"] == "estimate"


def test_robust_bootstrap_resamples_and_refits_robustly(spdfit, logs):
    out = json.loads(fit(spdfit, "--method", "ls", "--robust", "huber", "--bootstrap", "30", "--seed", "2", "--json",
                         logs["A"], logs["Bbad"]).stdout)
    se = np.array(out["standard_errors"])
    assert se.shape == (3, 3) and np.all(se > 0) and np.all(se < 0.02)
    assert out["bootstrap"]["replicates"] == 30


@pytest.mark.parametrize("args,fragment", [
    (["--method", "spde", "--robust", "huber"], "--robust"),
    (["--method", "ls", "--robust", "bisquare"], "--robust"),
    (["--method", "ls", "--robust", "huber", "--stream"], "--stream"),
    (["--method", "ls", "--robust-tuning", "2"], "--robust"),
    (["--method", "ls", "--robust", "huber", "--robust-tuning", "0"], "--robust-tuning"),
])
def test_misuse_is_a_usage_error_naming_the_option(spdfit, logs, args, fragment):
    r = fit(spdfit, *args, logs["A"], logs["B"], expect=2)
    assert fragment in r.stderr, r.stderr


def test_a_sentinel_has_the_outliers_code(spdfit, logs, tmp_path):
    A, B, _ = logs["arrays"]
    A = A.copy()
    A[4, 1] = 9.9e37
    out = json.loads(fit(spdfit, "--method", "ls", "--json", write(tmp_path / "A.csv", A), logs["B"]).stdout)
    assert out["warning_codes"][0] == "outliers" and "row 5 (9.9e+37 in A's column 2)" in out["warnings"][0]
