"""spdfit.solve and spdfit.linkage against NumPy, and their Python manners."""
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
    assert np.allclose(result.solution[:, 0], np.array([21, 10, -2]) / 13, rtol=0, atol=1e-14)
    assert "one point in common" in result.explanation


def test_solve_raises_numerical_error_when_the_solution_overflows():
    with pytest.raises(spdfit.NumericalError, match="overflows the range of double precision numbers") as error:
        spdfit.solve(np.eye(2) * 1e-300, np.full(2, 1e300))
    assert error.value.result.rank == 2
    x = spdfit.solve(np.eye(2) * 1e-310, np.full(2, 2e-310)).solution
    assert np.allclose(x, 2.0)


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
