"""Results pickle, so multiprocessing and joblib can return them: every attribute survives the
round trip, for every method, a failure, and through a process pool; so do the results of solve,
spdfit.linkage, spdfit.hexapod and spdfit.experiment, and the plain options classes. Every class
pickles under every protocol, 0 to 5, and copies with copy.copy and copy.deepcopy; a state carries
its pickle format's number and a state of another format (another version of spdfit) is refused
with a message. The library's results travel as their exact JSON (spdfit/render.hpp), +-inf and
NaN included."""
import concurrent.futures
import copy
import functools
import io
import json
import math
import pickle
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.experiment as ex
import spdfit.hexapod as hx
import spdfit.linkage as lk
import thesis_reference as ref
from spdfit import _spdfit

# The pickle format of this build (pickle.hpp's kPickleFormat): every state is (FORMAT, payload).
FORMAT = 2

FIELDS = ["m", "n", "rank_a", "rank_b", "cond_a", "cond_b", "residual_norm", "symmetric", "positive_definite",
          "positive_semidefinite", "min_eigenvalue", "max_eigenvalue", "area_criterion", "area_criterion_minimum",
          "cross_term_positive_definite", "tls_sigma_n", "tls_sigma_n1", "tls_correction_norm",
          "tls_v22_min_singular_value", "noise_sigma", "iterations", "gradient_norm", "converged",
          "chosen_method"]


def same(a, b):
    assert (a.method, a.status, a.message, a.warnings, a.ok) == (b.method, b.status, b.message, b.warnings, b.ok)
    assert np.array_equal(a.X, b.X)
    assert (a.row_names, a.column_names) == (b.row_names, b.column_names)
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


def test_a_state_of_no_format_is_refused():
    # The fields' tuple of the releases before pickles had a format number.
    with pytest.raises(pickle.UnpicklingError, match=r"cannot unpickle FitResult: it was pickled by another "
                                                     r"version of spdfit \(a state of no pickle format\); this spdfit "
                                                     rf"\(.*\) reads format {FORMAT} only"):
        spdfit.FitResult.__new__(spdfit.FitResult).__setstate__(("spde", "success", "", np.eye(2)))


# ---- Every class of the module ----------------------------------------------------------------

MODULES = (_spdfit, _spdfit.linkage, _spdfit.hexapod, _spdfit.experiment)


def module_classes():
    """{name: class} of every class the compiled module defines (but its exception)."""
    return {name: c for module in MODULES for name, c in vars(module).items()
            if isinstance(c, type) and not issubclass(c, BaseException)}


def attributes(obj):
    """The names of the attributes (properties) of one of the module's objects."""
    names = [name for name, value in vars(type(obj)).items() if isinstance(value, property)]
    assert names, type(obj).__name__
    return names


def ours(obj):
    return type(obj).__module__.startswith("spdfit._spdfit")


def assert_same(a, b, where="result"):
    """a and b equal attribute by attribute, into the module's nested objects; arrays equal in
    shape, dtype and every value (NaN where NaN)."""
    assert type(a) is type(b), where
    if isinstance(a, _spdfit.TriangularFactor):  # R is not an attribute: the whole state, bit for bit
        assert a.serialize() == b.serialize(), where
    if ours(a):
        for name in attributes(a):
            assert_same(getattr(a, name), getattr(b, name), f"{where}.{name}")
    elif isinstance(a, np.ndarray):
        assert (a.shape, a.dtype) == (b.shape, b.dtype), where
        assert np.array_equal(a, b, equal_nan=True), where
    elif isinstance(a, dict):
        assert list(a) == list(b), where
        for key in a:
            assert_same(a[key], b[key], f"{where}[{key!r}]")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{i}]")
    elif isinstance(a, float):
        assert a == b or (math.isnan(a) and math.isnan(b)), where
    else:
        assert a == b, where


def nested(obj):
    """obj and every object of the module inside it (attributes, lists, tuples, dicts)."""
    if isinstance(obj, dict):
        yield from nested(list(obj.values()))
    elif isinstance(obj, (list, tuple)):
        for item in obj:
            yield from nested(item)
    elif ours(obj):
        yield obj
        for name in attributes(obj):
            yield from nested(getattr(obj, name))


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


def numerical_failure(function, *args, **kwargs):
    """The result attached to the NumericalError that function raises."""
    with pytest.raises(spdfit.NumericalError) as error:
        quiet(function, *args, **kwargs)
    return error.value.result


