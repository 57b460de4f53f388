"""The noise estimate (diagnostics.noise_sigma) and the noise ratio of the total least-squares
methods, against NumPy: sigma^2 = sum_{i>n} s_i^2 / (n (m - n)) from numpy's SVD of [A, B / r], its
unbiasedness by Monte Carlo on the thesis model, and TLS on [A, B / r] scaled back."""
import numpy as np
import pytest

import spdfit
import thesis_reference as ref


def numpy_noise_variance(A, B, ratio=1.0):
    n = A.shape[1]
    s = np.linalg.svd(np.hstack([A, B / ratio]), compute_uv=False)
    return float(np.sum(s[n:] ** 2) / (n * (A.shape[0] - n)))


def numpy_tls(A, B, ratio=1.0):
    n = A.shape[1]
    V = np.linalg.svd(np.hstack([A, B / ratio]))[2].T
    return -ratio * V[:n, n:] @ np.linalg.inv(V[n:, n:])


@pytest.mark.parametrize("ratio", [1.0, 0.25, 3.0])
def test_noise_sigma_is_numpys_formula_for_every_method(ratio):
    rng = np.random.default_rng(1)
    A, B, _ = ref.thesis_generator(200, 6, 3.2, rng)
    expected = np.sqrt(numpy_noise_variance(A, B, ratio))
    for method in ("tls", "tls-sym", "tls-psd"):
        r = spdfit.fit(A, B, method, noise_ratio=ratio)
        assert r.diagnostics.noise_sigma == pytest.approx(expected, rel=1e-12)
    # Methods that do not take a noise ratio report the estimate for ratio 1.
    for method in ("ls", "procrustes", "spde"):
        r = spdfit.fit(A, B, method)
        assert r.diagnostics.noise_sigma == pytest.approx(np.sqrt(numpy_noise_variance(A, B)), rel=1e-12)


def test_noise_sigma_is_absent_when_m_equals_n():
    rng = np.random.default_rng(2)
    A = rng.standard_normal((3, 3))
    assert spdfit.fit(A, A @ np.diag([1.0, 2.0, 3.0]), "spde").diagnostics.noise_sigma is None


def test_noise_variance_is_unbiased_on_the_thesis_model():
    # Uniform noise of width nm in A and B: variance nm^2 / 12 = 0.8533 at nm = 3.2. The mean of
    # sigma_hat^2 over the trials must be within 4 standard errors (from the trials' own spread).
    rng = np.random.default_rng(3)
    nm, trials = 3.2, 400
    for m in (12, 100):
        values = np.array([spdfit.fit(*ref.thesis_generator(m, 6, nm, rng)[:2], "ls")
                           .diagnostics.noise_sigma ** 2 for _ in range(trials)])
        se = values.std(ddof=1) / np.sqrt(trials)
        assert abs(values.mean() - nm ** 2 / 12) < 4 * se, (m, values.mean(), se)


def test_noise_variance_scales_with_the_noise_ratio():
    # Noise of std 0.1 in A and 0.5 in B: with noise_ratio 5 the estimate is A's variance 0.01.
    rng = np.random.default_rng(4)
    X = np.array([[2.0, 0.3], [0.3, 1.0]])
    values = []
    for _ in range(200):
        A0 = rng.uniform(-5, 5, (300, 2))
        A = A0 + 0.1 * rng.standard_normal(A0.shape)
        B = A0 @ X + 0.5 * rng.standard_normal(A0.shape)
        values.append(spdfit.fit(A, B, "tls", noise_ratio=5.0).diagnostics.noise_sigma ** 2)
    values = np.array(values)
    assert abs(values.mean() - 0.01) < 4 * values.std(ddof=1) / np.sqrt(len(values))


@pytest.mark.parametrize("ratio", [0.1, 1.0, 7.0])
def test_tls_with_a_noise_ratio_is_tls_of_the_rescaled_data(ratio):
    rng = np.random.default_rng(5)
    A, B, _ = ref.thesis_generator(50, 6, 1.0, rng)
    X = spdfit.fit(A, B, "tls", noise_ratio=ratio).X
    assert np.linalg.norm(X - numpy_tls(A, B, ratio)) < 1e-10 * np.linalg.norm(X)
    # And the defining identity, within spdfit: tls(A, B, r) = r tls(A, B / r, 1).
    assert np.linalg.norm(X - ratio * spdfit.fit(A, B / ratio, "tls").X) < 1e-12 * np.linalg.norm(X)
    sym = spdfit.fit(A, B, "tls-sym", noise_ratio=ratio).X
    assert np.allclose(sym, (X + X.T) / 2, rtol=0, atol=1e-13 * np.linalg.norm(X))


def test_noise_ratio_is_refused_for_methods_that_do_not_take_it():
    A = np.eye(3)
    with pytest.raises(ValueError, match="noise_ratio applies to the total least-squares methods"):
        spdfit.fit(A, A, "spde", noise_ratio=2.0)
    for bad in (0.0, -1.0, float("inf"), float("nan")):
        with pytest.raises(ValueError, match="noise_ratio"):
            spdfit.fit(A, A, "tls", noise_ratio=bad)
