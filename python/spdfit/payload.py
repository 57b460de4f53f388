"""A payload on a wrist force/torque sensor: its mass, centre of mass and inertia and the sensor's
biases from a log over many poses, physically consistent (docs/payload.md), and the poses to log.

    >>> import numpy as np, spdfit.payload as pl
    >>> rng = np.random.default_rng(1)
    >>> q = rng.normal(size=(20, 4)); q /= np.linalg.norm(q, axis=1, keepdims=True)   # x y z w
    >>> def rot(q):
    ...     x, y, z, w = q
    ...     return np.array([[1 - 2*(y*y + z*z), 2*(x*y - z*w), 2*(x*z + y*w)],
    ...                      [2*(x*y + z*w), 1 - 2*(x*x + z*z), 2*(y*z - x*w)],
    ...                      [2*(x*z - y*w), 2*(y*z + x*w), 1 - 2*(x*x + y*y)]])
    >>> g = np.array([0, 0, -9.80665]); m, c = 1.2, np.array([0.08, 0.0, 0.03])
    >>> s = np.array([-rot(qi).T @ g for qi in q])                     # specific force at rest
    >>> wrench = -np.hstack([m * s, np.cross(m * c, s)]) + [5, 0, 0, 0.3, 0, 0]
    >>> est = pl.identify(wrench=wrench, quaternion=q)
    >>> round(est["mass"], 9), np.round(est["center_of_mass"], 9).tolist() == [0.08, 0.0, 0.03]
    (1.2, True)
"""
import contextlib as _contextlib
import json as _json
import os as _os

import numpy as _np

from ._common import _takes_options
from ._errors import NumericalError, warn as _warn
from ._records import PayloadDesign, PayloadEstimate, record as _record
from ._spdfit import payload as _core

__all__ = ["PayloadDesign", "PayloadEstimate", "design", "identify", "urdf_link"]

# The signals' keyword arguments and the column options that choose them from a table.
_SIGNALS = ("wrench", "quaternion", "rotation", "gravity_in_sensor", "accel", "specific_force", "omega", "alpha",
            "time")
_COLUMNS = {"wrench": "wrench_cols", "quaternion": "quat_cols", "rotation": "rotation_cols",
            "gravity_in_sensor": "gravity_cols", "accel": "accel_cols", "specific_force": "specific_force_cols",
            "omega": "omega_cols", "alpha": "alpha_cols", "time": "time_col"}


def _arrays(value):
    """JSON lists as float64 arrays (null as NaN), recursively through dicts."""
    if isinstance(value, dict):
        return {k: (_arrays(v) if k not in ("names", "warnings", "warning_codes", "undetermined") else v) for k, v in value.items()}
    if isinstance(value, list) and value and not isinstance(value[0], (str, dict)):
        return _np.array([_np.nan if v is None else v for v in value] if not isinstance(value[0], list) else
                         [[_np.nan if x is None else x for x in row] for row in value], dtype=_np.float64)
    return value


@_contextlib.contextmanager
def _keyword_names(path, arrays, options):
    """Signals given as arrays: an error message names the keyword (quaternion=) where the library
    names the column option (quat_cols) a file's signals come from, unless that option was given."""
    try:
        yield
    except (ValueError, TypeError) as error:
        if path is not None or not arrays:
            raise
        message = str(error)
        for keyword, option in _COLUMNS.items():
            if keyword in arrays and option not in options:
                message = message.replace("`" + option + "`", "`" + keyword + "=`").replace(option, keyword + "=")
        if message == str(error):
            raise
        raise type(error)(message) from None


def _signals(log, signals, options, need_wrench=True):
    """(path or None, {signal: array}) from a file path, a pandas DataFrame with the *_cols options
    as column labels, or the signals given as arrays."""
    given = {name: value for name, value in signals.items() if value is not None}
    if log is None:
        if need_wrench and "wrench" not in given:
            raise TypeError("identify() needs a log (a file path or a DataFrame) or the signals as arrays (wrench=..., "
                            "quaternion=... or rotation=... or gravity_in_sensor=..., ...)")
        return None, {k: _np.asarray(v, dtype=_np.float64) for k, v in given.items()}
    if given:
        raise TypeError("give a log or the signals as arrays, not both")
    if isinstance(log, (str, _os.PathLike)):
        return _os.fspath(log), {}
    if hasattr(log, "columns") and hasattr(log, "loc"):  # a pandas DataFrame: *_cols are column labels
        arrays = {}
        for signal, option in _COLUMNS.items():
            labels = options.pop(option, None)
            if labels is None:
                continue
            if isinstance(labels, str):
                labels = [label.strip() for label in labels.split(",")] if "," in labels else [labels]
            arrays[signal] = log.loc[:, list(labels)].to_numpy(dtype=_np.float64)
        if option_missing := [k for k in ("wrench",) if need_wrench and k not in arrays]:
            raise TypeError("with a DataFrame, wrench_cols names the wrench's 6 columns (" + ", ".join(option_missing)
                            + ")")
        return None, arrays
    raise TypeError(f"log must be a file path or a pandas DataFrame, got {type(log).__name__}")


