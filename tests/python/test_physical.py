"""Physical identification of a hexapod payload (spdfit.physical) against an independent NumPy/SciPy
reference: the model M_p(m, c, I) and the errors-in-variables criterion written out in NumPy, a
reference optimizer (SciPy's BFGS on a Cholesky factor of the pseudo-inertia, several starts) that
spdfit's estimate must match or beat, the first-order conditions by finite differences, exact
recovery from noise-free data, consistency (the error falls like 1/sqrt(m)), invariance under a
change of units with the noise converted alike, and clear errors for bad input."""
import json

import numpy as np
import pytest
import scipy.optimize

import spdfit
import spdfit.hexapod as hx
import spdfit.physical as ph

# The estimate minimizes the criterion to rounding; the reference stops at SciPy's gradient
# tolerance, so spdfit's criterion must be at most the reference's, to this relative slack.
CRITERION_SLACK = 1e-10
# Noise-free data: every identifiable parameter comes back to this relative accuracy (the goal).
RECOVERY = 1e-9
# Units: kg/m and g/mm fits agree to this relative accuracy (the goal).
UNITS = 1e-9
NOISE_VAR = 3.2 ** 2 / 12  # the thesis' experiment 2: uniform noise of width 3.2


# ---- the independent NumPy model -------------------------------------------------------------

def jacobian(g):
    q = np.asarray(g["base_points"], dtype=float)
    p = np.asarray(g["payload_points"], dtype=float)
    o = np.asarray(g["payload_origin"], dtype=float)
    R = np.asarray(g.get("payload_rotation", np.eye(3)), dtype=float)
    r = p @ R.T
    s = o + r - q
    u = s / np.linalg.norm(s, axis=1)[:, None]
    return np.hstack([u, np.cross(r, u)]), R


def cross(c):
    return np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])


def mass_matrix(g, mass, com, inertia, struts=None):
    """M_p = J^-T R M_x R^T J^-1 + diag(struts), M_x = [[m 1, -m[c]x], [m[c]x, I - m[c]x^2]]."""
    J, R = jacobian(g)
    C = cross(np.asarray(com, dtype=float))
    Mx = np.block([[mass * np.eye(3), -mass * C], [mass * C, np.asarray(inertia) - mass * C @ C]])
    Rb = np.kron(np.eye(2), R)
    Jinv = np.linalg.inv(J)
    s = np.broadcast_to(np.asarray(g["strut_mass"] if struts is None else struts, dtype=float), (6,))
    return Jinv.T @ Rb @ Mx @ Rb.T @ Jinv + np.diag(s)


def criterion(A, B, M, Sa=None, Sb=None):
    """sum_i r_i^T (M Sa M + Sb)^-1 r_i, r_i the rows of A M - B."""
    Sa = np.eye(6) if Sa is None else Sa
    Sb = np.eye(6) if Sb is None else Sb
    Rm = A @ M - B
    W = M @ Sa @ M + Sb
    return float(np.sum(Rm * np.linalg.solve(W, Rm.T).T))


def body_from_pseudo_inertia(P):
    """mass, centre of mass, inertia about it from the pseudo-inertia [[S, h], [h^T, m]]."""
    m = P[3, 3]
    c = P[:3, 3] / m
    Sc = P[:3, :3] - m * np.outer(c, c)
    return m, c, np.trace(Sc) * np.eye(3) - Sc


def pseudo_inertia(mass, com, inertia):
    com = np.asarray(com, dtype=float)
    Sc = 0.5 * np.trace(inertia) * np.eye(3) - np.asarray(inertia)
    P = np.zeros((4, 4))
    P[:3, :3] = Sc + mass * np.outer(com, com)
    P[:3, 3] = P[3, :3] = mass * com
    P[3, 3] = mass
    return P


