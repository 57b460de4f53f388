"""Reading and writing data files as the command line does: delimited text, .npy, MATLAB .mat
(level 5 and 7.3) and .npz, with the reader's errors naming the file, line and column.

    >>> import pathlib, tempfile, numpy as np, spdfit.io
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     spdfit.io.write_csv(pathlib.Path(folder) / "X.csv", np.eye(2))
    ...     spdfit.io.read_matrix(pathlib.Path(folder) / "X.csv")
    array([[1., 0.],
           [0., 1.]])
"""
import os as _os

from . import _spdfit
from ._common import _as_matrix
from ._errors import warn as _warn

__all__ = ["read_matrix", "read_table", "write_csv"]


def read_matrix(path, *, allow_nonfinite=False, index_col=None, header=None):
    r"""Read a matrix from a data file.

    Delimited text (commas, semicolons, tabs or spaces; '#' comments; an optional header row), a
    .npy file, a MATLAB .mat file (level 5 or 7.3) or a NumPy .npz archive, read as the command
    line reads it: "log.mat:accel" names the array in a .mat or .npz file.

    Parameters
    ----------
    path : str or os.PathLike
        The file's name (a pathlib.Path works).
    allow_nonfinite : bool, default False
        Accept NaN and Inf, which are rejected otherwise; an empty field of delimited text (as
        pandas' to_csv writes NaN) then reads as NaN.
    index_col : bool or None, default None
        True when the first column holds row labels (an index, as pandas' to_csv and R's write.csv
        write one): it is dropped. False: the first column is data. None: a header whose first cell
        is empty marks an index, which is dropped with a SpdfitWarning, and a first column 0, 1, 2,
        ... under any other header raises DataError.
    header : bool or None, default None
        Whether the first line of a text file is a header row of column names. None: decided from
        the file: a line with no number in it is a header, and so is a first line of two or more
        fields that is exactly 0, 1, ..., k - 1 (what pandas' to_csv(index=False) writes for a
        frame without column names), with a SpdfitWarning; a single field is data. True: the first
        line is a header whatever it holds. False: it is data.

    Returns
    -------
    numpy.ndarray
        The values, float64, m x n.

    Raises
    ------
    DataError
        Bad input (a ValueError); the message names the file, line and column.
    TypeError
        `path` is neither a str nor an os.PathLike.

    Warns
    -----
    SpdfitWarning
        An index column was found and dropped (index_col=None), or pandas' header 0, 1, ..., k - 1
        was read as column names (header=None).

    See Also
    --------
    read_table : the values and the header's column names.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import spdfit
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "A.csv"
    ...     _ = path.write_text("# accelerations\nx,y\n1.5,2\n-3,0.25\n")
    ...     A = spdfit.read_matrix(path)
    >>> A
    array([[ 1.5 ,  2.  ],
           [-3.  ,  0.25]])
    """
    return read_table(path, allow_nonfinite=allow_nonfinite, index_col=index_col, header=header)[0]


def read_table(path, *, allow_nonfinite=False, index_col=None, header=None):
    r"""Read a data file as read_matrix does, with the header row's column names.

    Parameters
    ----------
    path : str or os.PathLike
        The file's name (a pathlib.Path works).
    allow_nonfinite : bool, default False
        Accept NaN and Inf, which are rejected otherwise; an empty field of delimited text (as
        pandas' to_csv writes NaN) then reads as NaN.
    index_col : bool or None, default None
        Whether the first column holds row labels, as in read_matrix.
    header : bool or None, default None
        Whether the first line is a header row, as in read_matrix.

    Returns
    -------
    values : numpy.ndarray
        The values, float64, m x n.
    column_names : list of str
        The names in the header row (an empty list without a header).

    Raises
    ------
    DataError
        Bad input (a ValueError); the message names the file, line and column.
    TypeError
        `path` is neither a str nor an os.PathLike.

    Warns
    -----
    SpdfitWarning
        An index column was found and dropped (index_col=None), or pandas' header 0, 1, ..., k - 1
        was read as column names (header=None).

    See Also
    --------
    read_matrix : the values only.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import spdfit
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "forces.csv"
    ...     _ = path.write_text("Fx,Fy\n1.5,2\n-3,0.25\n")
    ...     values, names = spdfit.read_table(path)
    >>> names
    ['Fx', 'Fy']
    >>> values.shape
    (2, 2)
    """
    if header is not None and not isinstance(header, bool):
        raise TypeError(f"header must be True, False or None, not {type(header).__name__}")
    values, names, messages = _spdfit.read_table(_os.fspath(path), allow_nonfinite=allow_nonfinite,
                                                 index_col=index_col, header=header)
    for w in messages:
        _warn(w.text, w.code)
    return values, names


def write_csv(path, X):
    """Write X as CSV with values that read back exactly.

    Parameters
    ----------
    path : str or os.PathLike
        The file's name (a pathlib.Path works).
    X : array_like
        The matrix (any real dtype; a 1-D array is one column).

    Returns
    -------
    None

    Raises
    ------
    DataError
        The file cannot be written; the message names it and says why.
    ValueError
        X is not a real numeric matrix.
    TypeError
        `path` is neither a str nor an os.PathLike.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np, spdfit
    >>> X = np.array([[0.1, 2.0 / 3.0], [2.0 / 3.0, 1e-300]])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     spdfit.write_csv(pathlib.Path(folder) / "X.csv", X)
    ...     back = spdfit.read_matrix(pathlib.Path(folder) / "X.csv")
    >>> bool(np.array_equal(back, X))
    True
    """
    _spdfit.write_csv(_os.fspath(path), _as_matrix("X", X))
