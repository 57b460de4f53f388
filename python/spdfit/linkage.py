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

# Gauss-Newton's defaults are the library's (GaussNewtonOptions), not retyped here.
_GAUSS_NEWTON = _core.GaussNewtonOptions()

# The command line's default input range for --steering (degrees).
STEERING_PSI_RANGE = (-30.0, 30.0)


def _vector(name, value):
    array = _np.asarray(value, dtype=_np.float64).reshape(-1)
    if not _np.all(_np.isfinite(array)):
        raise ValueError(f"{name} contains NaN or Inf")
    return array


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


def synthesize(psi=None, phi=None, *, weights=None, steering=None, function=None, x_range=None,
               psi_range=None, phi_range=None, points=21, spacing="uniform", alpha=None, beta=None,
               fit_dial_zeros=False, refine=True, tolerance=_GAUSS_NEWTON.tolerance,
               max_iterations=_GAUSS_NEWTON.max_iterations, radians=False):
    """Synthesize a 4R function generator k1 + k2 cos(phi) - k3 cos(psi) = cos(psi - phi) (eq. 3.3).

    Give exactly one of: psi and phi, prescribed input/output angles; steering=rho, the steering
    condition; function=name, y = f(x). The design-error solution (section 3.4, Householder QR or the
    edited SVD) is refined by Gauss-Newton on the structural error (section 3.6, eq. 3.18) unless
    refine=False; with exactly three pairs the synthesis is exact (3.3.3); fit_dial_zeros also
    solves for alpha, beta (eq. 3.7). Angles are in degrees unless radians=True.

    Parameters
    ----------
    psi, phi : array_like, optional
        Prescribed input/output angles: changes from the dial zeros alpha, beta when those are given,
        absolute angles otherwise.
    weights : array_like, optional
        A weight per psi/phi pair.
    steering : float, optional
        rho of the steering condition (eq. 3.5) over psi_range (default -30..30 deg), with the
        trapezoid dial zeros unless alpha/beta or fit_dial_zeros.
    function : str, optional
        y = f(x) (see function_names()) over x_range mapped onto psi_range and phi_range.
    x_range, psi_range, phi_range : tuple of float, optional
        The ranges of function= (all three needed); psi_range is steering='s too.
    points : int, default 21
        The number of pairs for steering= and function=.
    spacing : str, default "uniform"
        The pairs' spacing: "uniform" or "chebyshev".
    alpha, beta : float, optional
        The dial zeros of the input and the output.
    fit_dial_zeros : bool, default False
        Also solve for alpha and beta (eq. 3.7).
    refine : bool, default True
        Refine by Gauss-Newton on the structural error.
    tolerance, max_iterations : optional
        Gauss-Newton's stopping rule (the library's defaults, GaussNewtonOptions).
    radians : bool, default False
        Angles in radians instead of degrees.

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
        its ranges, an unknown spacing or function, NaN or Inf, fewer than three pairs.

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
    to_rad = (lambda x: x) if radians else _math.radians
    sources = (psi is not None) + (steering is not None) + (function is not None)
    if sources != 1:
        raise ValueError("give exactly one of psi/phi pairs, steering=rho or function=name")
    if spacing not in ("uniform", "chebyshev"):
        raise ValueError(f"spacing must be 'uniform' or 'chebyshev', got {spacing!r}")
    a = None if alpha is None else to_rad(alpha)
    b = None if beta is None else to_rad(beta)
    if psi is not None:
        if phi is None:
            raise ValueError("psi needs phi")
        dpsi = _vector("psi", psi) if radians else _np.radians(_vector("psi", psi))
        dphi = _vector("phi", phi) if radians else _np.radians(_vector("phi", phi))
    elif steering is not None:
        lo, hi = psi_range if psi_range is not None else STEERING_PSI_RANGE
        dpsi, dphi = _core.steering_pairs(float(steering), to_rad(lo), to_rad(hi), int(points), spacing)
        if not fit_dial_zeros and a is None and b is None:
            zeros = _core.trapezoid_dial_zeros(float(steering))
            a, b = zeros.alpha, zeros.beta
    else:
        if x_range is None or psi_range is None or phi_range is None:
            raise ValueError("function= needs x_range, psi_range and phi_range")
        dpsi, dphi = _core.function_pairs(function, x_range[0], x_range[1], to_rad(psi_range[0]),
                                          to_rad(psi_range[1]), to_rad(phi_range[0]), to_rad(phi_range[1]),
                                          int(points), spacing)
    w = _np.empty(0) if weights is None else _vector("weights", weights)
    result = _core.synthesize(dpsi, dphi, w, a, b, bool(fit_dial_zeros), bool(refine), float(tolerance),
                              int(max_iterations))
    for message, code in zip(result.warnings, result.warning_codes):
        _warn(_spdfit.spell_options(message), code)
    if not result.ok:
        raise NumericalError(_spdfit.spell_options(result.message), result)
    return result


def analyze(lengths, psi=None, *, psi_range=(-180.0, 180.0), points=361, radians=False):
    """Position analysis of a four-bar over input angles.

    The output angle on both assembly branches, the transmission angle and the dead points.

    Parameters
    ----------
    lengths : FourBar or sequence of float
        (a1, a2, a3, a4): ground, input, coupler, output.
    psi : array_like, optional
        The input angles (default: `points` angles over psi_range).
    psi_range : tuple of float, default (-180.0, 180.0)
        The input angles' range when psi is not given.
    points : int, default 361
        Their number.
    radians : bool, default False
        Angles in radians instead of degrees.

    Returns
    -------
    Analysis
        The Grashof type, whether the input turns fully, the dead points, one sample per input angle
        (psi, phi_plus, phi_minus, transmission_angle; None where the linkage cannot be assembled)
        and the transmission angle's range; angles in radians.

    Raises
    ------
    ValueError
        A length that is not positive and finite, or NaN or Inf in psi.

    Examples
    --------
    >>> import spdfit.linkage as lk
    >>> a = lk.analyze((4, 1, 3.5, 3))
    >>> a.grashof, a.input_fully_rotates, len(a.samples)
    ('crank-rocker', True, 361)
    """
    bar = lengths if isinstance(lengths, FourBar) else FourBar(*map(float, lengths))
    if psi is None:
        lo, hi = psi_range
        psi = _np.linspace(lo, hi, int(points))
    psi = _vector("psi", psi)
    return _core.analyze(bar, psi if radians else _np.radians(psi))
