"""spdfit: estimate symmetric positive definite matrices from imperfect measurements.

Given measurements A X ~= B with noise in both A and B (A, B m x n, one sample per row),
estimate X (n x n):

    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.fit(A, A @ X, method="spde")
    >>> bool(np.allclose(r.X, X))
    True

Methods (the names of the command line): "ls" (least squares), "procrustes" (symmetric least
squares), "tls", "tls-sym", "tls-psd" (total least squares and its repairs), "spde" (the
area-criterion estimate, always symmetric positive definite), "spd-tls" (total least squares over
the positive definite matrices), "psd-ls" (least squares over X >= min_eig I, with an optimality
certificate) and "auto" (spde, spd-tls or psd-ls, chosen from the data; fit's default). "ls" and
"tls" also take B with d != n columns and return an n x d X. Every method works from the
Householder QR of [A B], not from Gram matrices; spdfit.Factor holds that factor as a value that
merges, for fits spread over processes or machines. Numerical failures raise NumericalError; bad
input raises ValueError (DataError for files); warnings are SpdfitWarning.
"""
import numbers as _numbers
import os as _os
import sys as _sys
import warnings as _warnings

import numpy as _np

from . import _spdfit
from ._errors import DataError, NumericalError, SpdfitWarning, WARNING_CLASSES as _WARNING_CLASSES
from ._errors import warn as _warn
from ._spdfit import (AutoReason, Diagnostics, FitResult, LinearSystemResult, NearestResult,
                      NoiseModel, PsdCertificate, BoundaryCertificate, Bootstrap, Interval, SpectrumUncertainty)

# The repairs' one result class, under the names each function's documentation uses.
NearestSpdResult = NearestCorrelationResult = NearestResult

__version__ = _spdfit.__version__

# Every method name fit accepts, from the library: the estimators, then "auto".
METHODS = _spdfit.METHODS

__all__ = [
    "METHODS", "DataError", "Diagnostics", "Factor", "FitResult", "NearestSpdResult", "NoiseModel", "NumericalError",
    "LinearSystemResult", "SpdfitWarning", "area_criterion", "solve", "fit", "fit_all", "fit_files",
    "least_squares", "nearest_spd", "nearest_correlation", "nearest_covariance", "read_matrix",
    "read_table", "spde", "symmetric_procrustes", "total_least_squares", "total_least_squares_psd",
    "spd_total_least_squares", "psd_least_squares", "auto_fit", "PsdCertificate", "BoundaryCertificate", "AutoReason", "Bootstrap", "Interval", "SpectrumUncertainty",
    "NearestCorrelationResult", "NearestResult", "REPAIR_FLOOR_DEFAULT",
    "total_least_squares_symmetric", "write_csv", "outcome_codes",
    *sorted(cls.__name__ for cls in _WARNING_CLASSES.values()),
]

globals().update({cls.__name__: cls for cls in _WARNING_CLASSES.values()})


def outcome_codes():
    """Every code of spdfit's errors and warnings (docs/errors.md prints the same table).

    An exception raised by the library carries its code's name in ``e.code``; a result's
    ``warning_codes`` lists its warnings' codes, and each warning is issued with its code's class.

    Returns
    -------
    list of tuple
        (name, tier, Python class, MATLAB identifier, meaning); tier is "usage", "data",
        "numerical", "internal" or "warning".

    Examples
    --------
    >>> import spdfit
    >>> [row for row in spdfit.outcome_codes() if row[0] == "rank_deficient"][0][:4]
    ('rank_deficient', 'warning', 'RankDeficientWarning', 'spdfit:rankDeficient')
    >>> try:
    ...     spdfit.fit([[1.0], [2.0]], [[1.0]], "ls")
    ... except spdfit.DataError as e:
    ...     print(e.code)
    data_shape
    """
    return [tuple(row) for row in _spdfit.outcome_codes()]


from . import _blas_core  # noqa: E402,F401  (warns once if OpenBLAS runs generic kernels here)

def _as_matrix(name, value):
    """A float64 2-D array from any real numeric array-like; a 1-D array is one column."""
    array = _np.asarray(value)
    # Booleans read as 0 and 1, as the command line reads a boolean .npy file.
    if array.dtype.kind not in "fiub":
        raise ValueError(f"{name} must be a real numeric array, got dtype {array.dtype}")
    if array.ndim == 1:
        array = array[:, None]
    if array.ndim != 2:
        raise ValueError(f"{name} must be a matrix (2-D array), got {array.ndim} dimensions")
    return _np.asarray(array, dtype=_np.float64)