@_takes_options("payload.identify")
def identify(log=None, *, wrench=None, quaternion=None, rotation=None, gravity_in_sensor=None, accel=None,
             specific_force=None, omega=None, alpha=None, time=None, **options):
    """A payload's mass, centre of mass, inertia and the sensor's biases from a force/torque log.

    The wrench the sensor applies to the payload is linear in its mass m, first moment m c and
    inertia I_S about the sensor's origin (docs/payload.md); the readings are its opposite plus six
    biases (wrench_sign="load", what sensors report) or the wrench itself (wrench_sign="applied").
    Static poses determine m, c and the biases; moving poses (omega given, with the acceleration)
    the inertia too. Physically consistent by default (m >= 0; the pseudo-inertia positive
    semidefinite), least squares or errors in variables (criterion="eiv", with the noise model).

    Parameters
    ----------
    log : str, os.PathLike or pandas.DataFrame, optional
        A log file (any format spdfit reads; columns chosen by the *_cols options in the command
        line's syntax) or a DataFrame (the *_cols options as column labels). Or give the signals:
    wrench : array_like, optional
        m x 6 readings: fx fy fz (N), tx ty tz (N m).
    quaternion : array_like, optional
        m x 4 orientation (the rotation from the sensor frame to the world; x y z w unless
        quat_order="wxyz").
    rotation : array_like, optional
        m x 9 rotation matrices, row-major.
    gravity_in_sensor : array_like, optional
        m x 3 gravity in the sensor frame (m/s^2).
    accel : array_like, optional
        m x 3 kinematic acceleration of the sensor's origin in the sensor frame.
    specific_force : array_like, optional
        m x 3 IMU specific force (gravity included: no orientation needed).
    omega : array_like, optional
        m x 3 angular velocity (rad/s): the inertia enters the model.
    alpha : array_like, optional
        m x 3 angular acceleration; without it, omega's central differences in `time`.
    time : array_like, optional
        m times (s).
    {options}

    Returns
    -------
    PayloadEstimate
        The keys of ``spdfit payload identify --json`` (mass, center_of_mass, inertia,
        principal_moments, principal_axes, force_bias, torque_bias, standard_errors, residual_rms,
        condition, undetermined, certificate, ... ; vectors and matrices as float64 arrays, null
        as NaN), with "residuals" (m x 6) and "report" (the command line's text).

    Raises
    ------
    TypeError
        Neither a log nor the signals, or an option of the wrong type.
    ValueError
        Bad options or signals (the message names the keyword or the row): a quaternion far from
        unit norm, a significantly negative mass (the wrench_sign convention), ...
    DataError
        A bad log file (the message names the file).
    NumericalError
        The optimizer failed on valid data.

    Examples
    --------
    >>> import numpy as np, spdfit.payload as pl
    >>> g = np.array([[0, 0, -9.80665], [0, -9.80665, 0], [9.80665, 0, 0], [0, 6.93, -6.93]])
    >>> s = -g
    >>> wrench = -np.hstack([2.0 * s, np.cross(2.0 * np.array([0.1, 0, 0]), s)])
    >>> est = pl.identify(wrench=wrench, gravity_in_sensor=g)
    >>> round(est["mass"], 9), round(est["center_of_mass"][0], 9)
    (2.0, 0.1)
    """
    path, arrays = _signals(log, {"wrench": wrench, "quaternion": quaternion, "rotation": rotation,
                                  "gravity_in_sensor": gravity_in_sensor, "accel": accel,
                                  "specific_force": specific_force, "omega": omega, "alpha": alpha, "time": time},
                            options)
    with _keyword_names(path, arrays, options):
        text, residuals, report = _core.identify(path, arrays, options)
    result = _arrays(_json.loads(text))
    if result["status"] != "success":
        raise NumericalError(result.get("error", "payload identification failed"), result)
    for message, code in zip(result["warnings"], result["warning_codes"]):
        _warn(message, code)
    result["residuals"] = _np.asarray(residuals)
    result["report"] = report
    return _record(PayloadEstimate, result)