def gauss_newton_options():
    options = _spdfit.linkage.GaussNewtonOptions()
    options.tolerance, options.max_iterations, options.threshold = 1e-8, 7, 1e-12
    return options


def stream_options():
    options = _spdfit.StreamOptions()
    options.block_rows, options.threads = 1000, 3
    return options


def simulation_options():
    """SimulationOptions away from every default (Python can only make the defaults: the state
    is the way in)."""
    options = _spdfit.hexapod.SimulationOptions.__new__(_spdfit.hexapod.SimulationOptions)
    options.__setstate__((FORMAT, (30, 0.0, 0.25, 2.0, "gaussian", np.array([0.2, 0.4, 0.8, 0.2, 0.4, 0.8]),
                                   np.array([3.0]), 2000, np.arange(1.0, 7.0), 1e-3)))
    return options


def gaussian(*shape, seed=5):
    return np.random.default_rng(seed).standard_normal(shape)


@functools.lru_cache(maxsize=None)
def identified(truth_and_modes):
    sim = hx.simulate(samples=24, noise_var=0.3, seed=2)
    if not truth_and_modes:
        return quiet(hx.identify, sim.A, sim.B)
    stiffness = np.diag(hx.geometry().strut_stiffness)
    return quiet(hx.identify, sim.A, sim.B, truth=sim.truth, stiffness=stiffness, bootstrap=12, threads=1)


def boundary_fit():
    """spd-tls with a noise model whose likelihood's infimum is on the boundary (issue 42's
    reproduction, seed 1 of tests/python/test_boundary_ml.py): its diagnostics hold a
    BoundaryCertificate."""
    rng = np.random.default_rng(1)
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    X = Q @ np.diag(np.logspace(0, -6, 3)) @ Q.T

    def covariance():
        G = rng.standard_normal((3, 3))
        C = G @ G.T + 0.3 * np.eye(3)
        return 0.09 * 3 * C / np.trace(C)

    cov_a, cov_b = covariance(), covariance()
    A0 = rng.standard_normal((40, 3))
    A = A0 + rng.multivariate_normal(np.zeros(3), cov_a, 40)
    B = A0 @ X + rng.multivariate_normal(np.zeros(3), cov_b, 40)
    return quiet(spdfit.fit, A, B, "spd-tls", noise=spdfit.NoiseModel(cov_a=cov_a, cov_b=cov_b))


# Objects made through the public API, with their optional parts present and absent.
EXAMPLES = {
    "fit, spd-tls on the boundary": boundary_fit,
    "fit, auto": lambda: quiet(spdfit.fit, *ref.thesis_generator(30, 6, 1.0, np.random.default_rng(8))[:2]),
    "nearest_spd": lambda: quiet(spdfit.nearest_spd, np.array([[2.0, 3.0], [3.0, 1.0]]), full_output=True),
    "solve, full rank, 3 right-hand sides": lambda: spdfit.solve(gaussian(7, 4), gaussian(7, 3, seed=6)),
    "solve, rank-deficient": lambda: quiet(spdfit.solve, gaussian(7, 2) @ gaussian(2, 4, seed=6),
                                           gaussian(7, 2, seed=7)),
    "solve, underdetermined": lambda: spdfit.solve(gaussian(3, 5), gaussian(3, 2, seed=6)),
    "solve, 1-D b": lambda: spdfit.solve(gaussian(7, 4), gaussian(7, seed=6)),
    "solve, failed": lambda: numerical_failure(spdfit.solve, np.eye(2) * 1e-300, np.full((2, 1), 1e300)),
    "synthesize, steering": lambda: quiet(lk.synthesize, steering=0.5),
    "synthesize, dial zeros fitted": lambda: quiet(lk.synthesize, steering=0.5, fit_dial_zeros=True),
    "synthesize, no real linkage": lambda: numerical_failure(lk.synthesize, [0, 10, 20, 30], [0, -10, -20, -30]),
    "analyze, crank-rocker": lambda: lk.analyze((1.0, 0.4, 1.1, 0.9), points=37),
    "analyze, mostly unassemblable": lambda: lk.analyze((1.0, 2.0, 0.5, 0.6), points=37),
    "FourBar": lambda: lk.FourBar(1.0, 0.5, 1.2, 0.8),
    "GaussNewtonOptions": gauss_newton_options,
    "Geometry": lambda: hx.geometry(),
    "Warning": lambda: _spdfit.Warning("rank_deficient", "A is rank-deficient (rank 2 < n = 3)", "A"),
    "ModelDescription": lambda: _spdfit.hexapod.describe(hx.geometry()),
    "SimulationOptions, default": lambda: _spdfit.hexapod.SimulationOptions(),
    "SimulationOptions": simulation_options,
    "identify, bootstrap and modes": lambda: identified(True),
    "identify, no truth": lambda: identified(False),
    "thesis": lambda: ex.thesis(0.86, samples=14, trials=6, seed=3, threads=1, force_noise_var=0.4,
                                distribution="gaussian", methods=["tls", "spde", "psd-ls"]),
    "paper_2x2": lambda: ex.paper_2x2(0.5, trials=40, seed=2, threads=1),
    "paper_hexapod": lambda: ex.paper_hexapod(trials=3, threads=1),
    "paired comparison": lambda: example("thesis").compare("spde", "tls"),
    "paired comparisons per entry": lambda: example("paper_2x2").compare("spde", "procrustes"),
    "StreamOptions": stream_options,
    "NoiseModel": lambda: spdfit.NoiseModel.from_rest(gaussian(30, 3) * [0.2, 0.4, 0.8],
                                                      5.0 + gaussian(30, 2, seed=6) * [3.0, 0.3]),
    "NoiseModel, std": lambda: spdfit.NoiseModel.from_std([0.2, 0.0, 0.5], 1.0),
    "NoiseModel, cov": lambda: spdfit.NoiseModel(cov_a=np.diag([1.0, 2.0]), cov_b=np.array([[2.0, 0.5], [0.5, 1.0]])),
    "TriangularFactor": lambda: _spdfit.TriangularFactor.from_data(gaussian(9, 3), gaussian(9, 2, seed=6)),
}