def _options(**values):
    """Integer arguments that are not the library's options (Factor's n, d, block_rows, threads)
    checked for type: a short TypeError naming the argument (instead of pybind11's listing of
    every signature); None means the default. Returns them in the order given. The options of the
    fits and repairs are checked by the library, by name (_takes_options)."""
    for name, value in values.items():
        if name in _BOOL_OPTIONS:  # no None: a bool option has a bool default
            if not isinstance(value, bool):
                raise TypeError(f"{name} must be a bool, got {type(value).__name__}")
        elif value is None:
            continue
        elif name in _INT_OPTIONS:
            if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
                raise TypeError(f"{name} must be an int, got {type(value).__name__}")
            if value < 0 and name not in _RANGE_IN_LIBRARY:
                raise ValueError(f"{name} must be >= 0, got {value}")
        elif isinstance(value, bool) or not isinstance(value, _numbers.Real):
            raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    return tuple(v if v is None or k in _BOOL_OPTIONS else (int(v) if k in _INT_OPTIONS else float(v))
                 for k, v in values.items())


_INT_OPTIONS = ("block_rows", "threads", "n", "d")
_BOOL_OPTIONS = ()
# The int options whose range the library checks, with its own message ("block_rows must be an
# integer in [1, 16777216]", "A and B must each have at least one column").
_RANGE_IN_LIBRARY = ("block_rows", "n", "d")



# Sections that many docstrings share, written once: a docstring names one as {name} on a line of
# its own (indented as a section), and _shared_doc puts the text in.
_DOC_PARTS = {
    "returns": """Returns
    -------
    FitResult
        The estimate X with its diagnostics and warnings.""",
    "bad_input": """ValueError
        Bad input: shapes, NaN/Inf, m < n.
    TypeError
        An option of the wrong type.""",
    "warns": """Warns
    -----
    SpdfitWarning
        A condition worth knowing (rank deficiency, ill-conditioning, ...), one per entry of
        result.warnings.""",
    "rank_tolerance": """rank_tolerance : float, optional
        Relative singular-value cut-off for numerical rank (default max(m, n) eps, lecture notes 002
        section 3.8).""",
    "noise_ratio": """noise_ratio : float, optional
        sigma_B / sigma_A, the noise in B relative to the noise in A (default 1).""",
}


def _shared_doc(function):
    """Fills the {name} placeholders of function's docstring with _DOC_PARTS (plain replacement:
    docstrings also hold braces of their own, as sigma_{n+1}). The parts are written for a
    function's docstring, indented by 4; a method's placeholder is indented further, and the
    part's lines with it."""
    for name, text in _DOC_PARTS.items():
        placeholder = "{" + name + "}"
        for line in function.__doc__.splitlines():
            if line.strip() == placeholder:
                deeper = line[:len(line) - len(line.lstrip())][4:]
                function.__doc__ = function.__doc__.replace(placeholder, text.replace("\n", "\n" + deeper))
                break
    return function


# The options each function takes, from the library's option tables: {function: [(keyword, type,
# help, default text, default value)]}. The functions take them as **options, which the library
# binds by name (checking types, ranges and which method takes which); _takes_options gives each
# function the signature and docstring entries that list them.
_KEYWORDS = _spdfit.KEYWORDS


# Options Python takes in more forms than the table's text (fit_files' column selections take
# lists and slices too, _column_spec): their documented type and what the text adds.
_PYTHON_FORMS = {
    "a_cols": ("str, list or slice", "; or a list of header labels and 0-based positions, or a slice of labels "
                                     "(inclusive) or of 0-based positions, as fit takes them from a DataFrame"),
    "b_cols": ("str, list or slice", ""),
}


def _option_doc(keyword, kind, text, default_text, default):
    """The numpydoc entry of one option (indented by 4, as a function's Parameters section)."""
    import textwrap
    if keyword in _PYTHON_FORMS:
        kind, more = _PYTHON_FORMS[keyword]
        text = text.rstrip(".") + more
    head = f"{keyword} : {kind}, " + ("optional" if default is None else f"default {default!r}")
    if default is None and default_text:
        text += f" (default {default_text})"
    body = textwrap.fill(text.rstrip(".") + ".", width=96, initial_indent=" " * 8, subsequent_indent=" " * 8)
    return "    " + head + "\n" + body


def _takes_options(*entries, given=()):
    """Gives a function of signature (..., **options) the keyword-only parameters of the library's
    table entries `entries` ("fit", "fit_files", "fit:spde", ...; several in order) but those in
    `given` (parameters it spells out itself), after its own, with the defaults the library says
    to show, and fills the "{options}" line of its docstring (the last of its Parameters) with
    their documentation."""
    keywords = [k for entry in entries for k in _KEYWORDS[entry] if k[0] not in given]

    def decorate(function):
        import inspect
        signature = inspect.signature(function)
        parameters = [p for p in signature.parameters.values() if p.kind != p.VAR_KEYWORD]
        before = [p for p in parameters if p.kind != p.KEYWORD_ONLY]
        after = [p for p in parameters if p.kind == p.KEYWORD_ONLY]
        generated = [inspect.Parameter(k[0], inspect.Parameter.KEYWORD_ONLY, default=k[4]) for k in keywords]
        function.__signature__ = signature.replace(parameters=before + after + generated)
        for line in function.__doc__.splitlines():
            if line.strip() == "{options}":
                deeper = line[:len(line) - len(line.lstrip())][4:]
                text = "\n".join(_option_doc(*k) for k in keywords).replace("\n", "\n" + deeper)
                function.__doc__ = function.__doc__.replace(line, deeper + text)
                break
        return function

    return decorate


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


