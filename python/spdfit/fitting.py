"""Estimating X in A X ~= B: fit (any method, "auto" by default), fit_all (every estimator from one
QR), fit_files (data files of any length, a block of rows at a time), one function per method, and
the area criterion that spde minimizes. Every name here is also spdfit's (spdfit.fit is this
module's fit).

    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> bool(np.allclose(spdfit.fitting.spde(A, A @ np.eye(2)).X, np.eye(2)))
    True
"""
import os as _os

from . import _spdfit
from ._common import _checked, _column_spec, _data, _as_matrix, _shared_doc, _takes_options
from ._errors import warn as _warn

__all__ = ["fit", "fit_all", "fit_files", "least_squares", "symmetric_procrustes", "total_least_squares",
           "total_least_squares_symmetric", "total_least_squares_psd", "spde", "spd_total_least_squares",
           "psd_least_squares", "auto_fit", "area_criterion"]


@_shared_doc
@_takes_options("fit")
def fit(A, B=None, method="auto", *, a_cols=None, b_cols=None, **options):
    """Estimate X in A X ~= B with `method` (one of METHODS).

    The default, "auto", chooses spde, spd-tls or psd-ls from the data (and the noise model,
    noise=) and returns a positive definite X, or a warning says that it could not; result.method is the method it ran and result.diagnostics.reason says why (the
    default was "spde" before; docs/changes.md). "ls" and "tls" also take B with d != n columns (X
    n x d, as numpy.linalg.lstsq returns for several right-hand sides; tls then needs m >= n + d); the
    other methods estimate a symmetric X.

    The options are the library's (the command line's, spelled as keywords); each is checked for its
    type and range, and one that the method does not take (noise_ratio with spde, ...) is an error.
    With bootstrap=N > 0 the rows of [A B] are resampled N times and each resample refitted with the
    same method (auto: the one it chose); the result then has standard_errors (the shape of X),
    interval (level, type, lower, upper: of the kind the `interval` option names, by default
    auto: the basic interval where X, or at least 10% of the replicates, is singular, else the
    percentile one, the central `confidence` fraction of the replicates; `type` says which), bias (their
    mean minus X) and bootstrap (replicates, failed, seed, eigenvalues with their intervals); without
    it these attributes are None. reported_diagnostics=False skips the diagnostics that neither X
    nor a warning needs (at n = 2000 more than half of spde's time); X and the other warnings are
    the same.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n and m x d, one sample per row (d = n but for "ls" and "tls"); any
        real dtype, converted to float64; a 1-D array is one column. With a_cols and b_cols, A is
        a pandas DataFrame holding both, and B is left out.
    method : str, default "auto"
        One of METHODS.
    a_cols, b_cols : label, list, slice, str or None, default None
        A's and B's columns of the DataFrame A: labels, a list of labels, a label slice (inclusive,
        as df.loc), 0-based positions (a list or slice of ints, as df.iloc), or a str that is not
        one of its labels: a selection as the command line and fit_files write it ("acc1:acc6",
        "2:7" counting from 1, "1,3:5,F1"); both or neither, no column in both. The other columns
        (a timestamp, text) are ignored. The result keeps the labels: row_names are A's column
        labels (X's rows), column_names B's, and a_columns and b_columns say which columns of the
        DataFrame they were ("DataFrame columns acc1..acc6 (2-7)", counting from 1). DataFrames A
        and B given apart label the result the same way.
    {options}

    {returns}

    Raises
    ------
    ValueError
        Bad input: shapes, NaN/Inf, m < n, an unknown method, B with d != n columns for a method
        that estimates a symmetric X, an option out of range, or an option with a method that does
        not take it (noise_ratio, max_iter or min_eig) or without the one it needs (confidence,
        seed without bootstrap).
    TypeError
        An option of the wrong type (method=3, max_iter=2.5, ...) or one the function does not
        take, named in the message.
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    See Also
    --------
    fit_all : every estimator on the same data.
    fit_files : the same estimate from data files of any length.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.fit(A, A @ X)
    >>> r.method, r.diagnostics.reason.code
    ('spde', 'noise_free')
    >>> bool(np.allclose(r.X, X))
    True
    >>> spdfit.fit(A, A @ X, method="procrustes").diagnostics.cross_term_positive_definite
    True

    A and B from the columns of one pandas DataFrame (labels, a label slice, or 0-based positions, as
    df.loc and df.iloc take them; the other columns, such as a timestamp, are ignored):

    >>> import pandas as pd
    >>> log = pd.DataFrame({"time": pd.date_range("2024-01-01", periods=4, freq="s"),
    ...                     "a1": A[:, 0], "a2": A[:, 1], "f1": (A @ X)[:, 0], "f2": (A @ X)[:, 1]})
    >>> r = spdfit.fit(log, a_cols=["a1", "a2"], b_cols=[3, 4])
    >>> bool(np.allclose(r.X, X))
    True
    >>> r = spdfit.fit(log, a_cols="a1:a2", b_cols=slice("f1", "f2"))
    >>> r.row_names, r.column_names, r.a_columns
    (['a1', 'a2'], ['f1', 'f2'], 'DataFrame columns a1..a2 (2-3)')
    """
    A, B, labels = _data("fit", A, B, a_cols, b_cols)
    return _checked(_spdfit.fit(A, B, method, options, labels))