@functools.lru_cache(maxsize=None)
def example(label):
    return EXAMPLES[label]()


def test_every_class_of_the_module_pickles():
    classes = module_classes()
    assert len(classes) >= 29  # the 29 of issue 18; the scan must not come back empty
    assert [name for name, c in classes.items() if "__setstate__" not in vars(c)] == []


def test_the_examples_cover_every_class():
    # Every class is in some example, so test_round_trip reaches each one's pickle (nested ones
    # through their parents', which is how they travel).
    found = {type(obj).__name__ for label in EXAMPLES for obj in nested(example(label))}
    assert found == set(module_classes())


def test_the_examples_have_their_optional_parts_present_and_absent():
    assert example("synthesize, steering").structural.check is not None
    assert example("synthesize, steering").structural.lengths is not None
    assert example("synthesize, no real linkage").design.lengths is None
    assert example("synthesize, no real linkage").design.check is None
    samples = example("analyze, mostly unassemblable").samples
    assert any(s.phi_plus is None for s in samples) and any(s.phi_plus is not None for s in samples)
    assert example("analyze, mostly unassemblable").transmission is not None
    spde = example("identify, bootstrap and modes")["spde"]
    assert spde.modes_uncertainty is not None and spde.error_vs_truth is not None
    assert spde.result.bootstrap is not None
    assert example("identify, no truth")["spde"].error_vs_truth is None
    assert example("identify, no truth")["spde"].modes_hz is None
    assert not example("solve, failed").ok and example("solve, rank-deficient").nullity == 2
    assert example("solve, 1-D b").solution.shape == (4,)


def round_trip(obj):
    back = pickle.loads(pickle.dumps(obj))
    assert back is not obj
    assert_same(back, obj)
    return back


@pytest.mark.parametrize("label", list(EXAMPLES))
def test_round_trip(label):
    obj = example(label)
    round_trip(obj)


def test_the_comparison_sees_a_difference():
    # assert_same is what the round trips rest on: it must fail on one changed number, also deep
    # inside a nested object.
    with pytest.raises(AssertionError, match="result.a4"):
        assert_same(lk.FourBar(1, 2, 3, 4), lk.FourBar(1, 2, 3, 5))
    original = example("synthesize, steering")
    version, state = original.__getstate__()
    state = list(state)
    version, structural = state[13].__getstate__()
    structural = list(structural)
    structural[0] = structural[0] + np.array([0.0, 0.0, 1e-15])
    state[13] = type(original.structural).__new__(type(original.structural))
    state[13].__setstate__((version, tuple(structural)))
    changed = type(original).__new__(type(original))
    changed.__setstate__((version, tuple(state)))
    with pytest.raises(AssertionError, match="result.structural.k"):
        assert_same(changed, original)


