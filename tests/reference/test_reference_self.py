"""Checks that the reference implementation itself is right, so it can serve as an oracle."""
import numpy as np
import pytest
import scipy.linalg

import thesis_reference as ref
from cases import CASES, make_case

# Residuals of identities (Lyapunov 3.15, X P X = Q, A^ X = B^): backward-stable solves
# on well-conditioned data leave a few hundred ulps relative to the terms' size.
IDENTITY_RTOL = 1e-11
# The reference must agree with a Gram-free formulation 100x tighter than the CLI
# comparison (1e-10), so that a CLI mismatch cannot be the reference's own rounding.
ALT_RTOL = 1e-12
# Rank-deficient B through Gram matrices: zero eigenvalues of Q~ come out as
# O(eps ||Q~||), so their square roots (entries of Sigma_Q~) are O(sqrt(eps)) ~ 1e-8.
SQRT_EPS_RTOL = 1e-6
# Monte-Carlo checks (noise variance) with 200000 draws: relative std ~ 0.3%.
STAT_RTOL = 0.03


def rel(X, Y):
    return np.linalg.norm(X - Y) / np.linalg.norm(Y)


def random_spd(rng, n, scale=1.0):
    G = rng.standard_normal((n, n))
    return G @ G.T + scale * np.eye(n)


def procrustes_vech(A, B):
    """Symmetric Procrustes as a plain least squares problem in vech(X) (no Gram matrix)."""
    n = A.shape[1]
    cols = []
    for i, j in zip(*np.triu_indices(n)):
        E = np.zeros((n, n))
        E[i, j] = E[j, i] = 1.0
        cols.append((A @ E).ravel())
    x = np.linalg.lstsq(np.array(cols).T, B.ravel(), rcond=None)[0]
    X = np.zeros((n, n))
    X[np.triu_indices(n)] = x
    return X + np.triu(X, 1).T


def spde_qr(A, B):
    """Gram-free form of paper eq. (11): with A = QR, P = R'R, Z = R X R' solves
    Z^2 = R Q R' = M'M for M = B R', so Z = V S V' from the SVD M = U S V'."""
    R = np.linalg.qr(A, mode="r")
    _, s, Vt = np.linalg.svd(B @ R.T)
    Rinv = scipy.linalg.solve_triangular(R, np.eye(A.shape[1]))
    W = Rinv @ Vt.T
    return (W * s) @ W.T


def tls_from_approximation(A, B):
    """Solve A^ X = B^ (thesis 4.27) for the rank-n approximation (4.31) by least squares."""
    n = A.shape[1]
    U, s, Vt = np.linalg.svd(np.hstack([A, B]), full_matrices=False)
    C_hat = (U[:, :n] * s[:n]) @ Vt[:n]
    return np.linalg.lstsq(C_hat[:, :n], C_hat[:, n:], rcond=None)[0], C_hat


def ls_qr(A, B):
    Qa, R = np.linalg.qr(A)
    return scipy.linalg.solve_triangular(R, Qa.T @ B)


ALTERNATIVES = {
    "ls": ls_qr,
    "procrustes": procrustes_vech,
    "tls": lambda A, B: tls_from_approximation(A, B)[0],
    "spde": spde_qr,
}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("method", sorted(ALTERNATIVES))
def test_reference_matches_gram_free_formulation(case, method):
    A, B = make_case(case)
    assert ref.degeneracy(method, A, B) is None
    assert rel(ref.METHODS[method](A, B), ALTERNATIVES[method](A, B)) <= ALT_RTOL


def test_generator_exact_and_noise_levels():
    Mp = ref.MP_THESIS
    assert np.array_equal(Mp, Mp.T) and np.linalg.eigvalsh(Mp)[0] > 0
    A, B, X = ref.thesis_generator(50, 6, 0.0, np.random.default_rng(0))
    assert np.array_equal(X, Mp) and np.array_equal(B, A @ Mp)  # nm = 0: no noise at all
    for nm in (1.0, 3.2, 3.9):
        A, B, _ = ref.thesis_generator(200000, 6, nm, np.random.default_rng(1))
        var = nm ** 2 / 12
        # A = true + noise: variance 100/12 + nm^2/12; B - A Mp = v_f - v_l Mp (eq. 6.3-6.4)
        assert np.allclose(A.var(axis=0), 100 / 12 + var, rtol=STAT_RTOL)
        E = B - A @ Mp
        assert np.allclose(E.var(axis=0), var * (1 + (Mp ** 2).sum(axis=0)), rtol=STAT_RTOL)
        assert np.allclose(E.mean(axis=0), 0, atol=0.05)
    with pytest.raises(ValueError):
        ref.thesis_generator(12, 5, 1.0, np.random.default_rng(0))


@pytest.mark.parametrize("method", sorted(ref.METHODS))
def test_noise_free_data_recover_truth(method):
    A, B, X = ref.thesis_generator(12, 6, 0.0, np.random.default_rng(5))
    assert rel(ref.METHODS[method](A, B), X) <= IDENTITY_RTOL
    assert abs(ref.area_minimum(A, B)) <= IDENTITY_RTOL * np.trace(A.T @ B)
    assert ref.tls_correction_norm(A, B) <= IDENTITY_RTOL * np.linalg.norm(B)


