"""The maximum-likelihood estimate of a symmetric positive definite X from A X ~= B with noise
covariances Sigma_A (of each row of A) and Sigma_B (of each row of B), computed independently of
spdfit: SciPy's BFGS on the Cholesky factor L of X = L L^T, with the gradient in closed form
(checked against finite differences by tests/reference/test_noise_reference.py).

The criterion is twice the negative log-likelihood of the errors-in-variables model with the true
rows eliminated (up to a constant),

    f(X) = sum_i r_i^T (X Sigma_A X + Sigma_B)^-1 r_i,   r_i the i-th row of A X - B,

what spdfit's spd-tls minimizes when given a noise model. Used by bench/noise_table.py and usable
by tests once the Python module takes a noise model: ``ml_estimate(A, B, cov_a, cov_b)``.
"""

import numpy as np
from scipy import optimize


def criterion(A, B, X, cov_a, cov_b):
    """f(X) = sum_i r_i^T W^-1 r_i with W = X^T Sigma_A X + Sigma_B, row by row (no Gram matrices)."""
    R = A @ X - B
    W = X.T @ cov_a @ X + cov_b
    return float(np.sum(R * np.linalg.solve(W, R.T).T))


def gradient(A, B, X, cov_a, cov_b):
    """The gradient of f over symmetric X (a symmetric matrix, for the trace inner product):

        grad f = M K + K M^T - N F - F N^T,

    K = W^-1, E = R^T R, F = K E K, M = A^T R, N = Sigma_A X (from df = tr(dE K) - tr(F dW))."""
    R = A @ X - B
    W = X @ cov_a @ X + cov_b
    K = np.linalg.inv(W)
    K = 0.5 * (K + K.T)
    E = R.T @ R
    F = K @ E @ K
    M = A.T @ R
    N = cov_a @ X
    G = M @ K + K @ M.T - N @ F - F @ N.T
    return 0.5 * (G + G.T)


def _starts(A, B, cov_a, cov_b):
    """Starting points: least squares and generalized TLS (when Sigma_B is definite), each made
    symmetric and positive definite by clipping its eigenvalues."""
    n = A.shape[1]
    starts = []
    X_ls = np.linalg.lstsq(A, B, rcond=None)[0]
    starts.append(X_ls)
    if np.all(np.linalg.eigvalsh(cov_b) > 0) and np.any(cov_a != 0):
        # Whitening by the square roots' inverses, TLS by the SVD, and back.
        wa, Va = np.linalg.eigh(cov_a)
        noisy = wa > 1e-12 * wa.max()
        if np.all(noisy):
            Ta = Va @ np.diag(wa ** -0.5) @ Va.T
            Ta_inv = Va @ np.diag(wa ** 0.5) @ Va.T
            wb, Vb = np.linalg.eigh(cov_b)
            Tb = Vb @ np.diag(wb ** -0.5) @ Vb.T
            Tb_inv = Vb @ np.diag(wb ** 0.5) @ Vb.T
            C = np.hstack([A @ Ta, B @ Tb])
            V = np.linalg.svd(C)[2].T
            X_w = -V[:n, n:] @ np.linalg.inv(V[n:, n:])
            starts.append(Ta @ X_w @ Tb_inv)
    out = []
    for X in starts:
        S = 0.5 * (X + X.T)
        w, V = np.linalg.eigh(S)
        w = np.maximum(w, 1e-3 * max(w.max(), 1e-300))
        out.append(V @ np.diag(w) @ V.T)
    return out


def ml_estimate(A, B, cov_a, cov_b, start=None, gtol=1e-11, maxiter=20000):
    """The SPD X minimizing `criterion` by BFGS on the lower triangle of its Cholesky factor, from
    `start` (an SPD matrix) or from the better of least squares and generalized TLS made positive
    definite. Returns (X, f). The criterion is divided by its value at the start, so that `gtol`
    is relative."""
    A = np.asarray(A, float)
    B = np.asarray(B, float)
    cov_a = np.asarray(cov_a, float)
    cov_b = np.asarray(cov_b, float)
    n = A.shape[1]
    rows, cols = np.tril_indices(n)
    candidates = [np.asarray(start, float)] if start is not None else _starts(A, B, cov_a, cov_b)
    best = None
    for X0 in candidates:
        L0 = np.linalg.cholesky(0.5 * (X0 + X0.T))
        scale = criterion(A, B, X0, cov_a, cov_b)

        def unpack(theta):
            L = np.zeros((n, n))
            L[rows, cols] = theta
            return L

        def value_and_gradient(theta):
            L = unpack(theta)
            X = L @ L.T
            try:
                f = criterion(A, B, X, cov_a, cov_b)
                G = gradient(A, B, X, cov_a, cov_b)
            except np.linalg.LinAlgError:
                return np.inf, np.zeros_like(theta)
            # d tr(G (dL L^T + L dL^T)) = 2 tr(G L dL^T): the gradient in L is 2 G L.
            return f / scale, (2.0 * G @ L)[rows, cols] / scale

        result = optimize.minimize(value_and_gradient, L0[rows, cols], jac=True, method="BFGS",
                                   options={"gtol": gtol, "maxiter": maxiter})
        L = unpack(result.x)
        X = L @ L.T
        f = criterion(A, B, X, cov_a, cov_b)
        if best is None or f < best[1]:
            best = (X, f)
    return best
