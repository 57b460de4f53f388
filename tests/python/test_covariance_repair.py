"""Covariance repair (spdfit.nearest_spd): the relative default floor, keep_diag and via_corr,
against independent references: alternating projections with Dykstra's correction in NumPy (the
fixed-diagonal problem, weighted and with a floor), the closed-form eigenvalue clip, statsmodels'
cov_nearest, and the properties users rely on (Cholesky succeeds, the diagonal is kept exactly,
repairing s C gives s X)."""
import pickle
import warnings

import numpy as np
import pytest

import spdfit
from spdfit_testing import indefinite_covariance
from test_nearest_correlation import dykstra


def clip(C, floor):
    lam, V = np.linalg.eigh((C + C.T) / 2)
    return (V * np.maximum(lam, floor)) @ V.T


def test_default_floor_is_relative_and_the_result_factors():
    C = indefinite_covariance(30, 1)
    r = spdfit.nearest_spd(C, full_output=True)
    floor = spdfit.REPAIR_FLOOR_DEFAULT * np.linalg.eigvalsh(C)[-1]
    assert r.min_eig == pytest.approx(floor, rel=1e-13)
    np.testing.assert_allclose(r.X, clip(C, floor), atol=1e-13 * np.abs(C).max())
    assert r.cholesky_ok and r.iterations == 0 and r.converged
    np.linalg.cholesky(r.X)
    # min_eig=0 stays the plain semidefinite projection (its Cholesky usually fails).
    plain = spdfit.nearest_spd(C, min_eig=0, full_output=True)
    np.testing.assert_allclose(plain.X, clip(C, 0.0), atol=1e-13 * np.abs(C).max())


def test_relative_floor_follows_the_scale_and_an_absolute_one_warns():
    C = indefinite_covariance(8, 2, scale=1e-8)
    # Relative: the same repair at any scale.
    X = spdfit.nearest_spd(C)
    np.testing.assert_allclose(X * 1e8, spdfit.nearest_spd(C * 1e8), rtol=1e-12, atol=1e-20)
    # The absolute 1e-6 every old example showed is 100 times the matrix: a warning says so.
    with pytest.warns(spdfit.SpdfitWarning, match="moved the matrix by .* more than the repair itself"):
        spdfit.nearest_spd(C, min_eig=1e-6)
    # With a fixed diagonal the floor stays below the variances, but can still dwarf the repair: a
    # rank-one correlation, indefinite by 1e-9, floored at 0.5.
    R = np.ones((4, 4)) + 1e-9 * np.array([[0, 1, -1, 0], [1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 1, 0]])
    with pytest.warns(spdfit.SpdfitWarning, match="more than the repair itself"):
        spdfit.nearest_spd(R, min_eig=0.5, keep_diag=True)
    with pytest.warns(spdfit.SpdfitWarning, match="more than the repair itself"):
        spdfit.nearest_correlation(R, min_eig=0.5)


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("floor", [0.0, 0.05])
def test_keep_diag_agrees_with_dykstra(weighted, floor):
    C = indefinite_covariance(10, 3)
    w = np.linspace(0.5, 3.0, 10) if weighted else None
    r = spdfit.nearest_spd(C, floor, keep_diag=True, weights=w, full_output=True)
    assert r.converged
    np.testing.assert_allclose(r.X, dykstra(C, w, d=np.diag(C), floor=floor), atol=1e-8)
    assert np.array_equal(np.diag(r.X), np.diag(C))
    assert np.linalg.eigvalsh(r.X)[0] >= floor - 1e-12
    root = np.ones(10) if w is None else np.sqrt(w)
    assert r.distance == pytest.approx(np.linalg.norm(root[:, None] * (r.X - C) * root[None, :]), rel=1e-12)


@pytest.mark.parametrize("weighted", [False, True])
def test_keep_diag_relative_floor_is_of_the_correlation_matrix(weighted):
    """keep_diag's relative floor: D^-1/2 X D^-1/2 >= floor, floor = min_eig_rel times the largest
    eigenvalue of the correlation matrix D^-1/2 C D^-1/2; the same minimizer as Dykstra's on
    Y = X - floor D (Y >= 0 with diagonal (1 - floor) d, the target C - floor D)."""
    C = indefinite_covariance(10, 11)
    d = np.diag(C)
    w = np.linspace(0.5, 3.0, 10) if weighted else None
    rel = 0.05
    r = spdfit.nearest_spd(C, min_eig_rel=rel, keep_diag=True, weights=w, full_output=True)
    R = C / np.sqrt(np.outer(d, d))
    floor = rel * np.linalg.eigvalsh(R)[-1]
    assert r.min_eig == pytest.approx(floor, rel=1e-13)
    assert r.converged and r.cholesky_ok
    reference = dykstra(C - floor * np.diag(d), w, d=(1 - floor) * d) + floor * np.diag(d)
    np.testing.assert_allclose(r.X, reference, atol=1e-8)
    assert np.array_equal(np.diag(r.X), d)
    # Active: the correlation matrix's smallest eigenvalue sits at the floor.
    assert np.linalg.eigvalsh(r.X / np.sqrt(np.outer(d, d)))[0] == pytest.approx(floor, abs=1e-10)


