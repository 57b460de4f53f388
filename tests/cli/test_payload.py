"""`spdfit payload identify` and `payload design` against independent references: the NumPy wrench
model of tests/support/payload_reference.py (never spdfit's), NumPy/SciPy least squares, SciPy's
bounded least squares and CVXOPT's cone QP for the constrained fits; the orientation's forms
agree; bad input gets clear errors with the documented exit statuses."""
import json

import numpy as np
import pytest
from spdfit_testing import SANITIZED

from payload_reference import (G, eiv_criterion, inertia_about_origin, pseudo_inertia, random_quaternions, regressor,
                               rotation_from_quaternion, static_log, trajectory, wrench, write_log)

FORCE = ["fx", "fy", "fz", "tx", "ty", "tz"]
QUAT = ["qx", "qy", "qz", "qw"]


def identify(spdfit, log, *options):
    result = spdfit("payload", "identify", str(log), "--json", *options)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout), result.stderr


def static_file(tmp_path, log, name="static.csv"):
    return write_log(tmp_path / name, [(FORCE, log["wrench"]), (QUAT, log["quaternion"]),
                                       (["gx", "gy", "gz"], log["gravity"])])


STATIC = ("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw")


def test_static_noise_free_to_1e_9(spdfit, tmp_path):
    log = static_log(np.random.default_rng(1), 12, noise=None)
    out, _ = identify(spdfit, static_file(tmp_path, log), *STATIC)
    assert out["model"] == "static" and out["inertia"] is None
    assert out["mass"] == pytest.approx(1.2, rel=1e-9)
    np.testing.assert_allclose(out["center_of_mass"], [0.08, 0.0, 0.03], rtol=0, atol=1e-10)
    np.testing.assert_allclose(out["force_bias"] + out["torque_bias"], [5.0, -2.0, 1.0, 0.3, -0.1, 0.2],
                               rtol=1e-9, atol=1e-12)
    assert max(out["residual_rms"]) < 1e-9
    assert out["physically_consistent"] and not out["constraint_active"]


def test_orientation_forms_agree(spdfit, tmp_path):
    rng = np.random.default_rng(2)
    log = static_log(rng, 15)
    q = log["quaternion"]
    R = np.array([rotation_from_quaternion(qi).ravel() for qi in q])
    path = write_log(tmp_path / "forms.csv", [(FORCE, log["wrench"]), (QUAT, q), (["qw2", "qx2", "qy2", "qz2"],
                                              q[:, [3, 0, 1, 2]]), ([f"r{i}" for i in range(9)], R),
                                              (["gx", "gy", "gz"], log["gravity"])])
    forms = [("--quat-cols", "qx:qw"), ("--quat-cols", "qw2:qz2", "--quat-order", "wxyz"),
             ("--rotation-cols", "r0:r8"), ("--gravity-cols", "gx:gz")]
    results = [identify(spdfit, path, "--wrench-cols", "fx:tz", *form)[0] for form in forms]
    for r in results[1:]:
        np.testing.assert_allclose(r["parameters"], results[0]["parameters"], rtol=1e-12, atol=1e-14)
    # 1-based positions select the same columns as names.
    by_position = identify(spdfit, path, "--wrench-cols", "1:6", "--quat-cols", "7:10")[0]
    np.testing.assert_allclose(by_position["parameters"], results[0]["parameters"], rtol=1e-14)


def test_noisy_static_is_numpy_least_squares_with_sandwich_errors(spdfit, tmp_path):
    rng = np.random.default_rng(3)
    log = static_log(rng, 40)
    out, _ = identify(spdfit, static_file(tmp_path, log), *STATIC)
    X = regressor(-log["gravity"])
    w = log["wrench"].ravel()
    phi, *_ = np.linalg.lstsq(X, w, rcond=None)
    np.testing.assert_allclose(out["parameters"], phi, rtol=1e-9, atol=1e-12)
    assert out["unconstrained_mass"] == pytest.approx(phi[0], rel=1e-10)
    # The sandwich (HC1 over samples) computed here.
    r = X @ phi - w
    bread = np.linalg.inv(X.T @ X)
    meat = sum(np.outer(X[6 * k:6 * k + 6].T @ r[6 * k:6 * k + 6], X[6 * k:6 * k + 6].T @ r[6 * k:6 * k + 6])
               for k in range(40))
    cov = bread @ meat @ bread * (240 / (240 - 10))
    np.testing.assert_allclose(out["parameter_standard_errors"], np.sqrt(np.diag(cov)), rtol=1e-8)
    # Centre of mass by the delta method.
    m, h = phi[0], phi[1:4]
    J = np.hstack([-h[:, None] / m ** 2, np.eye(3) / m])
    np.testing.assert_allclose(out["standard_errors"]["center_of_mass"], np.sqrt(np.diag(J @ cov[:4, :4] @ J.T)),
                               rtol=1e-8)
    np.testing.assert_allclose(out["residual_rms"], np.sqrt(np.mean(r.reshape(-1, 6) ** 2, axis=0)), rtol=1e-9)


