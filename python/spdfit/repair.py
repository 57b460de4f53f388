"""Covariance and correlation repair with pandas in and out: nearest_spd, nearest_correlation and
nearest_covariance (`spdfit nearest`), through one path.

A pandas DataFrame given for the matrix (df.corr(), df.cov()) comes back as a DataFrame with the
same labels and dtype; a NumPy array comes back as NumPy. A mask of kept entries (``fixed``) or
elementwise weights (``h_weights``) given as DataFrames are aligned to the matrix's labels, and
``fixed`` may be a list of label pairs. The repairs themselves are the library's (`spdfit nearest`).
"""
import numpy as _np

from . import _spdfit
from ._common import _as_matrix, _takes_options
from ._errors import warn as _warn
from ._errors import DataError

__all__ = ["REPAIR_FLOOR_DEFAULT", "nearest_covariance", "nearest_correlation", "nearest_spd"]


def _is_frame(value):
    """Whether value is a pandas DataFrame (without importing pandas for NumPy users)."""
    kind = type(value)
    return kind.__name__ == "DataFrame" and kind.__module__.split(".")[0] == "pandas"


def _aligned(name, value, frame):
    """An option's matrix given as a DataFrame, reordered to the matrix's labels (as pandas aligns
    by label); a list of label pairs for `fixed` as 0-based positions; anything else as given."""
    if _is_frame(value):
        if frame is None:
            return value.to_numpy()
        rows, columns = list(frame.index), list(frame.columns)
        if sorted(map(str, value.index)) != sorted(map(str, rows)) or \
                sorted(map(str, value.columns)) != sorted(map(str, columns)):
            raise DataError(f"{name}: its labels differ from the matrix's (rows {list(value.index)[:4]}..., "
                             f"columns {list(value.columns)[:4]}...; the matrix's: {columns[:4]}...)")
        return value.loc[rows, columns].to_numpy()
    if name == "fixed" and frame is not None and isinstance(value, (list, tuple)) and len(value) > 0 \
            and all(isinstance(p, (list, tuple)) and len(p) == 2 for p in value):
        positions = {label: k for k, label in enumerate(frame.columns)}
        for pair in value:
            for label in pair:
                if label not in positions:
                    raise ValueError(f"fixed: no variable {label!r} in the DataFrame; its columns: "
                                     f"{list(frame.columns)}")
        return _np.array([[positions[a], positions[b]] for a, b in value], dtype=_np.float64)
    return value


def _repair(entry, C, options):
    """The library's repair `entry` of C with the options bound by name, its warnings as
    SpdfitWarning. Returns the result and the DataFrame C was (or None)."""
    frame = C if _is_frame(C) else None
    for name in ("fixed", "h_weights"):
        if options.get(name) is not None:
            options[name] = _aligned(name, options[name], frame)
    values = frame.to_numpy(dtype=_np.float64) if frame is not None else C
    if frame is not None and not _np.isfinite(values).all():
        # The library names the entry by position; a DataFrame's pair is named by its labels.
        i, j = map(int, _np.argwhere(~_np.isfinite(values))[0])
        what = "NaN" if _np.isnan(values[i, j]) else "Inf"
        raise DataError(f"the matrix to repair has {what} at ({frame.index[i]!r}, {frame.columns[j]!r}) (iloc [{i}, {j}]): "
                        f"a pair of variables never observed together (pandas' corr() and cov() give NaN there)? "
                        f"Every entry needs a value")
    result = _spdfit.nearest(_as_matrix("X" if entry == "nearest_spd" else "C", values), entry, options)
    for message, code in zip(result.warnings, result.warning_codes):
        _warn(f"{entry}: {_spdfit.spell_options(message)}", code)
    return result, frame