def test_options_keep_their_values():
    assert (example("GaussNewtonOptions").tolerance, example("GaussNewtonOptions").max_iterations,
            example("GaussNewtonOptions").threshold) == (1e-8, 7, 1e-12)
    back = round_trip(example("StreamOptions"))
    assert (back.block_rows, back.threads) == (1000, 3)
    back = round_trip(example("SimulationOptions"))
    assert (back.samples, back.noise_var, back.force_noise_var, back.signal_var, back.distribution) == \
           (30, 0.0, 0.25, 2.0, "gaussian")
    assert np.array_equal(back.noise_std_a, [0.2, 0.4, 0.8, 0.2, 0.4, 0.8])
    assert np.array_equal(back.noise_std_b, [3.0])
    assert (back.rest_samples, back.scale_b) == (2000, 1e-3)
    assert np.array_equal(back.rest_force, np.arange(1.0, 7.0))


def test_stream_options_keep_their_read_options():
    # Not attributes in Python (fit_files takes its own), but part of the value: the state
    # carries allow_nonfinite and the index column as read_table's index_col spells it.
    for read in [(False, None), (True, True), (False, False)]:
        options = _spdfit.StreamOptions.__new__(_spdfit.StreamOptions)
        options.__setstate__((FORMAT, (64, 2, read)))
        assert pickle.loads(pickle.dumps(options)).__getstate__() == (FORMAT, (64, 2, read))


def test_the_thesis_experiment_keeps_its_options():
    back = round_trip(example("thesis"))
    simulation, truth, methods = back.__getstate__()[1][0]
    assert (simulation.samples, simulation.noise_var, simulation.force_noise_var, simulation.distribution) == \
           (14, 0.86, 0.4, "gaussian")
    assert np.array_equal(truth, hx.thesis_mass_matrix()) and methods == ["tls", "spde", "psd-ls"]
    assert [m.method for m in back.methods] == methods


def identify_one(seed):
    sim = hx.simulate(samples=20, noise_var=0.5, seed=seed)
    return quiet(hx.identify, sim.A, sim.B, truth=sim.truth, stiffness=np.eye(6) * 1e4)


def synthesize_one(rho):
    return quiet(lk.synthesize, steering=rho)


def test_hexapod_and_linkage_results_come_back_from_a_process_pool():
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        identified_there = list(pool.map(identify_one, [1, 2]))
        synthesized_there = list(pool.map(synthesize_one, [0.4, 0.5]))
    for seed, there in zip([1, 2], identified_there):
        here = identify_one(seed)
        assert_same(there, here)
    for rho, there in zip([0.4, 0.5], synthesized_there):
        assert_same(there, synthesize_one(rho))


def first_instances():
    """{class name: (class, an instance)} from the examples."""
    found = {}
    for label in EXAMPLES:
        for item in nested(example(label)):
            found.setdefault(type(item).__name__, (type(item), item))
    return found


# The classes whose payload is the library's exact JSON (spdfit/render.hpp); the others' is the
# tuple of their fields (pickle.hpp), but TriangularFactor's, the library's serialization, whose
# checks test_factor.py corrupts byte by byte.
JSON_STATES = ["AutoReason", "Bootstrap", "ColumnClassification", "Diagnostics", "FitResult", "Interval",
               "LinearSystemResult", "MethodIdentification", "NearestResult", "NoiseModel", "PsdCertificate",
               "BoundaryCertificate", "SpectrumUncertainty"]
TUPLE_STATES = sorted(set(module_classes()) - set(JSON_STATES) - {"TriangularFactor"})


def test_the_state_lists_cover_every_class():
    assert set(JSON_STATES) <= set(module_classes())
    for name, (cls, obj) in first_instances().items():
        if name == "TriangularFactor":
            continue
        version, payload = obj.__getstate__()
        assert version == FORMAT, name
        if name == "LinearSystemResult":  # the JSON and whether b was 1-D
            payload = payload[0]
        assert isinstance(payload, str if name in JSON_STATES else tuple), name


@pytest.mark.parametrize("name", sorted(set(module_classes())))
@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_every_class_pickles_under_every_protocol(name, protocol):
    # Protocols 0 and 1 used to abort the interpreter (object.__new__ on a pybind11 class).
    cls, obj = first_instances()[name]
    back = pickle.loads(pickle.dumps(obj, protocol=protocol))
    assert type(back) is cls
    assert_same(back, obj, name)