def test_light_tool_meets_m_nonnegative_as_scipy_bounded_least_squares(spdfit, tmp_path):
    optimize = pytest.importorskip("scipy.optimize")
    around = np.array([0.0, 0.0, 0.0, 1.0])
    for seed in range(40):
        rng = np.random.default_rng(seed)
        q = random_quaternions(rng, 6, spread=np.radians(10), around=around)
        log = static_log(rng, 6, mass=0.03, com=(0.0, 0.0, 0.02), quaternions=q)
        X = regressor(-log["gravity"])
        w = log["wrench"].ravel()
        phi_ls, *_ = np.linalg.lstsq(X, w, rcond=None)
        if phi_ls[0] < 0:
            break
    else:
        pytest.fail("no seed gave a negative unconstrained mass")
    path = static_file(tmp_path, log)
    out, err = identify(spdfit, path, *STATIC)
    bounded = optimize.lsq_linear(X, w, bounds=([0] + [-np.inf] * 9, [np.inf] * 10), tol=1e-14, lsmr_tol=1e-14,
                                  method="bvls")
    assert out["mass"] == 0.0 and out["constraint_active"]
    np.testing.assert_allclose(out["parameters"][1:], bounded.x[1:], rtol=1e-7, atol=1e-10)
    assert out["criterion_value"] <= np.sum((X @ bounded.x - w) ** 2) * (1 + 1e-9)
    assert "constraint m >= 0 is active" in err
    # KKT: the gradient along m is >= 0 at m = 0, zero along the others.
    assert out["certificate"]["dual_min_eig"] >= -1e-9 and out["certificate"]["stationarity"] < 1e-6
    unconstrained, _ = identify(spdfit, path, *STATIC, "--unconstrained")
    np.testing.assert_allclose(unconstrained["parameters"], phi_ls, rtol=1e-9, atol=1e-12)


def moving_columns(log_t, omega, alpha, accel, q, w):
    return [("t", log_t), (FORCE, w), (QUAT, q), (["ax", "ay", "az"], accel), (["wx", "wy", "wz"], omega),
            (["alx", "aly", "alz"], alpha)]


MOVING = ("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw", "--accel-cols", "ax:az", "--omega-cols", "wx:wz",
          "--alpha-cols", "alx:alz")


def moving_log(rng, n, mass=2.5, com=(0.02, -0.01, 0.06), inertia=np.diag([0.012, 0.02, 0.015]),
               bias=(1.0, 2.0, -3.0, 0.1, 0.05, -0.2)):
    t, omega, alpha, accel, q = trajectory(rng, n)
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    w = -wrench(mass, com, inertia, accel - g_s, omega, alpha) + np.asarray(bias)
    return t, omega, alpha, accel, q, w