def _answer(result, frame, full_output, options):
    """What a repair returns: the NearestResult with full_output, else X (F with factors_only),
    as a DataFrame with the input's labels and dtype when the input was one."""
    if full_output:
        return result
    loadings = bool(options.get("factors_only"))
    out = result.F if loadings else result.X
    if frame is None:
        return out
    import pandas as pd
    dtypes = set(frame.dtypes)
    dtype = dtypes.pop() if len(dtypes) == 1 and _np.issubdtype(next(iter(set(frame.dtypes))), _np.floating) \
        else _np.float64
    columns = [f"factor {k + 1}" for k in range(out.shape[1])] if loadings else frame.columns
    return pd.DataFrame(out.astype(dtype, copy=False), index=frame.index, columns=columns)


@_takes_options("nearest_covariance")
def nearest_covariance(S, *, full_output=False, **options):
    """Repair a covariance keeping its variances (`spdfit nearest --keep-diag`).

    The nearest symmetric matrix to S with S's diagonal and every eigenvalue >= a floor (relative
    floors are of the correlation matrix D^-1/2 X D^-1/2, D = diag(S), so that variables in any
    units share one), by Qi and Sun's Newton method; with ``fixed`` entries kept exactly, with
    elementwise weights ``h_weights`` (an augmented Lagrangian method), or of rank at most ``rank``.
    Zero or negative variances, as pairwise deletion leaves them, are an error unless ``min_diag``
    raises them. A pandas DataFrame (``df.cov()``) comes back as a DataFrame with its labels.

    Parameters
    ----------
    S : array_like or pandas.DataFrame
        The square matrix to repair.
    full_output : bool, default False
        Return a NearestResult instead of the matrix.
    {options}

    Returns
    -------
    numpy.ndarray, pandas.DataFrame or NearestResult
        The matrix (a DataFrame when S is one), or with full_output=True a NearestResult.

    Raises
    ------
    DataError
        S is not a non-empty square matrix or has NaN/Inf; a variance <= 0 without ``min_diag``; a
        mask or weights that are not valid for S (or labelled by other variables); kept entries that
        no positive semidefinite matrix has (the message names them); ``rank`` above n.
    ValueError
        An option out of range, or options that exclude each other.
    TypeError
        An option of the wrong type.

    Warns
    -----
    SpdfitWarning
        Variances raised by ``min_diag`` (which).
    NotSymmetricWarning, NotConvergedWarning
        A non-symmetric S; no convergence.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> S = np.array([[4., 2., 2.1], [2., 3., 2.9], [2.1, 2.9, 2.]])
    >>> X = spdfit.nearest_covariance(S)
    >>> np.diag(X), bool(np.linalg.eigvalsh(X).min() > 0)
    (array([4., 3., 2.]), True)
    >>> Y = spdfit.nearest_covariance(S, fixed=[[0, 1]])  # S[0, 1] kept exactly
    >>> float(Y[0, 1]), float(Y[1, 0])
    (2.0, 2.0)
    """
    result, frame = _repair("nearest_covariance", S, options)
    return _answer(result, frame, full_output, options)


# The relative eigenvalue floor the repairs use when none is given (the library's, as the
# `nearest` command's): 1e-8 times the largest eigenvalue, as R's nearPD's posd.tol.
REPAIR_FLOOR_DEFAULT = _spdfit.REPAIR_FLOOR_DEFAULT


