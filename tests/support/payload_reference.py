"""An independent NumPy implementation of the wrist force/torque sensor's wrench model (docs/payload.md),
for the payload tests: rotations from quaternions, the wrench a payload needs, simulated logs, the
least-squares regressor, and the pseudo-inertia. Written from the model's equations, not from
spdfit's code:

    f = m s + alpha x (m c) + omega x (omega x (m c)),   s = a - R^T g,
    tau = I_S alpha + omega x (I_S omega) + (m c) x s,    I_S = I_c + m (|c|^2 1 - c c^T),

and a sensor reads w = -(f, tau) + b (the load) or (f, tau) + b (the applied wrench)."""
import numpy as np

G = np.array([0.0, 0.0, -9.80665])


def rotation_from_quaternion(q):
    """R (3 x 3) of a quaternion x, y, z, w (normalized first)."""
    x, y, z, w = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def random_quaternions(rng, n, spread=None, around=None):
    """n unit quaternions (x y z w): uniform over the rotations, or within `spread` radians of
    `around` (a quaternion)."""
    if spread is None:
        q = rng.standard_normal((n, 4))
        return q / np.linalg.norm(q, axis=1, keepdims=True)
    axis = rng.standard_normal((n, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    angle = rng.uniform(0, spread, n)
    small = np.hstack([axis * np.sin(angle / 2)[:, None], np.cos(angle / 2)[:, None]])
    return np.array([quaternion_product(around, d) for d in small])


def quaternion_product(p, q):
    """p q for quaternions x y z w."""
    px, py, pz, pw = p
    qx, qy, qz, qw = q
    return np.array([pw * qx + px * qw + py * qz - pz * qy, pw * qy - px * qz + py * qw + pz * qx,
                     pw * qz + px * qy - py * qx + pz * qw, pw * qw - px * qx - py * qy - pz * qz])


def inertia_about_origin(mass, com, inertia_com):
    c = np.asarray(com, dtype=float)
    return np.asarray(inertia_com, dtype=float) + mass * (c @ c * np.eye(3) - np.outer(c, c))


def wrench(mass, com, inertia_com, s, omega=None, alpha=None):
    """(f, tau) (n x 6) the sensor applies to the payload, per sample."""
    s = np.atleast_2d(s)
    n = len(s)
    omega = np.zeros((n, 3)) if omega is None else np.atleast_2d(omega)
    alpha = np.zeros((n, 3)) if alpha is None else np.atleast_2d(alpha)
    return body_wrench(mass, mass * np.asarray(com, dtype=float), inertia_about_origin(mass, com, inertia_com),
                       s, omega, alpha)


def body_wrench(m, h, I, s, omega, alpha):
    """(f, tau) (n x 6) from the mass m, first moment h = m c and inertia I about S's origin:
    f = m s + alpha x h + omega x (omega x h), tau = I alpha + omega x (I omega) + h x s."""
    f = m * s + np.cross(alpha, h) + np.cross(omega, np.cross(omega, h))
    tau = alpha @ I.T + np.cross(omega, omega @ I.T) + np.cross(h, s)
    return np.hstack([f, tau])


def pseudo_inertia(mass, com, inertia_com):
    """J = [[Sigma_o, m c], [m c^T, m]] about the origin."""
    I = inertia_about_origin(mass, com, inertia_com)
    sigma = 0.5 * np.trace(I) * np.eye(3) - I
    J = np.zeros((4, 4))
    J[:3, :3] = sigma
    J[:3, 3] = J[3, :3] = mass * np.asarray(com)
    J[3, 3] = mass
    return J


def regressor(s, omega=None, alpha=None, sign=-1.0, moving=False):
    """The stacked regressor (6 n x p) of the readings w = sign (f, tau) + b in the parameters
    (m, m c, [I_S xx xy xz yy yz zz], b_f, b_tau)."""
    s = np.atleast_2d(s)
    n = len(s)
    omega = np.zeros((n, 3)) if omega is None else np.atleast_2d(omega)
    alpha = np.zeros((n, 3)) if alpha is None else np.atleast_2d(alpha)
    p = 16 if moving else 10
    X = np.zeros((6 * n, p))
    basis = [np.eye(3)[:, [i]] @ np.eye(3)[[j], :] + (np.eye(3)[:, [j]] @ np.eye(3)[[i], :] if i != j else 0)
             for i, j in [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]]
    for k in range(n):
        rows = slice(6 * k, 6 * k + 6)
        for j in range(4 + (6 if moving else 0)):
            phi = np.zeros(10)
            phi[j] = 1.0
            m, h = phi[0], phi[1:4]
            I = sum(phi[4 + i] * basis[i] for i in range(6))
            f = m * s[k] + np.cross(alpha[k], h) + np.cross(omega[k], np.cross(omega[k], h))
            tau = I @ alpha[k] + np.cross(omega[k], I @ omega[k]) + np.cross(h, s[k])
            X[rows, j] = sign * np.concatenate([f, tau])
        X[rows, p - 6:] = np.eye(6)
    return X


def static_log(rng, n, mass=1.2, com=(0.08, 0.0, 0.03), bias=(5.0, -2.0, 1.0, 0.3, -0.1, 0.2),
               noise=(0.2, 0.01), quaternions=None):
    """A static log: quaternions (x y z w), the gravity in S, and the readings (load convention)."""
    q = random_quaternions(rng, n) if quaternions is None else quaternions
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    w = -wrench(mass, com, np.zeros((3, 3)), -g_s) + np.asarray(bias)
    if noise is not None:
        w[:, :3] += noise[0] * rng.standard_normal((n, 3))
        w[:, 3:] += noise[1] * rng.standard_normal((n, 3))
    return {"quaternion": q, "gravity": g_s, "wrench": w}


def trajectory(rng, n, duration=20.0, harmonics=5):
    """Smooth signals over time: omega (rad/s) and its exact derivative alpha, and an acceleration,
    each a sum of `harmonics` sines per axis; a quaternion per sample."""
    t = np.linspace(0.0, duration, n)
    omega = np.zeros((n, 3))
    alpha = np.zeros((n, 3))
    accel = np.zeros((n, 3))
    for axis in range(3):
        for k in range(harmonics):
            freq = 2 * np.pi * (k + 1) / duration * rng.uniform(0.8, 1.2) * 3
            amp, phase = rng.uniform(0.2, 1.0) / (k + 1), rng.uniform(0, 2 * np.pi)
            omega[:, axis] += amp * np.sin(freq * t + phase)
            alpha[:, axis] += amp * freq * np.cos(freq * t + phase)
            accel[:, axis] += 2.0 * rng.uniform(0.2, 1.0) / (k + 1) * np.sin(freq * t + rng.uniform(0, 2 * np.pi))
    return t, omega, alpha, accel, random_quaternions(rng, n)


def write_log(path, columns):
    """A CSV with a header: columns is [(name, array n or n x k with names name1..)]."""
    names, blocks = [], []
    for name, values in columns:
        values = np.asarray(values, dtype=float)
        if values.ndim == 1:
            names.append(name)
            blocks.append(values[:, None])
        else:
            names += name if isinstance(name, (list, tuple)) else [f"{name}{i}" for i in range(values.shape[1])]
            blocks.append(values)
    data = np.hstack(blocks)
    np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.17g")
    return path


def model_readings(phi, s, omega, alpha, sign=-1.0):
    """The readings (n x 6) the wrench model predicts, vectorized over samples: sign (f, tau) + b
    with phi = (m, m c, I_S xx xy xz yy yz zz, b_f, b_tau)."""
    xx, xy, xz, yy, yz, zz = phi[4:10]
    I = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    return sign * body_wrench(phi[0], phi[1:4], I, s, omega, alpha) + phi[10:16]


def eiv_criterion(phi, readings, s, omega, alpha, noise_w, noise_x, sign=-1.0):
    """sum_k r_k^T C_k^-1 r_k with C_k = J_k Sigma_x J_k^T + Sigma_w, J_k the model's Jacobian in
    the signals (s, omega, alpha) by central differences (exact: the model is quadratic in them)."""
    x = np.hstack([s, omega, alpha])
    J = np.empty((len(x), 6, 9))
    for c in range(9):
        step = np.zeros(9)
        step[c] = 1e-3
        plus, minus = x + step, x - step
        J[:, :, c] = (model_readings(phi, plus[:, :3], plus[:, 3:6], plus[:, 6:], sign)
                      - model_readings(phi, minus[:, :3], minus[:, 3:6], minus[:, 6:], sign)) / 2e-3
    C = J @ noise_x @ J.transpose(0, 2, 1) + noise_w
    r = readings - model_readings(phi, s, omega, alpha, sign)
    return float(np.einsum("ki,ki->", r, np.linalg.solve(C, r[:, :, None])[:, :, 0]))