@pytest.mark.parametrize("name", sorted(set(module_classes())))
def test_every_class_copies(name):
    cls, obj = first_instances()[name]
    for copied in (copy.copy(obj), copy.deepcopy(obj)):
        assert type(copied) is cls and copied is not obj
        assert_same(copied, obj, name)


def test_the_examples_under_every_protocol_in_a_process_pool():
    # What multiprocessing does with them, through the oldest protocol too.
    for label in ["fit, auto", "solve, 1-D b", "identify, bootstrap and modes", "thesis"]:
        obj = example(label)
        for protocol in (0, 1, 2, pickle.HIGHEST_PROTOCOL):
            assert_same(pickle.loads(pickle.dumps(obj, protocol=protocol)), obj, label)


@pytest.mark.parametrize("name", sorted(set(module_classes()) - {"TriangularFactor"}))
def test_a_state_of_another_format_is_refused(name):
    cls, obj = first_instances()[name]
    version, payload = obj.__getstate__()
    for state, says in [((version + 1, payload), f"pickle format {version + 1}"),
                        ((0, payload), "pickle format 0"),
                        (payload if isinstance(payload, tuple) and len(payload) != 2 else ("x", payload),
                         "a state of no pickle format")]:
        with pytest.raises(pickle.UnpicklingError, match=f"cannot unpickle {name}: it was pickled by another version "
                                                         f"of spdfit \\({says}\\); this spdfit .* reads format "
                                                         f"{FORMAT} only: recompute it, or unpickle it with the "
                                                         f"spdfit that pickled it"):
            cls.__new__(cls).__setstate__(state)


class OtherFormatPickler(pickle.Pickler):
    """Pickles the module's objects as another version of spdfit would: a state of the next format."""

    def reducer_override(self, obj):
        if isinstance(obj, spdfit.FitResult):
            function, arguments, (version, payload) = obj.__reduce__()
            return function, arguments, (version + 1, payload)
        return NotImplemented


def test_a_pickle_of_another_format_is_refused_by_pickle_loads():
    # As a user meets it: the bytes of another version's pickle.
    buffer = io.BytesIO()
    OtherFormatPickler(buffer, protocol=2).dump(example("fit, auto"))
    with pytest.raises(pickle.UnpicklingError, match=f"cannot unpickle FitResult: it was pickled by another version "
                                                     f"of spdfit \\(pickle format {FORMAT + 1}\\)"):
        pickle.loads(buffer.getvalue())


@pytest.mark.parametrize("name", TUPLE_STATES)
def test_a_state_of_the_wrong_length_is_refused(name):
    cls, obj = first_instances()[name]
    version, state = obj.__getstate__()
    for wrong in (state[:-1], state + (None,), ()):
        with pytest.raises(pickle.UnpicklingError, match=f"cannot unpickle {name}: expected {len(state)} fields, "
                                                         f"got {len(wrong)}"):
            cls.__new__(cls).__setstate__((version, wrong))


@pytest.mark.parametrize("name", JSON_STATES)
def test_a_json_state_that_is_not_the_classes_is_refused(name):
    cls, obj = first_instances()[name]
    version, state = obj.__getstate__()
    if name == "LinearSystemResult":  # (JSON, whether b was 1-D)
        text, vector_b = state
        with pytest.raises(pickle.UnpicklingError, match="cannot unpickle LinearSystemResult: expected 2 fields"):
            cls.__new__(cls).__setstate__((version, (text,)))
        wrap = lambda t: (t, vector_b)  # noqa: E731
    else:
        text, wrap = state, (lambda t: t)
    with pytest.raises(pickle.UnpicklingError, match=f"cannot unpickle {name}: the text is not JSON"):
        cls.__new__(cls).__setstate__((version, wrap(text[:-1])))
    with pytest.raises(pickle.UnpicklingError, match=f"cannot unpickle {name}: the JSON has no '"):
        cls.__new__(cls).__setstate__((version, wrap("{}")))


@pytest.mark.parametrize("label,index,message", [
    ("synthesize, steering", 0, "cannot unpickle SynthesisResult: unknown status 'bogus'"),
    ("analyze, crank-rocker", 2, "cannot unpickle Analysis: unknown Grashof type 'bogus'"),
    ("SimulationOptions", 4, "cannot unpickle SimulationOptions: unknown distribution 'bogus'"),
])
def test_an_unknown_name_in_a_state_is_refused(label, index, message):
    obj = example(label)
    version, state = obj.__getstate__()
    state = list(state)
    state[index] = "bogus"
    with pytest.raises(pickle.UnpicklingError, match=message):
        type(obj).__new__(type(obj)).__setstate__((version, tuple(state)))