@_takes_options("nearest_spd", given=("min_eig",))
def nearest_spd(X, min_eig=None, *, full_output=False, **options):
    """Repair a covariance: the nearest symmetric matrix to X with every eigenvalue >= a floor.

    The nearest in the Frobenius norm (`spdfit nearest`). Without a diagonal constraint this is
    Higham's (1988) eigenvalue clip of (X + X^T)/2 (thesis section 3.3). keep_diag=True keeps X's
    diagonal (trusted variances): the nearest matrix with that diagonal and the floor, by Qi and
    Sun's Newton method (as nearest_correlation). via_corr=True is statsmodels' cov_nearest route:
    scale to a correlation, repair it (the floor applies to the correlation), scale back.

    Parameters
    ----------
    X : array_like or pandas.DataFrame
        The square matrix to repair (a DataFrame comes back as one, with its labels).
    min_eig : float, optional
        An absolute floor; min_eig=0 is the plain positive semidefinite projection.
    full_output : bool, default False
        Return a NearestResult instead of the matrix.
    {options}

    Returns
    -------
    numpy.ndarray, pandas.DataFrame or NearestResult
        The matrix, or with full_output=True a NearestResult (X, distance, clipped,
        min_eigenvalue_before, min_eig, iterations, gradient_norm, converged, cholesky_ok, warnings).

    Raises
    ------
    ValueError
        X is not a non-empty square matrix or has NaN/Inf; keep_diag and via_corr both given; weights,
        max_iter or tol without keep_diag or via_corr.
    TypeError
        An option of the wrong type.

    Warns
    -----
    SpdfitWarning
        A non-symmetric X, eigenvalues raised to the floor (how many), a floor that moved X more than the
        repair itself, no convergence.

    Examples
    --------
    >>> import numpy as np, spdfit, warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     X = spdfit.nearest_spd([[1., 2.], [2., 1.]], min_eig=0)
    >>> X.round(12)
    array([[1.5, 1.5],
           [1.5, 1.5]])
    >>> print(caught[0].message)  # what the repair changed, as `spdfit nearest` says it
    nearest_spd: 1 eigenvalue(s) of the symmetric part were below 0 and were raised to it
    >>> S = np.array([[4., 2., 2.1], [2., 3., 2.9], [2.1, 2.9, 2.]])
    >>> r = spdfit.nearest_spd(S, keep_diag=True, full_output=True)
    >>> np.diag(r.X), r.clipped, r.cholesky_ok
    (array([4., 3., 2.]), 1, True)
    """
    if min_eig is not None:
        options["min_eig"] = min_eig
    result, frame = _repair("nearest_spd", X, options)
    return _answer(result, frame, full_output, options)


@_takes_options("nearest_correlation")
def nearest_correlation(C, *, full_output=False, **options):
    """The nearest correlation matrix to C (`spdfit nearest --corr`).

    Minimizes ||W^1/2 (X - C) W^1/2||_F over symmetric X with unit diagonal and every eigenvalue >=
    a floor (Higham 2002), W = diag(weights), by Qi and Sun's quadratically convergent Newton method
    on the dual (with Borsdorf and Higham's preconditioned conjugate gradients), not alternating
    projections. The floor is an exact constraint. The diagonal of X is exactly 1. ``fixed`` keeps
    entries exactly (a mask, 0-based index pairs, or label pairs of a DataFrame), ``h_weights``
    weights each entry (||H o (X - C)||_F), ``rank`` limits the rank, ``factors`` fits
    X = diag(1 - ||f_i||^2) + F F^T (``factors_only``: F alone). A pandas DataFrame (``df.corr()``)
    comes back as a DataFrame with its labels.

    Parameters
    ----------
    C : array_like or pandas.DataFrame
        The square matrix to repair.
    full_output : bool, default False
        Return a NearestResult instead of the matrix.
    {options}

    Returns
    -------
    numpy.ndarray, pandas.DataFrame or NearestResult
        The matrix (F with factors_only; a DataFrame when C is one), or with full_output=True a
        NearestResult (X, distance, iterations, gradient_norm, converged, clipped, min_eig,
        cholesky_ok, warnings, method, lower_bound, optimality_residual, F, starts, fixed_entries).

    Raises
    ------
    ValueError
        C is not a non-empty square matrix or has NaN/Inf, or the floor cannot be met with a unit
        diagonal.
    TypeError
        An option of the wrong type.

    Warns
    -----
    SpdfitWarning
        Not converging (X is then the best iterate), or a diagonal that is not 1 (C is repaired to a
        correlation matrix all the same).

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> C = np.array([[1., 1., 0.], [1., 1., 1.], [0., 1., 1.]])
    >>> spdfit.nearest_correlation(C, min_eig=0).round(4)
    array([[1.    , 0.7607, 0.1573],
           [0.7607, 1.    , 0.7607],
           [0.1573, 0.7607, 1.    ]])
    >>> r = spdfit.nearest_correlation(C, full_output=True)
    >>> r.converged, r.cholesky_ok
    (True, True)
    """
    result, frame = _repair("nearest_correlation", C, options)
    return _answer(result, frame, full_output, options)