_PACKAGE_DIR = _os.path.dirname(_os.path.abspath(__file__))


def _checked(result, files=()):
    """Warns of the result's warnings (the method's with its name first; a reader's, which name
    one of `files`, as they are) and raises NumericalError when it failed."""
    for message, code in zip(result.warnings, result.warning_codes):
        from_reader = any(message.startswith(name + ":") for name in files)
        _warn(_spdfit.spell_options(message) if from_reader else f"{result.method}: {_spdfit.spell_options(message)}",
              code)
    if not result.ok:
        raise NumericalError(_spdfit.spell_options(result.message), result)
    return result


def _column_spec(name, columns):
    """fit_files' a_cols or b_cols as the library's text: a str as it is ("acc1:acc6", "2:7", 1-based
    as on the command line), a list of header labels and 0-based int positions (as pandas' iloc), a
    slice of either."""
    import numbers
    if columns is None or isinstance(columns, str):
        return columns
    if isinstance(columns, slice):
        return _slice_spec(name, columns)
    if isinstance(columns, (numbers.Integral, bytes)) or not hasattr(columns, "__iter__"):
        raise TypeError(f"{name} must be a str (as --{name.replace('_', '-')} takes it) or a list of labels "
                        f"and 0-based positions, not {type(columns).__name__}")
    items = []
    for c in columns:
        if isinstance(c, numbers.Integral) and not isinstance(c, bool):
            if c < 0:
                raise ValueError(f"{name}: column positions count from 0 here, as in pandas' iloc; got {c}")
            items.append(str(int(c) + 1))
        elif isinstance(c, str):
            if not c or c.isdigit() or any(ch in c for ch in ",:"):
                raise ValueError(f"{name}: the label {c!r} cannot be selected by name (empty, digits, or with ',' "
                                 f"or ':'): give its 0-based position")
            items.append(c)
        else:
            raise TypeError(f"{name}: a column is a label (str) or a 0-based position (int), not {c!r}")
    if not items:
        raise ValueError(f"{name}: no columns given")
    return ",".join(items)


def _slice_spec(name, columns):
    """A slice of a file's columns as the library's text: labels inclusive ("acc1":"acc6", as
    df.loc), or 0-based positions with the end excluded (1:7 -> "2:7", as df.iloc)."""
    import numbers
    start, stop, step = columns.start, columns.stop, columns.step
    if step not in (None, 1):
        raise ValueError(f"{name}: a slice with a step cannot choose a file's columns; give a list")
    if all(x is None or (isinstance(x, numbers.Integral) and not isinstance(x, bool)) for x in (start, stop)):
        start = 0 if start is None else start
        if stop is None or start < 0 or stop < 0:
            raise ValueError(f"{name}: a slice of a file's columns needs a non-negative start and an end "
                             f"(the file's columns are not counted before it is read); got {columns}")
        if stop <= start:
            raise ValueError(f"{name}: the slice {columns} chooses no columns")
        return f"{start + 1}:{stop}"
    if isinstance(start, str) and isinstance(stop, str):
        return f"{_column_spec(name, [start])}:{_column_spec(name, [stop])}"
    raise TypeError(f"{name}: a slice of labels (str) or of 0-based positions (int), not {columns}")