def reference_fit(A, B, g, starts):
    """SciPy's BFGS on P = L L^T (L lower triangular: every P >= 0 and only those), from each start
    (a pseudo-inertia), scaled so that the parameters are of order one. The lowest criterion."""
    L_scale = np.sqrt(np.mean(np.sum(np.asarray(g["payload_points"], dtype=float) ** 2, axis=1)))
    D = np.diag([1 / L_scale] * 3 + [1.0])
    rows, cols = np.tril_indices(4)
    f_scale = criterion(A, B, np.zeros((6, 6)) + np.diag(np.broadcast_to(g["strut_mass"], (6,))))

    def unpack(x):
        L = np.zeros((4, 4))
        L[rows, cols] = x
        Ps = L @ L.T
        Dinv = np.linalg.inv(D)
        return Dinv @ Ps @ Dinv

    def objective(x):
        m, c, I = body_from_pseudo_inertia(unpack(x))
        if not m > 0:
            return np.inf
        return criterion(A, B, mass_matrix(g, m, c, I)) / f_scale

    best = None
    for P0 in starts:
        L0 = np.linalg.cholesky(D @ P0 @ D + 1e-12 * np.eye(4))
        res = scipy.optimize.minimize(objective, L0[rows, cols], method="BFGS", options={"gtol": 1e-10, "maxiter": 2000})
        value = res.fun * f_scale
        if best is None or value < best[0]:
            best = (value, body_from_pseudo_inertia(unpack(res.x)))
    return best


def as_dict(geometry):
    return json.loads(geometry.to_json())


def simulate(g, mass, com, inertia, samples, seed, noise_var=NOISE_VAR):
    truth = mass_matrix(g, mass, com, inertia)
    sim = hx.simulate(samples=samples, noise_var=noise_var, truth=truth, seed=seed)
    return sim.A, sim.B, truth


def asymmetric_geometry(seed=11):
    """The cubic hexapod with every joint moved by up to 2 cm and the payload turned: no two struts
    parallel, so that every strut's mass is identified."""
    rng = np.random.default_rng(seed)
    g = as_dict(hx.cubic_geometry())
    g["base_points"] = (np.asarray(g["base_points"]) + rng.uniform(-0.02, 0.02, (6, 3))).tolist()
    g["payload_points"] = (np.asarray(g["payload_points"]) + rng.uniform(-0.02, 0.02, (6, 3))).tolist()
    angle = 0.3
    g["payload_rotation"] = [[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]]
    g["strut_mass"] = [0.4, 0.5, 0.6, 0.45, 0.55, 0.35]
    return g


PAYLOAD = dict(mass=14.0, com=[0.012, -0.007, 0.021],
               inertia=np.array([[0.13, 0.004, -0.002], [0.004, 0.09, 0.006], [-0.002, 0.006, 0.11]]))


# ---- the tests ---------------------------------------------------------------------------------

