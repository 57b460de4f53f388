"""Independent NumPy/SciPy reference for spdfit, written from the source documents.

Sources (see /work/shared/seeds/README.md):
  thesis = Chen, "Estimation of a Hexapod's Joint Space Mass-Inertia Matrix", 1999
           (000_*.txt; sections 3.2, 3.3, 4.2-4.3, 5.1, chapter 6, appendix B),
  paper  = Chen & McInroy, "Estimation of Symmetric, Positive Definite Matrices
           from Imperfect Measurements" (001_*.txt).

Convention (both documents): A, B are m x n with one sample per row, and the model
is A X ~= B with X n x n.  The algorithms deliberately follow the MATLAB M-files of
appendix B, i.e. they work from the Gram matrices P = A'A and Q = B'B where the
M-files do.  This is a naive-but-standard implementation meant as a test oracle.
"""
import numpy as np
import scipy.linalg

# Ideal joint space mass-inertia matrix of UW's hexapod, thesis eq. (6.1).
# (The Mprel lines of the appendix-B M-file are garbled; eq. 6.1 is authoritative.)
MP_THESIS = np.array([
    [4.6881, 0.1978, -0.4042, 1.7981, -0.4046, 0.6110],
    [0.1978, 4.6881, 0.6110, -0.4046, 1.7981, -0.4042],
    [-0.4042, 0.6110, 4.6881, 0.1975, -0.4042, 1.7984],
    [1.7981, -0.4046, 0.1975, 4.6881, 0.6114, -0.4042],
    [-0.4046, 1.7981, -0.4042, 0.6114, 4.6881, 0.1975],
    [0.6110, -0.4042, 1.7984, -0.4042, 0.1975, 4.6881],
])

# The paper's 2x2 example (section IV): X = [[3,1],[1,1]], A (4x2), B = A X.
X_PAPER = np.array([[3.0, 1.0], [1.0, 1.0]])
A_PAPER = np.array([[5.0, 2.0], [-3.0, 1.0], [1.0, -2.0], [-1.0, 1.0]])
B_PAPER = A_PAPER @ X_PAPER  # = [[17,7],[-8,-2],[1,-1],[-2,0]] as printed in the paper


def least_squares(A, B):
    """Unconstrained least squares X = A^+ B (thesis section 3.1, after eq. 3.5)."""
    return np.linalg.lstsq(A, B, rcond=None)[0]


def procrustes(A, B):
    """Symmetric Procrustes estimate: the solution of the normal equation (thesis 3.15)
        A'A X + X A'A = A'B + B'A.
    Appendix B uses MATLAB `lyap(P, -(A'B+B'A))`, and MATLAB's lyap(A, C) solves
    A X + X A' + C = 0.  SciPy's solve_continuous_lyapunov(a, q) solves
    a X + X a^H = q, so the right-hand side is passed with a *plus* sign here.
    Unique iff rank(A) = n (Theorem 3.2)."""
    P = A.T @ A
    return scipy.linalg.solve_continuous_lyapunov(P, A.T @ B + B.T @ A)


def tls_parts(A, B):
    """SVD of [A B] split as in thesis (4.29): returns (singular values, V11, V12, V21, V22)."""
    n = A.shape[1]
    _, s, Vt = np.linalg.svd(np.hstack([A, B]))
    V = Vt.T
    return s, V[:n, :n], V[:n, n:], V[n:, :n], V[n:, n:]


def tls(A, B):
    """Multidimensional total least squares X_TLS = -V12 V22^{-1} (thesis 4.37, appendix B).
    Requires sigma_n > sigma_{n+1} and V22 nonsingular (Theorem 4.7)."""
    _, _, V12, _, V22 = tls_parts(A, B)
    return -V12 @ np.linalg.inv(V22)


def tls_correction_norm(A, B):
    """Minimal TLS correction ||[dA dB]||_F = sqrt(sum_{i=1}^{t} sigma_{n+i}^2),
    t = min(m-n, n) (thesis 4.33); 0 when m = n."""
    n = A.shape[1]
    s = np.linalg.svd(np.hstack([A, B]), compute_uv=False)
    return float(np.sqrt(np.sum(s[n:] ** 2)))


def tls_sym(A, B):
    """Nearest symmetric matrix to X_TLS: (X_TLS' + X_TLS)/2 (thesis 4.38)."""
    X = tls(A, B)
    return 0.5 * (X.T + X)


def higham_psd(X):
    """Higham's nearest symmetric positive semi-definite matrix in the Frobenius norm
    (thesis section 3.3 steps 1-4, eq. 4.39): B = (X+X')/2, B = U S V' (SVD),
    H = V S V' (the symmetric polar factor of B), result (B + H)/2."""
    Bs = 0.5 * (X + X.T)
    _, s, Vt = np.linalg.svd(Bs)
    H = Vt.T @ np.diag(s) @ Vt
    return 0.5 * (Bs + H)


def tls_psd(A, B):
    """Nearest symmetric PSD matrix to X_TLS, X_F = (B + H)/2 (thesis 4.39)."""
    return higham_psd(tls(A, B))


def nearest_spd(X, min_eig=0.0):
    """Nearest symmetric matrix with eigenvalues >= min_eig in the Frobenius norm.
    min_eig = 0: Higham's method (thesis 3.3).  min_eig > 0: the eigenvalues of the
    symmetric part (X+X')/2 are clipped at min_eig (same projection argument:
    the symmetric part is the nearest symmetric matrix, then clip its spectrum)."""
    if min_eig <= 0:
        return higham_psd(X)
    lam, V = np.linalg.eigh(0.5 * (X + X.T))
    return (V * np.maximum(lam, min_eig)) @ V.T


