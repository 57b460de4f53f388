"""The Python functions' defaults are the C++ library's own, read from its bound options structs,
not retyped: a default changed in C++ changes Python's with it."""
import inspect

import numpy as np
import pytest

import spdfit
import spdfit.linkage
from spdfit import _spdfit


def default(function, name):
    return inspect.signature(function).parameters[name].default


def test_fit_files_streams_with_the_library_block_size_and_threads():
    options = _spdfit.StreamOptions()
    assert default(spdfit.fit_files, "block_rows") == options.block_rows == 32768
    assert default(spdfit.fit_files, "threads") == options.threads == 0


def test_synthesize_refines_with_the_library_gauss_newton_defaults():
    options = _spdfit.linkage.GaussNewtonOptions()
    assert default(spdfit.linkage.synthesize, "tolerance") == options.tolerance == 1e-10
    assert default(spdfit.linkage.synthesize, "max_iterations") == options.max_iterations == 100


def test_a_result_reports_its_status_by_name(tmp_path):
    A = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
    B = [[2.0, 0.0], [0.0, 3.0], [2.0, 3.0]]
    assert spdfit.fit(A, B, "spde").status == "success"


def test_hexapod_and_experiment_defaults_are_the_librarys():
    import spdfit.experiment
    import spdfit.hexapod
    from spdfit._spdfit import experiment as core_experiment
    from spdfit._spdfit import hexapod as core_hexapod

    options = core_hexapod.SimulationOptions()
    assert default(spdfit.hexapod.simulate, "samples") == options.samples == 12
    assert default(spdfit.hexapod.simulate, "distribution") == options.distribution == "uniform"
    # simulate's generator options come from the command's table: None stands for the library's
    # default (25/3, as the docstring says) and gives the same data.
    assert default(spdfit.hexapod.simulate, "signal_var") is None and options.signal_var == 25.0 / 3.0
    assert "(default 25/3" in " ".join(spdfit.hexapod.simulate.__doc__.split())
    assert np.array_equal(spdfit.hexapod.simulate(seed=4).A, spdfit.hexapod.simulate(seed=4, signal_var=25.0 / 3.0).A)
    # The experiments take their options from the library's tables: None stands for the library's
    # default, which the docstring names, and gives the numbers of that value.
    assert default(spdfit.experiment.thesis, "signal_var") is None
    def doc(function):
        return " ".join(function.__doc__.split())

    assert "(default 25/3" in doc(spdfit.experiment.thesis)
    same = [spdfit.experiment.thesis(0.86, trials=5, methods="spde", **extra).methods[0].errors.tolist()
            for extra in ({}, {"signal_var": options.signal_var})]
    assert same[0] == same[1]
    assert default(spdfit.experiment.paper_hexapod, "noise_var") is None
    assert "(default 0.86)" in doc(spdfit.experiment.paper_hexapod)
    assert default(spdfit.experiment.paper_2x2, "std_b") == 1.0
    # The thesis' reported runs (eq. 6.6-6.22) come from the library's table.
    assert spdfit.experiment.THESIS_REPORTED[2] == (0.86, 2.3610, 2.3007, 1.9689)
    assert [run[0] for run in core_experiment.THESIS_REPORTED_RUNS] == [1, 2, 3]


def test_the_hexapod_model_is_the_librarys_one_description():
    import numpy as np
    import spdfit.hexapod

    model = spdfit.hexapod.model()
    J, M = model.jacobian, model.mass_matrix
    # Against NumPy: M_p's eigenvalues, cond(J), unit strut directions.
    assert np.allclose(model.mass_matrix_eigenvalues, np.linalg.eigvalsh(M), rtol=1e-12, atol=0)
    s = np.linalg.svd(J, compute_uv=False)
    assert model.jacobian_condition == pytest.approx(s[0] / s[-1], rel=1e-12)
    assert np.allclose(np.linalg.norm(model.strut_directions, axis=0), 1.0, rtol=0, atol=1e-14)
    # Modes: sqrt(eig(M^-1 K)) / 2 pi with K = diag(strut_stiffness).
    K = np.diag(model.geometry.strut_stiffness)
    expected = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)) / (2 * np.pi)
    assert np.allclose(model.modes_hz, expected, rtol=1e-10, atol=0)
