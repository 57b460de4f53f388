"""Physical identification of a hexapod's payload (its mass, centre of mass and inertia, and the
struts' moving masses) from accelerations and forces, physically consistent and certified, and the
repair of rigid-body inertias that no body can have (docs/hexapod.md, "Physical identification").

    >>> import numpy as np, spdfit.hexapod as hx, spdfit.physical as ph
    >>> g = hx.cubic_geometry()
    >>> truth = ph.mass_matrix(g, mass=14.0, center_of_mass=[0.01, 0, -0.02], inertia=np.diag([0.12, 0.1, 0.09]))
    >>> A = np.random.default_rng(1).normal(size=(50, 6))
    >>> est = ph.identify(A, A @ truth, g)
    >>> round(est["mass"], 9)
    14.0
"""
import json as _json
import os as _os

import numpy as _np

from . import hexapod
from ._common import _as_matrix, _data, _physical_arrays as _arrays, _takes_options
from ._errors import NumericalError, warn as _warn
from ._records import (InertiaRepair, PhysicalDesign, PhysicalEstimate, RegressFit, UrdfLinkRepair,
                       record as _record)
from ._spdfit import physical as _core

__all__ = ["InertiaRepair", "PhysicalDesign", "PhysicalEstimate", "RegressFit", "UrdfLinkRepair", "design", "identify",
           "inertia_repair", "inertia_repair_urdf", "mass_matrix", "regress"]

def _geometry(geometry):
    return hexapod.geometry(geometry)


@_takes_options("physical.identify")
def identify(A, B=None, geometry=None, *, a_cols=None, b_cols=None, strut_masses=None, **options):
    """The payload's mass, centre of mass and inertia (and strut masses) from A and B.

    Fits M_p(theta) = J^-T R M_x(theta) R^T J^-1 + diag(strut masses), linear in the ten inertial
    parameters theta, minimizing the errors-in-variables criterion
    sum_i r_i^T (M noise_cov_a M + noise_cov_b)^-1 r_i (r_i the rows of A M - B) over the physically
    consistent payloads (pseudo-inertia positive semidefinite, strut masses non-negative), from the
    certified least-squares fit.

    Parameters
    ----------
    A, B : array_like
        Accelerations along the struts and base forces, m x 6 each, one sample per row. With a_cols
        and b_cols, A is a pandas DataFrame holding both (one log), and B is left out (None).
    geometry : Geometry, str, os.PathLike or dict
        The hexapod (spdfit.hexapod.geometry): its Jacobian and nominal payload (the built-in one is
        spdfit.hexapod.cubic_geometry()).
    a_cols, b_cols : label, list, slice, str or None, default None
        The accelerations' and forces' columns of the DataFrame A, as spdfit.fit takes them.
    strut_masses : {'geometry', 'common', 'each'}, optional
        The old name of fit_strut_mass; give one of the two.
    {options}

    Returns
    -------
    PhysicalEstimate
        The keys of ``spdfit hexapod identify --json``'s ``physical`` object: mass,
        center_of_mass, inertia, principal_moments, principal_axes, strut_mass, M_p,
        M_p_eigenvalues, modes_hz, pseudo_inertia_min_eig, physically_consistent, certificate,
        start_certificate, criterion, iterations, converged, design, warnings, and with a
        bootstrap standard_errors, interval and bootstrap; vectors and matrices as arrays.

    Raises
    ------
    ValueError
        Bad shapes or options, an invalid geometry, a strut mass the geometry confounds, or data
        that cannot identify a parameter; the message names it.
    NumericalError
        The optimizer failed on valid data.

    Examples
    --------
    >>> import numpy as np, spdfit.hexapod as hx, spdfit.physical as ph
    >>> sim = hx.simulate(samples=500, noise_var=0.86, truth=hx.cubic_geometry(), seed=3)
    >>> est = ph.identify(sim.A, sim.B, hx.cubic_geometry())
    >>> est["physically_consistent"], abs(est["mass"] - 11.973) < 1.0
    (True, True)
    """
    if strut_masses is not None:
        if "fit_strut_mass" in options:
            raise ValueError("give fit_strut_mass or strut_masses, not both")
        options["fit_strut_mass"] = strut_masses
    A, B, _ = _data("physical.identify", A, B, a_cols, b_cols)
    text = _core.identify(A, B, None if geometry is None else _geometry(geometry), options)
    result = _arrays(_json.loads(text))
    if result["status"] != "success":
        raise NumericalError(result.get("error", "physical identification failed"), result)
    for message, code in zip(result["warnings"], result.get("warning_codes", ["warning"] * len(result["warnings"]))):
        _warn(f"physical: {message}", code)
    return _record(PhysicalEstimate, result)


