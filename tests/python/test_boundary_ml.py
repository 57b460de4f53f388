"""spd-tls with a noise model where the likelihood's infimum over the positive definite matrices is
on the boundary (issue 42's reproduction: n = 3, m = 40, full non-diagonal Sigma_A and Sigma_B, a
true X of condition 1e6 and noise large enough for the boundary), against SciPy's BFGS over
X = L L^T (L square, so that any positive semidefinite X is reachable) started from spdfit's answer
with its null space opened slightly and from the reference's own starts: spdfit's criterion is no
higher; A -> A D, B -> B D^-1 gives D^-1 X D^-1; the certificate is the first-order conditions of
the constrained problem, recomputed here with NumPy. And auto there: the same constrained estimate."""
import warnings

import numpy as np
import pytest
from scipy import optimize

import noise_reference as ref
import spdfit

# As tests/python/test_noise_model.py: no independent optimizer finds a criterion lower by more
# than rounding; the unit changes are exact in arithmetic and Newton's stopping rule leaves X far
# closer than this.
CRITERION_RTOL = 1e-10
UNITS_RTOL = 1e-9
# The KKT residuals at spdfit's X, relative to f in unit-diagonal coordinates: Newton stops at
# 1e-10 of f; NumPy's gradient carries rounding of about m eps times its terms.
KKT_TOLERANCE = 1e-8
INSTANCES = 20


def instance(seed, m=40, n=3, noise=0.3):
    """Errors-in-variables data with full covariances and a true X of condition 1e6."""
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    X = Q @ np.diag(np.logspace(0, -6, n)) @ Q.T

    def covariance():
        G = rng.standard_normal((n, n))
        C = G @ G.T + 0.3 * np.eye(n)
        return noise ** 2 * n * C / np.trace(C)

    cov_a, cov_b = covariance(), covariance()
    A0 = rng.standard_normal((m, n))
    A = A0 + rng.multivariate_normal(np.zeros(n), cov_a, m)
    B = A0 @ X + rng.multivariate_normal(np.zeros(n), cov_b, m)
    return A, B, cov_a, cov_b


def fit(A, B, cov_a, cov_b, method="spd-tls"):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = spdfit.fit(A, B, method, noise=spdfit.NoiseModel(cov_a=cov_a, cov_b=cov_b))
    return result, caught


def boundary_instances(count, first_seed=0):
    """The first `count` seeds whose spd-tls ends on the boundary, as spdfit's warning says (its
    class BoundaryWarning, the code 'boundary')."""
    found = []
    for seed in range(first_seed, first_seed + 40 * count):
        A, B, cov_a, cov_b = instance(seed)
        result, caught = fit(A, B, cov_a, cov_b)
        if any(issubclass(w.category, spdfit.BoundaryWarning) and "on the boundary" in str(w.message)
               for w in caught):
            found.append((seed, A, B, cov_a, cov_b, result))
            if len(found) == count:
                break
    return found


@pytest.fixture(scope="module")
def cases():
    found = boundary_instances(INSTANCES)
    assert len(found) == INSTANCES
    return found


def bfgs_over_square_factor(A, B, cov_a, cov_b, X0):
    """BFGS on every entry of a square L with X = L L^T, from X0 with its eigenvalues floored at
    1e-6 of the largest (a singular X0's null space opened, so that BFGS can grow into it: at a zero
    column of L the gradient 2 G L vanishes)."""
    n = X0.shape[0]
    w, V = np.linalg.eigh(0.5 * (X0 + X0.T))
    L0 = V @ np.diag(np.sqrt(np.maximum(w, 1e-6 * w.max())))
    scale = ref.criterion(A, B, X0, cov_a, cov_b)

    def value_and_gradient(theta):
        L = theta.reshape(n, n)
        X = L @ L.T
        f = ref.criterion(A, B, X, cov_a, cov_b)
        return f / scale, (2.0 * ref.gradient(A, B, X, cov_a, cov_b) @ L).ravel() / scale

    out = optimize.minimize(value_and_gradient, L0.ravel(), jac=True, method="BFGS",
                            options={"gtol": 1e-12, "maxiter": 20000})
    L = out.x.reshape(n, n)
    return ref.criterion(A, B, L @ L.T, cov_a, cov_b)


