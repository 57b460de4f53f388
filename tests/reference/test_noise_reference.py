"""The maximum-likelihood reference (noise_reference.py) checked on its own: its gradient against
finite differences, its optimum against closed forms (weighted symmetric least squares when A is
exact, equal noise against the TLS criterion's optimality), and against spdfit's spd-tls through
the command line where the two meet without a noise model (equal noise, `--noise-ratio`)."""
import numpy as np
import pytest

import noise_reference as ref

# Central differences with h = 1e-6 relative resolve the directional derivative to about 1e-8 of
# the criterion's size on these data.
GRADIENT_RTOL = 1e-6
# BFGS stops at a relative gradient of 1e-11: X is within about 1e-8 of the minimizer (cond ~ 10).
OPTIMUM_RTOL = 1e-6


def rel(X, Y):
    return np.linalg.norm(X - Y) / np.linalg.norm(Y)


def data(rng, m, std_a, std_b):
    n = len(std_a)
    G = rng.standard_normal((n, n))
    X0 = G @ G.T + n * np.eye(n)
    A0 = 3.0 * rng.standard_normal((m, n))
    A = A0 + rng.standard_normal((m, n)) * std_a
    B = A0 @ X0 + rng.standard_normal((m, n)) * std_b
    return A, B, np.diag(np.square(std_a)), np.diag(np.square(std_b))


def test_gradient_matches_finite_differences():
    rng = np.random.default_rng(1)
    A, B, Sa, Sb = data(rng, 40, [0.2, 0.8, 0.4], [3.0, 0.3, 1.0])
    Sa = Sa + 0.01
    G = rng.standard_normal((3, 3))
    X = G @ G.T + 3 * np.eye(3)
    grad = ref.gradient(A, B, X, Sa, Sb)
    f = ref.criterion(A, B, X, Sa, Sb)
    for _ in range(5):
        S = rng.standard_normal((3, 3))
        S = 0.5 * (S + S.T)
        h = 1e-6 * np.linalg.norm(X)
        fd = (ref.criterion(A, B, X + h * S, Sa, Sb) - ref.criterion(A, B, X - h * S, Sa, Sb)) / (2 * h)
        assert abs(fd - np.sum(grad * S)) <= GRADIENT_RTOL * f


def test_exact_a_is_weighted_symmetric_least_squares():
    """Sigma_A = 0 with a positive definite unconstrained minimizer: the weighted normal equation
    sym(A^T (A X - B) Sigma_B^-1) = 0, solved here as a linear system in vech(X)."""
    rng = np.random.default_rng(2)
    A, B, _, Sb = data(rng, 60, [0.0, 0.0, 0.0], [3.0, 0.3, 1.0])
    n = 3
    Sb_inv = np.linalg.inv(Sb)
    basis = []
    for i, j in zip(*np.triu_indices(n)):
        E = np.zeros((n, n))
        E[i, j] = E[j, i] = 1.0
        basis.append(E)
    # <E_k, sym(A^T A X Sb^-1)> = <E_k, sym(A^T B Sb^-1)> for every basis element.
    P = A.T @ A
    lhs = np.array([[np.sum(Ek * (P @ El @ Sb_inv)) for El in basis] for Ek in basis])
    rhs = np.array([np.sum(Ek * (A.T @ B @ Sb_inv)) for Ek in basis])
    X_closed = sum(c * E for c, E in zip(np.linalg.solve(lhs, rhs), basis))
    assert np.all(np.linalg.eigvalsh(X_closed) > 0)
    X, _ = ref.ml_estimate(A, B, np.zeros((n, n)), Sb)
    assert rel(X, X_closed) < OPTIMUM_RTOL


def test_equal_noise_optimum_has_a_vanishing_riemannian_gradient():
    rng = np.random.default_rng(3)
    A, B, Sa, Sb = data(rng, 50, [0.5] * 4, [0.5] * 4)
    X, f = ref.ml_estimate(A, B, Sa, Sb)
    root = np.linalg.cholesky(X)
    g = root.T @ ref.gradient(A, B, X, Sa, Sb) @ root
    assert np.linalg.norm(g) < 1e-8 * f


@pytest.mark.parametrize("ratio", [1.0, 2.5])
def test_equal_noise_is_spd_tls_of_the_command_line(run_cli, write_csv, ratio):
    """Sigma_A = s^2 I, Sigma_B = s^2 r^2 I: the criterion is spd-tls's over s^2, so the reference
    and `spdfit fit --method spd-tls --noise-ratio r` find the same X, and spdfit's criterion is
    no larger."""
    rng = np.random.default_rng(4)
    s = 0.6
    A, B, Sa, Sb = data(rng, 80, [s] * 3, [s * ratio] * 3)
    X_ref, f_ref = ref.ml_estimate(A, B, Sa, Sb)
    out = run_cli("fit", "--method", "spd-tls", "--noise-ratio", repr(ratio),
                  write_csv(f"eq-A-{ratio}", A), write_csv(f"eq-B-{ratio}", B))
    X = np.array([[float(v) for v in line.split(",")] for line in out.split()])
    assert rel(X, X_ref) < OPTIMUM_RTOL
    assert ref.criterion(A, B, X, Sa, Sb) <= f_ref * (1 + 1e-10)
