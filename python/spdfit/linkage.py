"""Four-bar function generators: Freudenstein synthesis and analysis (lecture notes 002,
sections 3.3-3.6). Angles are in degrees unless ``radians=True``.

    >>> import spdfit.linkage as lk
    >>> r = lk.synthesize(steering=0.5)          # the steering condition, rho = 0.5
    >>> r.structural.structural_error_rms < r.design.structural_error_rms
    True
"""
import math as _math
import warnings as _warnings

import numpy as _np

from . import NumericalError, SpdfitWarning
from ._spdfit import linkage as _core

FourBar = _core.FourBar
SynthesisResult = _core.SynthesisResult
LinkageSolution = _core.LinkageSolution
Analysis = _core.Analysis
function_names = _core.function_names
freudenstein_parameters = _core.freudenstein_parameters
link_lengths = _core.link_lengths
grashof_type = _core.grashof_type

__all__ = ["Analysis", "FourBar", "LinkageSolution", "SynthesisResult", "analyze", "freudenstein_parameters",
           "function_names", "grashof_type", "link_lengths", "synthesize"]

# Gauss-Newton's defaults are the library's (GaussNewtonOptions), not retyped here.
_GAUSS_NEWTON = _core.GaussNewtonOptions()

# The command line's default input range for --steering (degrees).
STEERING_PSI_RANGE = (-30.0, 30.0)


def _vector(name, value):
    array = _np.asarray(value, dtype=_np.float64).reshape(-1)
    if not _np.all(_np.isfinite(array)):
        raise ValueError(f"{name} contains NaN or Inf")
    return array


def synthesize(psi=None, phi=None, *, weights=None, steering=None, function=None, x_range=None,
               psi_range=None, phi_range=None, points=21, spacing="uniform", alpha=None, beta=None,
               fit_dial_zeros=False, refine=True, tolerance=_GAUSS_NEWTON.tolerance,
               max_iterations=_GAUSS_NEWTON.max_iterations, radians=False):
    """Synthesize a 4R function generator k1 + k2 cos(phi) - k3 cos(psi) = cos(psi - phi) (eq. 3.3).

    Give exactly one of:
      psi, phi             prescribed input/output angles (changes from the dial zeros alpha, beta
                           when those are given; absolute angles otherwise); optional weights;
      steering=rho         the steering condition (eq. 3.5) over psi_range (default -30..30 deg),
                           with the trapezoid dial zeros unless alpha/beta or fit_dial_zeros;
      function=name        y = f(x) (see function_names()) over x_range mapped onto psi_range
                           and phi_range, at `points` points, "uniform" or "chebyshev" spacing.
    The design-error solution (section 3.4, Householder QR or the edited SVD) is refined by
    Gauss-Newton on the structural error (section 3.6, eq. 3.18) unless refine=False; with exactly
    three pairs the synthesis is exact (3.3.3); fit_dial_zeros also solves for alpha, beta (eq.
    3.7). Returns a SynthesisResult (angles in it are radians); raises NumericalError when no real
    or assemblable linkage results or Gauss-Newton diverges, ValueError for bad input.
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
    for message in result.warnings:
        _warnings.warn(message, SpdfitWarning, stacklevel=2)
    if not result.ok:
        raise NumericalError(result.message, result)
    return result


def analyze(lengths, psi=None, *, psi_range=(-180.0, 180.0), points=361, radians=False):
    """Position analysis of a four-bar (a1, a2, a3, a4) over input angles: the output angle on both
    assembly branches, the transmission angle and the dead points. Returns an Analysis (radians)."""
    bar = lengths if isinstance(lengths, FourBar) else FourBar(*map(float, lengths))
    if psi is None:
        lo, hi = psi_range
        psi = _np.linspace(lo, hi, int(points))
    psi = _vector("psi", psi)
    return _core.analyze(bar, psi if radians else _np.radians(psi))
