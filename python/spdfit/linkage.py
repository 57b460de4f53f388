"""Four-bar function generators: Freudenstein synthesis and analysis (lecture notes 002,
sections 3.3-3.6). Angles are in degrees unless ``radians=True``.

    >>> import spdfit.linkage as lk
    >>> r = lk.synthesize(steering=0.5)          # the steering condition, rho = 0.5
    >>> r.structural.structural_error_rms < r.design.structural_error_rms
    True
"""
import math as _math

import numpy as _np

from . import _spdfit
from ._common import _takes_options
from ._errors import NumericalError, warn as _warn
from ._spdfit import linkage as _core

FourBar = _core.FourBar
SynthesisResult = _core.SynthesisResult
LinkageSolution = _core.LinkageSolution
Analysis = _core.Analysis
AnalysisSample = _core.AnalysisSample
AngleRange = _core.AngleRange
DialZeros = _core.DialZeros
MotionCheck = _core.MotionCheck

__all__ = ["Analysis", "AnalysisSample", "AngleRange", "DialZeros", "FourBar", "LinkageSolution", "MotionCheck",
           "SynthesisResult", "analyze", "freudenstein_parameters", "function_names", "grashof_type", "link_lengths",
           "synthesize"]

# The default input range of steering= (degrees): the library's (linkage::kSteeringPsiRange).
STEERING_PSI_RANGE = _core.STEERING_PSI_RANGE


def _vector(value):
    # The library checks the values (finite pairs, finite angles) and names them.
    return _np.asarray(value, dtype=_np.float64).reshape(-1)


def _range_in_degrees(value):
    """A range given in radians as (lo, hi), in degrees as the library takes it; text as it is."""
    if value is None or isinstance(value, str):
        return value
    return tuple(_math.degrees(float(x)) for x in value)


# The compiled module's functions, wrapped in Python functions that carry NumPy-format docstrings
# (a compiled function's docstring cannot be set from Python).
def function_names():
    """The functions y = f(x) that synthesize(function=name) accepts.

    linear, square, cube, sqrt, reciprocal, exp, ln, log10, sin, cos, tan (x in radians for the last
    three).

    Returns
    -------
    list of str
        The names, sorted.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> lk.function_names()
    ['cos', 'cube', 'exp', 'linear', 'ln', 'log10', 'reciprocal', 'sin', 'sqrt', 'square', 'tan']
    """
    return _core.function_names()


def freudenstein_parameters(bar):
    """The Freudenstein parameters k = [k1, k2, k3] of a four-bar (lecture notes 002, eq. 3.4).

    k1 = (a1^2 + a2^2 + a4^2 - a3^2) / (2 a2 a4), k2 = a1 / a2, k3 = a1 / a4.

    Parameters
    ----------
    bar : FourBar
        The link lengths: a1 ground, a2 input, a3 coupler, a4 output.

    Returns
    -------
    numpy.ndarray
        k, shape (3,).

    Raises
    ------
    ValueError
        A length that is not positive and finite.
    TypeError
        `bar` is not a FourBar.

    See Also
    --------
    link_lengths : the inverse, scaled to a1 = 1.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> lk.freudenstein_parameters(lk.FourBar(4, 1, 3.5, 3))
    array([2.29166667, 4.        , 1.33333333])
    """
    return _core.freudenstein_parameters(bar)


def link_lengths(k):
    """The link lengths of Freudenstein parameters k, scaled to a1 = 1 (lecture notes 002, eq. 3.4).

    a2 = 1/k2, a4 = 1/k3, a3 = (1 + a2^2 + a4^2 - 2 a2 a4 k1)^(1/2).

    Parameters
    ----------
    k : array_like
        [k1, k2, k3].

    Returns
    -------
    FourBar
        The linkage with a1 = 1.

    Raises
    ------
    ValueError
        No real linkage has these parameters: k2 <= 0 or k3 <= 0 (a negative or infinite length) or
        a3^2 <= 0; the message says which, in words a designer can act on.
    TypeError
        `k` is not three numbers.

    See Also
    --------
    freudenstein_parameters : the inverse.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> lk.link_lengths([2.29166667, 4., 1.33333333])
    FourBar(a1=1, a2=0.25, a3=0.875, a4=0.75)
    """
    return _core.link_lengths(k)


def grashof_type(bar):
    """Grashof's classification of a four-bar by its link lengths.

    With s, l the shortest and longest links and p, q the others, the linkage is Grashof (some link
    turns fully) when s + l < p + q, and then the type depends on which link is the shortest: the
    input (crank-rocker), the output (rocker-crank), the ground (double-crank, a drag link) or the
    coupler (double-rocker, the coupler turns fully). s + l == p + q (to a relative 1e-12) is a
    change-point linkage (it can fold flat: parallelogram, kite); s + l > p + q is non-Grashof, a
    triple-rocker (no link turns fully).

    Parameters
    ----------
    bar : FourBar
        The link lengths: a1 ground, a2 input, a3 coupler, a4 output.

    Returns
    -------
    str
        "crank-rocker", "rocker-crank", "double-crank", "double-rocker", "change-point" or
        "triple-rocker".

    Raises
    ------
    ValueError
        A length that is not positive and finite.
    TypeError
        `bar` is not a FourBar.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> lk.grashof_type(lk.FourBar(4, 1, 3.5, 3))
    'crank-rocker'
    >>> lk.grashof_type(lk.FourBar(1, 1, 1, 1))
    'change-point'
    """
    return _core.grashof_type(bar)