def test_model_matches_numpy():
    g = as_dict(hx.cubic_geometry())
    ours = ph.mass_matrix(g, mass=PAYLOAD["mass"], center_of_mass=PAYLOAD["com"], inertia=PAYLOAD["inertia"])
    np.testing.assert_allclose(ours, mass_matrix(g, **PAYLOAD), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("samples, seed", [(12, 1), (12, 2), (30, 3), (100, 4)])
def test_at_least_as_good_as_a_reference_optimizer(samples, seed):
    g = as_dict(hx.cubic_geometry())
    A, B, _ = simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"], samples, seed)
    est = ph.identify(A, B, g)
    ours = criterion(A, B, est["M_p"])
    assert ours == pytest.approx(est["criterion"], rel=1e-9)
    nominal = pseudo_inertia(g["payload_mass"], [0, 0, 0], np.asarray(g["payload_inertia"]))
    starts = [nominal, 0.5 * nominal, pseudo_inertia(est["mass"], est["center_of_mass"], est["inertia"])
              + 1e-3 * np.eye(4)]
    ref_value, _ = reference_fit(A, B, g, starts)
    assert ours <= ref_value * (1 + CRITERION_SLACK)
    assert est["physically_consistent"]


def test_first_order_conditions_by_finite_differences():
    """At an interior estimate the criterion's gradient in the ten inertial parameters vanishes
    (relative to its size at the start of the scale), checked by central differences in NumPy."""
    g = as_dict(hx.cubic_geometry())
    A, B, _ = simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"], 200, 7)
    est = ph.identify(A, B, g)
    assert est["pseudo_inertia_min_eig"] > 0
    P = pseudo_inertia(est["mass"], est["center_of_mass"], est["inertia"])
    f0 = criterion(A, B, est["M_p"])
    rows, cols = np.triu_indices(4)
    gradient = []
    for i, j in zip(rows, cols):
        h = 1e-6 * abs(P[i, j]) + 1e-9
        E = np.zeros((4, 4))
        E[i, j] = E[j, i] = h
        values = [criterion(A, B, mass_matrix(g, *body_from_pseudo_inertia(P + s * E))) for s in (1, -1)]
        gradient.append((values[0] - values[1]) / (2 * h) * max(abs(P[i, j]), 1e-3))
    # Central differences: error ~ h^2 f''' + eps f / h, about 1e-9 f here.
    assert np.max(np.abs(gradient)) < 1e-6 * f0
    cert = est["certificate"]
    assert cert["stationarity"] < 1e-9 and abs(cert["complementarity"]) < 1e-10
    assert cert["primal_min_eig"] > 0 and cert["dual_min_eig"] > -1e-10


def test_exact_recovery_on_the_built_in_geometry():
    g = as_dict(hx.cubic_geometry())
    truth = mass_matrix(g, **PAYLOAD)
    A = np.random.default_rng(3).uniform(-5, 5, (40, 6))
    est = ph.identify(A, A @ truth, g)
    assert est["mass"] == pytest.approx(PAYLOAD["mass"], rel=RECOVERY)
    np.testing.assert_allclose(est["center_of_mass"], PAYLOAD["com"], rtol=RECOVERY)
    np.testing.assert_allclose(est["inertia"], PAYLOAD["inertia"], rtol=0, atol=RECOVERY * np.abs(PAYLOAD["inertia"]).max())
    np.testing.assert_array_equal(est["strut_mass"], np.broadcast_to(g["strut_mass"], (6,)))  # from the file


def test_exact_recovery_of_each_strut_mass_on_an_asymmetric_geometry():
    g = asymmetric_geometry()
    assert ph.design(g, "each")["rank"] == 16
    truth = mass_matrix(g, **PAYLOAD)
    A = np.random.default_rng(4).uniform(-5, 5, (60, 6))
    est = ph.identify(A, A @ truth, g, strut_masses="each")
    assert est["mass"] == pytest.approx(PAYLOAD["mass"], rel=RECOVERY)
    np.testing.assert_allclose(est["center_of_mass"], PAYLOAD["com"], rtol=RECOVERY)
    np.testing.assert_allclose(est["inertia"], PAYLOAD["inertia"], rtol=0, atol=RECOVERY * np.abs(PAYLOAD["inertia"]).max())
    np.testing.assert_allclose(est["strut_mass"], g["strut_mass"], rtol=RECOVERY)


def test_a_common_strut_mass_is_confounded_on_the_cubic_hexapod():
    d = ph.design(None, "common")
    assert (d["parameters"], d["rank"]) == (11, 10)
    A = np.random.default_rng(5).uniform(-5, 5, (40, 6))
    with pytest.raises(ValueError, match=r"fit_strut_mass = common cannot be estimated on this geometry: adding 1 kg"):
        ph.identify(A, A @ hx.thesis_mass_matrix(), hx.cubic_geometry(), strut_masses="common")


def test_error_falls_like_one_over_root_m():
    """Monte Carlo on the thesis' set-up: the RMS error of M_p at m = 4000 is a quarter of that at
    m = 250, to within three standard errors of the ratio (delta method)."""
    g = as_dict(hx.cubic_geometry())
    truth = mass_matrix(g, **PAYLOAD)
    trials = 60
    rms = {}
    for m in (250, 4000):
        errors = np.array([np.linalg.norm(ph.identify(*simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"],
                                                                 m, 1000 * m + k)[:2], g)["M_p"] - truth)
                           for k in range(trials)])
        rms[m] = (np.mean(errors ** 2), np.std(errors ** 2, ddof=1) / np.sqrt(trials))
    ratio = np.sqrt(rms[250][0] / rms[4000][0])
    # se of sqrt(a / b) by the delta method: (1/2) ratio sqrt((se_a / a)^2 + (se_b / b)^2).
    se = 0.5 * ratio * np.hypot(rms[250][1] / rms[250][0], rms[4000][1] / rms[4000][0])
    assert abs(ratio - 4.0) < 3 * se, (ratio, se)


