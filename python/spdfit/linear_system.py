"""Classifying and solving linear systems A x = b from the SVD with small singular values edited
(lecture notes 002, sections 3.3.2 and 3.7-3.8): spdfit.solve, as `spdfit solve`.

    >>> import spdfit
    >>> spdfit.linear_system.solve([[1., 0.], [0., 1.]], [1., 2.]).solution
    array([1., 2.])
"""
import numpy as _np

from . import _spdfit
from ._common import _as_matrix
from ._errors import NumericalError, warn as _warn

__all__ = ["solve"]


def solve(A, b, *, threshold=None):
    """Classify and solve A x = b (lecture notes 002, sections 3.3.2 and 3.7-3.8).

    From the SVD of A with singular values below threshold * sigma_max edited to zero: rank,
    nullity, condition number, whether the system is consistent, the dimension of the finite
    solution set (-1 none, 0 a point, 1 a line, ...) and of the solutions at infinity (the
    homogeneous [A | -b][x; w] = 0 with w = 0), the minimum-norm least-squares solution, the
    residual, bases of the null space and range, and an explanation in words. b may have several
    columns (each is classified on its own).

    Shapes follow numpy.linalg.lstsq: result.solution has shape (n,) for b of shape (m,) and (n, k)
    for b of shape (m, k), (m, 1) included. The per-right-hand-side classification keeps one entry
    per column of b whatever its dimensionality, as lstsq's residuals do: result.columns is a list of
    one ColumnClassification for a 1-D b, result.p is 1, and result.residual_norm (||A X - b||_F, a
    scalar) is ||A x - b||_2. A pickled result keeps the solution's shape.

    Parameters
    ----------
    A : array_like
        The m x n matrix.
    b : array_like
        The right-hand side(s): shape (m,) or (m, k).
    threshold : float, optional
        The relative cut-off of the singular values (default max(m, n) eps).

    Returns
    -------
    LinearSystemResult
        The classification, the solution and the explanation.

    Raises
    ------
    ValueError
        Bad input: b's rows not A's, NaN/Inf, a non-numeric array.
    TypeError
        threshold is not a number.
    NumericalError
        The solution does not fit in a double (b huge against A); the failed result is its `result`.

    Warns
    -----
    SpdfitWarning
        A is ill-conditioned, and the other conditions in result.warnings.

    Examples
    --------
    >>> import spdfit
    >>> r = spdfit.solve([[1., 0.], [0., 1.], [1., 1.]], [1., 1., 0.])
    >>> r.rank, r.consistent, r.solution.shape
    (2, False, (2,))
    >>> r.solution.round(6)
    array([0.333333, 0.333333])
    >>> print(r.explanation.splitlines()[0])
    3 equations in 2 unknowns (overdetermined): 3 lines in the plane. Rank 2, nullity 0.
    """
    result = _spdfit.solve(_as_matrix("A", A), _as_matrix("b", b), threshold, _np.ndim(b) == 1)
    for message, code in zip(result.warnings, result.warning_codes):
        _warn(message, code)
    if not result.ok:
        raise NumericalError(result.message, result)
    return result
