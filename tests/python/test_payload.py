"""spdfit.payload and spdfit.physical.regress from Python, against the NumPy wrench model of
tests/support/payload_reference.py and NumPy least squares; the arrays, the DataFrame and the file
routes agree; errors are Python's exceptions with Python's spelling."""
import json
import os
import pathlib
import sys
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.payload as pl
import spdfit.physical as ph

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "tests" / "support"))
from payload_reference import (G, regressor, rotation_from_quaternion, static_log, trajectory,  # noqa: E402
                               wrench, write_log)

FORCE = ["fx", "fy", "fz", "tx", "ty", "tz"]


def test_arrays_give_numpy_least_squares():
    rng = np.random.default_rng(1)
    log = static_log(rng, 30)
    est = pl.identify(wrench=log["wrench"], quaternion=log["quaternion"])
    phi, *_ = np.linalg.lstsq(regressor(-log["gravity"]), log["wrench"].ravel(), rcond=None)
    np.testing.assert_allclose(est["parameters"], phi, rtol=1e-9, atol=1e-12)
    assert est["residuals"].shape == (30, 6) and "mass" in est["report"]
    # The same from gravity in the sensor frame, and with the quaternion's other order.
    g = pl.identify(wrench=log["wrench"], gravity_in_sensor=log["gravity"])
    w_first = pl.identify(wrench=log["wrench"], quaternion=log["quaternion"][:, [3, 0, 1, 2]], quat_order="wxyz")
    np.testing.assert_allclose(g["parameters"], phi, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(w_first["parameters"], phi, rtol=1e-12, atol=1e-14)


def test_file_and_dataframe_routes_agree(tmp_path):
    pd = pytest.importorskip("pandas")
    rng = np.random.default_rng(2)
    log = static_log(rng, 20)
    path = write_log(tmp_path / "log.csv", [(FORCE, log["wrench"]), (["qx", "qy", "qz", "qw"], log["quaternion"])])
    from_file = pl.identify(path, wrench_cols="fx:tz", quat_cols="qx:qw")
    frame = pd.read_csv(path)
    from_frame = pl.identify(frame, wrench_cols=FORCE, quat_cols=["qx", "qy", "qz", "qw"])
    np.testing.assert_allclose(from_frame["parameters"], from_file["parameters"], rtol=1e-12)


def test_moving_with_alpha_from_time_and_urdf():
    rng = np.random.default_rng(3)
    t, omega, alpha, accel, q = trajectory(rng, 3000)
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    inertia = np.diag([0.02, 0.03, 0.025])
    w = -wrench(3.0, [0.01, 0.02, 0.05], inertia, accel - g_s, omega, alpha)
    with pytest.warns(spdfit.PhysicalWarning, match="central differences"):
        est = pl.identify(wrench=w, quaternion=q, accel=accel, omega=omega, time=t)
    np.testing.assert_allclose(est["inertia"], inertia, atol=3e-4)
    text = pl.urdf_link(est, "tool")
    import re
    assert '<link name="tool">' in text
    assert float(re.search(r'mass value="([^"]+)"', text).group(1)) == pytest.approx(3.0, rel=1e-5)


def test_errors_are_python_exceptions():
    rng = np.random.default_rng(4)
    log = static_log(rng, 10)
    with pytest.raises(TypeError, match="needs a log"):
        pl.identify(quaternion=log["quaternion"])
    with pytest.raises(ValueError, match="criterion"):
        pl.identify(wrench=log["wrench"], quaternion=log["quaternion"], criterion="tls")
    with pytest.raises(ValueError, match="noise_std_wrench"):
        pl.identify(wrench=log["wrench"], quaternion=log["quaternion"], criterion="eiv")
    with pytest.raises(spdfit.DataError, match="wrench_sign"):
        pl.identify(wrench=-log["wrench"], quaternion=log["quaternion"])
    with pytest.raises(TypeError):
        pl.identify(wrench=log["wrench"], quaternion=log["quaternion"], bootstrap=1.5)
    with pytest.raises(ValueError, match="quat_cols"):
        pl.identify(wrench=log["wrench"], quaternion=log["quaternion"], quat_cols="1:4")
    # Arrays: the messages name the keywords, not the command line's column options.
    with pytest.raises(spdfit.DataError, match=r"quaternion= must give 4 columns"):
        pl.identify(wrench=log["wrench"], quaternion=log["quaternion"][:, :3])
    with pytest.raises(spdfit.DataError, match=r"wrench= must give 6 columns"):
        pl.identify(wrench=log["wrench"][:, :5], quaternion=log["quaternion"])
    with pytest.raises(spdfit.DataError):
        pl.identify(str(ROOT / "examples" / "payload" / "nope.csv"), wrench_cols="1:6", quat_cols="7:10")


def test_design_beats_the_random_tenth_percentile():
    rng = np.random.default_rng(5)
    g = rng.standard_normal((1000, 3))
    g *= 9.80665 / np.linalg.norm(g, axis=1, keepdims=True)
    d = pl.design(gravity_in_sensor=g, poses=6, random=300)
    assert d["se_mass"] <= d["random"]["se_mass"][0]
    chosen = g[np.array(d["chosen"]) - 1]
    X = regressor(-chosen)
    assert d["se_mass"] == pytest.approx(np.sqrt(np.linalg.inv(X.T @ X)[0, 0]), rel=1e-9)


def test_regress_with_a_prior_and_pinocchio_order():
    rng = np.random.default_rng(6)
    Y = rng.standard_normal((100, 10))
    phi = np.array([2.0, 0.2, 0.0, 0.1, 0.05, 0.0, -0.01, 0.06, 0.0, 0.04])
    fit = ph.regress(Y, Y @ phi)
    np.testing.assert_allclose(fit["parameters"], phi, rtol=1e-9, atol=1e-12)
    order = [0, 1, 2, 3, 4, 5, 7, 6, 8, 9]
    pin = ph.regress(Y[:, order], Y @ phi, param_order="pinocchio")
    np.testing.assert_allclose(pin["parameters"], phi[order], rtol=1e-9, atol=1e-12)
    # Two identical columns: the masses undetermined, then set by the prior.
    Y2 = np.hstack([Y, Y])
    Y2[:, 10:] = rng.standard_normal((100, 10))
    Y2[:, 10] = Y2[:, 0]
    phi2 = np.concatenate([phi, phi])
    with pytest.warns(spdfit.RankDeficientWarning, match="do not determine"):
        r = ph.regress(Y2, Y2 @ phi2, bodies=2)
    assert np.isnan(r["parameters"][0]) and np.isnan(r["parameters"][10])
    body = {"mass": 2.0, "center_of_mass": [0.1, 0.0, 0.05], "inertia": np.diag([0.045, 0.035, 0.02]).tolist()}
    with pytest.warns(spdfit.SpdfitWarning, match="prior sets them"):
        r = ph.regress(Y2, Y2 @ phi2, bodies=2, prior=[body, body])
    assert r["parameters"][0] + r["parameters"][10] == pytest.approx(4.0, rel=1e-7)
    with pytest.raises(ValueError, match="prior_weight"):
        ph.regress(Y, Y @ phi, prior_weight=-1.0, prior=[body])
    # prior_weight with the prior given as bodies (it was refused as if the prior were missing):
    # on noisy outputs a heavier prior pulls the determined parameters towards its own.
    tau = Y2 @ phi2 + 0.05 * rng.standard_normal(100)
    light = {"mass": 1.5, "center_of_mass": [0.2, 0.0, 0.0], "inertia": np.diag([0.03, 0.025, 0.015]).tolist()}
    fits = {}
    for weight in (1.0, 1e4):
        with pytest.warns(spdfit.SpdfitWarning, match="prior sets them"):
            fits[weight] = ph.regress(Y2, tau, bodies=2, prior=[light, light], prior_weight=weight)
    far = lambda f: abs(f["parameters"][1] - 1.5 * 0.2)  # noqa: E731 (m c_x against the prior's)
    assert far(fits[1e4]) < far(fits[1.0])
    with pytest.raises(ValueError, match="with_prior|prior"):
        ph.regress(Y, Y @ phi, prior=[body], unconstrained=True)
    with pytest.raises(ValueError, match="give `prior`|prior"):
        ph.regress(Y, Y @ phi, prior_weight=2.0)
