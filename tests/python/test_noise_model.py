"""spdfit.NoiseModel and the keyword noise= of fit, fit_files, Factor.fit and hexapod.identify.

References: SciPy's BFGS on the Cholesky factor (tests/reference/noise_reference.py, independent of
spdfit) for the likelihood criterion; NumPy's sample covariance for from_rest; the unit invariance
of the model (A -> aA, B -> bB gives (b/a) X; A -> A D, B -> B D^-1 gives D^-1 X D^-1) with the
rest rows converted alike."""
import pickle

import numpy as np
import pytest

import noise_reference as ref
import spdfit
import spdfit.hexapod as hx

STD_A = np.array([0.2, 0.4, 0.8, 0.2, 0.4, 0.8])
STD_B = np.array([3.0, 1.0, 0.3, 3.0, 1.0, 0.3])

# spdfit's X minimizes the criterion: no independent optimizer finds a value lower by more than
# rounding (the criterion is O(m d), summed in a different order: 1e-10 relative is ~1e6 ulps).
CRITERION_RTOL = 1e-10
# The unit changes are exact in arithmetic; spd-tls' Newton iterations stop at a gradient
# tolerance, whose effect on X is far below this.
UNITS_RTOL = 1e-9


def simulated(m, seed, rest_rows=2000):
    """The issue's data: the thesis' M_p, accelerations uniform on [-5, 5], per-column Gaussian
    noise, and rest rows (accelerations zero, a constant load in B)."""
    rng = np.random.default_rng(seed)
    X = hx.thesis_mass_matrix()
    A0 = rng.uniform(-5, 5, (m, 6))
    A = A0 + rng.standard_normal((m, 6)) * STD_A
    B = A0 @ X + rng.standard_normal((m, 6)) * STD_B
    rest_A = rng.standard_normal((rest_rows, 6)) * STD_A
    rest_B = X.sum(axis=0) + rng.standard_normal((rest_rows, 6)) * STD_B
    return A, B, rest_A, rest_B, X


def quiet(function, *args, **kwargs):
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


def test_from_rest_is_numpys_sample_covariance():
    _, _, rest_A, rest_B, _ = simulated(50, 1, rest_rows=300)
    model = spdfit.NoiseModel.from_rest(rest_A, rest_B)
    assert model.source == "rest" and model.rest_rows == 300
    np.testing.assert_allclose(model.cov_a, np.cov(rest_A, rowvar=False), rtol=1e-12, atol=0)
    np.testing.assert_allclose(model.cov_b, np.cov(rest_B, rowvar=False), rtol=1e-12, atol=0)


def test_constructors_and_their_errors():
    model = spdfit.NoiseModel(cov_a=np.eye(2), cov_b=2 * np.eye(2))
    assert model.source == "cov" and np.array_equal(model.cov_b, 2 * np.eye(2))
    by_std = spdfit.NoiseModel.from_std(0.5, [1.0, 2.0])
    assert by_std.source == "std" and by_std.cov_a is None and np.array_equal(by_std.std_b, [1.0, 2.0])
    with pytest.raises(ValueError, match="cov_a is not symmetric"):
        spdfit.NoiseModel(cov_a=np.array([[1.0, 0.5], [0.0, 1.0]]), cov_b=np.eye(2))
    with pytest.raises(ValueError, match="cov_b is not positive semidefinite"):
        spdfit.NoiseModel(cov_a=np.eye(2), cov_b=np.array([[1.0, 2.0], [2.0, 1.0]]))
    with pytest.raises(ValueError, match="std_a"):
        spdfit.NoiseModel.from_std([0.1, -1.0], 1.0)
    with pytest.raises(ValueError, match="rest_b"):
        spdfit.NoiseModel.from_rest(np.ones((5, 2)), np.ones((4, 2)))
    with pytest.raises(TypeError):
        spdfit.NoiseModel(np.eye(2), np.eye(2))  # keywords only