def test_units_give_the_same_physical_answer_with_the_noise_converted():
    g = as_dict(hx.cubic_geometry())
    A, B, _ = simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"], 300, 9)
    Sa, Sb = NOISE_VAR * np.eye(6), NOISE_VAR * np.eye(6)
    si = ph.identify(A, B, g, noise_cov_a=Sa, noise_cov_b=Sb)
    # g and mm: lengths x 1e3, masses x 1e3, accelerations x 1e3, forces (g mm / s^2) x 1e6.
    mm = dict(g)
    for key in ("base_points", "payload_points", "payload_origin"):
        mm[key] = (np.asarray(g[key]) * 1e3).tolist()
    mm["payload_mass"] = g["payload_mass"] * 1e3
    mm["payload_inertia"] = (np.asarray(g["payload_inertia"]) * 1e9).tolist()
    mm["strut_mass"] = (np.asarray(g["strut_mass"]) * 1e3).tolist()
    mm["strut_stiffness"] = (np.asarray(g["strut_stiffness"]) * 1e3).tolist()
    mm["strut_damping"] = (np.asarray(g["strut_damping"]) * 1e3).tolist()
    small = ph.identify(A * 1e3, B * 1e6, mm, noise_cov_a=Sa * 1e6, noise_cov_b=Sb * 1e12)
    assert small["mass"] / 1e3 == pytest.approx(si["mass"], rel=UNITS)
    np.testing.assert_allclose(small["center_of_mass"] / 1e3, si["center_of_mass"], rtol=UNITS)
    np.testing.assert_allclose(small["inertia"] / 1e9, si["inertia"], rtol=UNITS, atol=UNITS * np.abs(si["inertia"]).max())
    np.testing.assert_allclose(small["M_p"] / 1e3, si["M_p"], rtol=UNITS, atol=UNITS * np.abs(si["M_p"]).max())
    # With the equal-noise default the implied noise ratio changes with the units (docs say so).
    default_si = ph.identify(A, B, g)
    default_mm = ph.identify(A * 1e3, B * 1e6, mm)
    assert abs(default_mm["mass"] / 1e3 - default_si["mass"]) > 1e-6 * default_si["mass"]


def test_bad_geometry_and_too_few_rows_are_clear_errors():
    g = as_dict(hx.cubic_geometry())
    bad = dict(g)
    bad["payload_points"] = [g["payload_points"][0]] * 6
    A = np.random.default_rng(6).uniform(-5, 5, (40, 6))
    with pytest.raises(ValueError, match="payload_points"):
        ph.identify(A, A, bad)
    # One row gives 6 forces for 10 parameters (three would already give 18).
    with pytest.raises(ValueError, match=r"the data cannot identify the payload's .*A has rank 1 of 6 \(m = 1 row\)"):
        ph.identify(A[:1], A[:1] @ hx.thesis_mass_matrix(), g)
    with pytest.raises(ValueError, match="m x 6"):
        ph.identify(A[:, :5], A[:, :5], g)
    with pytest.raises(ValueError, match="must be one of 'geometry', 'common' or 'each', got 'some'"):
        ph.identify(A, A, g, strut_masses="some")


