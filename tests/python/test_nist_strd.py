"""Least squares at certified accuracy (issue 17): spdfit.solve on NIST's StRD linear-regression
sets (tests/data/nist_strd) against the certified coefficients, against the exact least-squares
solution of the double-precision data (rational arithmetic), and side by side with NumPy."""
from fractions import Fraction

import numpy as np
import pytest

import spdfit
from nist_strd import DATA_SETS, design, lre, read_set

# The LRE each set reaches with the default settings (bench/nist_accuracy.py, measured 14.1, 13.5,
# 14.7, 15.0, 7.9, 14.6, 15.0, 13.2, 15.0, 15.0, 15.0), asserted half a digit lower. Where it stays
# below 15 the data limit it, not the solver (test_matches_the_exact_solution_of_the_doubles):
# Filippelli's x^k columns and Wampler2's and Pontius' decimals are rounded on the way to double.
FLOOR = {"Norris": 13.5, "Pontius": 13.0, "NoInt1": 14.0, "NoInt2": 14.5, "Filippelli": 7.4,
         "Longley": 14.0, "Wampler1": 14.5, "Wampler2": 12.7, "Wampler3": 14.5, "Wampler4": 14.5,
         "Wampler5": 14.5}


def exact_least_squares(X, y):
    """The least-squares solution of the double-precision data in exact rational arithmetic
    (normal equations by Gaussian elimination on Fractions: no rounding at all)."""
    A = [[Fraction(v) for v in row] for row in X]
    b = [Fraction(v) for v in y]
    n = len(A[0])
    M = [[sum(A[i][r] * A[i][c] for i in range(len(A))) for c in range(n)] for r in range(n)]
    v = [sum(A[i][r] * b[i] for i in range(len(A))) for r in range(n)]
    for c in range(n):
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            M[r] = [M[r][k] - f * M[c][k] for k in range(n)]
            v[r] -= f * v[c]
    x = [Fraction(0)] * n
    for r in reversed(range(n)):
        x[r] = (v[r] - sum(M[r][k] * x[k] for k in range(r + 1, n))) / M[r][r]
    return np.array([float(t) for t in x])


@pytest.mark.parametrize("name", DATA_SETS)
def test_certified_coefficients(name):
    data = read_set(name)
    X = design(data)
    result = spdfit.solve(X, data["y"])
    assert result.rank == X.shape[1], "full rank: the columns' sizes are units, not collinearity"
    assert lre(result.solution, data["beta"]) >= FLOOR[name]


@pytest.mark.parametrize("name", DATA_SETS)
def test_matches_the_exact_solution_of_the_doubles(name):
    # What the solver itself adds to the data's rounding: nearly nothing, whatever cond(A).
    data = read_set(name)
    X = design(data)
    exact = exact_least_squares(X, data["y"])
    assert lre(spdfit.solve(X, data["y"]).solution, exact) >= 14.0


@pytest.mark.parametrize("name", DATA_SETS)
def test_at_least_as_accurate_as_numpy(name):
    data = read_set(name)
    X = design(data)
    ours = lre(spdfit.solve(X, data["y"]).solution, data["beta"])
    numpy = lre(np.linalg.lstsq(X, data["y"], rcond=None)[0], data["beta"])
    assert ours >= numpy - 0.05
    if data["difficulty"] == "Higher":
        assert ours >= numpy + 1.0, "a digit ahead on NIST's hard sets"


def test_filippelli_is_full_rank_only_in_unit_free_terms():
    # Unscaled, cond(A) ~ 2e15 is beyond the default cut-off max(m, n) eps ~ 2e-14; with unit-norm
    # columns it is ~ 5e9, well inside.
    data = read_set("Filippelli")
    result = spdfit.solve(design(data), data["y"])
    assert result.condition_number * 82 * np.finfo(float).eps > 1.0
    assert result.scaled_condition_number < 1e11
    assert result.refinement_steps >= 1
    assert result.rank == 11 and not result.warnings
