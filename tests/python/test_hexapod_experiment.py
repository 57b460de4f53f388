"""spdfit.hexapod and spdfit.experiment against the CLI and independent NumPy computations."""
import json
import os
import subprocess

import numpy as np
import pytest

import spdfit
import spdfit.experiment as ex
import spdfit.hexapod as hx
import thesis_reference as ref


def test_model_is_spd_and_close_to_thesis_eq_6_1():
    model = hx.model()
    M = model.mass_matrix
    assert np.allclose(M, M.T, rtol=0, atol=1e-14) and np.linalg.eigvalsh(M)[0] > 0
    assert np.abs(M - ref.MP_THESIS).max() < 1e-3
    # M_p = J^-T M_x J^-1 + M_s, eq. 2.12, computed here from the returned J and M_x.
    J = model.jacobian
    Jinv = np.linalg.inv(J)
    Ms = np.diag(model.geometry.strut_mass)
    assert np.allclose(Jinv.T @ model.payload_mass_matrix @ Jinv + Ms, M, rtol=1e-12, atol=1e-12)


def test_geometry_from_dict_and_errors():
    text = hx.cubic_geometry().to_json()
    as_dict = json.loads(text)
    assert np.array_equal(hx.model(as_dict).mass_matrix, hx.model().mass_matrix)
    as_dict["payload_mass"] = -1.0
    with pytest.raises(ValueError, match="payload_mass"):
        hx.model(as_dict)


def test_simulate_matches_the_cli(tmp_path):
    cli = os.environ.get("SPDFIT_CLI")
    if not cli:
        pytest.skip("SPDFIT_CLI not set")
    subprocess.run([cli, "hexapod", "simulate", "--noise-var", "0.86", "--seed", "7", "--out", tmp_path],
                   check=True, capture_output=True)
    sim = hx.simulate(noise_var=0.86, seed=7)
    assert np.array_equal(np.loadtxt(tmp_path / "A.csv", delimiter=",", ndmin=2), sim.A)
    assert np.array_equal(np.loadtxt(tmp_path / "B.csv", delimiter=",", ndmin=2), sim.B)


def test_identify_reports_errors_against_the_truth():
    sim = hx.simulate(samples=60, noise_var=0.082, seed=2)
    results = hx.identify(sim.A, sim.B, truth=sim.truth)
    assert list(results) == [m for m in spdfit.METHODS if m != "auto"]
    for method, r in results.items():
        assert r.error_vs_truth == pytest.approx(np.linalg.norm(r.result.X - sim.truth))


def test_thesis_experiment_matches_the_cli_and_is_thread_independent():
    one = ex.thesis(0.86, trials=50, seed=4, threads=1)
    two = ex.thesis(0.86, trials=50, seed=4, threads=2)
    for a, b in zip(one.methods, two.methods):
        assert np.array_equal(a.errors, b.errors)
    cli = os.environ.get("SPDFIT_CLI")
    if cli:
        out = json.loads(subprocess.run([cli, "experiment", "thesis", "--noise-var", "0.86", "--trials", "50",
                                         "--seed", "4", "--json"], check=True, capture_output=True,
                                        text=True).stdout)
        for m in one.methods:
            assert out["methods"][m.method]["mean"] == pytest.approx(m.summary.mean, rel=1e-15)


def test_thesis_experiment_errors_are_reference_errors():
    """Trial 0 of the experiment is `simulate` with the same seed; its errors are those of the
    independent NumPy reference on the same data."""
    result = ex.thesis(1.28, trials=1, seed=11)
    sim = hx.simulate(noise_var=1.28, seed=11)
    for m in result.methods:
        X = {"ls": ref.least_squares, "procrustes": ref.procrustes, "tls": ref.tls, "tls-sym": ref.tls_sym,
             "tls-psd": ref.tls_psd, "spde": ref.spde}[m.method](sim.A, sim.B)
        assert m.errors[0] == pytest.approx(np.linalg.norm(X - sim.truth), rel=1e-9)


def test_paper_2x2_entries():
    r = ex.paper_2x2(1.0, trials=500, seed=1)
    assert [s.method for s in r.methods] == ["procrustes", "tls", "spde"]
    assert r.entries == [(0, 0), (0, 1), (1, 1)]
    for s in r.methods:
        assert np.allclose(s.mae, np.abs(s.errors).mean(axis=0))


def test_bad_arguments_are_value_errors():
    with pytest.raises(ValueError):
        ex.thesis(-1.0, trials=10)
    with pytest.raises(ValueError, match="distribution"):
        hx.simulate(distribution="cauchy")


def test_experiments_take_methods_like_the_cli():
    # The Python face of `experiment ... --methods`: the same numbers as the default run for the
    # methods chosen, in the order given; unknown names and repeats raise ValueError.
    import pytest

    from spdfit import experiment

    everything = {m.method: m.summary.mean for m in experiment.thesis(0.86, trials=50).methods}
    chosen = experiment.thesis(0.86, trials=50, methods=["tls-sym", "spde"]).methods
    assert [m.method for m in chosen] == ["tls-sym", "spde"]
    assert all(m.summary.mean == everything[m.method] for m in chosen)
    two = experiment.paper_2x2(0.5, trials=200, methods=["spde", "ls"]).methods
    assert [m.method for m in two] == ["spde", "ls"]
    with pytest.raises(ValueError, match="bogus is not one of ls, procrustes"):
        experiment.paper_2x2(0.5, trials=10, methods=["spde", "bogus"])
    with pytest.raises(ValueError, match="listed twice"):
        experiment.paper_hexapod(trials=10, methods=["spde", "spde"])


def test_simulate_takes_whole_sample_counts_and_warns_of_too_few_as_the_cli():
    # The CLI's side (the same warning text, --samples 12.9 refused): tests/cli/test_messages.py.
    # int(12.9) would quietly simulate 12 rows; the CLI refuses --samples 12.9, Python raises.
    for bad in (12.9, 12.0, "12", True):
        with pytest.raises(TypeError, match="samples must be an int"):
            hx.simulate(bad, 0.86)
    with pytest.raises(TypeError, match="seed must be an int"):
        hx.simulate(12, 0.86, seed=1.5)
    assert hx.simulate(np.int64(12), 0.86).A.shape == (12, 6)
    # Too few samples for the estimators: the CLI's warning, pointing at this line.
    import inspect
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        data = hx.simulate(2, 0.86)
    assert data.A.shape == (2, 6)
    assert [str(w.message) for w in caught] == [
        "fewer samples (2) than M_p has columns (6): the estimators need m >= n"]
    assert caught[0].category is spdfit.FewSamplesWarning and issubclass(caught[0].category, spdfit.SpdfitWarning)
    assert caught[0].filename == __file__ and caught[0].lineno == line
    with warnings.catch_warnings(record=True) as enough:
        warnings.simplefilter("always")
        hx.simulate(6, 0.86)
    assert enough == []
