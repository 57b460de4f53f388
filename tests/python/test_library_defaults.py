"""The Python functions' defaults are the C++ library's own, read from its bound options structs,
not retyped: a default changed in C++ changes Python's with it."""
import inspect

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