@pytest.mark.parametrize("case", sorted(CASES))
def test_procrustes_normal_equation(case):
    A, B = make_case(case)
    X, P, C = ref.procrustes(A, B), A.T @ A, A.T @ B + B.T @ A
    scale = 2 * np.linalg.norm(P) * np.linalg.norm(X) + np.linalg.norm(C)
    assert np.linalg.norm(P @ X + X @ P - C) <= IDENTITY_RTOL * scale  # eq. (3.15)
    assert np.linalg.norm(X - X.T) <= IDENTITY_RTOL * np.linalg.norm(X)
    rng = np.random.default_rng(7)
    f0 = np.linalg.norm(A @ X - B) ** 2
    for _ in range(50):  # Theorem 3.2: a minimiser over symmetric matrices
        E = rng.standard_normal(X.shape) * 1e-3
        assert np.linalg.norm(A @ (X + E + E.T) - B) ** 2 >= f0
    if ref.cross_term_positive_definite(A, B)[0]:  # Theorem 3.2 (3)
        assert np.linalg.eigvalsh(0.5 * (X + X.T))[0] > 0


@pytest.mark.parametrize("case", sorted(CASES))
def test_spde_optimality(case):
    A, B = make_case(case)
    X, P, Q = ref.spde(A, B), A.T @ A, B.T @ B
    assert np.array_equal(X, X.T)
    assert np.linalg.eigvalsh(X)[0] > 0
    assert np.linalg.norm(X @ P @ X - Q) <= IDENTITY_RTOL * np.linalg.norm(Q)  # paper eq. (10)
    f0, fmin = ref.area_criterion(A, B, X), ref.area_minimum(A, B)
    scale = 2 * abs(np.trace(A.T @ B))  # cancellation in 2 tr(Sigma - A'B)
    assert abs(f0 - fmin) <= IDENTITY_RTOL * scale  # Corollary III.4
    rng = np.random.default_rng(11)
    for eps in (1e-1, 1e-3):
        for _ in range(30):
            L = np.linalg.cholesky(X) @ (np.eye(len(X)) + eps * rng.standard_normal(X.shape))
            assert ref.area_criterion(A, B, L @ L.T) >= f0 - IDENTITY_RTOL * scale


def test_spde_rank_deficient_b():
    """Paper Corollary III.7: rank(B) = r < n gives a PSD rank-r X with X P X = Q and
    h(X) = tr(P X + X^+ Q) = 2 tr(Sigma_Q~)."""
    rng = np.random.default_rng(3)
    A = rng.standard_normal((20, 4))
    B = rng.standard_normal((20, 2)) @ rng.standard_normal((2, 4))
    X, P, Q = ref.spde(A, B), A.T @ A, B.T @ B
    lam = np.linalg.eigvalsh(X)
    # Semidefinite to rounding: the zero eigenvalues come out as +-1e-17 or so (sign depends
    # on the BLAS NumPy runs on).
    assert np.all(lam >= -1e-12 * lam[-1]) and np.sum(lam > SQRT_EPS_RTOL * lam[-1]) == 2
    assert np.linalg.norm(X @ P @ X - Q) <= SQRT_EPS_RTOL * np.linalg.norm(Q)
    h = np.trace(P @ X + np.linalg.pinv(X, rcond=SQRT_EPS_RTOL) @ Q)
    assert np.isclose(h, ref.area_minimum(A, B) + 2 * np.trace(A.T @ B), rtol=SQRT_EPS_RTOL)
    assert ref.degeneracy("spde", A, B) == "rank(B) < n"


@pytest.mark.parametrize("case", sorted(CASES))
def test_tls_solves_rank_n_approximation(case):
    A, B = make_case(case)
    n = A.shape[1]
    X = ref.tls(A, B)
    X_alt, C_hat = tls_from_approximation(A, B)
    A_hat, B_hat = C_hat[:, :n], C_hat[:, n:]
    assert np.linalg.norm(A_hat @ X - B_hat) <= IDENTITY_RTOL * np.linalg.norm(B_hat)  # (4.27)
    s = np.linalg.svd(np.hstack([A, B]), compute_uv=False)
    corr = np.linalg.norm(np.hstack([A, B]) - C_hat)
    expected = np.sqrt(np.sum(np.sort(s)[: len(s) - n] ** 2))  # (4.33)
    assert abs(ref.tls_correction_norm(A, B) - expected) <= 1e-12 * s[0]
    assert abs(corr - expected) <= 1e-12 * s[0]
    Xs, Xf = ref.tls_sym(A, B), ref.tls_psd(A, B)
    assert np.array_equal(Xs, Xs.T) and np.linalg.eigvalsh(Xf)[0] >= -IDENTITY_RTOL * np.linalg.norm(Xf)
    if np.linalg.eigvalsh(Xs)[0] > 0:  # PD X_S: Higham's step leaves it unchanged
        assert rel(Xf, Xs) <= IDENTITY_RTOL


def test_higham_nearest_psd():
    rng = np.random.default_rng(13)
    for n in (1, 2, 6):
        X = rng.standard_normal((n, n)) * 3
        F = ref.nearest_spd(X)
        lam, V = np.linalg.eigh(0.5 * (X + X.T))
        assert rel(F, (V * np.maximum(lam, 0)) @ V.T) <= IDENTITY_RTOL
        assert np.linalg.eigvalsh(F)[0] >= -IDENTITY_RTOL * np.linalg.norm(F)
        assert rel(ref.nearest_spd(F), F) <= IDENTITY_RTOL  # a projection: idempotent
        d0 = np.linalg.norm(X - F)
        for _ in range(50):  # nearest among PSD matrices
            G = rng.standard_normal((n, n))
            assert np.linalg.norm(X - (F + 1e-2 * G @ G.T)) >= d0
        G = ref.nearest_spd(X, min_eig=0.5)
        assert np.linalg.norm(G - G.T) <= IDENTITY_RTOL * np.linalg.norm(G)
        assert np.linalg.eigvalsh(G)[0] >= 0.5 * (1 - IDENTITY_RTOL)
    S = random_spd(rng, 4)
    assert rel(ref.nearest_spd(S), S) <= IDENTITY_RTOL
