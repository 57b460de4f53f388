"""The flexure-jointed hexapod (Stewart platform) of the thesis (shared/seeds/000, ch. 2):
its joint-space mass-inertia matrix M_p = J^-T R M_x R^T J^-1 + M_s (eq. 2.12), its modes,
simulated measurements (appendix B) and the identification of M_p from them.

    >>> import spdfit.hexapod as hx
    >>> model = hx.model()                       # the built-in cubic-configuration hexapod
    >>> A, B, truth = hx.simulate(samples=12, noise_var=0.86, seed=1)[:3]
    >>> estimates = hx.identify(A, B, truth=truth)
"""
import json as _json
import numbers as _numbers
import os as _os
from collections import namedtuple as _namedtuple

import numpy as _np

from . import _spdfit
from ._common import _as_matrix, _data, _physical_arrays, _takes_options
from ._errors import NumericalError, warn as _warn
from ._records import PhysicalEstimate, record as _record
from ._spdfit import hexapod as _core

Geometry = _core.Geometry
MethodIdentification = _core.MethodIdentification

__all__ = ["Geometry", "MethodIdentification", "Model", "Simulation", "cubic_geometry", "geometry", "identify",
           "model", "simulate", "thesis_mass_matrix"]

Model = _namedtuple("Model", "geometry jacobian mass_matrix payload_mass_matrix modes_hz strut_lengths "
                             "mass_matrix_eigenvalues jacobian_condition strut_directions")
Model.__doc__ = ("The hexapod model (hexapod::describe): J, M_p (eq. 2.12), the payload's M_x, the modes in "
                 "Hz, the strut lengths, M_p's eigenvalues, cond(J) and the unit strut vectors (columns).")

# The generator's defaults are the library's (SimulationOptions), not retyped here; the thesis'
# experiment 2 noise (0.86) is the documented default of `spdfit hexapod simulate` examples.
_SIMULATION = _core.SimulationOptions()

_SimulationFields = _namedtuple("Simulation", "A B truth A_true B_true")


class Simulation(_SimulationFields):
    """Simulated measurements A (accelerations), B (forces), the true X of the data (M_p times
    scale_b) and the noise-free data; rest_A and rest_B are the rows recorded at rest (0 rows
    without rest_samples)."""

    rest_A = None
    rest_B = None


class _DefaultNoise(float):
    """noise_var's default (the thesis' 0.86), told apart from the same number given: the
    per-sensor deviations (noise_std_a, noise_std_b) replace the default, not a noise_var given."""

    def __repr__(self):
        return "0.86"


_DEFAULT_NOISE = _DefaultNoise(0.86)


# The compiled module's functions, wrapped in Python functions that carry NumPy-format docstrings
# (a compiled function's docstring cannot be set from Python).
def cubic_geometry():
    """The built-in cubic-configuration hexapod (mutually orthogonal struts).

    Its joint-space mass-inertia matrix reproduces the thesis' M_p (eq. 6.1).

    Returns
    -------
    Geometry
        The geometry and masses, in SI units.

    See Also
    --------
    geometry : a Geometry from a file or a dict.

    Examples
    --------
    >>> import spdfit.hexapod as hx
    >>> g = hx.cubic_geometry()
    >>> g.base_points.shape, g.payload_points.shape
    ((3, 6), (3, 6))
    """
    return _core.cubic_geometry()


def thesis_mass_matrix():
    """M_p of thesis eq. 6.1: the joint-space mass-inertia matrix of the thesis' hexapod (kg).

    The truth of the thesis' experiments. (The appendix-B M-file's copy is garbled; eq. 6.1 is
    right.)

    Returns
    -------
    numpy.ndarray
        The 6 x 6 symmetric positive definite M_p.

    Examples
    --------
    >>> import numpy as np, spdfit.hexapod as hx
    >>> M = hx.thesis_mass_matrix()
    >>> M.shape, bool(np.array_equal(M, M.T)), bool(np.all(np.linalg.eigvalsh(M) > 0))
    ((6, 6), True, True)
    """
    return _core.thesis_mass_matrix()


