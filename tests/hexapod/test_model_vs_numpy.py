"""M_p, J and the modes of `spdfit hexapod model --geometry G.json --json` against an
independent NumPy computation from the same geometry file (thesis 000, eq. 2.10/2.12-2.13).

The NumPy side forms J row by row from the strut unit vectors u_i and the lever arms
r_i = R p_i, M_p = J^-T (R M_x R^T) J^-1 + M_s with explicit inverses, and the modes from
scipy's generalized symmetric eigensolver: a different route to the same numbers.
"""
import json

import numpy as np
import pytest
import scipy.linalg

import thesis_reference as ref

# Relative tolerance between the CLI and NumPy: both are backward stable on 6x6 problems with
# cond(J) < 100 here, so they agree to ~1e-14; 1e-11 leaves room for cond(J)^2 eps.
RTOL = 1e-11


def numpy_model(g):
    q = np.array(g["base_points"], dtype=float)
    p = np.array(g["payload_points"], dtype=float)
    o = np.array(g["payload_origin"], dtype=float)
    R = np.array(g.get("payload_rotation", np.eye(3)), dtype=float)
    r = p @ R.T                       # lever arms in {B} axes
    s = o + r - q                     # strut vectors
    u = s / np.linalg.norm(s, axis=1)[:, None]
    J = np.hstack([u, np.cross(r, u)])
    Mx = np.zeros((6, 6))
    Mx[:3, :3] = g["payload_mass"] * np.eye(3)
    Mx[3:, 3:] = R @ np.array(g["payload_inertia"], dtype=float) @ R.T
    Jinv = np.linalg.inv(J)
    Ms = np.diag(np.broadcast_to(np.asarray(g["strut_mass"], dtype=float), (6,)))
    Mp = Jinv.T @ Mx @ Jinv + Ms
    K = np.diag(np.broadcast_to(np.asarray(g["strut_stiffness"], dtype=float), (6,)))
    modes = np.sqrt(scipy.linalg.eigh(K, Mp, eigvals_only=True)) / (2 * np.pi)
    return J, Mp, modes


def random_rotation(rng):
    Q, Rr = np.linalg.qr(rng.standard_normal((3, 3)))
    Q = Q * np.sign(np.diag(Rr))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    return Q


def random_geometry(rng):
    """A 6-6 Stewart platform: base joint pairs at 120k +- 15 deg (r = 0.2 m), struts leaning to
    payload joints at 120k +- 45 deg (r = 0.1 m, 0.2 m up), jittered; random payload orientation,
    a box-shaped payload (a physical inertia), random strut properties."""
    R = random_rotation(rng)
    o = np.array([0.0, 0.0, 0.2]) + rng.uniform(-0.01, 0.01, 3)
    base, payload = [], []
    for i in range(6):
        k, side = i // 2, (-1 if i % 2 == 0 else 1)
        a_b = 2 * np.pi * k / 3 + side * np.pi / 12
        a_p = 2 * np.pi * k / 3 + side * np.pi / 4
        base.append([0.2 * np.cos(a_b), 0.2 * np.sin(a_b), 0.0] + 0.003 * rng.standard_normal(3))
        joint = np.array([0.1 * np.cos(a_p), 0.1 * np.sin(a_p), 0.0]) + 0.003 * rng.standard_normal(3)
        payload.append(R.T @ joint)
    m = rng.uniform(2, 20)
    a, b, c = rng.uniform(0.05, 0.3, 3)
    W = random_rotation(rng)
    inertia = W @ np.diag(m / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])) @ W.T
    return {
        "base_points": np.array(base).tolist(),
        "payload_points": np.array(payload).tolist(),
        "payload_origin": o.tolist(),
        "payload_rotation": R.tolist(),
        "payload_mass": m,
        "payload_inertia": (0.5 * (inertia + inertia.T)).tolist(),
        "strut_mass": rng.uniform(0.1, 1.0, 6).tolist(),
        "strut_stiffness": rng.uniform(5e3, 5e4, 6).tolist(),
        "strut_damping": 20.0,
    }


def rel(X, Y):
    return np.linalg.norm(np.asarray(X) - np.asarray(Y)) / np.linalg.norm(Y)


@pytest.mark.parametrize("seed", range(6))
def test_random_geometry_matches_numpy(cli_json, tmp_path, seed):
    g = random_geometry(np.random.default_rng(seed))
    path = tmp_path / "G.json"
    path.write_text(json.dumps(g))
    out = cli_json("hexapod", "model", "--geometry", path)
    J, Mp, modes = numpy_model(g)
    assert rel(out["jacobian"], J) < RTOL
    assert rel(out["mass_matrix"], Mp) < RTOL
    assert rel(out["modes_hz"], modes) < RTOL
    M = np.array(out["mass_matrix"])
    assert np.array_equal(M, M.T)
    assert np.linalg.eigvalsh(M)[0] > 0


def test_builtin_geometry_matches_numpy_and_thesis(cli_json, tmp_path):
    out = cli_json("hexapod", "model")
    g = out["geometry"]
    J, Mp, modes = numpy_model(g)
    assert rel(out["jacobian"], J) < RTOL
    assert rel(out["mass_matrix"], Mp) < RTOL
    assert rel(out["modes_hz"], modes) < RTOL
    # Calibrated to thesis eq. 6.1, printed with 4 decimals (and its symmetry-equal entries
    # differ by up to 4e-4 in print).
    assert np.abs(np.array(out["mass_matrix"]) - ref.MP_THESIS).max() < 5e-4
    # Cubic configuration: adjacent struts orthogonal, opposite ones parallel.
    u = np.array(out["strut_directions"])
    for i in range(6):
        assert abs(u[i] @ u[(i + 1) % 6]) < 1e-14
        assert abs(abs(u[i] @ u[(i + 3) % 6]) - 1) < 1e-14


def test_written_geometry_reads_back_to_the_same_model(cli, cli_json, tmp_path):
    cli("hexapod", "model", "--write-geometry", tmp_path / "cube.json")
    again = cli_json("hexapod", "model", "--geometry", tmp_path / "cube.json")
    builtin = cli_json("hexapod", "model")
    assert again["mass_matrix"] == builtin["mass_matrix"]


def test_kinetic_energy_metric(cli_json, tmp_path):
    """(1/2) l_dot' (M_p - M_s) l_dot = (1/2) x_dot' M_x x_dot for l_dot = J x_dot."""
    rng = np.random.default_rng(42)
    g = random_geometry(rng)
    g["strut_mass"] = 0.0
    path = tmp_path / "G.json"
    path.write_text(json.dumps(g))
    out = cli_json("hexapod", "model", "--geometry", path)
    J, Mp, Mx = (np.array(out[k]) for k in ("jacobian", "mass_matrix", "payload_mass_matrix"))
    for _ in range(10):
        x_dot = rng.standard_normal(6)
        l_dot = J @ x_dot
        assert abs(l_dot @ Mp @ l_dot - x_dot @ Mx @ x_dot) < 1e-11 * (x_dot @ Mx @ x_dot)
