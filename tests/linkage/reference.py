"""An independent NumPy implementation of the lecture notes' function-generator synthesis
(shared/seeds/002, sections 3.3.3-3.6), written from the notes, not from spdfit's C++: the
design error by numpy.linalg.lstsq and the structural error by the plain Gauss-Newton iteration
of eq. 3.18 (full steps, D^-1 S dk = -s, stop when ||dk|| is tiny)."""
import numpy as np


def synthesis_matrix(psi, phi):
    return np.c_[np.ones_like(psi), np.cos(phi), -np.cos(psi)], np.cos(psi - phi)


def design(psi, phi, w=None):
    """k minimizing 1/2 d^T W d (eq. 3.10) and the condition number of W^(1/2) S."""
    S, b = synthesis_matrix(psi, phi)
    r = np.ones_like(psi) if w is None else np.sqrt(w)
    k = np.linalg.lstsq(r[:, None] * S, r * b, rcond=None)[0]
    return k, np.linalg.cond(r[:, None] * S)


def output_angle(k, psi, branch):
    A, B, C = k[1] - np.cos(psi), -np.sin(psi), k[0] - k[2] * np.cos(psi)
    return np.arctan2(B, A) + branch * np.arccos(-C / np.hypot(A, B))


def wrap(x):
    return x - 2 * np.pi * np.round(x / (2 * np.pi))


def structural_error(k, psi, phi, branch):
    return wrap(phi - output_angle(k, psi, branch))


def gauss_newton(k, psi, phi, branch, iterations=200, tol=1e-12):
    """Eq. 3.18 with full steps; returns k and the number of steps."""
    k = np.array(k, dtype=float)
    for it in range(iterations):
        s = structural_error(k, psi, phi, branch)
        gen = phi - s
        D = -k[1] * np.sin(gen) - np.sin(psi - gen)
        S, _ = synthesis_matrix(psi, gen)
        dk = np.linalg.lstsq(S / D[:, None], -s, rcond=None)[0]
        k = k + dk
        if np.linalg.norm(dk) < tol:
            return k, it + 1
    raise AssertionError("the reference Gauss-Newton did not converge")


def lengths(k):
    a2, a4 = 1 / k[1], 1 / k[2]
    return np.array([1.0, a2, np.sqrt(1 + a2**2 + a4**2 - 2 * a2 * a4 * k[0]), a4])


def steering(rho, dpsi):
    """eq. 3.5 solved for dphi: cot(dpsi) - cot(dphi) = rho."""
    return np.arctan2(np.sin(dpsi), np.cos(dpsi) - rho * np.sin(dpsi))