def geometry(source=None):
    """A hexapod's Geometry, from the built-in one, a file or a dict.

    Parameters
    ----------
    source : None, Geometry, str, os.PathLike or dict, optional
        None (the built-in cubic hexapod), a Geometry (returned as it is), a path to a geometry JSON
        file, or a dict in that file's format (base_points, payload_points, payload_origin,
        payload_mass, payload_inertia, strut_mass, strut_stiffness, ...).

    Returns
    -------
    Geometry
        The geometry and masses, in SI units.

    Raises
    ------
    DataError
        A bad geometry file or dict (a ValueError); the message names the file (``<dict>`` for a
        dict) and the key.
    ValueError
        `source` is of none of these types.

    Examples
    --------
    >>> import json
    >>> import spdfit.hexapod as hx
    >>> g = hx.geometry()                                  # the built-in cubic hexapod
    >>> same = hx.geometry(json.loads(g.to_json()))        # a dict in the file's format
    >>> same.payload_mass == g.payload_mass
    True
    """
    if source is None:
        return _core.cubic_geometry()
    if isinstance(source, Geometry):
        return source
    if isinstance(source, dict):
        return _core.parse_geometry(_json.dumps(source), "<dict>")
    if isinstance(source, (str, _os.PathLike)):
        return _core.read_geometry(_os.fspath(source))
    raise ValueError(f"geometry must be None, a Geometry, a path or a dict, got {type(source).__name__}")


# geometry() under a name that identify()'s parameter `geometry` does not hide.
_geometry = geometry


def model(geometry_source=None):
    """The Jacobian, the mass-inertia matrix and the modes of a hexapod.

    The Jacobian J, the joint-space mass-inertia matrix M_p (thesis eq. 2.12) and the modal
    frequencies sqrt(eig(M_p^-1 K)) / 2 pi in Hz (section 2.2).

    Parameters
    ----------
    geometry_source : None, Geometry, str, os.PathLike or dict, optional
        The hexapod, as `geometry` takes it (default: the built-in cubic hexapod).

    Returns
    -------
    Model
        A named tuple: geometry, jacobian (J), mass_matrix (M_p), payload_mass_matrix (M_x), modes_hz,
        strut_lengths, mass_matrix_eigenvalues, jacobian_condition (cond(J)) and strut_directions
        (unit vectors, columns).

    Raises
    ------
    DataError
        A bad geometry file or dict (a ValueError).
    ValueError
        `geometry_source` is of none of the types `geometry` takes.

    Examples
    --------
    >>> import spdfit.hexapod as hx
    >>> m = hx.model()                       # the built-in cubic-configuration hexapod
    >>> m.mass_matrix.shape, m.jacobian.shape
    ((6, 6), (6, 6))
    >>> m.modes_hz.round(1)
    array([ 6.2,  6.2,  6.2,  8.3,  8.3, 14.1])
    """
    g = geometry(geometry_source)
    d = _core.describe(g)
    return Model(g, d.jacobian, d.mass_matrix, d.payload_mass_matrix, d.modes_hz, d.strut_lengths,
                 d.mass_matrix_eigenvalues, d.jacobian_condition, d.strut_directions)


