"""The estimator bindings against the independent NumPy/SciPy reference, and the module's
NumPy manners: dtypes, memory orders, 1-D input, exceptions, warnings."""
import json
import os
import subprocess
import warnings

import numpy as np
import pytest

import spdfit
import thesis_reference as ref

# Well-conditioned data: spdfit (QR-based) and the Gram-based reference agree to ~1e-13.
AGREEMENT = 1e-10

REFERENCE = {
    "ls": ref.least_squares, "procrustes": ref.procrustes, "tls": ref.tls,
    "tls-sym": ref.tls_sym, "tls-psd": ref.tls_psd, "spde": ref.spde,
}


@pytest.fixture(params=[0, 1, 2])
def problem(request):
    rng = np.random.default_rng(request.param)
    return ref.thesis_generator(12, 6, [1.0, 3.2, 3.9][request.param], rng)[:2]


def relative(X, Y):
    return np.linalg.norm(X - Y) / np.linalg.norm(Y)


# The source documents' methods, which tests/reference implements; spd-tls, psd-ls and auto
# have their own references in test_constrained_methods.py.
SEED_METHODS = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde"]


def test_methods_are_the_librarys_with_auto_last():
    assert list(spdfit.METHODS) == SEED_METHODS + ["spd-tls", "psd-ls", "auto"]


@pytest.mark.parametrize("method", SEED_METHODS)
def test_every_method_matches_the_reference(problem, method):
    A, B = problem
    r = spdfit.fit(A, B, method=method)
    assert r.ok and r.method == method
    assert relative(r.X, REFERENCE[method](A, B)) < AGREEMENT
    assert r.diagnostics.residual_norm == pytest.approx(np.linalg.norm(A @ r.X - B), rel=1e-12)


def test_named_functions_are_fit(problem):
    A, B = problem
    pairs = [(spdfit.least_squares, "ls"), (spdfit.symmetric_procrustes, "procrustes"),
             (spdfit.total_least_squares, "tls"), (spdfit.total_least_squares_symmetric, "tls-sym"),
             (spdfit.total_least_squares_psd, "tls-psd"), (spdfit.spde, "spde"),
             (spdfit.spd_total_least_squares, "spd-tls"), (spdfit.psd_least_squares, "psd-ls"),
             (spdfit.auto_fit, "auto")]
    for function, method in pairs:
        assert np.array_equal(function(A, B).X, spdfit.fit(A, B, method).X)


def test_spde_identities(problem):
    A, B = problem
    r = spdfit.spde(A, B)
    X, P, Q = r.X, A.T @ A, B.T @ B
    assert np.array_equal(X, X.T)
    assert np.linalg.eigvalsh(X)[0] > 0
    assert np.linalg.norm(X @ P @ X - Q) < 1e-12 * np.linalg.norm(Q)
    assert r.diagnostics.area_criterion == pytest.approx(ref.area_criterion(A, B, X), rel=1e-10)
    assert r.diagnostics.area_criterion_minimum == pytest.approx(ref.area_minimum(A, B), rel=1e-8)
    assert spdfit.area_criterion(A, B, X) == pytest.approx(r.diagnostics.area_criterion, rel=1e-12)


def test_fit_all_returns_every_method(problem):
    A, B = problem
    results = spdfit.fit_all(A, B)
    assert list(results) == [m for m in spdfit.METHODS if m != "auto"]
    for method, r in results.items():
        assert np.array_equal(r.X, spdfit.fit(A, B, method).X)


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.float16, np.longdouble, np.int64, np.int32])
@pytest.mark.parametrize("order", ["C", "F"])
def test_dtypes_and_orders_convert_without_surprises(dtype, order):
    A = np.array([[5, 2], [-3, 1], [1, -2], [-1, 1]])
    B = A @ np.array([[3, 1], [1, 1]]) + np.array([[1, 0], [0, -1], [1, 1], [0, 0]])
    expected = spdfit.spde(A.astype(np.float64), B.astype(np.float64)).X
    got = spdfit.spde(np.asarray(A, dtype=dtype, order=order), np.asarray(B, dtype=dtype, order=order)).X
    assert got.dtype == np.float64 and got.shape == (2, 2)
    assert np.array_equal(got, expected)  # these small integers are exact in every dtype


def test_non_contiguous_views_are_read_correctly():
    rng = np.random.default_rng(3)
    big_A, big_B = rng.standard_normal((24, 12)), rng.standard_normal((24, 12))
    A, B = big_A[::2, 1::3], big_B[::2, 1::3]
    assert np.array_equal(spdfit.spde(A, B).X, spdfit.spde(A.copy(), B.copy()).X)


def test_one_dimensional_input_is_one_column():
    a = np.array([1.0, 2.0, -1.0, 3.0])
    b = np.array([2.2, 3.9, -2.1, 6.3])
    assert spdfit.spde(a, b).X[0, 0] == pytest.approx(np.linalg.norm(b) / np.linalg.norm(a), rel=1e-15)


def test_nearest_spd():
    C = np.array([[1.0, 0.9, 0.7], [0.9, 1.0, -0.4], [0.7, -0.4, 1.0]])
    X = spdfit.nearest_spd(C, min_eig=0)
    assert np.allclose(X, ref.nearest_spd(C), rtol=0, atol=1e-14)
    # The default floor: 1e-8 times the largest eigenvalue, so the result is positive definite.
    default = spdfit.nearest_spd(C, full_output=True)
    assert default.min_eig == pytest.approx(1e-8 * np.linalg.eigvalsh(C)[-1], rel=1e-14)
    assert np.allclose(default.X, ref.nearest_spd(C, default.min_eig), rtol=0, atol=1e-14)
    assert default.cholesky_ok and np.linalg.cholesky(default.X).shape == (3, 3)
    full = spdfit.nearest_spd(C, min_eig=0.05, full_output=True)
    assert np.linalg.eigvalsh(full.X)[0] >= 0.05 * (1 - 1e-12)
    assert full.clipped == 1 and full.distance == pytest.approx(np.linalg.norm(C - full.X))


