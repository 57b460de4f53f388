"""Issue 17: A X ~= B with B of d != n columns. spdfit's ls equals numpy.linalg.lstsq with several
right-hand sides, its tls the SVD solution of [A B] computed here with NumPy and, for one column,
scipy.odr's orthogonal distance regression; the streamed fit equals the in-memory one; the
symmetric methods raise ValueError naming ls and tls."""
import pickle

import numpy as np
import pytest
import scipy.odr

import spdfit


def problem(m, n, d, sigma, seed):
    rng = np.random.default_rng(seed)
    A0 = rng.standard_normal((m, n))
    X = rng.standard_normal((n, d))
    return A0 + sigma * rng.standard_normal((m, n)), A0 @ X + sigma * rng.standard_normal((m, d))


def tls_reference(A, B):
    n, d = A.shape[1], B.shape[1]
    V = np.linalg.svd(np.hstack([A, B]))[2].T
    return -V[:n, n:] @ np.linalg.inv(V[n:, n:])


@pytest.mark.parametrize("n, d", [(4, 2), (2, 5), (3, 1), (1, 3)])
def test_ls_is_lstsq_and_tls_is_the_svd_solution(n, d):
    A, B = problem(50, n, d, 0.05, seed=10 * n + d)
    ls = spdfit.fit(A, B, "ls")
    assert ls.X.shape == (n, d) and ls.diagnostics.n == n and ls.diagnostics.d == d
    np.testing.assert_allclose(ls.X, np.linalg.lstsq(A, B, rcond=None)[0], rtol=1e-12, atol=1e-14)
    tls = spdfit.fit(A, B, "tls")
    assert tls.X.shape == (n, d)
    np.testing.assert_allclose(tls.X, tls_reference(A, B), rtol=1e-11, atol=1e-13)
    assert tls.diagnostics.residual_norm == pytest.approx(np.linalg.norm(A @ tls.X - B), rel=1e-12)
    assert not tls.diagnostics.symmetric and tls.diagnostics.min_eigenvalue is None


def test_tls_with_one_column_is_orthogonal_distance_regression():
    # scipy.odr with equal weights on x and y and no intercept minimizes the same sum of squared
    # orthogonal distances as total least squares.
    A, B = problem(80, 3, 1, 0.05, seed=3)
    model = scipy.odr.Model(lambda beta, x: beta @ x)
    start = np.linalg.lstsq(A, B[:, 0], rcond=None)[0]
    out = scipy.odr.ODR(scipy.odr.RealData(A.T, B[:, 0]), model, beta0=start, sstol=1e-15, partol=1e-15,
                        maxit=1000).run()
    # ODR stops at about sqrt(eps) relative; least squares is 1e-3 away, so this tells them apart.
    tls = spdfit.fit(A, B, "tls").X[:, 0]
    np.testing.assert_allclose(tls, out.beta, rtol=1e-6)
    assert np.max(np.abs(tls - start) / np.abs(start)) > 1e-4


@pytest.mark.parametrize("method", [m for m in spdfit.METHODS if m not in ("ls", "tls")])
def test_symmetric_methods_refuse_a_non_square_x(method):
    A, B = problem(30, 3, 2, 0.01, seed=1)
    with pytest.raises(ValueError, match=f"{method} estimates a symmetric X.*use ls or tls"):
        spdfit.fit(A, B, method)


def test_fit_all_runs_ls_and_tls_only():
    A, B = problem(30, 3, 2, 0.01, seed=2)
    results = spdfit.fit_all(A, B)
    assert list(results) == ["ls", "tls"]
    np.testing.assert_array_equal(results["tls"].X, spdfit.fit(A, B, "tls").X)


def test_tls_needs_n_plus_d_rows():
    A, B = problem(4, 3, 2, 0.01, seed=4)
    with pytest.warns(spdfit.SpdfitWarning, match="degrees of freedom"):
        spdfit.fit(A, B, "ls")
    with pytest.raises(ValueError, match=r"n \+ d = 5"):
        spdfit.fit(A, B, "tls")


def test_streamed_files_and_pickles(tmp_path):
    A, B = problem(500, 4, 2, 0.05, seed=5)
    np.save(tmp_path / "A.npy", A)
    np.savetxt(tmp_path / "B.csv", B, delimiter=",")
    for method in ("ls", "tls"):
        streamed = spdfit.fit_files(tmp_path / "A.npy", tmp_path / "B.csv", method, block_rows=64)
        np.testing.assert_allclose(streamed.X, spdfit.fit(A, B, method).X, rtol=1e-12)
        back = pickle.loads(pickle.dumps(streamed))
        np.testing.assert_array_equal(back.X, streamed.X)
        assert back.diagnostics.d == 2
    with pytest.raises(spdfit.DataError, match="B.csv.*use ls or tls"):
        spdfit.fit_files(tmp_path / "A.npy", tmp_path / "B.csv", "spde")


def test_bootstrap_standard_errors_have_the_shape_of_x():
    A, B = problem(200, 3, 2, 0.05, seed=6)
    r = spdfit.fit(A, B, "tls", bootstrap=100)
    assert r.standard_errors.shape == (3, 2) and r.interval.lower.shape == (3, 2)
    assert r.bootstrap.eigenvalues is None