@_shared_doc
@_takes_options("fit_files")
def fit_files(A_path, B_path=None, method="auto", **options):
    """Estimate X from A and B in two data files (or the columns of one) read a block of rows at a time.

    As `spdfit fit --stream`: any number of rows in O(threads * block_rows * n + n^2) memory. The
    files are read as read_matrix reads them (.npy files and MATLAB 7.3 variables a block of rows
    at a time, delimited text parsed as it is read; level-5 .mat files and .npz arrays whole, with
    a SpdfitWarning that memory grows with their rows); each block's triangular QR factor of [A B] is computed on up to `threads` threads and the
    factors are merged in block order (TSQR), so the estimate is fit(read_matrix(A_path),
    read_matrix(B_path), method)'s to rounding, the same for every thread count.

    bootstrap=N runs the streaming bootstrap in the same one pass: the rows are cut into groups of
    4096, each group gets a Poisson(1) count per replicate (keyed by seed, replicate and group), and
    the groups' factors are merged, so weighted, into the replicates' factors. It needs about 100
    groups (409,600 rows) or more; its numbers agree with fit's in-memory bootstrap within Monte
    Carlo error, not exactly. With fewer rows, the files are read again and their rows resampled
    in memory as fit does (a SpdfitWarning says so) when A and B take at most 256 MiB as doubles;
    beyond that, or from standard input, DataError. The other options are fit's.

    Parameters
    ----------
    A_path, B_path : str or os.PathLike
        The data files of A and B (the same number of rows). Without B_path, a_cols and b_cols choose
        A's and B's columns in A_path's one file ("log.mat:log" names a .mat or .npz array): as the
        command line's --a-cols and --b-cols ("acc1:acc6", "2:7", "1,3:5,F1": header names and
        1-based positions), lists of header labels and 0-based positions (as pandas' iloc), or
        slices of labels (inclusive, as df.loc) or of 0-based positions (as df.iloc), as fit
        takes them from a DataFrame.
    method : str, default "auto"
        One of METHODS, as in fit.
    {options}

    {returns}

    Raises
    ------
    DataError
        A bad file (a ValueError); the message names the file, line and column.
    ValueError
        Bad arguments, as in fit.
    TypeError
        An option of the wrong type.
    NumericalError
        The method has no answer for this data, as in fit.

    {warns}

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     spdfit.write_csv(pathlib.Path(folder) / "A.csv", A)
    ...     spdfit.write_csv(pathlib.Path(folder) / "B.csv", A @ X)
    ...     r = spdfit.fit_files(pathlib.Path(folder) / "A.csv", pathlib.Path(folder) / "B.csv", "spde")
    >>> bool(np.allclose(r.X, spdfit.fit(A, A @ X, "spde").X))
    True
    """
    a_path = _os.fspath(A_path)
    b_path = "" if B_path is None else _os.fspath(B_path)
    for name in ("a_cols", "b_cols"):
        if name in options:
            options[name] = _column_spec(name, options[name])
    if not b_path and options.get("a_cols") is None and options.get("b_cols") is None:
        raise TypeError("fit_files() needs B_path, or a_cols and b_cols choosing A's and B's columns in A_path")
    files = (a_path, b_path) if b_path else (a_path, a_path.rsplit(":", 1)[0])
    return _checked(_spdfit.fit_files(a_path, b_path, method, options), files=files)