def _frame_columns(frame, name, columns):
    """0-based positions of `columns` in a pandas DataFrame, as df.loc (labels, a label slice,
    inclusive) or df.iloc (ints, an int slice) would take them; a str that is not one of its labels
    is a selection as the command line and fit_files write it ("acc1:acc6", "2:7" 1-based,
    "1,3:5,F1"), read by the library's rules for a file with that header."""
    import numbers
    import numpy as np
    labels = frame.columns
    if isinstance(columns, slice):
        if all(x is None or (isinstance(x, numbers.Integral) and not isinstance(x, bool))
               for x in (columns.start, columns.stop)):
            return list(range(len(labels)))[columns]
        start, stop = labels.slice_locs(columns.start, columns.stop)
        return list(range(start, stop))[::columns.step or 1]
    if isinstance(columns, str) and not (labels.is_unique and columns in labels):
        (chosen,) = _spdfit.select_columns([(columns, name)], [str(c) for c in labels], "the DataFrame")
        return [p - 1 for p in chosen]
    if isinstance(columns, str) or not hasattr(columns, "__iter__"):
        columns = [columns]
    columns = list(columns)
    if all(isinstance(c, numbers.Integral) and not isinstance(c, bool) for c in columns) and not all(
            c in labels for c in columns):
        n = len(labels)
        bad = [c for c in columns if not -n <= c < n]
        if bad:
            raise ValueError(f"{name}: position {bad[0]} is beyond the DataFrame's {n} columns")
        return [int(c) % n for c in columns]
    positions = labels.get_indexer(columns) if labels.is_unique else np.full(len(columns), -2)
    for c, p in zip(columns, positions):
        if p == -1:
            raise ValueError(f"{name}: no column {c!r} in the DataFrame; its columns: {list(labels)}")
        if p == -2:
            raise ValueError(f"{name}: the DataFrame's column labels are not unique: give 0-based positions")
    return [int(p) for p in positions]


def _labels_of(value):
    """A DataFrame's column labels (a Series' name) as str, or [] for an array."""
    if hasattr(value, "columns"):
        return [str(c) for c in value.columns]
    name = getattr(value, "name", None) if hasattr(value, "iloc") else None
    return [] if name is None else [str(name)]


def _split_frame(A, B, a_cols, b_cols):
    """A, B and their labels (X's row and column names, the columns each came from) from the
    columns of one pandas DataFrame, for fit(df, a_cols=..., b_cols=...) and the other functions
    that take them."""
    if (a_cols is None) != (b_cols is None):
        raise ValueError("a_cols and b_cols come together: the columns of A and of B in the one table")
    if isinstance(B, str):
        raise ValueError(f"a_cols and b_cols choose A and B from one table, but B was given too: {B!r}; "
                         f"give the method by name, method={B!r}")
    if B is not None:
        raise ValueError("a_cols and b_cols choose A and B from one table, but B was given too")
    if hasattr(A, "iloc") and hasattr(A, "columns"):
        a = _frame_columns(A, "a_cols", a_cols)
        b = _frame_columns(A, "b_cols", b_cols)
        labels = _labels_of(A)
        both = sorted(set(a) & set(b))
        if both:
            raise ValueError(f"a_cols and b_cols both select column {labels[both[0]]!r} (position {both[0]}): a "
                             f"column can be in one of them only")
        a_names, b_names = [labels[i] for i in a], [labels[i] for i in b]
        described = ["DataFrame " + _spdfit.describe_columns([i + 1 for i in chosen], names)
                     for chosen, names in ((a, a_names), (b, b_names))]
        return (_as_matrix("A", A.iloc[:, a]), _as_matrix("B", A.iloc[:, b]),
                (a_names, b_names, described[0], described[1]))
    raise TypeError("a_cols and b_cols choose columns of a pandas DataFrame; slice an array instead, "
                    f"fit(T[:, a], T[:, b]) (got {type(A).__name__})")


def _data(function, A, B, a_cols, b_cols):
    """A, B and the labels a result carries, from (A, B) or from one DataFrame A with a_cols and
    b_cols; None for labels when neither is labelled."""
    if a_cols is not None or b_cols is not None:
        return _split_frame(A, B, a_cols, b_cols)
    if B is None:
        raise TypeError(f"{function}() needs B, or a_cols and b_cols choosing A's and B's columns of a DataFrame A")
    labels = (_labels_of(A), _labels_of(B), "", "")
    return _as_matrix("A", A), _as_matrix("B", B), labels if labels[0] or labels[1] else None


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
    interval (level, lower, upper: the central `confidence` fraction of the replicates), bias (their
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


# The streaming defaults are the library's (StreamOptions), not retyped here.
_STREAM_DEFAULTS = _spdfit.StreamOptions()


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


# The relative eigenvalue floor the repairs use when none is given (the library's, as the
# `nearest` command's): 1e-8 times the largest eigenvalue, as R's nearPD's posd.tol.
REPAIR_FLOOR_DEFAULT = _spdfit.REPAIR_FLOOR_DEFAULT


def _repair(entry, C, options, full_output):
    """The one path of nearest_spd, nearest_correlation and nearest_covariance (repair.py): the
    library's repair with the options bound by name, its warnings as SpdfitWarning, pandas in and out."""
    from . import repair
    result, frame = repair._repair(entry, C, options)
    return repair._answer(result, frame, full_output, options)


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
    return _repair("nearest_spd", X, options, full_output)


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
    return _repair("nearest_correlation", C, options, full_output)


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


# Submodules (imported last: they use the helpers above).
from . import experiment, hexapod, linkage, payload, physical  # noqa: E402
from .repair import nearest_covariance  # noqa: E402
from .factor import Factor  # noqa: E402