def test_bootstrap_intervals_and_unconstrained_grey_box():
    g = as_dict(hx.cubic_geometry())
    A, B, _ = simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"], 400, 12)
    est = ph.identify(A, B, g, bootstrap=40, seed=3, threads=2)
    assert est["standard_errors"]["mass"] > 0
    assert est["interval"]["lower"]["mass"] < est["interval"]["upper"]["mass"]
    assert est["standard_errors"]["M_p"].shape == (6, 6)
    assert len(est["bootstrap"]["M_p_eigenvalues"]["estimate"]) == 6
    grey = ph.identify(A, B, g, consistent=False)
    assert grey["M_p"].shape == (6, 6)


def test_inertia_repair_is_the_eigenvalue_clip_up_to_the_floor():
    rng = np.random.default_rng(8)
    for _ in range(20):
        Q, _r = np.linalg.qr(rng.standard_normal((3, 3)))
        I = Q @ np.diag([rng.uniform(0.05, 0.2), rng.uniform(0.1, 0.3), rng.uniform(0.6, 1.0)]) @ Q.T
        I = 0.5 * (I + I.T)
        for rel in (0.0, 1e-6):
            r = ph.inertia_repair(3.0, [0.1, 0.2, 0.3], I, min_eig_rel=rel, metric="second-moment")
            S = 0.5 * np.trace(I) * np.eye(3) - I
            w, V = np.linalg.eigh(S)
            floor = rel * np.abs(w).max()
            Sp = V @ np.diag(np.maximum(w, floor)) @ V.T
            np.testing.assert_allclose(r["inertia"], np.trace(Sp) * np.eye(3) - Sp, rtol=0, atol=1e-14)
            assert r["changed"] and r["mass"] == 3.0
            assert r["distance"] == pytest.approx(np.linalg.norm(np.trace(Sp) * np.eye(3) - Sp - I), abs=1e-14)
    consistent = ph.inertia_repair(1.0, [0, 0, 0], np.diag([0.3, 0.4, 0.5]))
    assert not consistent["changed"] and consistent["distance"] == 0.0


URDF = """<?xml version="1.0"?>
<!-- a robot: two links break the triangle inequality -->
<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base">
    <inertial><origin xyz="0 0 0.1" rpy="0.1 0 0"/><mass value="3"/>
      <inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0" izz="0.25"/></inertial>
  </link>
  <link name="upper">
    <inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.05"/></inertial>
    <collision><geometry><cylinder radius="0.1" length="0.5"/></geometry></collision>
  </link>
  <!-- <link name="commented"><inertial><mass value="1"/><inertia ixx="9" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link> -->
  <link name="lower"><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='3'/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <gazebo reference="upper"><mu1>0.2</mu1></gazebo>
</robot>
"""


def test_inertia_repair_default_metric_is_no_farther_than_the_clip():
    rng = np.random.default_rng(9)
    for _ in range(10):
        Q, _r = np.linalg.qr(rng.standard_normal((3, 3)))
        I = Q @ np.diag([rng.uniform(0.05, 0.2), rng.uniform(0.1, 0.3), rng.uniform(0.6, 1.0)]) @ Q.T
        I = 0.5 * (I + I.T)
        nearest = ph.inertia_repair(3.0, [0.1, 0.2, 0.3], I)
        clip = ph.inertia_repair(3.0, [0.1, 0.2, 0.3], I, metric="second-moment")
        assert nearest["metric"] == "inertia" and nearest["distance"] <= clip["distance"] * (1 + 1e-12)
        moments = np.linalg.eigvalsh(nearest["inertia"])
        assert moments[2] < moments[0] + moments[1]
    with pytest.raises(ValueError, match="metric"):
        ph.inertia_repair(1.0, [0, 0, 0], np.eye(3), metric="clip")


