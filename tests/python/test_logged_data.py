"""Data as logged (issue 42) through Python: the same answers as the command line's to a logger's
code for an invalid reading, to forces in kN against a geometry in SI, and to untared forces
(offsets='rest'), against NumPy's taring and unit conversion by hand."""
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.hexapod as hx

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
SAME = 1e-9  # the same arithmetic on rows that differ by a subtraction or a power of ten


def test_a_sentinel_is_a_warning_naming_the_row():
    rng = np.random.default_rng(6)
    A = rng.uniform(-1, 1, (200, 3))
    B = A @ X_TRUE + 0.05 * rng.standard_normal((200, 3))
    A[9, 2] = 9.9e37
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = spdfit.fit(A, B, "ls")
    assert any("row 10 (9.9e+37 in A's column 3)" in w for w in r.warnings), r.warnings
    assert any("row 10 (9.9e+37" in str(w.message) for w in caught)


def test_forces_in_kn_are_a_data_error_naming_the_factor():
    g = hx.cubic_geometry()
    sim = hx.simulate(samples=300, noise_var=0.5, truth=g, seed=5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(spdfit.DataError, match="multiply the forces by 1000"):
            hx.identify(sim.A, sim.B / 1000, geometry=g, physical=True)
        si = hx.identify(sim.A, sim.B, geometry=g, physical=True)["physical"]
        unchecked = hx.identify(sim.A, sim.B / 1000, geometry=g, physical=True, no_plausibility_check=True)
    assert abs(si["mass"] - g.payload_mass) < 0.05 * g.payload_mass
    assert unchecked["physical"]["mass"] < g.payload_mass / 100



def test_scale_a_and_scale_b_fit_data_in_other_units():
    """scale_b=1000 on forces in kN gives the fit of the forces in N (issue 42 item 2): fit, fit_all,
    hexapod.identify's physical fit, and the error naming the keyword. (rows and rest_rows are the
    command line's: Python slices its arrays and DataFrames.)"""
    g = hx.cubic_geometry()
    sim = hx.simulate(samples=300, noise_var=0.5, truth=g, seed=5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(spdfit.DataError, match=r"multiply the forces by 1000 \(scale_b 1000"):
            hx.identify(sim.A, sim.B / 1000, geometry=g, physical=True)
        si = hx.identify(sim.A, sim.B, geometry=g, physical=True)["physical"]
        kn = hx.identify(sim.A, sim.B / 1000, geometry=g, physical=True, scale_b=1000)["physical"]
        assert abs(kn["mass"] - si["mass"]) <= 1e-9 * si["mass"]
        for method in ("ls", "spd-tls", "auto"):
            want = spdfit.fit(sim.A, sim.B, method=method).X
            got = spdfit.fit(sim.A / 9.80665, sim.B / 1000, method=method, scale_a=9.80665, scale_b=[1000.0] * 6).X
            assert np.linalg.norm(got - want) <= 1e-10 * np.linalg.norm(want), method
        every, plain = spdfit.fit_all(sim.A, sim.B / 1000, scale_b=1000), spdfit.fit_all(sim.A, sim.B)
        assert list(every) == list(plain)
        for method in plain:
            if plain[method].ok:
                assert np.linalg.norm(every[method].X - plain[method].X) <= 1e-9 * np.linalg.norm(plain[method].X)
    with pytest.raises(ValueError, match="scale_b"):
        spdfit.fit(sim.A, sim.B, method="ls", scale_b=[1.0, 2.0])
    with pytest.raises(ValueError, match="scale_b"):
        spdfit.fit(sim.A, sim.B, method="ls", scale_b=0)


def test_offsets_rest_tares_the_physical_fit():
    g = hx.cubic_geometry()
    sim = hx.simulate(samples=400, noise_var=0.5, truth=g, seed=3)
    rng = np.random.default_rng(4)
    preload = np.linspace(20.0, 22.0, 6)
    rest_a = np.sqrt(0.5) * rng.standard_normal((200, 6))
    rest_b = preload + np.sqrt(0.5) * rng.standard_normal((200, 6))
    B = sim.B + preload
    rest = spdfit.NoiseModel.from_rest(rest_a, rest_b)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hx.identify(sim.A, B, geometry=g, physical=True, noise=rest)
    assert any("the forces look untared" in str(w.message) and "offsets rest" in str(w.message)
               for w in caught), [str(w.message) for w in caught]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tared = hx.identify(sim.A, B, geometry=g, physical=True, noise=rest,
                            offsets="rest")["physical"]
        by_hand = hx.identify(sim.A - rest_a.mean(0), B - rest_b.mean(0), geometry=g, physical=True,
                              noise=rest)["physical"]
    assert abs(tared["mass"] - by_hand["mass"]) <= SAME * by_hand["mass"]
    np.testing.assert_allclose(tared["M_p"], by_hand["M_p"], rtol=SAME, atol=SAME * np.abs(by_hand["M_p"]).max())
    assert abs(tared["mass"] - g.payload_mass) < 0.05 * g.payload_mass
    with pytest.raises(ValueError, match="offsets"):
        hx.identify(sim.A, B, geometry=g, physical=True, offsets="rest")
    with pytest.raises(ValueError, match="'none', 'estimate' or 'rest'"):
        hx.identify(sim.A, B, geometry=g, physical=True, noise=rest, offsets="tare")

