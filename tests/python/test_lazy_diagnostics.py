"""noise_sigma, cond_a_scaled and cond_b_scaled are computed when first read, not by fit(): the
numbers read late, from a copy, a pickle or the JSON are the same, and they agree with NumPy's."""
import copy
import pickle

import numpy as np
import pytest

import spdfit

# LAPACK's SVD of [A B] (NumPy) against spdfit's of its triangular factor: both backward stable,
# the trailing singular values here are within 1e3 of the largest, so 1e-10 leaves a margin of
# about 1e3 over rounding.
TWO_SVDS_AGREE = 1e-10


def noisy(n, m, seed):
    rng = np.random.default_rng(seed)
    A0 = rng.standard_normal((m, n))
    X = np.diag(np.linspace(1.0, 3.0, n))
    return A0 + 0.3 * rng.standard_normal((m, n)), A0 @ X + 0.3 * rng.standard_normal((m, n))


@pytest.mark.parametrize("n", [4, 70])
@pytest.mark.parametrize("method", ["spde", "procrustes", "tls"])
def test_read_late_from_copies_pickles_and_json_is_the_same_number(n, method):
    A, B = noisy(n, 4 * n, n)
    result = spdfit.fit(A, B, method)
    pickled = pickle.loads(pickle.dumps(result))  # the pickle reads every diagnostic
    copied = copy.copy(result)
    sigma = result.diagnostics.noise_sigma
    assert sigma == copied.diagnostics.noise_sigma == pickled.diagnostics.noise_sigma
    assert result.diagnostics.cond_a_scaled == pickled.diagnostics.cond_a_scaled
    assert result.diagnostics.cond_b_scaled == pickled.diagnostics.cond_b_scaled
    assert spdfit.fit(A, B, method).diagnostics.noise_sigma == sigma  # read at once: the same bits
    # Against NumPy: the n smallest singular values of [A B], and cond of A, B with unit-norm columns.
    tail = np.linalg.svd(np.hstack([A, B]), compute_uv=False)[-n:]
    assert sigma == pytest.approx(np.sqrt(tail @ tail / (n * (4 * n - n))), rel=TWO_SVDS_AGREE)
    for M, cond in ((A, result.diagnostics.cond_a_scaled), (B, result.diagnostics.cond_b_scaled)):
        s = np.linalg.svd(M / np.linalg.norm(M, axis=0), compute_uv=False)
        # spdfit scales each column by a power of two, within a factor of 2 of its norm: the two
        # scalings differ by a diagonal matrix of condition number at most 4.
        assert s[0] / s[-1] / 4 <= cond <= s[0] / s[-1] * 4