def test_moving_noise_free_determines_all_16_to_1e_9(spdfit, tmp_path):
    rng = np.random.default_rng(4)
    t, omega, alpha, accel, q, w = moving_log(rng, 300)
    path = write_log(tmp_path / "moving.csv", moving_columns(t, omega, alpha, accel, q, w))
    out, _ = identify(spdfit, path, *MOVING)
    assert out["model"] == "moving" and out["rank"] == 16
    assert out["mass"] == pytest.approx(2.5, rel=1e-9)
    np.testing.assert_allclose(out["center_of_mass"], [0.02, -0.01, 0.06], atol=1e-11)
    np.testing.assert_allclose(out["inertia"], np.diag([0.012, 0.02, 0.015]), atol=1e-11)
    np.testing.assert_allclose(out["force_bias"] + out["torque_bias"], [1.0, 2.0, -3.0, 0.1, 0.05, -0.2],
                               rtol=1e-9, atol=1e-11)
    np.testing.assert_allclose(np.sort(out["principal_moments"]), [0.012, 0.015, 0.02], rtol=1e-9)
    # Errors in variables on the same exact data: the criterion is 0 at least squares' fit, its
    # minimum; it used to chase the rounding for 500 Newton steps and warn that it had not converged.
    eiv, err = identify(spdfit, path, *MOVING, "--criterion", "eiv", "--noise-std-wrench", "0.2,0.01",
                        "--noise-std-accel", "0.1", "--noise-std-omega", "0.01", "--noise-std-alpha", "0.05")
    assert eiv["converged"] and "not converge" not in err
    assert eiv["mass"] == pytest.approx(2.5, rel=1e-9)
    np.testing.assert_allclose(eiv["inertia"], np.diag([0.012, 0.02, 0.015]), atol=1e-11)


def test_alpha_from_omega_by_central_differences(spdfit, tmp_path):
    rng = np.random.default_rng(5)
    t, omega, alpha, accel, q, w = moving_log(rng, 4000)
    path = write_log(tmp_path / "moving.csv", moving_columns(t, omega, alpha, accel, q, w))
    options = [o for o in MOVING if o not in ("--alpha-cols", "alx:alz")]
    out, err = identify(spdfit, path, *options, "--time-col", "t")
    assert "central differences" in err
    # The differences' error is O(dt^2 omega'''), small against the inertia here.
    np.testing.assert_allclose(out["inertia"], np.diag([0.012, 0.02, 0.015]), atol=2e-4)
    assert out["mass"] == pytest.approx(2.5, rel=1e-6)
    bad = spdfit("payload", "identify", str(path), *options)
    assert bad.returncode == 2 and "--time-col" in bad.stderr


def test_frame_base_and_specific_force_agree(spdfit, tmp_path):
    rng = np.random.default_rng(6)
    t, omega, alpha, accel, q, w = moving_log(rng, 200)
    R = [rotation_from_quaternion(qi) for qi in q]
    w_base = np.hstack([np.array([Ri @ wi[:3] for Ri, wi in zip(R, w)]), np.array([Ri @ wi[3:] for Ri, wi in zip(R, w)])])
    specific = accel - np.array([Ri.T @ G for Ri in R])
    path = write_log(tmp_path / "m.csv", moving_columns(t, omega, alpha, accel, q, w) +
                     [(["bfx", "bfy", "bfz", "btx", "bty", "btz"], w_base), (["sx", "sy", "sz"], specific)])
    reference, _ = identify(spdfit, path, *MOVING)
    base, _ = identify(spdfit, path, "--frame", "base", "--wrench-cols", "bfx:btz", *MOVING[2:])
    np.testing.assert_allclose(base["parameters"], reference["parameters"], rtol=1e-9, atol=1e-12)
    imu, _ = identify(spdfit, path, "--wrench-cols", "fx:tz", "--specific-force-cols", "sx:sz", "--omega-cols",
                      "wx:wz", "--alpha-cols", "alx:alz")
    np.testing.assert_allclose(imu["parameters"], reference["parameters"], rtol=1e-9, atol=1e-12)
    twice = spdfit("payload", "identify", str(path), *MOVING, "--specific-force-cols", "sx:sz")
    assert twice.returncode == 2 and "twice" in twice.stderr


def cvxopt_constrained_least_squares(X, w):
    """min ||X phi - w||^2 over phi = (m, h, I_S, b) with the pseudo-inertia J(phi) >= 0 (CVXOPT's
    cone QP with one 4 x 4 semidefinite cone), from the columns scaled to unit norm."""
    cvxopt = pytest.importorskip("cvxopt")
    from cvxopt import matrix, solvers
    scale = 1.0 / np.linalg.norm(X, axis=0)
    Xs = X * scale
    P = 2 * Xs.T @ Xs
    q = -2 * Xs.T @ w
    # J(phi) in the columns of the 4 x 4 (column-major) semidefinite cone: s = h - G x = J.
    basis = {0: (0, 0), 1: (1, 1), 2: (2, 2), 3: (0, 1), 4: (0, 2), 5: (1, 2)}
    Gm = np.zeros((16, 16))
    for j in range(16):
        phi = np.zeros(16)
        phi[j] = scale[j]
        m, h = phi[0], phi[1:4]
        I = np.array([[phi[4], phi[5], phi[6]], [phi[5], phi[7], phi[8]], [phi[6], phi[8], phi[9]]])
        J = np.zeros((4, 4))
        J[:3, :3] = 0.5 * np.trace(I) * np.eye(3) - I
        J[:3, 3] = J[3, :3] = h
        J[3, 3] = m
        Gm[:, j] = -J.ravel(order="F")
    solvers.options.update({"show_progress": False, "abstol": 1e-13, "reltol": 1e-13, "feastol": 1e-13,
                            "maxiters": 200})
    sol = solvers.coneqp(matrix(P), matrix(q), matrix(Gm), matrix(np.zeros(16)), {"l": 0, "q": [], "s": [4]})
    phi = np.array(sol["x"]).ravel() * scale
    return phi, np.sum((X @ phi - w) ** 2)