def urdf_link(estimate, name="payload", precision=9):
    """The identified payload as a URDF link with its inertial element.

    Parameters
    ----------
    estimate : dict
        identify's result (moving poses: the inertia is needed).
    name : str, optional
        The link's name (default "payload").
    precision : int, optional
        Significant digits (default 9).

    Returns
    -------
    str
        ``<link name="...">`` with ``<inertial>``: origin = centre of mass, mass, inertia about it.

    Raises
    ------
    ValueError
        The estimate has no inertia (static poses) or no positive mass.

    Examples
    --------
    >>> import spdfit.payload as pl
    >>> est = {"mass": 1.5, "center_of_mass": [0.0, 0.0, 0.05], "inertia": [[0.002, 0, 0], [0, 0.002, 0], [0, 0, 0.001]],
    ...        "force_bias": [0, 0, 0]}
    >>> print(pl.urdf_link(est, "gripper", 4).splitlines()[2].strip())
    <origin xyz="0 0 0.05" rpy="0 0 0"/>
    """
    def plain(value):
        return _np.asarray(value, dtype=float).tolist()

    if estimate.get("inertia") is None or _np.isnan(_np.asarray(estimate["inertia"], dtype=float)).any():
        raise ValueError("the estimate has no inertia (static poses do not determine it): log moving poses")
    body = {"mass": float(estimate["mass"]), "center_of_mass": plain(estimate["center_of_mass"]),
            "inertia": plain(estimate["inertia"])}
    return _core.urdf(_json.dumps(body), name, int(precision))


@_takes_options("payload.design")
def design(candidates=None, *, quaternion=None, rotation=None, gravity_in_sensor=None, **options):
    """Choose the poses of a payload calibration: K of the candidate orientations.

    Maximizes the information of the static regressor about the mass, the first moment and the
    biases (D-optimal: log det; criterion="E" or "A" for the others) by greedy additions and
    Fedorov exchanges, and compares the choice with random K-pose choices from the same pool.

    Parameters
    ----------
    candidates : str, os.PathLike or pandas.DataFrame, optional
        A file of candidate poses (one per row; the orientation's columns by quat_cols,
        rotation_cols or gravity_cols) or a DataFrame (those options as column labels). Or:
    quaternion : array_like, optional
        n x 4 candidate quaternions.
    rotation : array_like, optional
        n x 9 candidate rotation matrices, row-major.
    gravity_in_sensor : array_like, optional
        n x 3 candidate gravity vectors in the sensor frame.
    {options}

    Returns
    -------
    PayloadDesign
        The keys of ``spdfit payload design --json``: chosen (1-based rows), log_det, condition,
        se_mass, se_center_of_mass, random (the random choices' percentiles) ..., and "report".

    Raises
    ------
    TypeError
        No candidates, or an option of the wrong type.
    ValueError
        Bad options (more poses than candidates, ...).
    DataError
        A bad candidates file.

    Examples
    --------
    >>> import numpy as np, spdfit.payload as pl
    >>> rng = np.random.default_rng(2)
    >>> g = rng.normal(size=(200, 3)); g *= 9.80665 / np.linalg.norm(g, axis=1, keepdims=True)
    >>> d = pl.design(gravity_in_sensor=g, poses=6, random=200)
    >>> len(d["chosen"]), bool(d["se_mass"] <= d["random"]["se_mass"][0])
    (6, True)
    """
    path, arrays = _signals(candidates, {"quaternion": quaternion, "rotation": rotation,
                                         "gravity_in_sensor": gravity_in_sensor}, options, need_wrench=False)
    if path is None and not arrays:
        raise TypeError("design() needs the candidates: a file, a DataFrame, or quaternion=, rotation= or "
                        "gravity_in_sensor=")
    with _keyword_names(path, arrays, options):
        text, report = _core.design(path, arrays, options)
    result = _json.loads(text)
    for key in ("log_det", "condition", "se_mass", "se_center_of_mass_norm"):
        result[key] = _np.nan if result[key] is None else result[key]
    result["se_center_of_mass"] = _arrays(result["se_center_of_mass"])
    result["random"] = _arrays(result["random"])
    for message, code in zip(result["warnings"], result["warning_codes"]):
        _warn(message, code)
    result["report"] = report
    return _record(PayloadDesign, result)