@pytest.mark.parametrize("label,key,message", [
    ("fit, auto", "method", "cannot unpickle FitResult: unknown method 'bogus'"),
    ("fit, auto", "status", "cannot unpickle FitResult: unknown status 'bogus'"),
    ("solve, rank-deficient", "shape", "cannot unpickle LinearSystemResult: unknown shape 'bogus'"),
    ("solve, rank-deficient", "status", 'cannot unpickle LinearSystemResult: unknown status "bogus"'),
])
def test_an_unknown_name_in_a_json_state_is_refused(label, key, message):
    obj = example(label)
    version, state = obj.__getstate__()
    text = state[0] if isinstance(state, tuple) else state
    document = json.loads(text)
    document[key] = "bogus"
    text = json.dumps(document)
    with pytest.raises(pickle.UnpicklingError, match=message):
        type(obj).__new__(type(obj)).__setstate__((version, (text, state[1]) if isinstance(state, tuple) else text))


def test_nested_options_of_the_wrong_length_are_refused():
    result = example("thesis")
    version, state = result.__getstate__()
    state = list(state)
    state[0] = state[0][:2]
    with pytest.raises(pickle.UnpicklingError,
                       match="cannot unpickle ThesisExperimentResult's options: expected 3 fields, got 2"):
        type(result).__new__(type(result)).__setstate__((version, tuple(state)))


def test_infinities_and_nan_survive_exactly():
    # cond(A) is +inf for a singular A; a bootstrap whose replicates all fail has NaN intervals.
    A = np.array([[1.0, 0.0], [2.0, 0.0], [3.0, 0.0]])
    result = quiet(spdfit.fit, A, A, "ls")
    assert result.diagnostics.cond_a == math.inf
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        back = pickle.loads(pickle.dumps(result, protocol=protocol))
        assert back.diagnostics.cond_a == math.inf
        assert_same(back, result)
    # Every non-finite value in every place a number can be: the state's JSON edited, then pickled.
    version, text = result.__getstate__()
    document = json.loads(text)
    document["X"][0] = ["-inf", "nan"]
    document["diagnostics"]["residual_norm"] = "nan"
    document["diagnostics"]["noise_sigma"] = "-inf"
    edited = spdfit.FitResult.__new__(spdfit.FitResult)
    edited.__setstate__((version, json.dumps(document)))
    assert edited.X[0, 0] == -math.inf and math.isnan(edited.X[0, 1])
    back = pickle.loads(pickle.dumps(edited, protocol=0))
    assert back.X[0, 0] == -math.inf and math.isnan(back.X[0, 1]) and math.isnan(back.diagnostics.residual_norm)
    assert back.diagnostics.noise_sigma == -math.inf
    # Every double, bit for bit: -0.0, subnormals, the largest.
    document["X"][0] = [-0.0, 5e-324]
    document["X"][1] = [1.7976931348623157e308, 0.1]
    edited.__setstate__((version, json.dumps(document)))
    back = pickle.loads(pickle.dumps(edited))
    assert np.array_equal(back.X.view(np.uint64), edited.X.view(np.uint64))
    assert math.copysign(1.0, back.X[0, 0]) == -1.0


def test_records_pickle_with_a_format():
    # The physical results are records (spdfit._records): dicts whose keys are attributes. They
    # pickle as (class name, format, items); another format is refused with a message.
    import spdfit.physical as ph
    from spdfit import _records

    r = ph.inertia_repair(2.0, [0.0, 0.0, 0.0], np.diag([0.1, 0.2, 0.5]))
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        twin = pickle.loads(pickle.dumps(r, protocol=protocol))
        assert type(twin) is ph.InertiaRepair and twin.keys() == r.keys()
        assert np.array_equal(twin.inertia, r.inertia) and twin.changed is True
    function, (name, number, items) = r.__reduce__()
    with pytest.raises(pickle.UnpicklingError, match="another version of spdfit"):
        function(name, number + 1, items)
    with pytest.raises(AttributeError, match="no attribute 'nonsense'; its keys: mass, center_of_mass"):
        r.nonsense
    assert isinstance(r, dict) and json.loads(r.to_json())["changed"] is True
    assert _records.record(_records.Record, {"a": {"b": 1}}).a.b == 1