@pytest.mark.parametrize("A, B, fragment", [
    (np.ones((4, 2)), np.ones((3, 2)), "same numbers of rows"),
    (np.ones((2, 3)), np.ones((2, 3)), "at least as many rows"),
    (np.array([[1.0, np.nan], [1, 2], [3, 4]]), np.ones((3, 2)), "NaN"),
    (np.ones((3, 2)) * (1 + 1j), np.ones((3, 2)), "real numeric"),
    (np.ones((3, 2, 1)), np.ones((3, 2, 1)), "2-D"),
    (np.array([["a", "b"]]), np.ones((1, 2)), "real numeric"),
])
def test_bad_input_raises_value_error(A, B, fragment):
    with pytest.raises(ValueError, match=fragment):
        spdfit.fit(A, B, "spde")


def test_unknown_method_is_a_value_error():
    with pytest.raises(ValueError, match="unknown method 'bogus'"):
        spdfit.fit(np.eye(3), np.eye(3), "bogus")


def test_numerical_failure_raises_with_the_cli_message(tmp_path):
    A = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])
    B = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    with pytest.raises(spdfit.NumericalError) as error:
        spdfit.spde(A, B)
    assert not error.value.result.ok and error.value.result.diagnostics.rank_a == 1
    cli = os.environ.get("SPDFIT_CLI")
    if cli:
        np.savetxt(tmp_path / "A.csv", A, delimiter=",")
        np.savetxt(tmp_path / "B.csv", B, delimiter=",")
        out = subprocess.run([cli, "fit", "--method", "spde", tmp_path / "A.csv", tmp_path / "B.csv"],
                             capture_output=True, text=True)
        assert out.stderr.strip() == f"spdfit: error: {error.value}"


def test_warnings_become_python_warnings():
    A = np.array([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])
    with pytest.warns(spdfit.SpdfitWarning, match="rank-deficient"):
        r = spdfit.least_squares(A, np.ones((3, 2)))
    assert any("rank-deficient" in w for w in r.warnings)


def test_read_matrix_and_data_error(tmp_path):
    path = tmp_path / "A.csv"
    path.write_text("# comment\nx,y\n1,2\n3,4\n")
    assert np.array_equal(spdfit.read_matrix(str(path)), [[1.0, 2.0], [3.0, 4.0]])
    values, names = spdfit.read_table(str(path))
    assert names == ["x", "y"]
    path.write_text("1,2\n3,abc\n")
    with pytest.raises(spdfit.DataError, match=r"A.csv:2:3: 'abc' is not a number"):
        spdfit.read_matrix(str(path))
    assert issubclass(spdfit.DataError, ValueError)


def test_gil_is_released_during_fits():
    """Threads running fits overlap (the GIL is released in C++): a smoke test of correctness
    under concurrency; the timing is not asserted."""
    import concurrent.futures
    rng = np.random.default_rng(9)
    A, B = rng.standard_normal((400, 40)), rng.standard_normal((400, 40))
    expected = spdfit.spde(A, B).X
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        for X in pool.map(lambda _: spdfit.spde(A, B).X, range(8)):
            assert np.array_equal(X, expected)


def test_type_stubs_ship_with_the_package_and_name_real_functions():
    import ast
    import pathlib
    package = pathlib.Path(spdfit.__file__).parent
    assert (package / "py.typed").exists()
    for stub, module in (("fitting.pyi", spdfit.fitting), ("io.pyi", spdfit.io), ("repair.pyi", spdfit.repair),
                         ("linear_system.pyi", spdfit.linear_system), ("hexapod.pyi", spdfit.hexapod),
                         ("experiment.pyi", spdfit.experiment), ("linkage.pyi", spdfit.linkage)):
        tree = ast.parse((package / stub).read_text())
        functions = [node.name for node in tree.body if isinstance(node, ast.FunctionDef)]
        assert functions, stub
        for name in functions:
            assert callable(getattr(module, name)), f"{stub} declares {name}, which the module lacks"


@pytest.mark.parametrize("method", spdfit.METHODS)
def test_fit_files_streams_to_the_in_memory_estimate(tmp_path, method):
    rng = np.random.default_rng(9)
    A, B = ref.thesis_generator(3001, 6, 1.0, rng)[:2]
    np.save(tmp_path / "A.npy", np.asfortranarray(A))
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    whole = spdfit.fit(A, B, method)
    for block_rows, threads in ((100, 1), (1000, 2)):
        streamed = spdfit.fit_files(tmp_path / "A.npy", str(tmp_path / "B.csv"), method,
                                    block_rows=block_rows, threads=threads)
        assert relative(streamed.X, whole.X) < 1e-12
        assert streamed.diagnostics.m == 3001


def test_fit_files_errors(tmp_path):
    (tmp_path / "A.csv").write_text("1,2\n3,4\n5,6\n")
    (tmp_path / "B.csv").write_text("1,2\n3,x\n5,6\n")
    with pytest.raises(spdfit.DataError, match=r"B.csv:2:3: 'x' is not a number"):
        spdfit.fit_files(tmp_path / "A.csv", tmp_path / "B.csv")
    with pytest.raises(ValueError, match="block_rows"):
        spdfit.fit_files(tmp_path / "A.csv", tmp_path / "A.csv", block_rows=0)