@_shared_doc
@_takes_options("fit_all")
def fit_all(A, B=None, *, a_cols=None, b_cols=None, **options):
    """Every estimator (METHODS but "auto") on the same data, from one shared QR.

    For B with d != n columns only "ls" and "tls", which fit a non-square X. Failures are not raised
    here: check `result.ok` and `result.message`.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column). With a_cols and b_cols, A is a pandas DataFrame holding both, and B is left out.
    a_cols, b_cols : label, list, slice, str or None, default None
        A's and B's columns of the DataFrame A, as fit takes them; every result keeps the labels.
    {options}

    Returns
    -------
    dict of str to FitResult
        {method: FitResult}, in the order of METHODS.

    Raises
    ------
    {bad_input}

    Warns
    -----
    SpdfitWarning
        Each method's warnings, prefixed with its name.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> results = spdfit.fit_all(A, B)
    >>> list(results)
    ['ls', 'procrustes', 'tls', 'tls-sym', 'tls-psd', 'spde', 'spd-tls', 'psd-ls']
    >>> all(r.ok for r in results.values())
    True
    """
    A, B, labels = _data("fit_all", A, B, a_cols, b_cols)
    results = {}
    for result in _spdfit.fit_all(A, B, options, labels):
        for message, code in zip(result.warnings, result.warning_codes):
            _warn(f"{result.method}: {_spdfit.spell_options(message)}", code)
        results[result.method] = result
    return results


@_shared_doc
@_takes_options("fit:ls")
def least_squares(A, B, **options):
    """Least squares X = A^+ B minimizing ||A X - B||_F (thesis 000 section 3.1).

    Back substitution in R11 X = R12 from the QR of [A B]; for rank-deficient A the minimum-norm
    solution from the SVD with small singular values edited (notes 002 eq. 3.21).

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n and m x d (d may differ from n: X is then n x d).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.least_squares(A, A @ X)
    >>> bool(np.allclose(r.X, X))
    True
    """
    return fit(A, B, "ls", **options)


@_shared_doc
@_takes_options("fit:procrustes")
def symmetric_procrustes(A, B, **options):
    """The symmetric X minimizing ||A X - B||_F.

    The solution of A^T A X + X A^T A = A^T B + B^T A (thesis eq. 3.15). Positive definite when
    A^T B + B^T A is (Theorem 3.2 (3)); see result.diagnostics.cross_term_positive_definite.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.symmetric_procrustes(A, B)
    >>> r.X.round(4)
    array([[3.0031, 0.9846],
           [0.9846, 0.9861]])
    >>> r.diagnostics.cross_term_positive_definite
    True
    """
    return fit(A, B, "procrustes", **options)


@_shared_doc
@_takes_options("fit:tls")
def total_least_squares(A, B, **options):
    """Total least squares X = -V12 V22^-1 from the SVD of [A B] (thesis eq. 4.37).

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n and m x d (d may differ from n: X is then n x d, and m >= n + d).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        V22 is singular (no total least-squares solution); the failed FitResult is its `result`.

    Warns
    -----
    SpdfitWarning
        sigma_n = sigma_{n+1} (the solution is not unique), and the other conditions of fit.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.total_least_squares(A, A @ X)
    >>> bool(np.allclose(r.X, X))
    True
    """
    return fit(A, B, "tls", **options)


@_shared_doc
@_takes_options("fit:tls-sym")
def total_least_squares_symmetric(A, B, **options):
    """(X_TLS + X_TLS^T) / 2, the nearest symmetric matrix to the TLS estimate (thesis eq. 4.38).

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.total_least_squares_symmetric(A, B)
    >>> r.X.round(4)
    array([[2.994 , 1.0147],
           [1.0147, 0.9955]])
    """
    return fit(A, B, "tls-sym", **options)


@_shared_doc
@_takes_options("fit:tls-psd")
def total_least_squares_psd(A, B, **options):
    """Higham's nearest symmetric positive semidefinite matrix to X_TLS (thesis eq. 4.39).

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.total_least_squares_psd(A, B)
    >>> r.diagnostics.positive_semidefinite
    True
    """
    return fit(A, B, "tls-psd", **options)


@_shared_doc
@_takes_options("fit:spde")
def spde(A, B, **options):
    """The area-criterion estimate: the unique SPD X with X (A^T A) X = B^T B.

    Minimizes ||A Y - B Y^-T||_F^2 over X = Y Y^T (Chen & McInroy, Definition II.1, Theorem III.3).
    Computed as X = L L^T, L = R11^-1 V_M S^(1/2) from the polar decomposition of M = R_b R11^T, so X
    is exactly symmetric and positive definite, with error ~cond(A) eps on noise-free data.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        A is rank-deficient; the failed FitResult is its `result`.

    Warns
    -----
    SpdfitWarning
        B has rank r < n: X is then the PSD minimizer of rank r (Corollary III.7). And the other
        conditions of fit.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.spde(A, B)
    >>> r.X.round(4)
    array([[3.0126, 0.9732],
           [0.9732, 0.9629]])
    >>> r.diagnostics.positive_definite
    True
    >>> d = r.diagnostics          # Corollary III.4: the minimum, in closed form
    >>> bool(np.isclose(d.area_criterion, d.area_criterion_minimum))
    True
    """
    return fit(A, B, "spde", **options)


