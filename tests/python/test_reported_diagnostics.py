"""reported_diagnostics=False (spdfit.fit, fit_files, fit_all, Factor.fit): the same X and warnings
(but the noise estimate's) without the diagnostics only a report shows; a TypeError for a value
that is not a bool."""
import warnings

import numpy as np
import pytest

import spdfit


def caught(call, *args, **options):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        result = call(*args, **options)
    return result, [str(w.message) for w in seen]


def fitted(A, B, method, **options):
    return caught(spdfit.fit, A, B, method, **options)


def noisy(n, m, seed):
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((m, n))
    return A, A @ np.diag(np.linspace(1.0, 3.0, n)) + 0.1 * rng.standard_normal((m, n))


def assert_lean(lean, full):
    """lean (reported_diagnostics=False) against full: the same estimate, the reported-only
    diagnostics unset."""
    assert np.array_equal(lean.X, full.X)
    assert lean.method == full.method
    assert full.diagnostics.noise_sigma is not None and lean.diagnostics.noise_sigma is None
    assert lean.diagnostics.residual_norm == 0.0 and full.diagnostics.residual_norm > 0.0
    assert lean.diagnostics.cond_b_scaled == 0.0 and full.diagnostics.cond_b_scaled >= 1.0
    assert lean.diagnostics.min_eigenvalue == full.diagnostics.min_eigenvalue


@pytest.mark.parametrize("method", ["spde", "procrustes", "tls", "auto"])
@pytest.mark.parametrize("n", [4, 70])
def test_same_estimate_without_what_only_a_report_shows(method, n):
    rng = np.random.default_rng(n)
    m = n + n // 2  # m - n < n: the noise estimate's thin-data warning
    A = rng.standard_normal((m, n))
    B = A @ np.diag(np.linspace(1.0, 3.0, n)) + 0.1 * rng.standard_normal((m, n))
    full, full_warnings = fitted(A, B, method)
    lean, lean_warnings = fitted(A, B, method, reported_diagnostics=False)
    assert np.array_equal(lean.X, full.X)
    assert lean.method == full.method
    assert full.diagnostics.noise_sigma is not None and lean.diagnostics.noise_sigma is None
    # The full residual against NumPy's; the lean one is not computed.
    assert full.diagnostics.residual_norm == pytest.approx(np.linalg.norm(A @ full.X - B), rel=1e-10)
    assert lean.diagnostics.residual_norm == 0.0
    assert lean.diagnostics.cond_b_scaled == 0.0
    assert lean.diagnostics.min_eigenvalue == full.diagnostics.min_eigenvalue
    assert lean_warnings == [w for w in full_warnings if "noise estimate" not in w]
    assert len(lean_warnings) < len(full_warnings)


@pytest.mark.parametrize("method", ["spde", "tls", "auto"])
def test_fit_files_and_factor_fit_without_what_only_a_report_shows(method, tmp_path):
    A, B = noisy(5, 300, 3)
    np.save(tmp_path / "A.npy", A)
    np.save(tmp_path / "B.npy", B)
    paths = (tmp_path / "A.npy", tmp_path / "B.npy")
    full, full_warnings = caught(spdfit.fit_files, *paths, method)
    lean, lean_warnings = caught(spdfit.fit_files, *paths, method, reported_diagnostics=False)
    assert_lean(lean, full)
    assert lean_warnings == full_warnings
    # The full noise estimate against NumPy's: the d smallest singular values of [A B].
    tail = np.linalg.svd(np.hstack([A, B]), compute_uv=False)[-5:]
    assert full.diagnostics.noise_sigma == pytest.approx(np.sqrt(tail @ tail / (5 * (300 - 5))), rel=1e-10)

    factor = spdfit.Factor.from_data(A, B)
    full, full_warnings = caught(factor.fit, method)
    lean, lean_warnings = caught(factor.fit, method, reported_diagnostics=False)
    assert_lean(lean, full)
    assert lean_warnings == full_warnings


def test_fit_all_without_what_only_a_report_shows():
    A, B = noisy(4, 200, 5)
    full, full_warnings = caught(spdfit.fit_all, A, B)
    lean, lean_warnings = caught(spdfit.fit_all, A, B, reported_diagnostics=False)
    assert list(lean) == list(full)
    for method in full:
        assert np.array_equal(lean[method].X, full[method].X), method
        assert lean[method].diagnostics.noise_sigma is None
        assert lean[method].diagnostics.residual_norm == 0.0
        assert full[method].diagnostics.residual_norm == pytest.approx(
            np.linalg.norm(A @ full[method].X - B), rel=1e-10)
    assert lean_warnings == full_warnings


@pytest.mark.parametrize("value", [0, 1, "no", None])
def test_reported_diagnostics_must_be_a_bool(value, tmp_path):
    A = np.eye(3)
    np.save(tmp_path / "A.npy", A)
    calls = [lambda: spdfit.fit(A, A, "spde", reported_diagnostics=value),
             lambda: spdfit.fit_all(A, A, reported_diagnostics=value),
             lambda: spdfit.fit_files(tmp_path / "A.npy", tmp_path / "A.npy", reported_diagnostics=value),
             lambda: spdfit.Factor.from_data(A, A).fit(reported_diagnostics=value)]
    for call in calls:
        with pytest.raises(TypeError, match="reported_diagnostics must be a bool"):
            call()
