"""spdfit.nearest_correlation against independent references: Higham's (2002) alternating
projections with Dykstra's correction, written here in NumPy and run to convergence (weighted
too), statsmodels' corr_nearest where it applies, and the properties users rely on (unit
diagonal, Cholesky with a floor)."""
import warnings

import numpy as np
import pytest

import spdfit


def dykstra(C, w=None, d=None, floor=0.0, tol=1e-13, max_iter=200_000):
    """Higham 2002, Algorithm 3.3: alternating projections onto {X >= floor I} (in the W-norm,
    W = diag(w)) and the matrices with diagonal d (default ones), with Dykstra's correction."""
    n = C.shape[0]
    w = np.ones(n) if w is None else np.asarray(w, float)
    d = np.ones(n) if d is None else np.asarray(d, float)
    root = np.sqrt(w)
    Y = (C + C.T) / 2
    dS = np.zeros_like(Y)
    for _ in range(max_iter):
        R = Y - dS
        # The W-norm projection onto X >= floor I: X - floor I = W^-1/2 (W^1/2 (R - floor I) W^1/2)_+ W^-1/2.
        M = root[:, None] * (R - floor * np.eye(n)) * root[None, :]
        lam, V = np.linalg.eigh(M)
        X = (V * np.maximum(lam, 0)) @ V.T / (root[:, None] * root[None, :]) + floor * np.eye(n)
        dS = X - R
        Y_next = X.copy()
        np.fill_diagonal(Y_next, d)
        if np.linalg.norm(Y_next - Y) <= tol * np.linalg.norm(Y):
            return Y_next
        Y = Y_next
    raise AssertionError("Dykstra did not converge")


def random_indefinite(n, seed):
    rng = np.random.default_rng(seed)
    M = rng.uniform(-1, 1, (n, n))
    C = M + M.T
    np.fill_diagonal(C, 1.0)
    return C


@pytest.mark.parametrize("n,seed", [(4, 2), (10, 2), (25, 3)])
def test_agrees_with_dykstra_alternating_projections(n, seed):
    C = random_indefinite(n, seed)
    assert np.linalg.eigvalsh(C)[0] < 0
    r = spdfit.nearest_correlation(C, min_eig=0, full_output=True)
    assert r.converged
    np.testing.assert_allclose(r.X, dykstra(C), atol=1e-8)
    np.testing.assert_array_equal(np.diag(r.X), np.ones(n))
    assert r.distance == pytest.approx(np.linalg.norm(r.X - C), rel=1e-12)


def test_weighted_agrees_with_weighted_dykstra():
    C = random_indefinite(8, 4)
    w = np.linspace(0.5, 4.0, 8)
    X = spdfit.nearest_correlation(C, weights=w, min_eig=0)
    np.testing.assert_allclose(X, dykstra(C, w), atol=1e-8)
    # The weights change the answer: heavier rows move less.
    plain = spdfit.nearest_correlation(C, min_eig=0)
    assert not np.allclose(X, plain, atol=1e-6)


def test_statsmodels_corr_nearest_on_a_unit_diagonal_input():
    from statsmodels.stats import correlation_tools as statsmodels
    C = random_indefinite(6, 5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its iteration limit: it stops short of our tolerance
        theirs = statsmodels.corr_nearest(C, threshold=1e-15, n_fact=100)
    ours = spdfit.nearest_correlation(C, min_eig=0)
    # Its alternating projections (threshold 1e-15: the plain problem) reach the same matrix.
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-9)


def test_alpha_gives_a_cholesky_factorable_unit_diagonal_matrix():
    C = random_indefinite(30, 6)
    r = spdfit.nearest_correlation(C, alpha=1e-3, full_output=True)
    assert r.cholesky_ok
    np.linalg.cholesky(r.X)
    assert np.linalg.eigvalsh(r.X)[0] >= 1e-3 - 1e-12
    assert np.max(np.abs(np.diag(r.X) - 1)) <= 1e-14
    # NAG's alpha and the floor are one constraint (X >= alpha I): the same minimizer.
    np.testing.assert_allclose(r.X, spdfit.nearest_correlation(C, min_eig=1e-3), atol=1e-10)


@pytest.mark.parametrize("floor", [0.05, 0.3])
def test_floor_is_an_exact_constraint_as_dykstra_finds_it(floor):
    C = random_indefinite(12, 8)
    r = spdfit.nearest_correlation(C, min_eig=floor, full_output=True)
    np.testing.assert_allclose(r.X, dykstra(C, floor=floor), atol=1e-8)
    assert r.min_eig == floor and np.linalg.eigvalsh(r.X)[0] >= floor - 1e-12
    # Between the unconstrained optimum and a feasible point built from it, (1 - f) X0 + f I.
    X0 = dykstra(C)
    assert np.linalg.norm(C - X0) <= r.distance <= np.linalg.norm(C - ((1 - floor) * X0 + floor * np.eye(12)))


