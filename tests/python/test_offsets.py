"""Constant offsets through Python: fit, fit_all and fit_files with offsets='estimate' (A X + 1 c^T
~= B: the fit of the column-centred data, c = mean(B) - X^T mean(A)) and offsets='rest' (the rest
rows' means subtracted), result.offsets, pickling, the warnings of the default offsets='none' and
the errors.

Reference: NumPy, independently of the library: the data centred or tared by NumPy and fitted
without offsets, numpy.linalg.lstsq on [1 A], the singular values of the centred [A B]."""
import pickle
import warnings

import numpy as np
import pytest

import spdfit
from spdfit_testing import save_csv

SAME = 1e-10  # relative: the same fit of data that differ by a subtraction (centring, taring) or a shift

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
SD_A, SD_B = np.array([0.05, 0.1, 0.2]), np.array([0.3, 0.2, 0.1])
OFF_A, OFF_B = np.array([3.0, -2.0, 4.0]), np.array([20.0, -5.0, 2.0])


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """m = 300 rows, n = d = 3, with offsets in A's and B's columns (A_off, B_off); centred by
    NumPy (A_c, B_c); shifted by 1e4 times each column's spread, a different multiple per column
    (A_big, B_big); 600 rest rows with the offsets; the data tared by their means (A_t, B_t); and
    the data as CSV files."""
    d = tmp_path_factory.mktemp("offsets_py")
    rng = np.random.default_rng(17)
    m = 300
    A0 = rng.uniform(-5, 5, (m, 3))
    A_off = A0 + OFF_A + rng.standard_normal((m, 3)) * SD_A
    B_off = A0 @ X_TRUE + OFF_B + rng.standard_normal((m, 3)) * SD_B
    rest_A = OFF_A + rng.standard_normal((600, 3)) * SD_A
    rest_B = OFF_B + rng.standard_normal((600, 3)) * SD_B
    out = {"A_off": A_off, "B_off": B_off, "A_c": A_off - A_off.mean(axis=0), "B_c": B_off - B_off.mean(axis=0),
           "A_big": A_off + 1e4 * A_off.std(axis=0) * np.array([1.0, -0.7, 0.4]),
           "B_big": B_off + 1e4 * B_off.std(axis=0) * np.array([-0.5, 1.0, 0.8]),
           "rest_A": rest_A, "rest_B": rest_B,
           "A_t": A_off - rest_A.mean(axis=0), "B_t": B_off - rest_B.mean(axis=0)}
    for name in ("A_off", "B_off", "A_big", "B_big", "rest_A", "rest_B"):
        out[name + "_path"] = str(save_csv(d / f"{name}.csv", out[name]))
    return out


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return function(*args, **kwargs)


def assert_same_x(got, want, rtol=SAME):
    assert np.linalg.norm(got - want) <= rtol * np.linalg.norm(want), (got, want)


def assert_c(offsets, X, A, B, rtol=SAME):
    assert offsets["mode"] == "estimate" and set(offsets) == {"mode", "c"}, offsets
    assert isinstance(offsets["c"], np.ndarray) and offsets["c"].shape == (B.shape[1],)
    want = B.mean(axis=0) - X.T @ A.mean(axis=0)
    scale = np.linalg.norm(B.mean(axis=0)) + np.linalg.norm(X) * np.linalg.norm(A.mean(axis=0))
    np.testing.assert_allclose(offsets["c"], want, rtol=0, atol=rtol * scale)


def offsets_warnings(caught):
    return [str(w.message) for w in caught if "offsets" in str(w.message)]


@pytest.mark.parametrize("method", ["ls", "procrustes", "spd-tls"])
def test_estimate_is_the_fit_of_the_centred_data(data, method):
    est = quiet(spdfit.fit, data["A_off"], data["B_off"], method, offsets="estimate")
    ref = quiet(spdfit.fit, data["A_c"], data["B_c"], method)
    assert_same_x(est.X, ref.X)
    assert ref.offsets is None
    assert quiet(spdfit.fit, data["A_off"], data["B_off"], method).offsets is None
    assert quiet(spdfit.fit, data["A_off"], data["B_off"], method, offsets="none").offsets is None
    assert_c(est.offsets, est.X, data["A_off"], data["B_off"])


def test_estimate_with_ls_is_lstsq_with_an_intercept(data):
    A, B = data["A_off"], data["B_off"]
    coef, *_ = np.linalg.lstsq(np.column_stack([np.ones(len(A)), A]), B, rcond=None)
    est = quiet(spdfit.fit, A, B, "ls", offsets="estimate")
    assert_same_x(est.X, coef[1:])
    np.testing.assert_allclose(est.offsets["c"], coef[0], rtol=SAME, atol=0)