def design(geometry=None, strut_masses="geometry"):
    """Which parameters a hexapod's geometry lets M_p determine.

    Parameters
    ----------
    geometry : None, Geometry, str, os.PathLike or dict, optional
        The hexapod (spdfit.hexapod.geometry); None is the built-in cubic one.
    strut_masses : {'geometry', 'common', 'each'}, optional
        Which strut masses would be estimated.

    Returns
    -------
    PhysicalDesign
        parameters, rank and condition of the 21 x parameters design of theta -> M_p(theta),
        length_scale (m), null_space (a basis, parameters x nullity) and confounded (the
        confounded combination in words, empty when there is none).

    Raises
    ------
    ValueError
        An invalid geometry or strut_masses.

    Examples
    --------
    >>> import spdfit.physical as ph
    >>> d = ph.design(strut_masses="common")     # the cubic hexapod confounds a common strut mass
    >>> d["parameters"], d["rank"]
    (11, 10)
    """
    return _record(PhysicalDesign, _core.design(_geometry(geometry), strut_masses))


def mass_matrix(geometry=None, *, mass, center_of_mass, inertia):
    """M_p of a hexapod carrying a payload that differs from the geometry's nominal one.

    Parameters
    ----------
    geometry : None, Geometry, str, os.PathLike or dict, optional
        The hexapod; None is the built-in cubic one.
    mass : float
        The payload's mass (kg).
    center_of_mass : array_like
        Its centre of mass (3 numbers, m) in {P}'s axes, from {P}'s origin.
    inertia : array_like
        Its 3 x 3 inertia about the centre of mass, {P} axes (kg m^2).

    Returns
    -------
    numpy.ndarray
        The 6 x 6 joint-space mass-inertia matrix (strut masses from the geometry).

    Raises
    ------
    ValueError
        An invalid geometry, or a mass that is not positive or an inertia that is not symmetric.

    Examples
    --------
    >>> import numpy as np, spdfit.hexapod as hx, spdfit.physical as ph
    >>> g = hx.cubic_geometry()
    >>> M = ph.mass_matrix(g, mass=g.payload_mass, center_of_mass=[0, 0, 0], inertia=g.payload_inertia)
    >>> bool(np.allclose(M, hx.model(g).mass_matrix))
    True
    """
    return _core.mass_matrix(_geometry(geometry), float(mass), _np.asarray(center_of_mass, dtype=_np.float64),
                             _np.asarray(inertia, dtype=_np.float64))


@_takes_options("physical.inertia_repair")
def inertia_repair(mass, center_of_mass, inertia, **options):
    """The nearest physically consistent inertia, mass and centre of mass kept.

    The second moment about the centre of mass, (1/2) tr(I) 1 - I, must have eigenvalues at least
    min_eig_rel times the largest, so that every principal moment is below the sum of the other
    two. metric="inertia" (the default) gives the nearest such inertia in ||I' - I||_F (the distance
    reported); metric="second-moment" the nearest second moment (an eigenvalue clip).

    Parameters
    ----------
    mass : float
        kg, positive.
    center_of_mass : array_like
        3 numbers (m).
    inertia : array_like
        3 x 3 symmetric, about the centre of mass (kg m^2).
    {options}

    Returns
    -------
    InertiaRepair
        mass, center_of_mass, inertia (arrays), changed, distance, certificate, min_eig,
        principal_moments, principal_moments_before, second_moments_before, metric, warnings.

    Raises
    ------
    ValueError
        A mass that is not positive, non-finite numbers, an inertia that is not symmetric, or a
        floor outside [0, 1).

    Examples
    --------
    >>> import numpy as np, spdfit.physical as ph
    >>> r = ph.inertia_repair(2.0, [0, 0, 0], np.diag([0.1, 0.2, 0.5]))   # 0.5 > 0.1 + 0.2
    >>> r["changed"], bool(r["principal_moments"][2] < r["principal_moments"][0] + r["principal_moments"][1])
    (True, True)
    """
    text = _core.repair_inertia(float(mass), _np.asarray(center_of_mass, dtype=_np.float64),
                                _np.asarray(inertia, dtype=_np.float64), options)
    result = _json.loads(text)
    for key in ("center_of_mass", "inertia", "principal_moments", "principal_moments_before",
                "second_moments_before"):
        result[key] = _np.array(result[key], dtype=_np.float64)
    return _record(InertiaRepair, result)


@_takes_options("physical.inertia_repair_urdf")
def inertia_repair_urdf(text, *, source="<urdf>", **options):
    """Every link's inertia of a URDF document checked, the inconsistent ones repaired in place.

    Parameters
    ----------
    text : str
        The URDF document.
    source : str, optional
        The name errors give the document (a file name).
    {options}

    Returns
    -------
    tuple
        (the repaired document, every other byte unchanged; the report for people; a list with an
        UrdfLinkRepair per link with an <inertial>: link, line, changed, distance, mass, center_of_mass,
        inertia_before, inertia).

    Raises
    ------
    DataError
        XML that does not parse, a missing or non-numeric attribute, a second <inertia> (or
        <inertial>, <origin>, <mass>) where one is read, a mass that is not positive; the message
        names the source, the line and the link.
    TypeError
        text that is not a str (bytes, a path).

    Examples
    --------
    >>> import spdfit.physical as ph
    >>> urdf = '''<robot name="r"><link name="a"><inertial><mass value="2"/>
    ... <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.5"/></inertial></link></robot>'''
    >>> fixed, report, links = ph.inertia_repair_urdf(urdf)
    >>> links[0]["changed"], report.splitlines()[-1]
    (True, '1 of 1 links repaired')
    """
    if not isinstance(text, str):
        hint = "decode the bytes first" if isinstance(text, (bytes, bytearray)) else "pass the file's text, open(path).read()"
        raise TypeError(f"text is the URDF's text (a str), not {type(text).__name__}: {hint}")
    repaired, report, links = _core.repair_urdf(text, str(source), options)
    return repaired, report, [_record(UrdfLinkRepair, link) for link in links]