def test_moving_constrained_matches_cvxopt_on_a_thin_rod(spdfit, tmp_path):
    rng = np.random.default_rng(7)
    # A thin rod along z: its inertia about the centre of mass has one moment ~ 0, so noise pushes the
    # unconstrained fit outside the cone.
    rod = np.diag([0.02, 0.02, 1e-7])
    t, omega, alpha, accel, q, w0 = moving_log(rng, 150, mass=1.0, com=(0.0, 0.0, 0.1), inertia=rod)
    w = w0 + np.hstack([0.2 * rng.standard_normal((150, 3)), 0.01 * rng.standard_normal((150, 3))])
    path = write_log(tmp_path / "rod.csv", moving_columns(t, omega, alpha, accel, q, w))
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    X = regressor(accel - g_s, omega, alpha, moving=True)
    unconstrained, _ = identify(spdfit, path, *MOVING, "--unconstrained")
    out, err = identify(spdfit, path, *MOVING)
    phi_ref, f_ref = cvxopt_constrained_least_squares(X, w.ravel())
    assert out["criterion_value"] <= f_ref * (1 + 1e-6)
    assert out["physically_consistent"]
    if not unconstrained["physically_consistent"]:
        assert out["constraint_active"]
        np.testing.assert_allclose(out["parameters"], phi_ref, rtol=0, atol=2e-3 * np.abs(phi_ref).max())
    assert out["certificate"]["dual_min_eig"] >= -1e-8 and out["certificate"]["duality_gap"] < 1e-9


def test_errors_in_variables_without_pose_noise_is_weighted_least_squares(spdfit, tmp_path):
    rng = np.random.default_rng(8)
    t, omega, alpha, accel, q, w0 = moving_log(rng, 200)
    w = w0 + np.hstack([0.2 * rng.standard_normal((200, 3)), 0.01 * rng.standard_normal((200, 3))])
    path = write_log(tmp_path / "m.csv", moving_columns(t, omega, alpha, accel, q, w))
    ls, _ = identify(spdfit, path, *MOVING, "--noise-std-wrench", "0.2,0.01")
    eiv, _ = identify(spdfit, path, *MOVING, "--noise-std-wrench", "0.2,0.01", "--criterion", "eiv",
                      "--noise-std-accel", "0", "--noise-std-omega", "0", "--noise-std-alpha", "1e-12")
    np.testing.assert_allclose(eiv["parameters"], ls["parameters"], rtol=1e-6, atol=1e-9)
    # Weighted least squares in NumPy.
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    X = regressor(accel - g_s, omega, alpha, moving=True)
    weights = np.tile(1 / np.array([0.2] * 3 + [0.01] * 3), 200)
    phi, *_ = np.linalg.lstsq(X * weights[:, None], w.ravel() * weights, rcond=None)
    if ls["physically_consistent"] and not ls["constraint_active"]:
        np.testing.assert_allclose(ls["parameters"], phi, rtol=1e-8, atol=1e-11)


