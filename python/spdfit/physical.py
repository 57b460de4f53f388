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

import numpy as _np

from . import _as_matrix, _takes_options
from ._errors import NumericalError, warn as _warn
from ._spdfit import physical as _core

__all__ = ["design", "identify", "inertia_repair", "inertia_repair_urdf", "mass_matrix"]

# The keys of the estimate that are vectors or matrices, returned as NumPy arrays.
_ARRAY_KEYS = ("center_of_mass", "inertia", "principal_moments", "principal_axes", "M_p", "M_p_eigenvalues",
               "modes_hz")
_SPECTRUM_KEYS = ("estimate", "standard_errors", "lower", "upper")


def _arrays(result):
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


def _geometry(geometry):
    from . import hexapod
    return hexapod.geometry(geometry)


@_takes_options("physical.identify")
def identify(A, B, geometry=None, *, strut_masses=None, **options):
    """The payload's mass, centre of mass and inertia (and strut masses) from A and B.

    Fits M_p(theta) = J^-T R M_x(theta) R^T J^-1 + diag(strut masses), linear in the ten inertial
    parameters theta, minimizing the errors-in-variables criterion
    sum_i r_i^T (M noise_cov_a M + noise_cov_b)^-1 r_i (r_i the rows of A M - B) over the physically
    consistent payloads (pseudo-inertia positive semidefinite, strut masses non-negative), from the
    certified least-squares fit.

    Parameters
    ----------
    A, B : array_like
        Accelerations along the struts and base forces, m x 6 each, one sample per row.
    geometry : Geometry, str, os.PathLike or dict
        The hexapod (spdfit.hexapod.geometry): its Jacobian and nominal payload (the built-in one is
        spdfit.hexapod.cubic_geometry()).
    strut_masses : {'geometry', 'common', 'each'}, optional
        The old name of fit_strut_mass; give one of the two.
    {options}

    Returns
    -------
    dict
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
    text = _core.identify(_as_matrix("A", A), _as_matrix("B", B), None if geometry is None else _geometry(geometry),
                          options)
    result = _arrays(_json.loads(text))
    if result["status"] != "success":
        raise NumericalError(result.get("error", "physical identification failed"), result)
    for message, code in zip(result["warnings"], result.get("warning_codes", ["warning"] * len(result["warnings"]))):
        _warn(f"physical: {message}", code)
    return result


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
    dict
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
    return _core.design(_geometry(geometry), strut_masses)


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


def inertia_repair(mass, center_of_mass, inertia, *, min_eig_rel=None):
    """The nearest physically consistent inertia, mass and centre of mass kept.

    The second moment about the centre of mass, (1/2) tr(I) 1 - I, is replaced by its nearest
    matrix with eigenvalues at least min_eig_rel times the largest (an eigenvalue clip), so that
    every principal moment is below the sum of the other two.

    Parameters
    ----------
    mass : float
        kg, positive.
    center_of_mass : array_like
        3 numbers (m).
    inertia : array_like
        3 x 3 symmetric, about the centre of mass (kg m^2).
    min_eig_rel : float, optional
        The floor as a fraction of the largest second moment (default 1e-6; 0: the plain
        projection).

    Returns
    -------
    dict
        mass, center_of_mass, inertia (arrays), changed, distance, certificate, min_eig,
        principal_moments, principal_moments_before, second_moments_before.

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
                                _np.asarray(inertia, dtype=_np.float64), min_eig_rel)
    result = _json.loads(text)
    for key in ("center_of_mass", "inertia", "principal_moments", "principal_moments_before",
                "second_moments_before"):
        result[key] = _np.array(result[key], dtype=_np.float64)
    return result


def inertia_repair_urdf(text, *, min_eig_rel=None, source="<urdf>"):
    """Every link's inertia of a URDF document checked, the inconsistent ones repaired in place.

    Parameters
    ----------
    text : str
        The URDF document.
    min_eig_rel : float, optional
        As for inertia_repair.
    source : str, optional
        The name errors give the document (a file name).

    Returns
    -------
    tuple
        (the repaired document, every other byte unchanged; the report for people; a list with a
        dict per link with an <inertial>: link, line, changed, distance, mass, center_of_mass,
        inertia_before, inertia).

    Raises
    ------
    DataError
        XML that does not parse, a missing or non-numeric attribute, a mass that is not positive;
        the message names the source, the line and the link.

    Examples
    --------
    >>> import spdfit.physical as ph
    >>> urdf = '''<robot name="r"><link name="a"><inertial><mass value="2"/>
    ... <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.5"/></inertial></link></robot>'''
    >>> fixed, report, links = ph.inertia_repair_urdf(urdf)
    >>> links[0]["changed"], report.splitlines()[-1]
    (True, '1 of 1 links repaired')
    """
    return _core.repair_urdf(str(text), str(source), min_eig_rel)