@_takes_options("hexapod.simulate", given=("samples", "noise_var"))
def simulate(samples=_SIMULATION.samples, noise_var=_DEFAULT_NOISE, *, truth="thesis", **options):
    """Measurements as the thesis' appendix-B generator makes them.

    True accelerations uniform with variance signal_var (on [-5, 5] by default), true forces
    B_true = A_true M_p, and independent noise of variance noise_var (force_noise_var for B, if
    given) in every entry of A and B, or of standard deviations noise_std_a and noise_std_b per
    column; optionally rows at rest (rest_samples), an untared static load (preload), forces in
    other units (scale_b) and a payload that differs from the geometry's. The options are
    `spdfit hexapod simulate`'s, and the same seed and options give the same data.

    Parameters
    ----------
    samples : int, optional
        The number of samples m (rows); the library's default.
    noise_var : float, default 0.86
        The noise variance V in every entry (the thesis' experiment 2); not with noise_std_a.
    truth : "thesis", array_like, Geometry, str, os.PathLike or dict, default "thesis"
        "thesis" (eq. 6.1), an n x n array, or a geometry (see `geometry`) whose M_p is the truth
        (as the keyword geometry, which the payload options change).
    {options}

    Returns
    -------
    Simulation
        A named tuple (A, B, truth, A_true, B_true): the measured accelerations and forces (m x n),
        the true X (M_p times scale_b) and the noise-free data; its rest_A and rest_B attributes
        hold the rows at rest.

    Raises
    ------
    TypeError
        samples or seed not an int (12.9), as `spdfit hexapod simulate --samples 12.9` refuses it.
    ValueError
        Bad options (a negative variance, samples < 1, an unknown distribution, a truth that is not
        square, payload options without a geometry, noise_std_a without noise_std_b).
    DataError
        A bad geometry file or dict given as the truth (a ValueError).

    Warns
    -----
    SpdfitWarning
        Fewer samples than the truth has columns (the estimators need m >= n), as `spdfit hexapod
        simulate` warns.

    Examples
    --------
    >>> import numpy as np, spdfit.hexapod as hx
    >>> data = hx.simulate(samples=12, noise_var=0.86, seed=1)
    >>> data.A.shape, data.B.shape
    ((12, 6), (12, 6))
    >>> bool(np.allclose(data.B_true, data.A_true @ data.truth))
    True
    >>> logged = hx.simulate(samples=200, noise_std_a=0.01, noise_std_b=0.1, rest_samples=50, preload=21.0)
    >>> logged.rest_B.shape, bool(abs(logged.rest_B.mean() - 21.0) < 0.1)
    ((50, 6), True)
    """
    # Whole numbers only, as the command line's --samples: int(12.9) would quietly be 12 (the table
    # checks seed and the other options).
    if isinstance(samples, bool) or not isinstance(samples, _numbers.Integral):
        raise TypeError(f"samples must be an int, got {type(samples).__name__}")
    keywords = dict(options, samples=samples)
    if noise_var is not _DEFAULT_NOISE or options.get("noise_std_a") is None:
        keywords["noise_var"] = float(noise_var)
    M = None
    if isinstance(truth, (dict, Geometry)) or (isinstance(truth, (str, _os.PathLike)) and truth != "thesis"):
        if options.get("geometry") is not None:
            raise ValueError("truth and geometry both name the hexapod: give one")
        keywords["geometry"] = geometry(truth)
    elif not (isinstance(truth, str) and truth == "thesis"):
        M = _as_matrix("truth", truth)
    A, B, X, A_true, B_true, rest_A, rest_B, warnings = _core.simulate(M, keywords)
    for w in warnings:  # as `spdfit hexapod simulate` warns (too few samples to fit)
        _warn(_spdfit.spell_options(w.text), w.code)
    out = Simulation(A, B, X, A_true, B_true)
    out.rest_A, out.rest_B = rest_A, rest_B
    return out


