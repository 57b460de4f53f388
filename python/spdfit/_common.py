"""The package's private helpers, shared by its modules: NumPy arrays from array-likes, the
library's option tables as signatures and docstrings, the fits' warnings and failures, and A and
B from a pandas DataFrame's columns. Nothing here is public; every module imports from here (and
from _errors), never from the package's __init__, which only re-exports."""
import numbers as _numbers

import numpy as _np

from . import _spdfit
from ._errors import NumericalError, warn as _warn


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


# The keys of the estimate that are vectors or matrices, returned as NumPy arrays.
_ARRAY_KEYS = ("center_of_mass", "inertia", "principal_moments", "principal_axes", "M_p", "M_p_eigenvalues",
               "modes_hz")
_SPECTRUM_KEYS = ("estimate", "standard_errors", "lower", "upper")


def _physical_arrays(result):
    """The JSON object with its vectors and matrices as float64 arrays (null as NaN)."""
    def convert(value):
        return _np.array(value, dtype=_np.float64) if isinstance(value, list) else value

    for key in _ARRAY_KEYS + ("strut_mass",):
        if key in result:
            result[key] = convert(result[key])
    for group in ("standard_errors",):
        if group in result:
            result[group] = {k: convert(v) for k, v in result[group].items()}
    if "interval" in result:
        for side in ("lower", "upper"):
            result["interval"][side] = {k: convert(v) for k, v in result["interval"][side].items()}
    if "bootstrap" in result:
        for name in ("M_p_eigenvalues", "modes_hz"):
            if name in result["bootstrap"]:
                for k in _SPECTRUM_KEYS:
                    result["bootstrap"][name][k] = convert(result["bootstrap"][name][k])
    return result
