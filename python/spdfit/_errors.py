"""spdfit's exceptions and warning classes, and how the package warns.

Every error and warning of the library carries a code (``spdfit.outcome_codes()``); the compiled
module raises the exception class of an error's code, and :func:`warn` uses the warning class of
a warning's code: one class per code, each a subclass of :class:`SpdfitWarning`, so that
``warnings.simplefilter("ignore", spdfit.RankDeficientWarning)`` silences one kind.
"""
import os as _os
import sys as _sys
import warnings as _warnings

from . import _spdfit

_PACKAGE_DIR = _os.path.dirname(_os.path.abspath(__file__))


class DataError(ValueError):
    """Bad input data; the message names the file (and, for text, the line and column) or the argument."""

    __module__ = "spdfit"


class NumericalError(RuntimeError):
    """Valid input without an answer (e.g. A rank-deficient for spde, V22 singular for tls).

    The failed result, with the diagnostics of the data, is in the `result` attribute (None where
    the failure was raised before a result existed)."""

    __module__ = "spdfit"

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class SpdfitWarning(UserWarning):
    """A condition the user should know about (rank deficiency, ill-conditioning, ...); each kind has
    a subclass of its own, named after its code (RankDeficientWarning, ...)."""

    __module__ = "spdfit"


def _warning_classes():
    """One subclass of SpdfitWarning per warning code of the library's table."""
    classes = {}
    for name, tier, python_class, _matlab, meaning in _spdfit.outcome_codes():
        if tier != "warning" or python_class == "SpdfitWarning":
            continue
        classes[name] = type(python_class, (SpdfitWarning,), {
            "__doc__": meaning[0].upper() + meaning[1:] + f" (code '{name}').",
            "__module__": "spdfit",
        })
    return classes


WARNING_CLASSES = _warning_classes()
"""The warning class of each warning code, by the code's name."""

globals().update({cls.__name__: cls for cls in WARNING_CLASSES.values()})


def warning_class(code):
    """The warning class of a code's name ('rank_deficient' -> RankDeficientWarning); SpdfitWarning
    for 'warning' or a name without a class of its own."""
    return WARNING_CLASSES.get(code, SpdfitWarning)


def warn(message, code="warning"):
    """Warn with the class of `code` at the first caller outside this package: the user's line, not
    a wrapper's inside spdfit (nor sys:1 when a fixed stacklevel overshoots a short stack)."""
    frame = _sys._getframe(1)
    level = 2
    while frame is not None and _os.path.dirname(_os.path.abspath(frame.f_code.co_filename)) == _PACKAGE_DIR:
        frame = frame.f_back
        level += 1
    _warnings.warn(message, warning_class(code), stacklevel=level)


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
