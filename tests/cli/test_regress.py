"""`spdfit physical regress` against independent references: NumPy least squares and null spaces for
the base parameters, CVXOPT's cone QP (one 4 x 4 semidefinite cone per body) for the physically
consistent fit, both parameter orders, the prior, and errors."""
import json

import numpy as np
import pytest

from payload_reference import pseudo_inertia

PIN = [0, 1, 2, 3, 4, 5, 7, 6, 8, 9]  # pinocchio's order of the URDF entries (xy, yy, xz swap)


def random_body(rng, thin=False):
    """(m, c, I_c) of a random consistent body; `thin`: a rod (one principal moment ~ 0)."""
    m = rng.uniform(0.5, 5.0)
    c = rng.uniform(-0.2, 0.2, 3)
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    spread = rng.uniform(0.005, 0.05, 3)  # second moments: >= 0 is the triangle inequality
    if thin:
        spread = np.array([1e-7 * spread[0], 1e-7 * spread[0], spread[0]])  # a rod along one axis
    moments = spread.sum() - spread
    return m, c, Q @ np.diag(moments) @ Q.T


def urdf_parameters(m, c, I_c):
    """(m, m c, I_o xx xy xz yy yz zz)."""
    I = I_c + m * (c @ c * np.eye(3) - np.outer(c, c))
    return np.concatenate([[m], m * c, [I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]])


def write(path, A):
    np.savetxt(path, np.atleast_2d(A).reshape(len(A), -1), delimiter=",", fmt="%.17g")
    return path


def regress(spdfit, tmp_path, Y, tau, *options):
    y_path, t_path = write(tmp_path / "Y.csv", Y), write(tmp_path / "tau.csv", tau)
    result = spdfit("physical", "regress", str(y_path), str(t_path), "--json", *options)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout), result.stderr


def pseudo_from_parameters(phi):
    m, h = phi[0], phi[1:4]
    I = np.array([[phi[4], phi[5], phi[6]], [phi[5], phi[7], phi[8]], [phi[6], phi[8], phi[9]]])
    J = np.zeros((4, 4))
    J[:3, :3] = 0.5 * np.trace(I) * np.eye(3) - I
    J[:3, 3] = J[3, :3] = h
    J[3, 3] = m
    return J


def cvxopt_reference(Y, tau, K):
    """min ||Y phi - tau||^2 with each body's J(phi) >= 0 by CVXOPT's cone QP, columns scaled."""
    pytest.importorskip("cvxopt")
    from cvxopt import matrix, solvers
    p = Y.shape[1]
    scale = 1.0 / np.linalg.norm(Y, axis=0)
    Ys = Y * scale
    G = np.zeros((16 * K, p))
    for k in range(K):
        for j in range(10):
            phi = np.zeros(10)
            phi[j] = scale[10 * k + j]
            G[16 * k:16 * k + 16, 10 * k + j] = -pseudo_from_parameters(phi).ravel(order="F")
    solvers.options.update({"show_progress": False, "abstol": 1e-14, "reltol": 1e-14, "feastol": 1e-14,
                            "maxiters": 300})
    sol = solvers.coneqp(matrix(2 * Ys.T @ Ys), matrix(-2 * Ys.T @ tau), matrix(G), matrix(np.zeros(16 * K)),
                         {"l": 0, "q": [], "s": [4] * K})
    phi = np.array(sol["x"]).ravel() * scale
    return phi, np.sum((Y @ phi - tau) ** 2)


def problem(rng, K, rows, noise=0.0, thin=False, extra=0):
    phi = np.concatenate([urdf_parameters(*random_body(rng, thin)) for _ in range(K)] +
                         [rng.standard_normal(extra)])
    Y = rng.standard_normal((rows, 10 * K + extra))
    tau = Y @ phi + noise * rng.standard_normal(rows)
    return Y, tau, phi


@pytest.mark.parametrize("K", [1, 3, 7])
def test_noise_free_parameters_to_1e_9(spdfit, tmp_path, K):
    rng = np.random.default_rng(K)
    Y, tau, phi = problem(rng, K, 40 * K, extra=2)
    out, _ = regress(spdfit, tmp_path, Y, tau, "--bodies", str(K))
    np.testing.assert_allclose(out["parameters"], phi, rtol=1e-9, atol=1e-11)
    assert out["rank"] == 10 * K + 2 and out["physically_consistent"]


@pytest.mark.parametrize("K", range(1, 8))
def test_criterion_at_most_the_sdp_reference(spdfit, tmp_path, K):
    rng = np.random.default_rng(20 + K)
    Y, tau, _ = problem(rng, K, 15 * K, noise=0.5, thin=True)
    out, _ = regress(spdfit, tmp_path, Y, tau, "--bodies", str(K))
    _, f_ref = cvxopt_reference(Y, tau, K)
    assert out["criterion"] <= f_ref * (1 + 1e-6)
    for body in range(K):
        J = pseudo_from_parameters(np.array(out["parameters"][10 * body:10 * body + 10]))
        assert np.linalg.eigvalsh(J)[0] >= -1e-12 * np.abs(J).max()
    assert out["certificate"]["duality_gap"] < 1e-8 and out["certificate"]["dual_min_eig"] >= -1e-8
    unconstrained, _ = regress(spdfit, tmp_path, Y, tau, "--bodies", str(K), "--unconstrained")
    phi_ls, *_ = np.linalg.lstsq(Y, tau, rcond=None)
    np.testing.assert_allclose(unconstrained["parameters"], phi_ls, rtol=1e-8, atol=1e-10)
    assert unconstrained["criterion"] <= out["criterion"] * (1 + 1e-12)