def _prior_bodies(prior):
    """[(mass, center_of_mass, inertia)] from a file of bodies (JSON) or a sequence of dicts."""
    if prior is None:
        return None
    if isinstance(prior, (str, _os.PathLike)):
        with open(prior, encoding="utf-8") as f:
            prior = _json.load(f)
        if isinstance(prior, dict):
            prior = prior["bodies"]
    bodies = []
    for k, body in enumerate(prior):
        try:
            bodies.append((float(body["mass"]), _np.asarray(body["center_of_mass"], dtype=float).reshape(3),
                           _np.asarray(body["inertia"], dtype=float).reshape(3, 3)))
        except (KeyError, TypeError, ValueError) as error:
            raise ValueError(f"prior body {k + 1} must be a dict with mass, center_of_mass (3) and inertia (3 x 3): "
                             f"{error}") from None
    return bodies


@_takes_options("physical.regress")
def regress(Y, tau, *, noise_cov=None, prior=None, **options):
    """Physically consistent least squares for any model linear in K rigid bodies' parameters.

    Minimizes ||W^1/2 (Y phi - tau)||^2 over the parameters phi whose every body's pseudo-inertia
    is positive semidefinite (W the inverse noise covariance of a sample's outputs), with the base
    parameters (the combinations the data determine), the undetermined combinations named (or set
    by a prior through the log-determinant divergence) and the KKT certificate. Y's columns: 10 per
    body (m, m c, the inertia about the body frame's origin in param_order's order), then any extra
    columns (friction), unconstrained; pinocchio's computeJointTorqueRegressor gives Y in
    param_order="pinocchio".

    Parameters
    ----------
    Y : array_like
        The stacked regressor, rows = samples x outputs (sample-major).
    tau : array_like
        The stacked outputs, one per row of Y.
    noise_cov : array_like, optional
        d x d covariance of one sample's d outputs (Y's rows come in samples of d).
    prior : str, os.PathLike or sequence of dict, optional
        K prior bodies ({"mass", "center_of_mass", "inertia" about the centre of mass}, each
        body's frame), e.g. from CAD, or a JSON file of them.
    {options}

    Returns
    -------
    RegressFit
        The keys of ``spdfit physical regress --json`` (parameters, body, base_parameters,
        undetermined, criterion, certificate, ...; vectors and matrices as arrays, null as NaN)
        and "report".

    Raises
    ------
    ValueError
        Bad shapes or options (the message names them), a prior that is not strictly consistent.
    NumericalError
        The optimizer failed on valid data.

    Examples
    --------
    >>> import numpy as np, spdfit.physical as ph
    >>> rng = np.random.default_rng(0)
    >>> Y = rng.normal(size=(60, 10))
    >>> phi = np.array([2.0, 0.2, 0.0, 0.1, 0.05, 0.0, -0.01, 0.06, 0.0, 0.04])   # m, m c, I about the origin
    >>> fit = ph.regress(Y, Y @ phi, bodies=1)
    >>> bool(np.allclose(fit["parameters"], phi, atol=1e-9)), fit["physically_consistent"]
    (True, True)
    """
    cov = None if noise_cov is None else _as_matrix("noise_cov", noise_cov)
    text, report = _core.regress(_as_matrix("Y", Y), _as_matrix("tau", _np.reshape(_np.asarray(tau, dtype=float), (-1, 1))),
                                 cov, _prior_bodies(prior), options)
    result = _json.loads(text)
    if result["status"] != "success":
        raise NumericalError(result.get("error", "the regression failed"), result)

    def arrays(value):
        if isinstance(value, list) and value and not isinstance(value[0], (str, dict)):
            return _np.array(value, dtype=float) if not isinstance(value[0], list) else \
                _np.array([[_np.nan if x is None else x for x in row] for row in value], dtype=float)
        return value

    for key in ("parameters", "extra"):
        result[key] = _np.array([_np.nan if v is None else v for v in result[key]], dtype=float)
    for body in result["body"]:
        for key in ("center_of_mass", "inertia", "parameters"):
            value = body[key]
            body[key] = _np.array([[_np.nan if x is None else x for x in row] for row in value] if key == "inertia"
                                  else [_np.nan if x is None else x for x in value], dtype=float)
        body["mass"] = _np.nan if body["mass"] is None else body["mass"]
    for base in result["base_parameters"]:
        base["coefficients"] = arrays(base["coefficients"])
    for u in result["undetermined"]:
        u["coefficients"] = arrays(u["coefficients"])
    for message, code in zip(result["warnings"], result["warning_codes"]):
        _warn(message, code)
    result["report"] = report
    return _record(RegressFit, result)
