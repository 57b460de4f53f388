"""The flexure-jointed hexapod (Stewart platform) of the thesis (shared/seeds/000, ch. 2):
its joint-space mass-inertia matrix M_p = J^-T R M_x R^T J^-1 + M_s (eq. 2.12), its modes,
simulated measurements (appendix B) and the identification of M_p from them.

    >>> import spdfit.hexapod as hx
    >>> model = hx.model()                       # the built-in cubic-configuration hexapod
    >>> A, B, truth = hx.simulate(samples=12, noise_var=0.86, seed=1)
    >>> estimates = hx.identify(A, B, truth=truth)
"""
import json as _json
import os as _os
from collections import namedtuple as _namedtuple

import numpy as _np

from . import _as_matrix, _options
from ._spdfit import hexapod as _core

Geometry = _core.Geometry
cubic_geometry = _core.cubic_geometry
thesis_mass_matrix = _core.thesis_mass_matrix

__all__ = ["Geometry", "Model", "Simulation", "cubic_geometry", "geometry", "identify", "model", "simulate",
           "thesis_mass_matrix"]

Model = _namedtuple("Model", "geometry jacobian mass_matrix payload_mass_matrix modes_hz strut_lengths "
                             "mass_matrix_eigenvalues jacobian_condition strut_directions")
Model.__doc__ = ("The hexapod model (hexapod::describe): J, M_p (eq. 2.12), the payload's M_x, the modes in "
                 "Hz, the strut lengths, M_p's eigenvalues, cond(J) and the unit strut vectors (columns).")

# The generator's defaults are the library's (SimulationOptions), not retyped here; the thesis'
# experiment 2 noise (0.86) is the documented default of `spdfit hexapod simulate` examples.
_SIMULATION = _core.SimulationOptions()

Simulation = _namedtuple("Simulation", "A B truth A_true B_true")
Simulation.__doc__ = "Simulated measurements A (accelerations), B (forces) and the true M_p."


def geometry(source=None):
    """A Geometry from None (the built-in cubic hexapod), a Geometry, a path to a geometry JSON
    file, or a dict in that file's format (base_points, payload_points, payload_origin,
    payload_mass, payload_inertia, strut_mass, strut_stiffness, ...)."""
    if source is None:
        return _core.cubic_geometry()
    if isinstance(source, Geometry):
        return source
    if isinstance(source, dict):
        return _core.parse_geometry(_json.dumps(source), "<dict>")
    if isinstance(source, (str, _os.PathLike)):
        return _core.read_geometry(_os.fspath(source))
    raise ValueError(f"geometry must be None, a Geometry, a path or a dict, got {type(source).__name__}")


def model(geometry_source=None):
    """The Jacobian J, the joint-space mass-inertia matrix M_p (thesis eq. 2.12) and the modal
    frequencies sqrt(eig(M_p^-1 K)) / 2 pi in Hz (section 2.2) of a hexapod (see `geometry`)."""
    g = geometry(geometry_source)
    d = _core.describe(g)
    return Model(g, d.jacobian, d.mass_matrix, d.payload_mass_matrix, d.modes_hz, d.strut_lengths,
                 d.mass_matrix_eigenvalues, d.jacobian_condition, d.strut_directions)


def simulate(samples=_SIMULATION.samples, noise_var=0.86, *, seed=1, truth="thesis",
             signal_var=_SIMULATION.signal_var, distribution=_SIMULATION.distribution, force_noise_var=None):
    """Measurements as the thesis' appendix-B generator makes them: true accelerations uniform with
    variance signal_var (on [-5, 5] by default), true forces B_true = A_true M_p, and independent
    noise of variance noise_var (force_noise_var for B, if given) in every entry of A and B,
    "uniform" (half-width sqrt(3 V), the thesis') or "gaussian". truth: "thesis" (eq. 6.1), an
    n x n array, or a geometry (see `geometry`). The same seed gives the same data as
    `spdfit hexapod simulate --seed`. Returns Simulation(A, B, truth, A_true, B_true)."""
    if isinstance(truth, str) and truth == "thesis":
        M = _core.thesis_mass_matrix()
    elif isinstance(truth, (dict, Geometry)) or (isinstance(truth, (str, _os.PathLike)) and truth != "thesis"):
        M = _core.joint_space_mass_matrix(geometry(truth))
    else:
        M = _as_matrix("truth", truth)
    A, B, A_true, B_true = _core.simulate(M, int(samples), float(noise_var),
                                          None if force_noise_var is None else float(force_noise_var),
                                          float(signal_var), distribution, int(seed))
    return Simulation(A, B, M, A_true, B_true)


def identify(A, B, *, truth=None, stiffness=None, bootstrap=0, confidence=None, seed=None, threads=0):
    """Every estimator on accelerations A and forces B; a dict {method: MethodIdentification} with
    the FitResult, the eigenvalues, the modes (with a stiffness matrix K) and the error against
    a known truth.

    bootstrap=N (with confidence, seed and threads as in spdfit.fit) adds each method's bootstrap
    to its result (result.standard_errors, result.bootstrap.eigenvalues) and, with a stiffness,
    the modes' intervals (modes_uncertainty): N resamples of the rows, each refitted by every
    estimator."""
    bootstrap, confidence, seed, threads = _options(bootstrap=bootstrap, confidence=confidence, seed=seed,
                                                    threads=threads)
    results = _core.identify(_as_matrix("A", A), _as_matrix("B", B),
                             None if truth is None else _as_matrix("truth", truth),
                             None if stiffness is None else _as_matrix("stiffness", stiffness),
                             bootstrap, confidence, seed, threads)
    return {r.result.method: r for r in results}