@pytest.mark.parametrize("method", ["ls", "spd-tls"])
def test_estimate_is_invariant_to_large_constants(data, method):
    want = quiet(spdfit.fit, data["A_off"], data["B_off"], method, offsets="estimate")
    big = quiet(spdfit.fit, data["A_big"], data["B_big"], method, offsets="estimate")
    assert_same_x(big.X, want.X)
    assert_c(big.offsets, big.X, data["A_big"], data["B_big"])
    for block_rows in (7, 1000):
        for a, b in (("A_off", "B_off"), ("A_big", "B_big")):
            streamed = quiet(spdfit.fit_files, data[a + "_path"], data[b + "_path"], method, offsets="estimate",
                             block_rows=block_rows)
            assert_same_x(streamed.X, want.X)
            assert_c(streamed.offsets, streamed.X, data[a], data[b])


@pytest.mark.parametrize("method", ["ls", "spd-tls"])
def test_bootstrap_with_estimate_is_invariant_to_large_constants(data, method):
    want = quiet(spdfit.fit, data["A_off"], data["B_off"], method, offsets="estimate", bootstrap=20, seed=3)
    big = quiet(spdfit.fit, data["A_big"], data["B_big"], method, offsets="estimate", bootstrap=20, seed=3)
    assert_same_x(big.X, want.X)
    assert np.all(want.standard_errors > 0)
    np.testing.assert_allclose(big.standard_errors, want.standard_errors, rtol=1e-8, atol=0)


def rest_model(data):
    """The rest rows as Python takes them: a noise model (NoiseModel.from_rest), which keeps their means."""
    return {"noise": spdfit.NoiseModel.from_rest(data["rest_A"], data["rest_B"])}


