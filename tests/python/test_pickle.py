"""Results pickle (issue 18), so multiprocessing and joblib can return them: every attribute
survives the round trip, for every method, a failure, and through a process pool."""
import concurrent.futures
import pickle
import warnings

import numpy as np
import pytest

import spdfit
import thesis_reference as ref

FIELDS = ["m", "n", "rank_a", "rank_b", "cond_a", "cond_b", "residual_norm", "symmetric", "positive_definite",
          "positive_semidefinite", "min_eigenvalue", "max_eigenvalue", "area_criterion", "area_criterion_minimum",
          "cross_term_positive_definite", "tls_sigma_n", "tls_sigma_n1", "tls_correction_norm",
          "tls_v22_min_singular_value", "noise_sigma", "iterations", "gradient_norm", "converged",
          "chosen_method"]


def same(a, b):
    assert (a.method, a.status, a.message, a.warnings, a.ok) == (b.method, b.status, b.message, b.warnings, b.ok)
    assert np.array_equal(a.X, b.X)
    for name in FIELDS:
        assert getattr(a.diagnostics, name) == getattr(b.diagnostics, name), name
    for name in ("singular_values_a", "singular_values_b"):
        assert np.array_equal(getattr(a.diagnostics, name), getattr(b.diagnostics, name))
    ca, cb = a.diagnostics.certificate, b.diagnostics.certificate
    assert (ca is None) == (cb is None)
    if ca is not None:
        assert (ca.primal_min_eig, ca.dual_min_eig, ca.complementarity, ca.duality_gap) == \
               (cb.primal_min_eig, cb.dual_min_eig, cb.complementarity, cb.duality_gap)
    ra, rb = a.diagnostics.reason, b.diagnostics.reason
    assert (ra is None and rb is None) or (ra.code, ra.text) == (rb.code, rb.text)


@pytest.mark.parametrize("method", list(spdfit.METHODS))
def test_every_method_round_trips(method):
    rng = np.random.default_rng(3)
    A, B, _ = ref.thesis_generator(40, 6, 3.2, rng)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        result = spdfit.fit(A, B, method)
    same(pickle.loads(pickle.dumps(result)), result)


def test_a_failed_result_round_trips():
    A = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])
    with pytest.raises(spdfit.NumericalError) as error:
        spdfit.fit(A, A, "spde")
    failed = error.value.result
    back = pickle.loads(pickle.dumps(failed))
    same(back, failed)
    assert back.status == "numerical_failure" and back.X.size == 0


def fit_one(seed):
    A, B, _ = ref.thesis_generator(30, 6, 1.0, np.random.default_rng(seed))
    return spdfit.fit(A, B, "spd-tls")


def test_results_come_back_from_a_process_pool():
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(fit_one, [1, 2, 3]))
    for seed, result in zip([1, 2, 3], results):
        same(result, fit_one(seed))


def test_a_truncated_state_is_refused():
    with pytest.raises(RuntimeError, match="expected 6 fields"):
        spdfit.FitResult.__new__(spdfit.FitResult).__setstate__(("spde",))
