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
    ba, bb = a.bootstrap, b.bootstrap
    assert (ba is None) == (bb is None)
    if ba is not None:
        for name in ("replicates", "failed", "seed", "method", "scheme", "group_rows", "groups"):
            assert getattr(ba, name) == getattr(bb, name), name
        for name in ("standard_errors", "bias"):
            assert np.array_equal(getattr(ba, name), getattr(bb, name)), name
            assert np.array_equal(getattr(a, name), getattr(b, name)), name
        assert ba.interval.level == bb.interval.level
        assert np.array_equal(ba.interval.lower, bb.interval.lower)
        assert np.array_equal(ba.interval.upper, bb.interval.upper)
        ea, eb = ba.eigenvalues, bb.eigenvalues
        assert (ea is None) == (eb is None)
        if ea is not None:
            for name in ("estimate", "standard_errors", "lower", "upper"):
                assert np.array_equal(getattr(ea, name), getattr(eb, name)), name
            assert (ea.clusters, ea.failed) == (eb.clusters, eb.failed)


@pytest.mark.parametrize("method", list(spdfit.METHODS))
def test_every_method_round_trips(method):
    rng = np.random.default_rng(3)
    A, B, _ = ref.thesis_generator(40, 6, 3.2, rng)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        result = spdfit.fit(A, B, method)
    same(pickle.loads(pickle.dumps(result)), result)


@pytest.mark.parametrize("method", ["spde", "tls"])
def test_bootstrap_round_trips(method):
    A, B, _ = ref.thesis_generator(40, 6, 3.2, np.random.default_rng(4))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        result = spdfit.fit(A, B, method, bootstrap=30)
    assert result.bootstrap is not None
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
    with pytest.raises(RuntimeError, match="expected 7 fields"):
        spdfit.FitResult.__new__(spdfit.FitResult).__setstate__(("spde",))