def test_repr_and_pickle_keep_every_field():
    _, _, rest_A, rest_B, _ = simulated(50, 2, rest_rows=40)
    model = spdfit.NoiseModel.from_rest(rest_A, rest_B)
    assert repr(model).startswith("NoiseModel(") and "source='rest'" in repr(model) and "rest_rows=40" in repr(model)
    back = pickle.loads(pickle.dumps(model))
    assert np.array_equal(back.cov_a, model.cov_a) and back.rest_rows == 40 and back.warnings == model.warnings
    # Few rest rows: the warning travels with the model and the fits that use it.
    assert any("fewer than" in w for w in model.warnings)


@pytest.mark.parametrize("m", [100, 1000])
def test_spd_tls_with_a_noise_model_is_at_the_reference_minimum(m):
    A, B, _, _, _ = simulated(m, 3)
    cov_a, cov_b = np.diag(STD_A ** 2), np.diag(STD_B ** 2)
    r = spdfit.fit(A, B, "spd-tls", noise=spdfit.NoiseModel(cov_a=cov_a, cov_b=cov_b))
    assert r.ok and r.diagnostics.noise_model.source == "cov"
    f = ref.criterion(A, B, r.X, cov_a, cov_b)
    _, f_ref = ref.ml_estimate(A, B, cov_a, cov_b)
    assert f <= f_ref * (1 + CRITERION_RTOL)
    # And from spdfit's own X, BFGS finds nothing lower either.
    _, f_from_x = ref.ml_estimate(A, B, cov_a, cov_b, start=r.X)
    assert f <= f_from_x * (1 + CRITERION_RTOL)


@pytest.mark.parametrize("method", ["spd-tls", "auto"])
def test_units_scale_the_estimate_with_rest_rows(method):
    A, B, rest_A, rest_B, _ = simulated(300, 4, rest_rows=500)
    base = spdfit.fit(A, B, method, noise=spdfit.NoiseModel.from_rest(rest_A, rest_B))
    a, b = 9.81, 1e-3  # accelerations in g's reciprocal, forces in kN
    scaled = spdfit.fit(a * A, b * B, method, noise=spdfit.NoiseModel.from_rest(a * rest_A, b * rest_B))
    assert scaled.method == base.method
    np.testing.assert_allclose(scaled.X, (b / a) * base.X, rtol=0, atol=UNITS_RTOL * np.linalg.norm(base.X))
    D = np.diag([1.0, 2.0, 0.5, 10.0, 0.1, 3.0])
    D_inv = np.linalg.inv(D)
    moved = spdfit.fit(A @ D, B @ D_inv, method, noise=spdfit.NoiseModel.from_rest(rest_A @ D, rest_B @ D_inv))
    expected = D_inv @ base.X @ D_inv
    np.testing.assert_allclose(moved.X, expected, rtol=0, atol=UNITS_RTOL * np.linalg.norm(expected))


def test_every_entry_takes_noise(tmp_path):
    A, B, rest_A, rest_B, _ = simulated(200, 5, rest_rows=400)
    model = spdfit.NoiseModel.from_rest(rest_A, rest_B)
    X = spdfit.fit(A, B, "spd-tls", noise=model).X
    a, b = tmp_path / "A.csv", tmp_path / "B.csv"
    np.savetxt(a, A, delimiter=",", fmt="%.17g")
    np.savetxt(b, B, delimiter=",", fmt="%.17g")
    tolerance = 1e-8 * np.linalg.norm(X)  # the streamed factor against the whole data's, then Newton
    np.testing.assert_allclose(spdfit.fit_files(a, b, "spd-tls", noise=model).X, X, rtol=0, atol=tolerance)
    factor = spdfit.Factor.from_data(A, B)
    np.testing.assert_allclose(factor.fit("spd-tls", noise=model).X, X, rtol=0, atol=tolerance)
    identified = quiet(hx.identify, A, B, noise=model)
    np.testing.assert_allclose(identified["spd-tls"].result.X, X, rtol=0, atol=tolerance)
    assert identified["spd-tls"].result.diagnostics.noise_model.source == "rest"
    assert identified["spde"].result.diagnostics.noise_model is None  # spde runs unweighted
    results = quiet(spdfit.fit_all, A, B, noise=model)  # {method: FitResult}
    assert results["spd-tls"].diagnostics.noise_model.source == "rest"


