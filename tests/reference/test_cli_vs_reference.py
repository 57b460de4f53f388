"""Compare the spdfit CLI (path in $SPDFIT_CLI) with the independent NumPy reference.

Contract exercised:
  spdfit fit --method M [--json] A.csv B.csv    M in ls, procrustes, tls, tls-sym, tls-psd, spde
  spdfit nearest [--min-eig E] [--json] X.csv
JSON: {"method", "m", "n", "X", "diagnostics", "warnings"}; CSV: one matrix row per line.
"""
import json

import numpy as np
import pytest

import spdfit_testing
import thesis_reference as ref
from cases import CASES, make_case

# Relative Frobenius error allowed between CLI and reference X: both are backward stable
# and every case has cond(A), cond(B) <= 100, so they agree to ~1e-13; 1e-10 leaves margin.
X_RTOL = 1e-10
# Scalar diagnostics (norms, condition numbers, area criterion) are reported values that
# may be computed by a different formula; 1e-8 relative is far above rounding.
DIAG_RTOL = 1e-8
# Floor for quantities whose exact value is ~0 (square-case residuals, TLS correction),
# relative to the size of the terms they are computed from.
ZERO_ATOL = 1e-12
# Symmetry of outputs that are symmetric only up to rounding (tls-sym, tls-psd, nearest).
SYM_RTOL = 1e-13
# A'B+B'A definiteness is only compared when lambda_min is clearly away from 0.
DEFINITENESS_MARGIN = 1e-8

METHODS = sorted(ref.METHODS)
REQUIRED_DIAGNOSTICS = {"residual_norm", "rank_a", "rank_b", "cond_a", "cond_b"}
METHOD_DIAGNOSTICS = {
    "spde": {"area_criterion", "area_criterion_minimum"},
    "procrustes": {"cross_term_positive_definite"},
    "tls": {"tls_correction_norm"},
}


def rel(X, Y):
    return np.linalg.norm(X - Y) / np.linalg.norm(Y)


def parse_csv(text):
    rows = [line for line in text.splitlines() if line.strip()]
    return np.array([[float(v) for v in line.split(",")] for line in rows])


def assert_close(name, actual, expected, rtol=DIAG_RTOL, atol=0.0):
    assert abs(actual - expected) <= rtol * abs(expected) + atol, (
        f"{name}: CLI {actual!r} vs reference {expected!r}")


@pytest.fixture(scope="module")
def fit(run_cli, write_csv):
    """fit(case, method, as_json=True) -> parsed JSON dict or CSV matrix; cached per module."""
    cache = {}

    def get(case, method, as_json=True):
        key = (case, method, as_json)
        if key not in cache:
            A, B = make_case(case)
            a, b = write_csv(f"{case}-A", A), write_csv(f"{case}-B", B)
            flags = ["--json"] if as_json else []
            out = run_cli("fit", "--method", method, *flags, a, b)
            cache[key] = json.loads(out) if as_json else parse_csv(out)
        return cache[key]
    return get


def case_data(case, method):
    """(A, B) of a case; skipped only if the documents' own applicability conditions
    (ref.degeneracy) fail -- all cases in cases.py are chosen to satisfy them."""
    A, B = make_case(case)
    reason = ref.degeneracy(method, A, B)
    if reason:
        pytest.skip(f"reference formula for {method} does not apply: {reason}")
    return A, B


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", sorted(CASES))
def test_fit_matches_reference(fit, case, method):
    A, B = case_data(case, method)
    out = fit(case, method)
    m, n = A.shape
    assert out["method"] == method and out["m"] == m and out["n"] == n
    assert isinstance(out["warnings"], list) and all(isinstance(w, str) for w in out["warnings"])
    X = np.array(out["X"], dtype=float)
    X_ref = ref.METHODS[method](A, B)
    assert X.shape == (n, n)
    assert rel(X, X_ref) <= X_RTOL, f"{method} X differs from reference:\n{X}\nvs\n{X_ref}"

    d = out["diagnostics"]
    missing = (REQUIRED_DIAGNOSTICS | METHOD_DIAGNOSTICS.get(method, set())) - set(d)
    assert not missing, f"diagnostics missing {sorted(missing)}"
    assert d["rank_a"] == np.linalg.matrix_rank(A) and d["rank_b"] == np.linalg.matrix_rank(B)
    assert_close("cond_a", d["cond_a"], np.linalg.cond(A))
    assert_close("cond_b", d["cond_b"], np.linalg.cond(B))
    # residual ||A X - B||_F may move by ||A|| ||dX|| within the X tolerance
    atol = X_RTOL * np.linalg.norm(A, 2) * np.linalg.norm(X_ref)
    assert_close("residual_norm", d["residual_norm"], np.linalg.norm(A @ X_ref - B), atol=atol)

    if method == "spde":
        # 2 tr(Sigma - A'B) cancels: allow rounding of its terms
        atol = ZERO_ATOL * 2 * abs(np.trace(A.T @ B))
        f_min = ref.area_minimum(A, B)
        assert_close("area_criterion", d["area_criterion"], ref.area_criterion(A, B, X_ref), atol=atol)
        assert_close("area_criterion_minimum", d["area_criterion_minimum"], f_min, atol=atol)
    if method == "procrustes":
        flag, lam_min = ref.cross_term_positive_definite(A, B)
        if abs(lam_min) > DEFINITENESS_MARGIN * np.linalg.norm(A.T @ B + B.T @ A):
            assert d["cross_term_positive_definite"] is flag
    if "tls_correction_norm" in d:  # required for tls, optional for tls-sym/tls-psd
        s1 = np.linalg.norm(np.hstack([A, B]), 2)
        assert_close("tls_correction_norm", d["tls_correction_norm"],
                     ref.tls_correction_norm(A, B), atol=ZERO_ATOL * s1)