@pytest.mark.parametrize("n,seed", [(5, 1), (40, 2), (150, 3)])
def test_default_is_a_relative_floor_and_cholesky_succeeds(n, seed):
    C = random_indefinite(n, seed)
    r = spdfit.nearest_correlation(C, full_output=True)
    assert r.min_eig == pytest.approx(spdfit.REPAIR_FLOOR_DEFAULT * np.linalg.eigvalsh(C)[-1], rel=1e-12)
    assert r.cholesky_ok and r.converged
    np.linalg.cholesky(r.X)
    assert np.all(np.diag(r.X) == 1.0)
    assert np.max(np.abs(r.X - r.X.T)) == 0
    if n <= 40:
        np.testing.assert_allclose(r.X, dykstra(C, floor=r.min_eig), atol=1e-8)


def test_argument_checks_and_warnings():
    with pytest.raises(ValueError, match="weights"):
        spdfit.nearest_correlation(np.eye(3), weights=[1, 2])
    with pytest.raises(ValueError, match="weight 2 is -1"):
        spdfit.nearest_correlation(np.eye(3), weights=[1, -1, 1])
    with pytest.raises(ValueError, match="alpha"):
        spdfit.nearest_correlation(np.eye(3), alpha=1.0)
    with pytest.raises(ValueError, match="not both"):
        spdfit.nearest_correlation(np.eye(3), min_eig=0.1, min_eig_rel=1e-3)
    with pytest.raises(ValueError, match="not both"):
        spdfit.nearest_correlation(np.eye(3), alpha=0.1, min_eig=0.1)
    with pytest.raises(ValueError, match="not below diagonal entry 1"):
        spdfit.nearest_correlation(np.eye(3), min_eig=1.0)
    with pytest.raises(TypeError, match="max_iter must be an int"):
        spdfit.nearest_correlation(np.eye(3), max_iter=2.5)
    C = random_indefinite(20, 7)
    with pytest.warns(spdfit.SpdfitWarning, match="not converged"):
        r = spdfit.nearest_correlation(C, max_iter=1, full_output=True)
    assert not r.converged and np.all(np.diag(r.X) == 1)
    asymmetric = np.eye(3)
    asymmetric[0, 1] = 0.4
    with pytest.warns(spdfit.SpdfitWarning, match="not symmetric"):
        spdfit.nearest_correlation(asymmetric)


def test_r_matrix_symw_converges_and_is_optimal():
    """R's Matrix package's nearPD test matrix symW (tests/data/r_matrix): entries up to 1.8e8
    given for a correlation matrix, so that the dual matrix G + diag(y) has norm about 1e8 and the
    dual gradient cannot be computed below about eps * 1e8 (its eigendecomposition's rounding):
    the stopping test allows that level, and the answer is a certified minimizer. The certificate,
    from X alone: with y recovered from (X - C) X = diag(y) X (row by row), S = X - C - diag(y)
    is positive semidefinite and S X = 0, each to rounding of ||C||_2 (the eigendecomposition's
    backward error, n eps ||C||_2)."""
    from spdfit_testing import SOURCE_DIR
    C = np.loadtxt(SOURCE_DIR / "tests" / "data" / "r_matrix" / "symW.csv", delimiter=",")
    with pytest.warns(spdfit.DiagonalChangedWarning, match="the diagonal is not 1"):
        r = spdfit.nearest_correlation(C, min_eig=0, full_output=True)
    assert r.converged and r.iterations < 200
    X = r.X
    n = len(X)
    assert np.all(np.diag(X) == 1.0)
    rounding = n * np.finfo(float).eps * np.linalg.norm(C, 2)
    assert np.linalg.eigvalsh(X)[0] >= -n * np.finfo(float).eps * np.linalg.norm(X, 2)  # X >= 0 to rounding
    y = np.sum(((X - C) @ X) * X, axis=1) / np.sum(X * X, axis=1)
    S = X - C - np.diag(y)
    assert np.linalg.eigvalsh(S)[0] >= -rounding
    assert np.linalg.norm(S @ X) <= rounding * np.linalg.norm(X)


def test_large_n_with_single_precision_early_steps_is_certified():
    """From n = 1000 on, the Newton steps whose dual gradient is far above single precision's
    rounding level decompose in single precision (correlation_newton.cpp); the last steps and the
    answer are in double. The answer is certified as above, from X alone: S = X - C - diag(y)
    positive semidefinite and S X = 0 to 1e-10 ||C||_2 (the answer meets it by a factor of about
    600; X rounded to single precision misses it by factors of about 135 and 75)."""
    n = 1200
    C = random_indefinite(n, 11) / np.sqrt(n)
    np.fill_diagonal(C, 1.0)
    r = spdfit.nearest_correlation(C, min_eig=0, full_output=True)
    assert r.converged and r.iterations <= 10
    X = r.X
    assert np.all(np.diag(X) == 1.0) and np.max(np.abs(X - X.T)) == 0
    assert np.linalg.eigvalsh(X)[0] >= -n * np.finfo(float).eps * np.linalg.norm(X, 2)
    y = np.sum(((X - C) @ X) * X, axis=1) / np.sum(X * X, axis=1)
    S = X - C - np.diag(y)
    level = 1e-10 * np.linalg.norm(C, 2)
    assert np.linalg.eigvalsh(S)[0] >= -level
    assert np.linalg.norm(S @ X) <= level * np.linalg.norm(X)
    assert r.distance == pytest.approx(np.linalg.norm(X - C), rel=1e-12)
