"""spdfit.fit(..., reported_diagnostics=False): the same X and warnings (but the noise estimate's)
without the diagnostics only a report shows; a TypeError for a value that is not a bool."""
import warnings

import numpy as np
import pytest

import spdfit


def fitted(A, B, method, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = spdfit.fit(A, B, method, **options)
    return result, [str(w.message) for w in caught]


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


@pytest.mark.parametrize("value", [0, 1, "no", None])
def test_reported_diagnostics_must_be_a_bool(value):
    A = np.eye(3)
    with pytest.raises(TypeError, match="reported_diagnostics must be a bool"):
        spdfit.fit(A, A, "spde", reported_diagnostics=value)
