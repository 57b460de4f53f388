"""spdfit.solve and spdfit.linkage against NumPy, and their Python manners."""
import pickle
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.linkage as lk


@pytest.mark.parametrize("seed", range(6))
def test_solve_matches_numpy_pinv_and_rank(seed):
    rng = np.random.default_rng(seed)
    m, n, r = rng.integers(2, 9), rng.integers(2, 9), None
    r = int(rng.integers(1, min(m, n) + 1))
    A = rng.standard_normal((m, r)) @ rng.standard_normal((r, n))
    b = rng.standard_normal((m, 2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        result = spdfit.solve(A, b)
    assert result.rank == np.linalg.matrix_rank(A) == r
    assert result.nullity == n - r
    expected = np.linalg.pinv(A) @ b
    assert np.linalg.norm(result.solution - expected) <= 1e-9 * max(1.0, np.linalg.norm(expected))
    assert np.allclose(A @ result.null_space, 0, atol=1e-10 * np.linalg.norm(A))
    assert result.residual_norm == pytest.approx(np.linalg.norm(A @ expected - b), rel=1e-8, abs=1e-12)


def test_solve_explains_the_notes_example_one():
    # Notes 002 section 3.3.2, example 1: the unique solution (1/13) [21, 10, -2].
    result = spdfit.solve([[5, -1, 2], [-2, 6, 9], [-7, 5, -3]], [7, 0, -7])
    assert result.consistent and result.finite_solution_dimension == 0 and result.at_infinity_dimension == -1
    assert np.allclose(result.solution, np.array([21, 10, -2]) / 13, rtol=0, atol=1e-14)
    assert "one point in common" in result.explanation


def test_solve_raises_numerical_error_when_the_solution_overflows():
    with pytest.raises(spdfit.NumericalError, match="overflows the range of double precision numbers") as error:
        spdfit.solve(np.eye(2) * 1e-300, np.full(2, 1e300))
    assert error.value.result.rank == 2
    assert error.value.result.solution.shape == (0,), "1-D b, but nothing to return"
    x = spdfit.solve(np.eye(2) * 1e-310, np.full(2, 2e-310)).solution
    assert x.shape == (2,) and np.allclose(x, 2.0)


# ---- b's dimensionality, as numpy.linalg.lstsq (issue 18) ----------------------------------------

def full_rank(m=7, n=4, seed=0):
    return np.random.default_rng(seed).standard_normal((m, n))


def rank_deficient(m=7, n=4, r=2, seed=0):
    rng = np.random.default_rng(seed)
    return rng.standard_normal((m, r)) @ rng.standard_normal((r, n))


def quiet_solve(A, b):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return spdfit.solve(A, b)


@pytest.mark.parametrize("b_shape,x_shape", [((7,), (4,)), ((7, 1), (4, 1)), ((7, 3), (4, 3))])
def test_the_solution_has_the_dimensionality_of_b(b_shape, x_shape):
    A = full_rank()
    b = np.random.default_rng(1).standard_normal(b_shape)
    result = spdfit.solve(A, b)
    assert result.solution.shape == x_shape == np.linalg.lstsq(A, b, rcond=None)[0].shape
    # The per-right-hand-side classification keeps one entry per column of b, as lstsq's
    # residuals do (shape (1,) for a 1-D b).
    columns = 1 if b.ndim == 1 else b.shape[1]
    assert result.p == len(result.columns) == columns
    assert result.solution.flags.writeable


def test_a_list_b_is_1d_and_so_is_its_solution():
    result = spdfit.solve([[2.0, 0.0], [0.0, 4.0]], [2.0, 2.0])
    assert result.solution.shape == (2,)
    assert np.array_equal(result.solution, [1.0, 0.5])


@pytest.mark.parametrize("make_A,rank", [(full_rank, 4), (rank_deficient, 2)])
@pytest.mark.parametrize("b_shape", [(7,), (7, 1), (7, 3)])
def test_the_solution_is_numpy_lstsq(make_A, rank, b_shape):
    # The minimum-norm least-squares solution either way; for the rank-deficient A both cut the
    # same two singular values (about 1e-16 of sigma_max, far below either's cut-off).
    A = make_A()
    b = np.random.default_rng(2).standard_normal(b_shape)
    result = quiet_solve(A, b)
    x, _, numpy_rank, _ = np.linalg.lstsq(A, b, rcond=None)
    assert result.rank == numpy_rank == rank
    assert result.solution.shape == x.shape
    # Both are backward stable, so they differ by rounding times the (effective) condition number,
    # 3.4 and 1.8 here: about 1e-15 measured; 1e-12 leaves room for other BLAS builds.
    assert np.linalg.norm(result.solution - x) <= 1e-12 * np.linalg.norm(x)
    assert result.residual_norm == pytest.approx(np.linalg.norm(A @ x - b), rel=1e-10)
    if b.ndim == 1:
        assert result.columns[0].residual_norm == pytest.approx(result.residual_norm, rel=1e-12)


def test_the_1d_solution_of_each_column_is_the_matrix_solution_column():
    A, B = rank_deficient(), np.random.default_rng(3).standard_normal((7, 2))
    matrix = quiet_solve(A, B)
    for j in range(2):
        vector = quiet_solve(A, B[:, j])
        assert vector.solution.shape == (4,)
        assert np.array_equal(vector.solution, quiet_solve(A, B[:, [j]]).solution[:, 0])
        assert np.allclose(vector.solution, matrix.solution[:, j], rtol=0, atol=1e-14)


@pytest.mark.parametrize("b_shape", [(7,), (7, 1), (7, 3)])
def test_pickling_keeps_the_shape_of_the_solution(b_shape):
    result = spdfit.solve(full_rank(), np.random.default_rng(4).standard_normal(b_shape))
    back = pickle.loads(pickle.dumps(result))
    assert back.solution.shape == result.solution.shape
    assert np.array_equal(back.solution, result.solution)


def test_a_failed_result_keeps_its_shape_through_pickle():
    with pytest.raises(spdfit.NumericalError) as error:
        spdfit.solve(np.eye(2) * 1e-300, np.full(2, 1e300))
    back = pickle.loads(pickle.dumps(error.value.result))
    assert not back.ok and back.solution.shape == (0,) and back.message == error.value.result.message


def test_b_with_more_than_two_dimensions_is_refused():
    with pytest.raises(ValueError, match="b must be a matrix"):
        spdfit.solve(np.eye(2), np.ones((2, 1, 1)))


def test_steering_example_matches_the_documented_numbers():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        r = lk.synthesize(steering=0.5)
    assert np.allclose(r.design.k, [1.69259278, 1.66655770, 1.65662059], atol=1e-8)
    assert np.allclose(r.structural.k, [1.96307066, 2.20197577, 2.19606530], atol=1e-8)
    assert np.degrees(r.structural.structural_error_rms) < np.degrees(r.design.structural_error_rms)


def test_design_solution_is_numpy_lstsq():
    bar = lk.FourBar(1.0, 0.4, 1.1, 0.9)
    analysis = lk.analyze(bar, np.linspace(20, 80, 9))
    psi = np.array([s.psi for s in analysis.samples])
    phi = np.array([s.phi_plus for s in analysis.samples])
    noisy_phi = phi + 0.002 * np.sin(7 * psi)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        r = lk.synthesize(psi, noisy_phi, radians=True)
    S = np.column_stack([np.ones_like(psi), np.cos(noisy_phi), -np.cos(psi)])
    k, *_ = np.linalg.lstsq(S, np.cos(psi - noisy_phi), rcond=None)
    assert np.allclose(r.design.k, k, rtol=0, atol=1e-12)


def test_exact_pairs_recover_the_linkage():
    bar = lk.FourBar(1.0, 0.5, 1.2, 0.8)
    analysis = lk.analyze(bar, np.linspace(30, 90, 7))
    psi = np.degrees([s.psi for s in analysis.samples])
    phi = np.degrees([s.phi_plus for s in analysis.samples])
    with pytest.warns(spdfit.SpdfitWarning, match="transmission angle"):
        r = lk.synthesize(psi, phi)
    assert np.allclose(r.design.k, lk.freudenstein_parameters(bar), atol=1e-10)
    lengths = r.design.lengths
    assert (lengths.a2, lengths.a3, lengths.a4) == pytest.approx((0.5, 1.2, 0.8), abs=1e-9)


def test_bad_synthesis_input():
    with pytest.raises(ValueError, match="exactly one"):
        lk.synthesize()
    with pytest.raises(ValueError):
        lk.synthesize([1.0, 2.0], [1.0, 2.0])  # fewer than 3 pairs
    with pytest.raises(ValueError, match="NaN"):
        lk.synthesize([1.0, np.nan, 3.0], [1.0, 2.0, 3.0])


def test_non_finite_angles_are_refused_by_the_library():
    # The library checks the pairs and the input angles (as for the command line's files), naming
    # them: a NaN pair is a DataError, a NaN input angle of analyze a ValueError naming psi.
    with pytest.raises(spdfit.DataError, match="pair 2 is not finite"):
        lk.synthesize([0, np.nan, 80], [10, 20, 30])
    with pytest.raises(ValueError, match="input angles must be finite"):
        lk.analyze((4, 1, 3.5, 3), [0, np.inf])
    assert lk.STEERING_PSI_RANGE == (-30.0, 30.0)