@pytest.mark.parametrize("s", [8.0, 3.7, 1e-6])
def test_keep_diag_and_relative_floor_scale(s):
    C = indefinite_covariance(12, 4)
    X = spdfit.nearest_spd(C, keep_diag=True)
    Xs = spdfit.nearest_spd(s * C, keep_diag=True)
    if s == 8.0:  # a power of two: exactly
        assert np.array_equal(Xs, s * X)
    np.testing.assert_allclose(Xs, s * X, rtol=0, atol=1e-12 * s * np.abs(C).max())
    np.linalg.cholesky(Xs)


def test_via_corr_is_keep_diag_in_the_correlation_norm():
    C = indefinite_covariance(9, 5)
    via = spdfit.nearest_spd(C, 0, via_corr=True, full_output=True)
    # statsmodels' cov_nearest route = the fixed-diagonal problem with weights 1 / diag(C).
    kept = spdfit.nearest_spd(C, 0, keep_diag=True, weights=1 / np.diag(C))
    np.testing.assert_allclose(via.X, kept, atol=1e-9)
    assert np.array_equal(np.diag(via.X), np.diag(C))
    assert via.distance == pytest.approx(np.linalg.norm(via.X - C), rel=1e-12)
    # ... and a different answer from keep_diag's Frobenius-norm one, which is nearer in C's units.
    plain_kept = spdfit.nearest_spd(C, 0, keep_diag=True, full_output=True)
    assert plain_kept.distance < via.distance


def test_via_corr_against_statsmodels_cov_nearest():
    from statsmodels.stats import correlation_tools as statsmodels
    C = indefinite_covariance(6, 6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its iteration limit
        theirs = statsmodels.cov_nearest(C, method="nearest", threshold=1e-15, n_fact=100)
    ours = spdfit.nearest_spd(C, 0, via_corr=True)
    # Its alternating projections, run long enough, reach the same matrix.
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-9 * np.abs(C).max())


def test_every_default_output_factors():
    for seed in range(10):
        C = indefinite_covariance(25, 100 + seed)
        for kwargs in ({}, {"keep_diag": True}, {"via_corr": True}):
            r = spdfit.nearest_spd(C, full_output=True, **kwargs)
            assert r.cholesky_ok, (seed, kwargs)
            np.linalg.cholesky(r.X)
        with pytest.warns(spdfit.SpdfitWarning, match="the diagonal is not 1"):
            np.linalg.cholesky(spdfit.nearest_correlation(C))


def test_argument_checks():
    C = indefinite_covariance(4, 8)
    with pytest.raises(ValueError, match="not both"):
        spdfit.nearest_spd(C, keep_diag=True, via_corr=True)
    with pytest.raises(ValueError, match="not both"):
        spdfit.nearest_spd(C, 0.1, min_eig_rel=1e-3)
    with pytest.raises(ValueError, match="weights needs keep_diag"):
        spdfit.nearest_spd(C, weights=np.ones(4))
    with pytest.raises(ValueError, match=r"min_eig_rel must be a number in \[0, 1\)"):
        spdfit.nearest_spd(C, min_eig_rel=1.0)
    with pytest.raises(ValueError, match="no positive eigenvalue"):
        spdfit.nearest_spd(-np.eye(3))
    bad = C.copy()
    bad[2, 2] = -1.0
    with pytest.raises(ValueError, match="diagonal entry 3"):
        spdfit.nearest_spd(bad, via_corr=True)
    with pytest.raises(ValueError, match="not below diagonal entry"):
        spdfit.nearest_spd(C, 10.0, keep_diag=True)
    with pytest.raises(TypeError, match="min_eig_rel must be a real number"):
        spdfit.nearest_spd(C, min_eig_rel="1e-8")


def test_result_pickles():
    r = spdfit.nearest_spd(indefinite_covariance(5, 8), keep_diag=True, full_output=True)
    back = pickle.loads(pickle.dumps(r))
    assert np.array_equal(back.X, r.X) and back.iterations == r.iterations and back.min_eig == r.min_eig
    assert back.warnings == r.warnings and back.cholesky_ok == r.cholesky_ok
    assert spdfit.NearestSpdResult is spdfit.NearestCorrelationResult is spdfit.NearestResult