def test_errors_in_variables_on_a_long_log_is_a_minimum_of_the_numpy_criterion(spdfit, tmp_path):
    """40,000 rows (long enough that the fit starts from a subsample's): the estimate minimizes an
    independent NumPy evaluation of the criterion along every parameter (the first difference
    across one standard error vanishes beside the second), and least squares' estimate does not."""
    rng = np.random.default_rng(21)
    n = 40_000
    t, omega, alpha, accel, q, w = moving_log(rng, n)
    w = w + np.hstack([0.2 * rng.standard_normal((n, 3)), 0.01 * rng.standard_normal((n, 3))])
    std = [0.2 * np.sqrt(np.mean(x ** 2)) for x in (accel, omega, alpha)]
    noisy = [x + sd * rng.standard_normal(x.shape) for x, sd in zip((accel, omega, alpha), std)]
    path = write_log(tmp_path / "long.csv", moving_columns(t, noisy[1], noisy[2], noisy[0], q, w))
    options = (*MOVING, "--noise-std-wrench", "0.2,0.01", "--noise-std-accel", str(std[0]),
               "--noise-std-omega", str(std[1]), "--noise-std-alpha", str(std[2]), "--unconstrained")
    eiv, _ = identify(spdfit, path, *options, "--criterion", "eiv")
    ls, _ = identify(spdfit, path, *options)
    assert eiv["converged"]
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    s = noisy[0] - g_s
    noise_w = np.diag([0.04] * 3 + [1e-4] * 3)
    noise_x = np.diag(np.repeat(np.square(std), 3))

    def criterion(phi):
        return eiv_criterion(phi, w, s, noisy[1], noisy[2], noise_w, noise_x)

    phi = np.array(eiv["parameters"])
    at = criterion(phi)
    assert at == pytest.approx(eiv["criterion_value"], rel=1e-9)
    se = np.array(eiv["parameter_standard_errors"])

    def stationarity(estimate, parameters):
        """|F(+h) - F(-h)| / (F(+h) + F(-h) - 2 F) along each parameter, h a tenth of its standard
        error: about |gradient| / (h curvature), plus h F3 / (3 F2) from the third derivative."""
        centre = criterion(estimate)
        ratios = []
        for a in parameters:
            step = np.zeros(16)
            step[a] = 0.1 * se[a]
            plus, minus = criterion(estimate + step), criterion(estimate - step)
            ratios.append(abs(plus - minus) / (plus + minus - 2 * centre))
        return np.array(ratios)

    assert stationarity(phi, range(16)).max() < 1e-3
    # The check can fail: least squares' inertia is biased by the noise in the signals.
    assert stationarity(np.array(ls["parameters"]), range(4, 10)).max() > 10.0


@pytest.mark.skipif(SANITIZED, reason="a statistical comparison of 12 fits of 3000 rows: the plain build checks it")
def test_errors_in_variables_removes_the_attenuation_of_noisy_signals(spdfit, tmp_path):
    """Few trials, each with strong noise in alpha: least squares shrinks the inertia (attenuation
    by about 1 / (1 + noise variance / signal variance)); errors in variables does not."""
    ls_errors, eiv_errors = [], []
    inertia = np.diag([0.12, 0.2, 0.15])
    for seed in range(3):
        rng = np.random.default_rng(100 + seed)
        t, omega, alpha, accel, q, w = moving_log(rng, 3000, mass=4.0, inertia=inertia)
        noise = 0.3 * alpha.std(axis=0)
        alpha_measured = alpha + noise * rng.standard_normal(alpha.shape)
        w = w + np.hstack([0.05 * rng.standard_normal((3000, 3)), 0.002 * rng.standard_normal((3000, 3))])
        path = write_log(tmp_path / f"n{seed}.csv", moving_columns(t, omega, alpha_measured, accel, q, w))
        common = (*MOVING, "--noise-std-wrench", "0.05,0.002", "--noise-std-alpha", ",".join(map(str, noise)),
                  "--noise-std-accel", "1e-9", "--noise-std-omega", "1e-9")
        ls, _ = identify(spdfit, path, *common)
        eiv, _ = identify(spdfit, path, *common, "--criterion", "eiv")
        ls_errors.append(np.linalg.norm(np.array(ls["inertia"]) - inertia))
        eiv_errors.append(np.linalg.norm(np.array(eiv["inertia"]) - inertia))
    assert np.mean(eiv_errors) < 0.5 * np.mean(ls_errors), (ls_errors, eiv_errors)