def kkt(A, B, cov_a, cov_b, X, rank):
    """The certificate's numbers from NumPy: the gradient in the coordinates where X has a unit
    diagonal, split by X's range (its `rank` largest eigenvalues) and null space, relative to f."""
    d = np.sqrt(np.diag(X))
    Xh = X / np.outer(d, d)
    Gh = ref.gradient(A, B, X, cov_a, cov_b) * np.outer(d, d)
    w, V = np.linalg.eigh(Xh)
    n = X.shape[0]
    Vr, V0, root = V[:, n - rank:], V[:, :n - rank], np.sqrt(np.maximum(w[n - rank:], 0.0))
    f = ref.criterion(A, B, X, cov_a, cov_b)
    return (np.linalg.norm(root[:, None] * (Vr.T @ Gh @ Vr) * root[None, :]) / f,
            np.linalg.norm(root[:, None] * (Vr.T @ Gh @ V0)) / f,
            np.linalg.eigvalsh(V0.T @ Gh @ V0)[0] / f)


def test_the_criterion_is_at_the_constrained_minimum(cases):
    for seed, A, B, cov_a, cov_b, result in cases:
        assert result.ok and result.diagnostics.converged, seed
        f = ref.criterion(A, B, result.X, cov_a, cov_b)
        f_from_x = bfgs_over_square_factor(A, B, cov_a, cov_b, result.X)
        _, f_ref = ref.ml_estimate(A, B, cov_a, cov_b)  # from least squares and generalized TLS
        assert f <= min(f_from_x, f_ref) * (1 + CRITERION_RTOL), (seed, f, f_from_x, f_ref)


def test_the_certificate_is_the_first_order_conditions(cases):
    for seed, A, B, cov_a, cov_b, result in cases:
        c = result.diagnostics.certificate
        assert isinstance(c, spdfit.BoundaryCertificate), seed
        assert 1 <= c.rank < 3
        w = np.linalg.eigvalsh(result.X)
        assert np.all(np.abs(w[:3 - c.rank]) <= 1e-13 * w[-1]), (seed, w)
        stationarity, cross_block, multiplier = kkt(A, B, cov_a, cov_b, result.X, c.rank)
        assert stationarity <= KKT_TOLERANCE and cross_block <= KKT_TOLERANCE, (seed, stationarity, cross_block)
        assert multiplier >= -KKT_TOLERANCE, (seed, multiplier)
        assert c.stationarity <= KKT_TOLERANCE and c.cross_block <= KKT_TOLERANCE, (seed, c)
        assert c.multiplier_min_eig == pytest.approx(multiplier, rel=1e-6, abs=KKT_TOLERANCE), (seed, c)


def test_units_of_the_columns_give_the_congruent_estimate(cases):
    D = np.diag([3.0, 0.01, 70.0])
    D_inv = np.linalg.inv(D)
    for seed, A, B, cov_a, cov_b, result in cases:
        moved, _ = fit(A @ D, B @ D_inv, D @ cov_a @ D, D_inv @ cov_b @ D_inv)
        expected = D_inv @ result.X @ D_inv
        assert np.linalg.norm(moved.X - expected) <= UNITS_RTOL * np.linalg.norm(expected), seed
        assert moved.diagnostics.certificate.rank == result.diagnostics.certificate.rank


def test_auto_returns_the_constrained_maximum_likelihood_estimate(cases):
    D = np.diag([0.2, 5.0, 1e3])
    D_inv = np.linalg.inv(D)
    chose_spd_tls = 0
    for seed, A, B, cov_a, cov_b, result in cases[:6]:
        auto, caught = fit(A, B, cov_a, cov_b, "auto")
        if auto.method != "spd-tls":
            continue  # too few rows for its signal-to-noise ratio: spde
        chose_spd_tls += 1
        assert auto.diagnostics.reason.code == "boundary"
        assert "constrained maximum-likelihood" in auto.diagnostics.reason.text
        assert any(issubclass(w.category, spdfit.BoundaryWarning) and "auto: " in str(w.message)
                   for w in caught), seed
        np.testing.assert_array_equal(auto.X, result.X)
        assert isinstance(auto.diagnostics.certificate, spdfit.BoundaryCertificate)
        moved, _ = fit(A @ D, B @ D_inv, D @ cov_a @ D, D_inv @ cov_b @ D_inv, "auto")
        expected = D_inv @ auto.X @ D_inv
        assert np.linalg.norm(moved.X - expected) <= UNITS_RTOL * np.linalg.norm(expected), seed
    assert chose_spd_tls > 0


def test_interior_fits_have_no_certificate():
    rng = np.random.default_rng(5)
    A0 = rng.standard_normal((200, 3))
    A = A0 + 0.05 * rng.standard_normal((200, 3))
    B = A0 @ np.diag([3.0, 2.0, 1.0]) + 0.05 * rng.standard_normal((200, 3))
    result, _ = fit(A, B, 0.0025 * np.eye(3), 0.0025 * np.eye(3))
    assert result.diagnostics.positive_definite and result.diagnostics.certificate is None