@pytest.mark.parametrize("method", ["ls", "spd-tls", "auto"])
def test_rest_subtracts_the_rest_means(data, method):
    rest = rest_model(data)
    got = quiet(spdfit.fit, data["A_off"], data["B_off"], method, offsets="rest", **rest)
    want = quiet(spdfit.fit, data["A_t"], data["B_t"], method, **rest)
    assert got.method == want.method
    assert_same_x(got.X, want.X)
    assert got.offsets["mode"] == "rest" and set(got.offsets) == {"mode", "a", "b"}, got.offsets
    np.testing.assert_allclose(got.offsets["a"], data["rest_A"].mean(axis=0), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(got.offsets["b"], data["rest_B"].mean(axis=0), rtol=1e-12, atol=1e-14)
    # The rest rows from files (NoiseModel.from_rest_files), streamed (block_rows 7).
    files = {"noise": spdfit.NoiseModel.from_rest_files(data["rest_A_path"], data["rest_B_path"])}
    streamed = quiet(spdfit.fit_files, data["A_off_path"], data["B_off_path"], method, offsets="rest",
                     block_rows=7, **files)
    assert_same_x(streamed.X, want.X)
    np.testing.assert_allclose(streamed.offsets["b"], data["rest_B"].mean(axis=0), rtol=1e-12, atol=1e-14)


def test_fit_all_takes_offsets(data):
    est = quiet(spdfit.fit_all, data["A_off"], data["B_off"], offsets="estimate")
    ref = quiet(spdfit.fit_all, data["A_c"], data["B_c"])
    assert list(est) == list(ref)
    for method, r in ref.items():
        assert r.offsets is None, method
        if r.ok:
            assert_same_x(est[method].X, r.X, 1e-9)
            assert_c(est[method].offsets, est[method].X, data["A_off"], data["B_off"], 1e-9)
    rest = rest_model(data)
    tared = quiet(spdfit.fit_all, data["A_off"], data["B_off"], offsets="rest", **rest)
    ref = quiet(spdfit.fit_all, data["A_t"], data["B_t"], **rest)
    for method, r in ref.items():
        if r.ok:
            assert_same_x(tared[method].X, r.X, 1e-9)
            assert tared[method].offsets["mode"] == "rest", method
            np.testing.assert_allclose(tared[method].offsets["b"], data["rest_B"].mean(axis=0), rtol=1e-12)


def test_tls_noise_estimate_counts_the_lost_degree_of_freedom(data):
    A, B = data["A_off"], data["B_off"]
    m, n = A.shape
    d = B.shape[1]
    s = np.linalg.svd(np.hstack([A - A.mean(axis=0), B - B.mean(axis=0)]), compute_uv=False)
    want = np.sqrt(np.sum(s[-d:] ** 2) / (d * (m - 1 - n)))
    r = quiet(spdfit.fit, A, B, "tls", offsets="estimate")
    assert r.diagnostics.noise_sigma == pytest.approx(want, rel=1e-9)
    streamed = quiet(spdfit.fit_files, data["A_off_path"], data["B_off_path"], "tls", offsets="estimate",
                     block_rows=7)
    assert streamed.diagnostics.noise_sigma == pytest.approx(want, rel=1e-9)


def test_offsets_taken_for_signal_are_a_warning(data):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = spdfit.fit(data["A_off"], data["B_off"], "ls")
    found = offsets_warnings(caught)
    assert any("offsets estimate" in w for w in found), [str(w.message) for w in caught]
    assert any("offsets" in w for w in r.warnings), r.warnings
    for A, B, kwargs in ((data["A_c"], data["B_c"], {}), (data["A_off"], data["B_off"], {"offsets": "estimate"})):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            spdfit.fit(A, B, "ls", **kwargs)
        assert not offsets_warnings(caught), kwargs


def test_untared_b_is_a_warning():
    rng = np.random.default_rng(23)
    m = 300
    A0 = rng.uniform(-5, 5, (m, 3))
    A0 -= A0.mean(axis=0)
    A = A0 + rng.standard_normal((m, 3)) * SD_A
    B_clean = A0 @ X_TRUE + rng.standard_normal((m, 3)) * SD_B
    rest_A = rng.standard_normal((600, 3)) * SD_A
    noise_B = rng.standard_normal((600, 3)) * SD_B
    rest_B = OFF_B + noise_B
    B = B_clean + OFF_B
    rest_se = rest_B.std(axis=0, ddof=1) / np.sqrt(600)
    assert np.all(np.abs(rest_B.mean(axis=0)) > 5 * rest_se)
    assert np.all(np.abs(B.mean(axis=0) - rest_B.mean(axis=0)) <=
                  5 * np.hypot(rest_se, B.std(axis=0, ddof=1) / np.sqrt(m)))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spdfit.fit(A, B, "spd-tls", noise=spdfit.NoiseModel.from_rest(rest_A, rest_B))
    assert any("offsets rest" in w for w in offsets_warnings(caught)), [str(w.message) for w in caught]
    loaded, clean = spdfit.NoiseModel.from_rest(rest_A, rest_B), spdfit.NoiseModel.from_rest(rest_A, noise_B)
    for args, kwargs in (((A, B_clean), {"noise": clean}), ((A, B - rest_B.mean(axis=0)), {"noise": loaded}),
                         ((A, B), {"noise": loaded, "offsets": "rest"})):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            spdfit.fit(*args, "spd-tls", **kwargs)
        assert not offsets_warnings(caught), [str(w.message) for w in caught]


def test_errors(data):
    with pytest.raises(ValueError, match="offsets"):
        spdfit.fit(data["A_off"], data["B_off"], "spd-tls", offsets="rest")
    with pytest.raises(ValueError, match="offsets"):
        spdfit.fit(data["A_off"], data["B_off"], "ls", offsets="bogus")
    with pytest.raises(ValueError, match="offsets"):
        spdfit.fit_all(data["A_off"], data["B_off"], offsets="rest")
    quiet(spdfit.fit, data["A_off"][:3], data["B_off"][:3], "ls")  # m = n fits without offsets
    with pytest.raises(spdfit.DataError, match="offsets"):
        spdfit.fit(data["A_off"][:3], data["B_off"][:3], "ls", offsets="estimate")


def test_pickled_results_keep_their_offsets(data):
    est = quiet(spdfit.fit, data["A_off"], data["B_off"], "spd-tls", offsets="estimate")
    rest = quiet(spdfit.fit, data["A_off"], data["B_off"], "spd-tls", offsets="rest", **rest_model(data))
    plain = quiet(spdfit.fit, data["A_c"], data["B_c"], "spd-tls")
    for r in (est, rest):
        back = pickle.loads(pickle.dumps(r))
        assert set(back.offsets) == set(r.offsets)
        for key, value in r.offsets.items():
            if key == "mode":
                assert back.offsets[key] == value
            else:
                np.testing.assert_array_equal(back.offsets[key], value)
        np.testing.assert_array_equal(back.X, r.X)
    assert pickle.loads(pickle.dumps(plain)).offsets is None


def test_offsets_rest_without_a_rest_model_names_the_noise_model(data):
    # Python gives rest rows as a noise model (NoiseModel.from_rest): without one, rest is refused.
    with pytest.raises(ValueError) as e:
        spdfit.fit(data["A_off"], data["B_off"], "spd-tls", offsets="rest")
    assert "offsets" in str(e.value) and "rest" in str(e.value)