def _spde_factors(A, B):
    """Appendix B: [U,D1] = eig(P), Sigma1 = sqrt(D1), [V,D2] = eig(Sigma1 U' Q U Sigma1),
    Sigma2 = sqrt(D2).  Returns (U, sigma1, V, sigma2) with the diagonals as vectors.
    Q~ is symmetrised before eigh (MATLAB's eig would silently fall back to the
    nonsymmetric solver on a rounding-asymmetric matrix); eigenvalues of Q~ are
    clipped at 0 so that rank-deficient B (paper Corollary III.7) gives Sigma2 >= 0."""
    P = A.T @ A
    Q = B.T @ B
    d1, U = np.linalg.eigh(P)
    s1 = np.sqrt(d1)
    Qt = (s1[:, None] * (U.T @ Q @ U)) * s1[None, :]
    d2, V = np.linalg.eigh(0.5 * (Qt + Qt.T))
    return U, s1, V, np.sqrt(np.maximum(d2, 0.0))


def spde(A, B):
    """SPD estimate X = U Sigma1^{-1} V Sigma2 V' Sigma1^{-1} U' (thesis 5.24 / appendix B,
    paper Theorem III.3 eq. 11); the unique solution in P of X P X = Q (paper eq. 10)
    when rank(A) = rank(B) = n.  With rank(B) = r < n the same formula gives the PSD
    rank-r optimiser of Corollary III.7."""
    U, s1, V, s2 = _spde_factors(A, B)
    W = (U / s1[None, :]) @ V
    X = (W * s2[None, :]) @ W.T
    return 0.5 * (X + X.T)


def area_criterion(A, B, X):
    """Area criterion f(Y) = ||A Y - B Y^{-T}||_F^2 with X = Y Y' (paper Definition II.1,
    thesis 5.7); Y is the lower Cholesky factor of X (f depends on X only)."""
    Y = np.linalg.cholesky(X)
    BYinvT = scipy.linalg.solve_triangular(Y, B.T, lower=True).T  # B Y^{-T}
    return float(np.linalg.norm(A @ Y - BYinvT, "fro") ** 2)


def area_minimum(A, B):
    """Minimum of the area criterion, 2 tr(Sigma_Q~ - A'B) (paper Corollary III.4)."""
    _, _, _, s2 = _spde_factors(A, B)
    return float(2.0 * (np.sum(s2) - np.trace(A.T @ B)))


def cross_term_positive_definite(A, B):
    """Whether A'B + B'A is positive definite, Higham's sufficient condition for a PD
    Procrustes estimate (thesis Theorem 3.2 (3)).  Returns (flag, lambda_min)."""
    lam = np.linalg.eigvalsh(A.T @ B + B.T @ A)
    return bool(lam[0] > 0), float(lam[0])


def degeneracy(method, A, B, gap_tol=1e-6, cond_tol=1e8):
    """Why the documents' formula for `method` does not apply to (A, B), or None.
    ls: always defined (pseudo-inverse).  procrustes: rank(A) = n (Theorem 3.2).
    spde: rank(A) = rank(B) = n (Corollary 5.3 / Theorem III.3).
    tls*: sigma_n > sigma_{n+1} and V22 nonsingular (Theorem 4.7)."""
    n = A.shape[1]
    if method in ("procrustes", "spde") and np.linalg.matrix_rank(A) < n:
        return "rank(A) < n"
    if method == "spde" and np.linalg.matrix_rank(B) < n:
        return "rank(B) < n"
    if method.startswith("tls"):
        s, _, _, _, V22 = tls_parts(A, B)
        if len(s) > n and s[n - 1] - s[n] <= gap_tol * s[n - 1]:
            return "sigma_n ~= sigma_{n+1} (TLS solution not unique)"
        if np.linalg.cond(V22) > cond_tol:
            return "V22 (nearly) singular (no TLS solution)"
    return None


METHODS = {
    "ls": least_squares,
    "procrustes": procrustes,
    "tls": tls,
    "tls-sym": tls_sym,
    "tls-psd": tls_psd,
    "spde": spde,
}


def thesis_generator(m, n, nm, rng):
    """Appendix B's data generator (experiments 1-3 of chapter 6), with numpy's
    rng.random in place of MATLAB's rand, drawn in the M-file's order:
        lddot  = 10*(rand-0.5)              true strut accelerations (variance 100/12)
        lddotm = lddot + nm*(rand-0.5)      measured accelerations (eq. 6.3)
        fb     = lddot * Mprel              true base forces (eq. 6.2, row form)
        fbm    = fb + nm*(rand-0.5)         measured forces (eq. 6.4)
    Noise variance is nm^2/12: nm = 1, 3.2, 3.9 give 0.083, 0.85, 1.27, the thesis'
    0.082, 0.86, 1.28.  Returns (A, B, Mprel) = (lddotm, fbm, eq. 6.1)."""
    if n != MP_THESIS.shape[0]:
        raise ValueError("thesis_generator: Mprel (eq. 6.1) is 6x6, so n must be 6")
    lddot = 10.0 * (rng.random((m, n)) - 0.5)
    lddotm = lddot + nm * (rng.random((m, n)) - 0.5)
    fb = lddot @ MP_THESIS
    fbm = fb + nm * (rng.random((m, n)) - 0.5)
    return lddotm, fbm, MP_THESIS.copy()


def paper_example(rng, std_a=0.5, std_b=1.0):
    """The paper's 2x2 experiment (section IV): (A + Va) X ~= B + Vb with Gaussian
    noise of standard deviations std_a, std_b.  Returns (A, B, X_true)."""
    A = A_PAPER + std_a * rng.standard_normal(A_PAPER.shape)
    B = B_PAPER + std_b * rng.standard_normal(B_PAPER.shape)
    return A, B, X_PAPER.copy()