def test_pinocchio_order_gives_the_same_bodies(spdfit, tmp_path):
    rng = np.random.default_rng(30)
    Y, tau, phi = problem(rng, 2, 60, noise=0.01)
    order = np.concatenate([np.array(PIN), 10 + np.array(PIN)])
    urdf, _ = regress(spdfit, tmp_path, Y, tau, "--bodies", "2")
    pin, _ = regress(spdfit, tmp_path, Y[:, order], tau, "--bodies", "2", "--param-order", "pinocchio")
    np.testing.assert_allclose(np.array(pin["parameters"]), np.array(urdf["parameters"])[order], rtol=1e-9,
                               atol=1e-12)
    for a, b in zip(urdf["body"], pin["body"]):
        np.testing.assert_allclose(a["inertia"], b["inertia"], rtol=1e-9, atol=1e-12)
    assert pin["names"][6] == "I_yy_1" and urdf["names"][6] == "I_xz_1"


def test_base_parameters_and_the_prior(spdfit, tmp_path):
    rng = np.random.default_rng(31)
    K = 2
    Y, tau, phi = problem(rng, K, 80)
    # Two columns that always move together (a link's mass and the next one's, as on a robot).
    Y[:, 10] = Y[:, 0]
    tau = Y @ phi
    out, err = regress(spdfit, tmp_path, Y, tau, "--bodies", "2")
    assert out["rank"] == 19 and len(out["undetermined"]) == 1
    assert out["parameters"][0] is None and out["parameters"][10] is None
    assert "do not determine 1 combination" in err
    assert len(out["warning_codes"]) == len(out["warnings"]) and "rank_deficient" in out["warning_codes"]
    # Each base parameter is determined: orthogonal to NumPy's null space, and equal to its value at phi.
    null = np.linalg.svd(Y)[2][-1]
    for base in out["base_parameters"]:
        coefficients = np.array(base["coefficients"])
        assert abs(coefficients @ null) < 1e-9 * np.linalg.norm(coefficients)
        # Loosened from 1e-9: the ridge that bounds the barrier along the undetermined direction
        # puts body 1 on the boundary of its cone (pseudo-inertia eigenvalue ~1e-17), where the
        # barrier's last stage leaves the determined combinations about 1e-9 relative off.
        assert base["value"] == pytest.approx(coefficients @ phi, rel=1e-8, abs=1e-11)
    # A prior (the true bodies, perturbed) sets the masses.
    bodies = []
    for k in range(K):
        p = phi[10 * k:10 * k + 10]
        m, c = p[0], p[1:4] / p[0]
        I = np.array([[p[4], p[5], p[6]], [p[5], p[7], p[8]], [p[6], p[8], p[9]]])
        I_c = I - m * (c @ c * np.eye(3) - np.outer(c, c))
        bodies.append({"mass": m * 1.1, "center_of_mass": c.tolist(), "inertia": I_c.tolist()})
    prior = tmp_path / "prior.json"
    prior.write_text(json.dumps(bodies))
    with_prior, err = regress(spdfit, tmp_path, Y, tau, "--bodies", "2", "--prior", str(prior))
    assert all(v is not None for v in with_prior["parameters"])
    assert with_prior["parameters"][0] + with_prior["parameters"][10] == pytest.approx(phi[0] + phi[10], rel=1e-6)
    assert with_prior["physically_consistent"] and "the prior sets them" in err


def test_weighted_by_a_noise_covariance(spdfit, tmp_path):
    rng = np.random.default_rng(32)
    Y, tau, phi = problem(rng, 1, 90, noise=0.0)
    cov = np.array([[1.0, 0.3, 0.0], [0.3, 0.5, 0.1], [0.0, 0.1, 0.2]])
    L = np.linalg.cholesky(cov)
    tau = tau + (L @ rng.standard_normal((3, 30))).T.ravel() * 0.01
    cov_path = write(tmp_path / "cov.csv", cov)
    out, _ = regress(spdfit, tmp_path, Y, tau, "--noise-cov", str(cov_path), "--unconstrained")
    W = np.kron(np.eye(30), np.linalg.inv(L))
    phi_w, *_ = np.linalg.lstsq(W @ Y, W @ tau, rcond=None)
    np.testing.assert_allclose(out["parameters"], phi_w, rtol=1e-8, atol=1e-11)
    assert out["samples"] == 30 and out["outputs"] == 3


def test_bootstrap_and_errors(spdfit, tmp_path):
    rng = np.random.default_rng(33)
    Y, tau, phi = problem(rng, 1, 100, noise=0.1)
    out, _ = regress(spdfit, tmp_path, Y, tau, "--bootstrap", "100")
    assert out["bootstrap"]["replicates"] == 100 and all(s > 0 for s in out["bootstrap"]["parameters"]["standard_errors"])
    y_path, t_path = write(tmp_path / "Y.csv", Y), write(tmp_path / "tau.csv", tau)
    too_many = spdfit("physical", "regress", str(y_path), str(t_path), "--bodies", "2")
    assert too_many.returncode == 1 and "needs at least 20" in too_many.stderr
    order = spdfit("physical", "regress", str(y_path), str(t_path), "--param-order", "ros")
    assert order.returncode == 2 and "'urdf' or 'pinocchio'" in order.stderr
    weight = spdfit("physical", "regress", str(y_path), str(t_path), "--prior-weight", "2")
    assert weight.returncode == 2 and "--prior" in weight.stderr
    short = write(tmp_path / "short.csv", tau[:50])
    mismatch = spdfit("physical", "regress", str(y_path), str(short))
    assert mismatch.returncode == 1 and "short.csv" in mismatch.stderr