@pytest.mark.parametrize("method", ["procrustes", "spde", "tls-sym", "tls-psd"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_fit_output_properties(fit, case, method):
    A, B = case_data(case, method)
    out = fit(case, method)
    X = np.array(out["X"], dtype=float)
    if method in ("procrustes", "spde"):
        assert np.array_equal(X, X.T), "X must be exactly symmetric"
    else:
        assert np.linalg.norm(X - X.T) <= SYM_RTOL * np.linalg.norm(X)
    if method == "tls-psd":
        assert np.linalg.eigvalsh(X)[0] >= -SYM_RTOL * np.linalg.norm(X)
    if method == "spde":
        assert np.linalg.eigvalsh(X)[0] > 0, "spde estimate must be positive definite"
        np.linalg.cholesky(X)
        P, Q = A.T @ A, B.T @ B
        # X P X = Q (paper eq. 10); a perturbation dX of X moves X P X by ~2 ||dX|| ||P|| ||X||
        err = np.linalg.norm(X @ P @ X - Q)
        assert err <= 10 * X_RTOL * np.linalg.norm(P) * np.linalg.norm(X) ** 2


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", ["thesis-m12-nm3.9-s1", "paper-2x2-indef-s42", "scalar-n1-s1"])
def test_fit_csv_round_trips_json(fit, case, method):
    case_data(case, method)
    X_json = np.array(fit(case, method)["X"], dtype=float)
    X_csv = fit(case, method, as_json=False)
    assert X_csv.shape == X_json.shape
    assert np.array_equal(X_csv, X_json), "CSV output must print X with round-trip precision"


@pytest.mark.parametrize("min_eig", [None, 0.0, 0.5])
@pytest.mark.parametrize("n", [1, 2, 6])
def test_nearest_matches_reference(spdfit_cli, run_cli, write_csv, n, min_eig):
    rng = np.random.default_rng(100 + n)
    X_in = 3.0 * rng.standard_normal((n, n)) - (1.0 if n == 1 else 0.0)  # indefinite input
    path = write_csv(f"nearest-{n}", X_in)
    flags = [] if min_eig is None else ["--min-eig", repr(min_eig)]
    largest = np.linalg.eigvalsh(0.5 * (X_in + X_in.T))[-1]
    # The default floor is relative: 1e-8 times the largest eigenvalue of the symmetric part.
    floor = 1e-8 * largest if min_eig is None else min_eig
    if floor < 0:
        # No positive eigenvalue to be relative to (the negative 1x1 input): a data error.
        proc = spdfit_testing.run_cli(spdfit_cli, "nearest", path, timeout_s=60)
        assert proc.returncode == 1 and "no positive eigenvalue" in proc.stderr and str(path) in proc.stderr
        return
    out = json.loads(run_cli("nearest", *flags, "--json", path))
    X = np.array(out["X"], dtype=float)
    X_ref = ref.nearest_spd(X_in, floor)
    # relative to the input: X_ref is 0 for a negative 1x1 input (the projection is 1-Lipschitz)
    assert X.shape == (n, n) and np.linalg.norm(X - X_ref) <= X_RTOL * np.linalg.norm(X_in)
    assert np.linalg.norm(X - X.T) <= SYM_RTOL * np.linalg.norm(X)
    assert np.linalg.eigvalsh(0.5 * (X + X.T))[0] >= floor - SYM_RTOL * np.linalg.norm(X)
    assert out["min_eig"] == pytest.approx(floor, rel=1e-12)
    assert out["cholesky"] == (floor > 0)
    X_csv = parse_csv(run_cli("nearest", *flags, path))
    assert np.array_equal(X_csv, X)