def test_two_orientations_leave_a_named_combination(spdfit, tmp_path):
    rng = np.random.default_rng(9)
    q = random_quaternions(rng, 2)
    log = static_log(rng, 10, quaternions=np.repeat(q, 5, axis=0))
    out, err = identify(spdfit, static_file(tmp_path, log), *STATIC)
    assert out["rank"] == 9 and len(out["undetermined"]) == 1
    assert "do not determine 1 combination" in err and "2 distinct gravity directions" in err
    # The warning's code beside its text: the undetermined combination is a rank deficiency.
    assert len(out["warning_codes"]) == len(out["warnings"]) and "rank_deficient" in out["warning_codes"]
    # NumPy's null space of the regressor is the same combination.
    X = regressor(-log["gravity"])
    scale = np.linalg.norm(X, axis=0)
    null = np.linalg.svd(X / scale)[2][-1] / scale
    null /= np.linalg.norm(null)
    reported = np.array(out["undetermined"][0]["coefficients"])
    assert abs(abs(null @ reported) - 1) < 1e-8
    assert set(out["undetermined"][0]["parameters"]) <= {"mc_x", "mc_y", "mc_z", "b_tx", "b_ty", "b_tz"}
    assert out["mass"] == pytest.approx(1.2, rel=0.05)  # the mass is determined
    assert any(c is None for c in out["center_of_mass"])


def test_wrench_sign(spdfit, tmp_path):
    rng = np.random.default_rng(10)
    log = static_log(rng, 12)
    applied = dict(log, wrench=-log["wrench"])
    path = static_file(tmp_path, applied, "applied.csv")
    wrong = spdfit("payload", "identify", str(path), *STATIC)
    assert wrong.returncode == 1 and "--wrench-sign applied" in wrong.stderr
    out, _ = identify(spdfit, path, *STATIC, "--wrench-sign", "applied")
    assert out["mass"] == pytest.approx(1.2, rel=0.02)


def test_quaternion_norms(spdfit, tmp_path):
    rng = np.random.default_rng(11)
    log = static_log(rng, 12, noise=None)
    slightly = dict(log, quaternion=log["quaternion"] * 1.002)
    out, err = identify(spdfit, static_file(tmp_path, slightly, "a.csv"), *STATIC)
    assert "normalized" in err and out["mass"] == pytest.approx(1.2, rel=1e-9)
    far = log["quaternion"].copy()
    far[4] *= 1.3
    bad = spdfit("payload", "identify", str(static_file(tmp_path, dict(log, quaternion=far), "b.csv")), *STATIC)
    assert bad.returncode == 1 and "row 5" in bad.stderr and "norm 1.3" in bad.stderr


@pytest.mark.parametrize("options,status,message", [
    (("--wrench-cols", "fx:tx", "--quat-cols", "qx:qw"), 2, "selects 4 columns"),
    (("--wrench-cols", "fx:tz"), 2, "orientation"),
    (("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw", "--criterion", "eiv"), 2, "--noise-std-wrench"),
    (("--wrench-cols", "fx:tz", "--gravity-cols", "gx:gz", "--frame", "base"), 2, "--frame base"),
    (("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw", "--gravity", "0,0"), 2, "3 numbers"),
    (("--wrench-cols", "fx:tz", "--quat-cols", "nope:qw"), 2, "nope"),
    (("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw", "--rows", "50:"), 1, "beyond"),  # the data error fit gives
    (("--wrench-cols", "fx:tz", "--quat-cols", "qx:qw", "--quat-order", "zyx"), 2, "'xyzw' or 'wxyz'"),
])
def test_usage_errors(spdfit, tmp_path, options, status, message):
    path = static_file(tmp_path, static_log(np.random.default_rng(12), 10))
    result = spdfit("payload", "identify", str(path), *options)
    assert result.returncode == status, result.stderr
    assert message in result.stderr


def test_nan_is_a_data_error(spdfit, tmp_path):
    log = static_log(np.random.default_rng(13), 10)
    log["wrench"][3, 2] = np.nan
    result = spdfit("payload", "identify", str(static_file(tmp_path, log)), *STATIC)
    assert result.returncode == 1 and "static.csv" in result.stderr