def test_urdf_with_several_links_comments_and_other_elements():
    fixed, report, links = ph.inertia_repair_urdf(URDF, source="r.urdf", metric="second-moment")
    assert [link["link"] for link in links] == ["base", "upper", "lower"]
    assert [link["changed"] for link in links] == [False, True, True]
    assert report.splitlines()[-1] == "2 of 3 links repaired"
    # Every line but the two repaired <inertia> elements' is unchanged, the comment included.
    before, after = URDF.splitlines(), fixed.splitlines()
    assert len(before) == len(after)
    changed = [i for i, (a, b) in enumerate(zip(before, after)) if a != b]
    assert [before[i].strip()[:27] for i in changed] == ['<inertial><mass value="2"/>', '<link name="lower"><inertia']
    # The repaired values are the clip of each link's second moment.
    for link in links[1:]:
        S = 0.5 * np.trace(link["inertia_before"]) * np.eye(3) - link["inertia_before"]
        w, V = np.linalg.eigh(S)
        Sp = V @ np.diag(np.maximum(w, 1e-6 * np.abs(w).max())) @ V.T
        np.testing.assert_allclose(link["inertia"], np.trace(Sp) * np.eye(3) - Sp, rtol=0, atol=1e-14)
    # Idempotent.
    again, _, again_links = ph.inertia_repair_urdf(fixed, metric="second-moment")
    assert again == fixed and not any(link["changed"] for link in again_links)


@pytest.mark.parametrize("text", [b"<robot/>", bytearray(b"<robot/>")])
def test_urdf_text_that_is_not_a_str_is_a_type_error(text):
    with pytest.raises(TypeError, match="the URDF's text \\(a str\\), not (bytes|bytearray): decode the bytes first"):
        ph.inertia_repair_urdf(text)


def test_urdf_errors_name_the_source_line_and_link():
    with pytest.raises(spdfit.DataError, match=r"r\.urdf:3: link \"a\": <inertia izz> must be a finite number"):
        ph.inertia_repair_urdf('<robot>\n<link name="a"><inertial><mass value="1"/>\n'
                               '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="nan"/></inertial></link></robot>',
                               source="r.urdf")


def test_offsets_estimate_recovers_the_payload_and_the_constants_exactly():
    # Noise-free data with a constant in every force: B = A M_p + 1 c^T. The physical model with an
    # intercept recovers both (the closed form: mean(B) - M_p^T mean(A) is c).
    g = as_dict(hx.cubic_geometry())
    truth = mass_matrix(g, **PAYLOAD)
    A = np.random.default_rng(5).uniform(-5, 5, (40, 6))
    c = np.array([21.0, 20.0, 22.0, 21.5, 20.5, 21.0])
    est = ph.identify(A, A @ truth + c, g, offsets="estimate")
    assert est["mass"] == pytest.approx(PAYLOAD["mass"], rel=RECOVERY)
    np.testing.assert_allclose(est["M_p"], truth, rtol=0, atol=RECOVERY * np.abs(truth).max())
    assert est["offsets"]["mode"] == "estimate"
    np.testing.assert_allclose(est["offsets"]["c"], c, rtol=RECOVERY)
    with pytest.raises(ValueError, match="offsets"):
        ph.identify(A, A @ truth + c, g, offsets="sideways")


def test_robust_physical_fit_names_the_row_it_down_weights():
    g = as_dict(hx.cubic_geometry())
    A, B, _ = simulate(g, PAYLOAD["mass"], PAYLOAD["com"], PAYLOAD["inertia"], 200, 7)
    B = np.array(B)
    B[17, 3] += 100.0 * np.sqrt(NOISE_VAR)
    clean = ph.identify(np.delete(A, 17, 0), np.delete(B, 17, 0), g)
    plain = ph.identify(A, B, g)
    for loss in ("huber", "tukey"):
        est = ph.identify(A, B, g, robust=loss)
        assert est["robust"]["method"] == loss and 18 in est["robust"]["rows_downweighted"]
        assert abs(est["mass"] - clean["mass"]) < 0.5 * abs(plain["mass"] - clean["mass"]), loss
    # With the bootstrap, each resample reweighted (tests/hexapod compares it with the plain one).
    est = ph.identify(A, B, g, robust="huber", bootstrap=5, seed=1)
    assert est["bootstrap"]["replicates"] == 5 and est["standard_errors"]["mass"] > 0