@_takes_options("hexapod.identify", given=("truth", "stiffness", "geometry", "physical"))
def identify(A, B=None, *, a_cols=None, b_cols=None, truth=None, stiffness=None, geometry=None, physical=False,
             **options):
    """Every estimator on accelerations A and forces B, with eigenvalues, modes and errors.

    The options are spdfit.fit's (each method takes those that apply to it) and, with
    physical=True, the physical fit's. bootstrap=N > 0 adds each method's bootstrap to its result
    (result.standard_errors, result.bootstrap.eigenvalues) and, with a stiffness, the modes'
    intervals (modes_uncertainty): N resamples of the rows, each refitted by every estimator (and
    the physical fit).

    physical=True also fits the payload's mass, centre of mass and inertia (and with
    fit_strut_mass the struts' moving masses) with the geometry's Jacobian known, physically
    consistent (spdfit.physical.identify): under the key "physical", the dict of
    ``spdfit hexapod identify --physical --json``'s ``physical`` object, with error_vs_truth when a
    truth is given. max_iter and rank_tolerance, when given, apply to the physical fit too.

    Parameters
    ----------
    A, B : array_like
        The measured accelerations and forces, m x n each. With a_cols and b_cols, A is a pandas
        DataFrame holding both (one log), and B is left out.
    a_cols, b_cols : label, list, slice, str or None, default None
        The accelerations' and forces' columns of the DataFrame A, as spdfit.fit takes them.
    truth : array_like, optional
        A known M_p: each method's error_vs_truth is ||M_p - M_hat||_F.
    stiffness : float or array_like, optional
        The strut stiffness (N/m): one number for every strut, one per strut, or the n x n matrix K;
        each method's modes_hz are its modes sqrt(eig(M_hat^-1 K)) / 2 pi.
    geometry : None, Geometry, str, os.PathLike or dict, optional
        The hexapod (as `geometry` takes it): the modes' stiffness, and the Jacobian and nominal
        payload of the physical fit (which needs it: `cubic_geometry()` for the built-in one). Not
        with `stiffness`.
    physical : bool, optional
        Also fit the payload's physical parameters (default False).
    {options}

    Returns
    -------
    dict
        {method: MethodIdentification} with the FitResult, the eigenvalues, the modes and the error
        against the truth; with physical=True also "physical": a spdfit.physical.PhysicalEstimate (vectors and
        matrices as NumPy arrays).

    Raises
    ------
    ValueError
        Bad input: shapes (a truth or stiffness that is not n x n), NaN/Inf, m < n, bad options; a
        strut mass the geometry confounds (the message names the combination).
    TypeError
        An option of the wrong type, or a physical fit's option without physical=True.
    NumericalError
        The physical fit failed on valid data.

    Examples
    --------
    >>> import spdfit.hexapod as hx
    >>> data = hx.simulate(samples=200, noise_var=0.86, seed=1)
    >>> estimates = hx.identify(data.A, data.B, truth=data.truth)
    >>> list(estimates)
    ['ls', 'procrustes', 'tls', 'tls-sym', 'tls-psd', 'spde', 'spd-tls', 'psd-ls']
    >>> e = estimates["spd-tls"]
    >>> e.result.diagnostics.positive_definite, e.error_vs_truth < estimates["procrustes"].error_vs_truth
    (True, True)

    With the geometry known, the payload's physical parameters:

    >>> g = hx.cubic_geometry()
    >>> sim = hx.simulate(samples=200, noise_var=0.86, truth=g, seed=1)
    >>> out = hx.identify(sim.A, sim.B, truth=sim.truth, geometry=g, physical=True)
    >>> p = out["physical"]
    >>> p["physically_consistent"], abs(p["mass"] - g.payload_mass) < 1.0
    (True, True)
    >>> bool(p["error_vs_truth"] < out["spd-tls"].error_vs_truth)
    True
    """
    keywords = dict(options, truth=truth, stiffness=stiffness, physical=bool(physical),
                    geometry=None if geometry is None else _geometry(geometry))
    A, B, _ = _data("hexapod.identify", A, B, a_cols, b_cols)
    results, physical_text, warnings = _core.identify(A, B, keywords)
    for w in warnings:  # as `spdfit hexapod identify` warns: each method's, then the physical fit's
        _warn(_spdfit.spell_options(w.text), w.code)
    out = {r.result.method: r for r in results}
    if physical_text is not None:
        estimate = _physical_arrays(_json.loads(physical_text))
        if estimate["status"] != "success":
            raise NumericalError("the physical fit failed: " + estimate.get("error", ""), estimate)
        out["physical"] = _record(PhysicalEstimate, estimate)
    return out