@_takes_options("linkage.synthesize", given=("radians",))
def synthesize(psi=None, phi=None, *, radians=False, **options):
    """Synthesize a 4R function generator k1 + k2 cos(phi) - k3 cos(psi) = cos(psi - phi) (eq. 3.3).

    Give exactly one of: psi and phi, prescribed input/output angles (or pairs=, a file or an
    m x 2 array of them); steering=rho, the steering condition; function=name, y = f(x). This is
    `spdfit linkage synthesize`: the same options (its table), rules and numbers. The design-error solution (section 3.4, Householder QR or the
    edited SVD) is refined by Gauss-Newton on the structural error (section 3.6, eq. 3.18) unless
    refine=False; with exactly three pairs the synthesis is exact (3.3.3); fit_dial_zeros also
    solves for alpha, beta (eq. 3.7). Angles are in degrees unless radians=True.

    Parameters
    ----------
    psi, phi : array_like, optional
        Prescribed input/output angles: changes from the dial zeros alpha, beta when those are given,
        absolute angles otherwise.
    radians : bool, default False
        Every angle (psi, phi, the ranges, alpha, beta) in radians instead of degrees.
    {options}

    Returns
    -------
    SynthesisResult
        The design (design-error) and structural (refined) linkages; angles in it are radians.

    Raises
    ------
    NumericalError
        No real or assemblable linkage results, or Gauss-Newton diverges; the failed result is its
        `result`.
    ValueError
        Bad input: not exactly one of psi/phi, steering and function, psi without phi, function= without
        its ranges, an unknown spacing or function, a range with LO >= HI, points= with pairs.
    DataError
        Pairs or weights that cannot be used: NaN or Inf, fewer than three pairs (five with
        fit_dial_zeros), a weight that is not positive; the message names them.

    Warns
    -----
    SpdfitWarning
        A condition worth knowing, e.g. a transmission angle outside the usual 40..140 deg.

    Examples
    --------
    Three pairs from a known linkage give it back exactly, scaled to a1 = 1:

    >>> import numpy as np, spdfit.linkage as lk
    >>> samples = lk.analyze((4, 1, 3.5, 3), [0, 40, 80]).samples
    >>> phi = np.degrees([s.phi_plus for s in samples])
    >>> r = lk.synthesize([0, 40, 80], phi)
    >>> r.precision_point, r.structural.lengths
    (True, FourBar(a1=1, a2=0.25, a3=0.875, a4=0.75))

    The steering condition, rho = 0.5, with its warnings caught:

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     r = lk.synthesize(steering=0.5)
    >>> r.structural.structural_error_rms < r.design.structural_error_rms
    True
    >>> print(caught[0].message)
    the design linkage's transmission angle ranges over ... outside the usual 40..140 deg: ...
    """
    if psi is not None or phi is not None:
        if psi is None or phi is None:
            raise ValueError("psi and phi come together: give both (or pairs=)")
        if "pairs" in options and options["pairs"] is not None:
            raise ValueError("give psi and phi, or pairs=, not both")
        psi, phi = _vector(psi), _vector(phi)
        if psi.shape != phi.shape:
            raise ValueError(f"psi and phi must have the same length, got {psi.size} and {phi.size}")
        options["pairs"] = _np.column_stack([psi, phi])
    if radians:
        given_pairs = options.get("pairs") is not None
        # The library reads the pairs in radians (the command line's --radians); the other angles
        # it takes in degrees.
        for key in ("alpha", "beta"):
            if options.get(key) is not None:
                options[key] = _math.degrees(options[key])
        for key in ("psi_range", "phi_range"):
            if key in options:
                options[key] = _range_in_degrees(options[key])
        if given_pairs:
            options["radians"] = True
    result = _core.run_synthesize(options)
    for message, code in zip(result.warnings, result.warning_codes):
        _warn(_spdfit.spell_options(message), code)
    if not result.ok:
        raise NumericalError(_spdfit.spell_options(result.message), result)
    return result


@_takes_options("linkage.analyze")
def analyze(lengths, psi=None, *, radians=False, **options):
    """Position analysis of a four-bar over input angles.

    The output angle on both assembly branches, the transmission angle and the dead points.

    Parameters
    ----------
    lengths : FourBar or sequence of float
        (a1, a2, a3, a4): ground, input, coupler, output.
    psi : array_like, optional
        The input angles (default: `points` angles over psi_range).
    radians : bool, default False
        Angles (psi, psi_range) in radians instead of degrees.
    {options}

    Returns
    -------
    Analysis
        The Grashof type, whether the input turns fully, the dead points, one sample per input angle
        (psi, phi_plus, phi_minus, transmission_angle; None where the linkage cannot be assembled)
        and the transmission angle's range; angles in radians.

    Raises
    ------
    ValueError
        A length that is not positive and finite, NaN or Inf in psi, psi_range with LO >= HI, or
        psi with psi_range or points.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> a = lk.analyze((4, 1, 3.5, 3))
    >>> a.grashof, a.input_fully_rotates, len(a.samples)      # 37 angles over 0..360 deg
    ('crank-rocker', True, 37)
    """
    bar = lengths if isinstance(lengths, FourBar) else FourBar(*map(float, lengths))
    if psi is not None:
        psi = _vector(psi) if radians else _np.radians(_vector(psi))
    elif radians and options.get("psi_range") is not None:
        options["psi_range"] = _range_in_degrees(options["psi_range"])
    return _core.run_analyze([bar.a1, bar.a2, bar.a3, bar.a4], psi, options)
