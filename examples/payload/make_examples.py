"""Regenerates the payload examples (run with Debian's /usr/bin/python3 from the source tree).

The files are committed; this script documents exactly how they were made, from the wrench model
of docs/payload.md as tests/support/payload_reference.py writes it (not from spdfit):

  log.csv         a wrist force/torque sensor's log at 100 Hz with a 1.2 kg gripper whose centre
                  of mass is 8 cm off the sensor's axis: t (s), fx fy fz (N), tx ty tz (N m) as the
                  sensor reports them (the load: a hanging payload reads a downward force), the
                  sensor's orientation as a quaternion qx qy qz qw (from the robot's kinematics),
                  and the sensor origin's kinematic acceleration ax ay az (m/s^2) and angular
                  velocity wx wy wz (rad/s) in the sensor frame. Rows 1-100: the robot at rest
                  (rest rows for the noise model); rows 101-340: 12 static poses of 20 rows each;
                  rows 341-940: a moving trajectory (5 harmonics per axis, starting and stopping smoothly). Sensor biases (5, -2,
                  1) N and (0.3, -0.1, 0.2) N m; noise 0.2 N and 0.01 N m; a and omega with noise of
                  0.05 m/s^2 and 0.005 rad/s.
  candidates.csv  300 candidate orientations (quaternions, the tool pointing at most 120 degrees
                  from straight down) for `spdfit payload design`.
  truth.json      the gripper's true mass properties (mass, center_of_mass, inertia about it).
"""
import json
import os
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", HERE.parents[1])) / "tests" / "support"))
from payload_reference import G, random_quaternions, rotation_from_quaternion, wrench  # noqa: E402

MASS = 1.2
COM = np.array([0.08, 0.0, 0.03])
INERTIA = np.array([[0.004, 0.0, 0.0005], [0.0, 0.006, 0.0], [0.0005, 0.0, 0.003]])
BIAS = np.array([5.0, -2.0, 1.0, 0.3, -0.1, 0.2])
RATE = 100.0


def pointing_down(rng, n, max_angle):
    """Quaternions whose sensor z axis (the tool axis) is within max_angle of straight down."""
    out = []
    while len(out) < n:
        q = random_quaternions(rng, 1)[0]
        z = rotation_from_quaternion(q)[:, 2]
        if np.degrees(np.arccos(np.clip(-z[2], -1, 1))) <= max_angle:
            out.append(q)
    return np.array(out)


def make_log(rng):
    rest_q = pointing_down(rng, 1, 5)[0]
    static_q = pointing_down(rng, 12, 110)
    n_moving = 600
    t_moving = np.arange(n_moving) / RATE
    omega = np.zeros((n_moving, 3))
    accel = np.zeros((n_moving, 3))
    for axis in range(3):
        for k in range(5):
            f = 2 * np.pi * rng.uniform(0.2, 1.5)
            omega[:, axis] += rng.uniform(0.3, 1.0) / (k + 1) * np.sin(f * t_moving + rng.uniform(0, 2 * np.pi))
            accel[:, axis] += rng.uniform(0.5, 2.0) / (k + 1) * np.sin(f * t_moving + rng.uniform(0, 2 * np.pi))
    # A smooth start and stop (sin^2 window over the first and last second): the robot starts at rest.
    ramp = np.clip(np.minimum(t_moving, t_moving[-1] - t_moving) / 1.0, 0.0, 1.0)
    window = np.sin(0.5 * np.pi * ramp)[:, None] ** 2
    omega *= window
    accel *= window
    alpha = np.gradient(omega, t_moving, axis=0, edge_order=2)  # the true alpha (not logged)
    # A smooth orientation: interpolate the pose slowly between a few of them (the model needs no
    # relation between R and omega per sample).
    key = pointing_down(rng, 7, 100)
    idx = np.minimum((t_moving / t_moving[-1] * 6).astype(int), 5)
    frac = (t_moving / t_moving[-1] * 6) - idx
    moving_q = np.array([(1 - a) * key[i] + a * key[i + 1] for i, a in zip(idx, frac)])
    moving_q /= np.linalg.norm(moving_q, axis=1, keepdims=True)

    quats = np.vstack([np.repeat(rest_q[None], 100, axis=0), np.repeat(static_q, 20, axis=0), moving_q])
    a = np.vstack([np.zeros((340, 3)), accel])
    w = np.vstack([np.zeros((340, 3)), omega])
    al = np.vstack([np.zeros((340, 3)), alpha])
    n = len(quats)
    t = np.arange(n) / RATE
    s = np.array([ai - rotation_from_quaternion(qi).T @ G for ai, qi in zip(a, quats)])
    readings = -wrench(MASS, COM, INERTIA, s, w, al) + BIAS
    readings[:, :3] += 0.2 * rng.standard_normal((n, 3))
    readings[:, 3:] += 0.01 * rng.standard_normal((n, 3))
    a_logged = a + 0.05 * rng.standard_normal(a.shape)
    w_logged = w + 0.005 * rng.standard_normal(w.shape)
    table = np.hstack([t[:, None], readings, quats, a_logged, w_logged])
    header = "t,fx,fy,fz,tx,ty,tz,qx,qy,qz,qw,ax,ay,az,wx,wy,wz"
    np.savetxt(HERE / "log.csv", table, delimiter=",", header=header, comments="", fmt="%.7g")


def main():
    rng = np.random.default_rng(2026)
    make_log(rng)
    candidates = pointing_down(rng, 300, 120)
    np.savetxt(HERE / "candidates.csv", candidates, delimiter=",", header="qx,qy,qz,qw", comments="", fmt="%.9g")
    (HERE / "truth.json").write_text(json.dumps({"mass": MASS, "center_of_mass": COM.tolist(),
                                                 "inertia": INERTIA.tolist()}, indent=2) + "\n")


if __name__ == "__main__":
    main()
