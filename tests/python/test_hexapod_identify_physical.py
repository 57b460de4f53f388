"""spdfit.hexapod.identify(..., physical=True): the physical estimate beside the generic ones, the
same as spdfit.physical.identify (one library call, one option table), with the physical fit's
keywords from the library's table and clear errors."""
import inspect

import numpy as np
import pytest

import spdfit
import spdfit.hexapod as hx
import spdfit.physical as ph

NOISE_VAR = 3.2 ** 2 / 12  # the thesis' experiment 2: uniform noise of width 3.2


def simulated(samples=100, seed=2):
    g = hx.cubic_geometry()
    sim = hx.simulate(samples=samples, noise_var=NOISE_VAR, truth=g, seed=seed)
    return g, sim


def test_physical_agrees_with_spdfit_physical():
    g, sim = simulated()
    out = hx.identify(sim.A, sim.B, truth=sim.truth, geometry=g, physical=True)
    alone = ph.identify(sim.A, sim.B, g)
    p = out["physical"]
    # The same library call on the same data: bit for bit.
    for key in ("mass", "criterion", "iterations"):
        assert p[key] == alone[key], key
    for key in ("center_of_mass", "inertia", "M_p", "strut_mass"):
        np.testing.assert_array_equal(p[key], alone[key])
    assert p["error_vs_truth"] == pytest.approx(np.linalg.norm(p["M_p"] - sim.truth), rel=1e-14)
    assert set(out) == {"ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "physical"}


def test_options_reach_the_physical_fit():
    g, sim = simulated(samples=60, seed=5)
    grey = hx.identify(sim.A, sim.B, geometry=g, physical=True, consistent=False, criterion="ls")["physical"]
    alone = ph.identify(sim.A, sim.B, g, consistent=False, criterion="ls")
    assert grey["criterion_kind"] == "ls" and grey["consistent"] is False
    np.testing.assert_array_equal(grey["M_p"], alone["M_p"])
    boot = hx.identify(sim.A, sim.B, geometry=g, physical=True, bootstrap=20, seed=4, threads=2)["physical"]
    ref = ph.identify(sim.A, sim.B, g, bootstrap=20, seed=4, threads=2)
    np.testing.assert_array_equal(boot["standard_errors"]["M_p"], ref["standard_errors"]["M_p"])
    assert boot["bootstrap"]["replicates"] == 20


def test_keywords_come_from_the_table():
    parameters = inspect.signature(hx.identify).parameters
    for name in ("geometry", "physical", "fit_strut_mass", "criterion", "consistent", "bootstrap", "max_iter"):
        assert name in parameters, name
    assert parameters["consistent"].default is True
    assert "fit_strut_mass : str" in hx.identify.__doc__


def test_confounded_strut_mass_names_the_combination():
    g, sim = simulated(samples=40)
    with pytest.raises(ValueError, match=r"fit_strut_mass = common cannot be estimated on this geometry: adding 1 kg"):
        hx.identify(sim.A, sim.B, geometry=g, physical=True, fit_strut_mass="common")
    with pytest.raises(ValueError, match=r"fit_strut_mass = common cannot be estimated"):
        ph.identify(sim.A, sim.B, g, fit_strut_mass="common")


def test_bad_physical_options():
    g, sim = simulated(samples=40)
    # A physical fit's option without physical: a usage error naming both (ValueError, as the
    # command line's exit 2), the same rule in every front end.
    with pytest.raises(ValueError, match="fit_strut_mass needs physical"):
        hx.identify(sim.A, sim.B, fit_strut_mass="each")
    with pytest.raises(ValueError, match="fit_strut_mass must be one of 'geometry', 'common' or 'each', got 'some'"):
        hx.identify(sim.A, sim.B, physical=True, geometry=g, fit_strut_mass="some")
    with pytest.raises(TypeError, match="consistent must be a bool"):
        hx.identify(sim.A, sim.B, physical=True, consistent=1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'nonsense'"):
        hx.identify(sim.A, sim.B, physical=True, nonsense=1)


def test_the_package_imports_physical():
    assert spdfit.physical is ph and "identify" in dir(spdfit.physical)