def test_rows_rest_rows_bootstrap_and_report(spdfit, tmp_path):
    rng = np.random.default_rng(14)
    log = static_log(rng, 60)
    path = static_file(tmp_path, log)
    part, _ = identify(spdfit, path, *STATIC, "--rows", "1:30")
    X = regressor(-log["gravity"][:30])
    phi, *_ = np.linalg.lstsq(X, log["wrench"][:30].ravel(), rcond=None)
    np.testing.assert_allclose(part["parameters"], phi, rtol=1e-9, atol=1e-12)
    boot, _ = identify(spdfit, path, *STATIC, "--bootstrap", "200", "--seed", "3")
    assert boot["bootstrap"]["replicates"] == 200
    se_boot, se = boot["bootstrap_standard_errors"]["mass"], boot["standard_errors"]["mass"]
    assert 0.5 < se_boot / se < 2.0
    lower, upper = boot["interval"]["lower"]["mass"], boot["interval"]["upper"]["mass"]
    assert lower < boot["mass"] < upper
    text = spdfit("payload", "identify", str(path), *STATIC)
    assert text.returncode == 0 and "mass" in text.stdout and "+-" in text.stdout


def test_rows_beyond_the_log_are_refused_as_fit_refuses_them(spdfit, tmp_path):
    # `rows` as fit has them: a range reaching past the last row is the file's data error (exit 1,
    # naming the file), not a silent cut to the rows there are; bad syntax is a usage error.
    log = static_log(np.random.default_rng(15), 20)
    path = static_file(tmp_path, log)
    for rows in ("1:50", "30:50"):
        result = spdfit("payload", "identify", str(path), *STATIC, "--rows", rows)
        assert result.returncode == 1, (rows, result.stderr)
        assert "static.csv" in result.stderr and "row 50 is beyond the 20 data rows" in result.stderr
    fit = spdfit("fit", "--method", "ls", "--a-cols", "fx:fz", "--b-cols", "tx:tz", "--rows", "1:50", str(path))
    assert fit.returncode == 1 and "row 50 is beyond the 20 data rows" in fit.stderr
    for rows in ("0:5", "5:2", "abc"):
        assert spdfit("payload", "identify", str(path), *STATIC, "--rows", rows).returncode == 2, rows
    whole, _ = identify(spdfit, path, *STATIC, "--rows", "1:20")
    plain, _ = identify(spdfit, path, *STATIC)
    assert whole["parameters"] == plain["parameters"]


def test_robust_fits_resist_gross_errors_and_huber_solves_its_estimating_equation(spdfit, tmp_path):
    # 200 static poses, 4 of them (2 %) with a 40 N spike on one force axis (200 standard deviations).
    rng = np.random.default_rng(21)
    clean = static_log(rng, 200)
    log = {key: value.copy() for key, value in clean.items()}
    bad = rng.choice(200, 4, replace=False)
    log["wrench"][bad, rng.integers(0, 3, 4)] += 40.0
    path = static_file(tmp_path, log)
    noise = ("--noise-std-wrench", "0.2,0.01")
    truth = np.array([1.2, 1.2 * 0.08, 0.0, 1.2 * 0.03, 5.0, -2.0, 1.0, 0.3, -0.1, 0.2])
    reference, _ = identify(spdfit, static_file(tmp_path, clean, "clean.csv"), *STATIC, *noise)
    plain, _ = identify(spdfit, path, *STATIC, *noise)
    huber, _ = identify(spdfit, path, *STATIC, *noise, "--robust", "huber")
    tukey, _ = identify(spdfit, path, *STATIC, *noise, "--robust", "tukey")
    error = lambda fit: np.linalg.norm(np.array(fit["parameters"]) - truth)  # noqa: E731
    # Measured on seeds 21-26: plain 19-47, Huber 0.66-1.42, Tukey 0.84-1.21 times the clean fit's error.
    assert error(plain) > 10 * error(reference)
    assert error(huber) < 2.0 * error(reference) and error(tukey) < 1.5 * error(reference)
    assert set(bad + 1) <= set(huber["robust"]["rows_downweighted"])  # data rows, numbered as --rows numbers them
    assert tukey["robust"]["method"] == "tukey" and tukey["robust"]["weights_min"] == 0.0
    # Huber's M-estimate solves sum_k psi(u_k / s) du_k/dphi = 0, u_k the sample's residual wrench
    # whitened by the noise (0.2 N, 0.01 N m), s = median(u) / median of chi(6): with the weights
    # psi(t) / t = min(1, k / t) of its own residuals, the weighted normal equations hold.
    from scipy.stats import chi
    X = regressor(-log["gravity"])
    phi = np.array(huber["parameters"])
    white = np.tile([1 / 0.2] * 3 + [1 / 0.01] * 3, 200)
    r = (white * (X @ phi - log["wrench"].ravel())).reshape(200, 6)
    u = np.linalg.norm(r, axis=1)
    scale = np.median(u) / chi(6).median()
    k = huber["robust"]["tuning"]
    assert scale == pytest.approx(huber["robust"]["scale"], rel=1e-6)
    w = np.minimum(1.0, k / (u / scale))
    Xw = white[:, None] * X
    gradient = Xw.T @ (np.repeat(w, 6) * r.ravel())
    # (2e-7 measured: the reweighting stops when the parameters move by 1e-8; the plain fit gives 0.12)
    assert np.linalg.norm(gradient) < 1e-5 * np.linalg.norm(Xw.T @ (np.repeat(w, 6) * np.abs(r.ravel())))