def test_noise_keyword_errors():
    A, B, rest_A, rest_B, _ = simulated(100, 6, rest_rows=100)
    model = spdfit.NoiseModel.from_rest(rest_A, rest_B)
    with pytest.raises(ValueError, match="give noise or noise_ratio, not both"):
        spdfit.fit(A, B, "spd-tls", noise=model, noise_ratio=1.0)
    with pytest.raises(ValueError, match=r"noise applies to .*auto.*spd-tls.*not to spde"):
        spdfit.fit(A, B, "spde", noise=model)
    with pytest.raises(TypeError, match="noise must be a spdfit.NoiseModel"):
        spdfit.fit(A, B, "spd-tls", noise=np.eye(6))
    with pytest.raises(ValueError, match="rest_a"):
        spdfit.fit(A[:, :5], B[:, :5], "spd-tls", noise=model)


def test_results_carry_and_pickle_the_model():
    A, B, rest_A, rest_B, _ = simulated(100, 7, rest_rows=100)
    r = spdfit.fit(A, B, "auto", noise=spdfit.NoiseModel.from_rest(rest_A, rest_B))
    back = pickle.loads(pickle.dumps(r))
    assert back.diagnostics.noise_model.source == "rest"
    assert np.array_equal(back.diagnostics.noise_model.cov_a, r.diagnostics.noise_model.cov_a)
    plain = spdfit.fit(A, B, "auto")
    assert plain.diagnostics.noise_model is None
    assert "assumed equal noise" in plain.diagnostics.reason.text


def test_the_keyword_is_in_the_signatures():
    import inspect
    for function in (spdfit.fit, spdfit.fit_files, spdfit.Factor.fit, hx.identify):
        assert "noise" in inspect.signature(function).parameters
    assert "noise" not in inspect.signature(spdfit.spde).parameters


def test_the_physical_fit_weighs_by_the_noise_model():
    """hexapod.identify(physical=True, noise=...) gives the physical fit the model's covariances:
    the same library call as spdfit.physical.identify with noise_cov_a, noise_cov_b, bit for bit."""
    import spdfit.physical as ph
    g = hx.cubic_geometry()
    sim = hx.simulate(samples=100, noise_var=0.5, truth=g, seed=4)
    cov_a, cov_b = np.diag(STD_A ** 2), np.diag(STD_B ** 2)
    out = quiet(hx.identify, sim.A, sim.B, geometry=g, physical=True,
                noise=spdfit.NoiseModel(cov_a=cov_a, cov_b=cov_b))["physical"]
    alone = quiet(ph.identify, sim.A, sim.B, g, noise_cov_a=cov_a, noise_cov_b=cov_b)
    unweighted = quiet(ph.identify, sim.A, sim.B, g)
    np.testing.assert_array_equal(out["M_p"], alone["M_p"])
    assert not np.array_equal(out["M_p"], unweighted["M_p"])


def test_from_rest_names_a_loggers_invalid_code():
    # 9.9e37 among the rest rows would make the covariances its square (NumPy: np.cov's ~1e73)
    _, _, rest_A, rest_B, _ = simulated(50, 1, rest_rows=300)
    rest_A[99, 2] = 9.9e37
    model = spdfit.NoiseModel.from_rest(rest_A, rest_B)
    assert np.cov(rest_A, rowvar=False)[2, 2] > 1e70 and model.cov_a[2, 2] > 1e70
    named = [w for w in model.warnings if "1e30" in w]
    assert len(named) == 1 and named[0].startswith("the rest rows of A hold"), model.warnings
    assert "in rest row 100 (9.9e+37 in column 3)" in named[0] and "outliers" in model.warning_codes
    assert not any("1e30" in w for w in spdfit.NoiseModel.from_rest(rest_A[:99], rest_B[:99]).warnings)