@_shared_doc
@_takes_options("fit:spd-tls")
def spd_total_least_squares(A, B, **options):
    """Total least squares over the symmetric positive definite matrices (spd-tls).

    Minimizes f(X) = tr((A X - B)^T (A X - B) (r^2 I + X^2)^-1), r = noise_ratio, the TLS criterion
    ||[dA dB/r]||_F^2, over SPD X by a Riemannian Newton method from spde, until
    ||X^1/2 grad f X^1/2||_F <= 1e-10 f (diagnostics: iterations, gradient_norm, converged).
    Consistent (its error keeps falling with m) and positive definite.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    Warns
    -----
    SpdfitWarning
        The infimum is on the boundary (then X is semidefinite) or the iteration limit is reached;
        and the other conditions of fit.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.spd_total_least_squares(A, B)
    >>> r.diagnostics.converged, r.diagnostics.positive_definite
    (True, True)
    """
    return fit(A, B, "spd-tls", **options)


@_shared_doc
@_takes_options("fit:psd-ls")
def psd_least_squares(A, B, **options):
    """The symmetric X >= min_eig I minimizing ||A X - B||_F (psd-ls), with a certificate.

    Symmetric Procrustes when it is feasible; else spectral projected gradient with exact face
    solves, to a relative KKT residual <= 1e-12. result.diagnostics.certificate holds primal_min_eig,
    dual_min_eig, complementarity and duality_gap: X is optimal when the first two are >= 0 and the
    third is 0, to rounding.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> r = spdfit.psd_least_squares(A, B, min_eig=1.0)
    >>> round(float(np.linalg.eigvalsh(r.X)[0]), 10)
    1.0
    >>> c = r.diagnostics.certificate
    >>> c.primal_min_eig > -1e-12 and c.dual_min_eig > -1e-12 and abs(c.complementarity) < 1e-12
    True
    """
    return fit(A, B, "psd-ls", **options)


@_shared_doc
@_takes_options("fit:auto")
def auto_fit(A, B, **options):
    """fit(A, B, "auto"): spde, spd-tls or psd-ls, chosen from the data (and the noise model, noise=).

    The estimate is positive definite, or a warning says that it is not: when the chosen method
    ends on the boundary and psd-ls, auto's fallback, does not give a positive definite matrix
    either. Without noise=, auto assumes equal noise in every column of A and B in the units
    given, and its reason says so.

    result.method is the method it ran; result.diagnostics.chosen_method and .reason (code, text)
    say which and why.

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    {options}

    {returns}

    Raises
    ------
    {bad_input}
    NumericalError
        The method has no answer for this data; the failed FitResult is its `result`.

    {warns}

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.auto_fit(A, A @ X)
    >>> r.diagnostics.chosen_method, r.diagnostics.positive_definite
    ('spde', True)
    """
    return fit(A, B, "auto", **options)


def area_criterion(A, B, X):
    """The area criterion ||A Y - B Y^-T||_F^2 for X = Y Y^T (Chen & McInroy, Definition II.1).

    For X semidefinite of rank r < n, tr(P X + X^+ Q) - 2 tr(A^T B) (Corollary III.7).

    Parameters
    ----------
    A, B : array_like
        The measurements, m x n each, one sample per row (any real dtype; a 1-D array is one
        column).
    X : array_like
        The n x n matrix to evaluate.

    Returns
    -------
    float or None
        The criterion; None when X is not symmetric positive semidefinite.

    Raises
    ------
    ValueError
        Shapes that do not fit (X not n x n, A and B of different shapes) or a non-numeric array.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> B = A @ X + np.array([[0.1, -0.2], [0.05, 0.1], [-0.1, 0.], [0.2, 0.1]])
    >>> round(spdfit.area_criterion(A, B, X), 3)
    0.116
    >>> round(spdfit.area_criterion(A, B, spdfit.spde(A, B).X), 4)    # spde minimizes it
    0.0383
    >>> print(spdfit.area_criterion(A, B, -X))
    None
    """
    return _spdfit.area_criterion(_as_matrix("A", A), _as_matrix("B", B), _as_matrix("X", X))
