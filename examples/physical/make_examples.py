"""Regenerates the regression example (run with Debian's /usr/bin/python3): a two-link arm whose
joints turn about parallel z axes in a vertical plane (gravity -9.80665 along the base's y axis),
link 1 0.5 m long. Its joint torques are linear in the links' inertial parameters, tau = Y phi,
with phi = (m, m c, I about the link frame's origin in URDF order) per link; Y is computed here by
the recursive Newton-Euler algorithm applied to unit parameter vectors (the dynamics is linear in
them), written for this example, not taken from spdfit.

  Y.csv       200 samples x 2 joints = 400 rows (sample-major), 20 columns
  tau.csv     the measured torques (N m): Y phi_true plus noise of 0.05 N m
  cad.json    the links as a CAD model gives them (masses 5 % off, the inertias of simple shapes): a
              prior for the parameters the motion cannot determine
  truth.json  the true links
"""
import json
import pathlib

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
L1 = 0.5
G = np.array([0.0, -9.80665, 0.0])


def rot_z(q):
    c, s = np.cos(q), np.sin(q)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rnea(q, qd, qdd, params):
    """Joint torques of the arm for parameters params = [(m, h, I_o)] per link (any values)."""
    z = np.array([0.0, 0.0, 1.0])
    offsets = [np.zeros(3), np.array([L1, 0.0, 0.0])]  # frame i's origin in frame i - 1
    w, wd, a = np.zeros(3), np.zeros(3), -G  # the base: its acceleration includes gravity's
    forces, moments, rotations = [], [], []
    for i in range(2):
        R = rot_z(q[i])  # frame i in frame i - 1
        a = R.T @ (a + np.cross(wd, offsets[i]) + np.cross(w, np.cross(w, offsets[i])))
        wd = R.T @ wd + np.cross(R.T @ w, qd[i] * z) + qdd[i] * z
        w = R.T @ w + qd[i] * z
        m, h, I = params[i]
        forces.append(m * a + np.cross(wd, h) + np.cross(w, np.cross(w, h)))
        moments.append(I @ wd + np.cross(w, I @ w) + np.cross(h, a))
        rotations.append(R)
    tau = np.zeros(2)
    f_next, n_next = np.zeros(3), np.zeros(3)
    for i in (1, 0):
        R_next = rotations[i + 1] if i + 1 < 2 else np.eye(3)
        p_next = offsets[i + 1] if i + 1 < 2 else np.zeros(3)
        f = forces[i] + R_next @ f_next
        n = moments[i] + R_next @ n_next + np.cross(p_next, R_next @ f_next)
        tau[i] = n @ z
        f_next, n_next = f, n
    return tau


def unit_parameters(j):
    """The parameters of both links with entry j (of 20) one and the others zero."""
    phi = np.zeros(20)
    phi[j] = 1.0
    out = []
    for k in range(2):
        p = phi[10 * k:10 * k + 10]
        I = np.array([[p[4], p[5], p[6]], [p[5], p[7], p[8]], [p[6], p[8], p[9]]])
        out.append((p[0], p[1:4], I))
    return out


def link(m, c, I_c):
    c = np.asarray(c, dtype=float)
    I = np.asarray(I_c) + m * (c @ c * np.eye(3) - np.outer(c, c))
    return np.concatenate([[m], m * c, [I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]])


def main():
    rng = np.random.default_rng(7)
    truth = [(4.0, [0.25, 0.01, 0.0], np.diag([0.004, 0.09, 0.092])),
             (2.5, [0.18, 0.0, 0.02], np.diag([0.002, 0.035, 0.036]))]
    phi = np.concatenate([link(*body) for body in truth])
    t = np.linspace(0, 10, 200)
    q = np.stack([0.8 * np.sin(1.1 * t) + 0.3 * np.sin(2.9 * t + 1), 1.2 * np.sin(0.7 * t + 2) + 0.4 * np.sin(3.7 * t)], 1)
    qd = np.stack([0.8 * 1.1 * np.cos(1.1 * t) + 0.3 * 2.9 * np.cos(2.9 * t + 1),
                   1.2 * 0.7 * np.cos(0.7 * t + 2) + 0.4 * 3.7 * np.cos(3.7 * t)], 1)
    qdd = np.stack([-0.8 * 1.21 * np.sin(1.1 * t) - 0.3 * 8.41 * np.sin(2.9 * t + 1),
                    -1.2 * 0.49 * np.sin(0.7 * t + 2) - 0.4 * 13.69 * np.sin(3.7 * t)], 1)
    Y = np.zeros((2 * len(t), 20))
    for k in range(len(t)):
        for j in range(20):
            Y[2 * k:2 * k + 2, j] = rnea(q[k], qd[k], qdd[k], unit_parameters(j))
    tau = Y @ phi + 0.05 * rng.standard_normal(2 * len(t))
    np.savetxt(HERE / "Y.csv", Y, delimiter=",", fmt="%.17g")  # full precision: rounding would make the
    # undetermined combinations look determined (singular values at the rounding, above the rank cut-off)
    np.savetxt(HERE / "tau.csv", tau, delimiter=",", fmt="%.9g")
    cad = [{"mass": 4.2, "center_of_mass": [0.25, 0.0, 0.0], "inertia": np.diag([0.005, 0.085, 0.088]).tolist()},
           {"mass": 2.4, "center_of_mass": [0.2, 0.0, 0.0], "inertia": np.diag([0.002, 0.033, 0.034]).tolist()}]
    (HERE / "cad.json").write_text(json.dumps(cad, indent=1) + "\n")
    (HERE / "truth.json").write_text(json.dumps([{"mass": m, "center_of_mass": list(c), "inertia": I.tolist()}
                                                 for m, c, I in truth], indent=1) + "\n")


if __name__ == "__main__":
    main()