def test_urdf_export_reads_back_and_static_refuses(spdfit, tmp_path):
    rng = np.random.default_rng(15)
    t, omega, alpha, accel, q, w = moving_log(rng, 200)
    path = write_log(tmp_path / "m.csv", moving_columns(t, omega, alpha, accel, q, w))
    urdf = tmp_path / "payload.urdf"
    out, _ = identify(spdfit, path, *MOVING, "--urdf", str(urdf), "--link-name", "gripper")
    text = urdf.read_text()
    assert '<link name="gripper">' in text and 'mass value="2.5"' in text
    # The repair reads it (wrapped in a robot) and finds it consistent.
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r">\n' + text + "</robot>\n")
    repaired = spdfit("inertia", "repair", str(robot))
    assert repaired.returncode == 0 and "consistent" in repaired.stderr
    # inertia repair reads the identify JSON too.
    estimate = tmp_path / "estimate.json"
    estimate.write_text(json.dumps(out))
    assert spdfit("inertia", "repair", str(estimate)).returncode == 0
    static = static_file(tmp_path, static_log(rng, 10))
    refused = spdfit("payload", "identify", str(static), *STATIC, "--urdf", str(tmp_path / "x.urdf"))
    assert refused.returncode == 2 and "static poses" in refused.stderr


def test_design_beats_random_choices(spdfit, tmp_path):
    rng = np.random.default_rng(16)
    q = random_quaternions(rng, 500)
    path = write_log(tmp_path / "candidates.csv", [(QUAT, q)])
    chosen = tmp_path / "chosen.csv"
    result = spdfit("payload", "design", str(path), "--poses", "6", "--quat-cols", "qx:qw", "--random", "300",
                    "--json", "-o", str(chosen))
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert len(out["chosen"]) == 6 and out["se_mass"] <= out["random"]["se_mass"][0]
    # The predicted standard error of m from NumPy's information matrix of the chosen rows.
    g = np.array([rotation_from_quaternion(qi).T @ G for qi in q[np.array(out["chosen"]) - 1]])
    X = regressor(-g)
    assert out["se_mass"] == pytest.approx(np.sqrt(np.linalg.inv(X.T @ X)[0, 0]), rel=1e-9)
    rows = np.loadtxt(chosen, delimiter=",", skiprows=1)
    np.testing.assert_allclose(rows, q[np.array(out["chosen"]) - 1], rtol=0, atol=0)
    for criterion in ("E", "A"):
        r = spdfit("payload", "design", str(path), "--poses", "6", "--quat-cols", "qx:qw", "--criterion", criterion,
                   "--random", "50", "--json")
        assert r.returncode == 0 and len(json.loads(r.stdout)["chosen"]) == 6
    # Two poses leave the information singular, yet the mass is determined (identify says so): its
    # predicted standard error is sqrt(e_m^T F^+ e_m) by NumPy's pseudo-inverse, not infinite.
    two = spdfit("payload", "design", str(path), "--poses", "2", "--quat-cols", "qx:qw", "--random", "50", "--json")
    assert two.returncode == 0, two.stderr
    out = json.loads(two.stdout)
    g = np.array([rotation_from_quaternion(qi).T @ G for qi in q[np.array(out["chosen"]) - 1]])
    X = regressor(-g)
    assert np.linalg.matrix_rank(X.T @ X) < 10 and out["log_det"] is None
    assert out["se_mass"] == pytest.approx(np.sqrt(np.linalg.pinv(X.T @ X)[0, 0]), rel=1e-6)
