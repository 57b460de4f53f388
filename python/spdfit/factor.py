"""spdfit.Factor: the data's triangular factor as a value that merges.

Every estimate needs only R, the (n + d) x (n + d) triangular factor of the Householder QR of
[A B], and the factors of disjoint row sets merge into the factor of their union (TSQR). So a fit
can be spread over processes or machines: each makes the factor of its rows, the factors are
merged pairwise (in any grouping: the merge is associative to rounding), and the last one is
estimated from, with the numbers of spdfit.fit on all the rows. A Factor pickles as the library's
validated bytes (to_bytes), which is what Dask, multiprocessing and Spark send between processes.
"""
import numbers
import os as _os

from . import _spdfit
from ._common import _checked, _data, _options, _shared_doc, _takes_options
from ._errors import warn as _warn

# The streaming defaults are the library's (StreamOptions), not retyped here.
_STREAM_DEFAULTS = _spdfit.StreamOptions()

__all__ = ["Factor"]


class Factor:
    """The triangular factor of the data [A B]: what every estimate needs, mergeable.

    R is the (n + d) x (n + d) upper triangular factor of the Householder QR of [A B] (A m x n,
    B m x d), kept in O((n + d)^2) numbers for any number of rows m; A^T A, A^T B and the
    residual of any X follow from it without forming the Gram matrices. Factors of disjoint row
    sets merge into the factor of their union (TSQR), so the rows can be split among processes
    or machines in any way. A Factor is a value: merge returns a new one, and it pickles as the
    library's validated bytes (to_bytes). Made by from_data, from_files or from_bytes; the
    constructor makes the factor of no rows, for A with n columns and B with d, the neutral
    element of merge (Spark's treeAggregate wants one as its zeroValue).

    Parameters
    ----------
    n : int
        A's columns (X has n rows).
    d : int, optional
        B's columns (X has d columns; default n, a square X).

    Attributes
    ----------
    n : int
        A's columns.
    d : int
        B's columns.
    rows : int
        The rows (samples) accumulated.

    Raises
    ------
    ValueError
        n < 1 or d < 1.
    TypeError
        n or d is not an int.

    See Also
    --------
    fit : the estimate from the data in memory.
    fit_files : the estimate from data files, streamed.

    Examples
    --------
    >>> import numpy as np, spdfit
    >>> rng = np.random.default_rng(1)
    >>> A = rng.standard_normal((1000, 3))
    >>> B = A @ np.diag([1., 2., 3.]) + 0.1 * rng.standard_normal((1000, 3))
    >>> f = spdfit.Factor.from_data(A[:600], B[:600])
    >>> g = spdfit.Factor.from_data(A[600:], B[600:])
    >>> f.merge(g)
    Factor(n=3, d=3, rows=1000)
    >>> X = f.merge(g).fit("spde").X
    >>> bool(np.linalg.norm(X - spdfit.fit(A, B, "spde").X) <= 1e-12 * np.linalg.norm(X))
    True
    >>> spdfit.Factor(3)
    Factor(n=3, d=3, rows=0)
    """

    __slots__ = ("_core",)

    def __init__(self, n, d=None):
        n, d = _options(n=n, d=d)
        self._core = _spdfit.TriangularFactor(n, n if d is None else d)

    @classmethod
    def _wrap(cls, core):
        factor = cls.__new__(cls)
        factor._core = core
        return factor

    @classmethod
    def from_data(cls, A, B=None, *, a_cols=None, b_cols=None):
        """The factor of the data A (m x n) and B (m x d), one sample per row.

        Any number of rows, none included (a block of a split may be short). Cost O(m (n + d)^2).

        Parameters
        ----------
        A, B : array_like
            The measurements, m x n and m x d (any real dtype, converted to float64; a 1-D array
            is one column). With a_cols and b_cols, A is a pandas DataFrame holding both, and B is
            left out.
        a_cols, b_cols : label, list, slice, str or None, default None
            A's and B's columns of the DataFrame A, as spdfit.fit takes them.

        Returns
        -------
        Factor
            The factor of these rows.

        Raises
        ------
        ValueError
            A and B with different numbers of rows, no columns, NaN or Inf, or an array that is
            not a real numeric matrix.

        Examples
        --------
        >>> import numpy as np, spdfit
        >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
        >>> f = spdfit.Factor.from_data(A, A @ np.array([[3., 1.], [1., 1.]]))
        >>> f.rows, f.n, f.d
        (4, 2, 2)
        """
        A, B, _ = _data("Factor.from_data", A, B, a_cols, b_cols)
        return cls._wrap(_spdfit.TriangularFactor.from_data(A, B))

    @classmethod
    def from_files(cls, A_path, B_path, *, block_rows=_STREAM_DEFAULTS.block_rows, threads=_STREAM_DEFAULTS.threads):
        """The factor of A and B in two data files, read a block of rows at a time.

        As fit_files reads them (the formats of read_matrix; `.mat` and `.npz` as FILE:NAME), in
        O(threads * block_rows * (n + d) + (n + d)^2) memory for files of any length. Cost
        O(m (n + d)^2) on up to `threads` threads.

        Parameters
        ----------
        A_path, B_path : str or os.PathLike
            The data files of A and B (the same number of rows, at least as many as A's columns).
        block_rows : int, default 32768
            Rows per block (the library's default, StreamOptions).
        threads : int, default 0
            Threads (0: one per core); the factor does not depend on it.

        Returns
        -------
        Factor
            The factor of all the files' rows.

        Raises
        ------
        DataError
            A bad file (a ValueError); the message names the file, line and column.
        ValueError
            block_rows < 1.
        TypeError
            A path that is neither a str nor an os.PathLike, or an option that is not an int.

        Warns
        -----
        SpdfitWarning
            A first column of row labels was found and dropped, as read_matrix warns.

        Examples
        --------
        >>> import pathlib, tempfile
        >>> import numpy as np, spdfit
        >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     spdfit.write_csv(pathlib.Path(folder) / "A.csv", A)
        ...     spdfit.write_csv(pathlib.Path(folder) / "B.csv", 2 * A)
        ...     f = spdfit.Factor.from_files(pathlib.Path(folder) / "A.csv", pathlib.Path(folder) / "B.csv",
        ...                                  block_rows=3)
        >>> f
        Factor(n=2, d=2, rows=4)
        >>> bool(np.allclose(f.fit("ls").X, 2 * np.eye(2)))
        True
        """
        block_rows, threads = _options(block_rows=block_rows, threads=threads)
        core, messages = _spdfit.stream_factor(_os.fspath(A_path), _os.fspath(B_path), block_rows, threads)
        for w in messages:
            _warn(w.text, w.code)
        return cls._wrap(core)

    @classmethod
    def from_bytes(cls, data):
        """The factor that to_bytes wrote (and the library's TriangularFactor::serialize).

        The bytes are checked: a wrong magic or version, a size that does not fit n and d, an
        exponent out of range, a NaN or Inf entry are refused, so bytes from a file or the network
        cannot make a factor that is not one. Cost O((n + d)^2).

        Parameters
        ----------
        data : bytes, bytearray or memoryview
            The factor's bytes.

        Returns
        -------
        Factor
            The same factor, bit for bit.

        Raises
        ------
        ValueError
            The bytes are not a factor; the library's message says what is wrong.
        TypeError
            `data` is not bytes-like.

        Examples
        --------
        >>> import numpy as np, spdfit
        >>> f = spdfit.Factor.from_data(np.eye(3), 2 * np.eye(3))
        >>> g = spdfit.Factor.from_bytes(f.to_bytes())
        >>> g.to_bytes() == f.to_bytes(), g.rows
        (True, 3)
        """
        if not isinstance(data, (bytes, bytearray, memoryview)):
            raise TypeError(f"data must be bytes, got {type(data).__name__}")
        return cls._wrap(_spdfit.TriangularFactor.deserialize(bytes(data)))

    def to_bytes(self):
        """The factor's whole state as bytes, to store or to send to another process.

        The library's layout (TriangularFactor::serialize in spdfit/triangular_factor.hpp): the
        magic b"spdfitR\\0", a layout version, n (and d when d != n), the row count, A's and B's
        scaling exponents, and the upper triangle of R column by column as little-endian doubles;
        the same bytes on every machine. The pickle of a Factor holds these bytes.

        Returns
        -------
        bytes
            8 + 4 + 8 (+ 8 when d != n) + 8 + 2 * 5 + 8 (n + d)(n + d + 1) / 2 bytes.

        Examples
        --------
        >>> import numpy as np, spdfit
        >>> data = spdfit.Factor.from_data(np.eye(3), 2 * np.eye(3)).to_bytes()
        >>> data[:8], len(data)
        (b'spdfitR\\x00', 206)
        """
        return self._core.serialize()

    def merge(self, other):
        """The factor of the union of this factor's rows and `other`'s, as a new Factor.

        Both inputs are left unchanged. The rows must be disjoint: rows merged twice count twice.
        The merge is associative to rounding, so factors may be merged in any grouping (a pairwise
        tree, as Dask and Spark's treeAggregate do) with the same estimate. Cost O((n + d)^3).

        Parameters
        ----------
        other : Factor
            The factor of the other rows (the same n and d).

        Returns
        -------
        Factor
            The factor of both row sets.

        Raises
        ------
        ValueError
            The factors' column counts differ.
        TypeError
            `other` is not a Factor.

        Examples
        --------
        >>> import numpy as np, spdfit
        >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
        >>> B = A @ np.array([[3., 1.], [1., 1.]])
        >>> f, g = spdfit.Factor.from_data(A[:1], B[:1]), spdfit.Factor.from_data(A[1:], B[1:])
        >>> f.merge(g).rows, f.rows, g.rows
        (4, 1, 3)
        """
        if not isinstance(other, Factor):
            raise TypeError(f"other must be a spdfit.Factor, got {type(other).__name__}")
        return Factor._wrap(_spdfit.TriangularFactor.merged(self._core, other._core))

    @_shared_doc
    @_takes_options("Factor.fit")
    def fit(self, method="auto", *, bootstrap=0, **options):
        """Estimate X in A X ~= B from the factor, with `method` (one of METHODS).

        The estimate of spdfit.fit on all the factor's rows, to rounding (exactly the streaming
        fit's, `spdfit fit --stream`): the closed-form methods agree to about 1e-12 relative, the
        iterative ones (spd-tls, psd-ls, and auto when it runs one) to their convergence
        tolerance. A factor with d != n (B with d columns) fits "ls" and "tls" only. Cost O((n + d)^3)
        plus the method's iterations, whatever the number of rows.

        Parameters
        ----------
        method : str, default "auto"
            One of METHODS, as in fit.
        bootstrap : int, default 0
            Refused unless 0: the bootstrap resamples rows, which a factor no longer has. Use
            spdfit.fit or spdfit.fit_files with bootstrap=N.
        {options}

        {returns}

        Raises
        ------
        ValueError
            Fewer rows than columns, an unknown method, d != n for a method that estimates a
            symmetric X, an option the method does not take, or bootstrap=N.
        TypeError
            An option of the wrong type, named in the message.
        NumericalError
            The method has no answer for this data; the failed FitResult is its `result`.

        {warns}

        Examples
        --------
        >>> import numpy as np, spdfit
        >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
        >>> X = np.array([[3., 1.], [1., 1.]])
        >>> f = spdfit.Factor.from_data(A[:2], A[:2] @ X).merge(spdfit.Factor.from_data(A[2:], A[2:] @ X))
        >>> r = f.fit()
        >>> r.method, r.diagnostics.m
        ('spde', 4)
        >>> bool(np.allclose(r.X, X))
        True
        """
        if isinstance(bootstrap, bool) or not isinstance(bootstrap, numbers.Integral):
            raise TypeError(f"bootstrap must be an int, got {type(bootstrap).__name__}")
        if bootstrap:
            raise ValueError("Factor.fit cannot bootstrap: the bootstrap resamples the rows of [A B], which a factor "
                             "no longer holds; use spdfit.fit(A, B, bootstrap=N) or "
                             "spdfit.fit_files(A_path, B_path, bootstrap=N)")
        return _checked(_spdfit.fit_factor(self._core, method, options))

    @property
    def n(self):
        """A's columns: X has n rows."""
        return self._core.n

    @property
    def d(self):
        """B's columns: X has d columns (d = n: a square X)."""
        return self._core.d

    @property
    def rows(self):
        """The rows (samples) accumulated."""
        return self._core.rows

    def __repr__(self):
        return f"Factor(n={self.n}, d={self.d}, rows={self.rows})"

    # Pickling: the state is the library's bytes, checked again when unpickled.
    def __getstate__(self):
        return self.to_bytes()

    def __setstate__(self, state):
        self._core = Factor.from_bytes(state)._core
