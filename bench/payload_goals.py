"""The goals of payload identification and physical regression (docs/payload.md, "Accuracy"),
measured by Monte Carlo with the Python module against independent references:

  noise_free     static (m, c, biases) and moving (all 16) parameters from noise-free data, and
                 regress's base parameters for K = 1..7 bodies: the worst relative error
  static         a 1.2 kg gripper, centre of mass 8 cm off-axis, biases 5 N and 0.3 N m, noise
                 0.2 N / 0.01 N m, 3 to 100 random orientations: the consistent fit against
                 unconstrained least squares (identical where its mass is positive; never worse)
  light          a 30 g tool, orientations within 10 degrees of one pose: the constraint binds;
                 the ratios of mean errors of m and c to least squares', and m >= 0 always
  moving         trajectories of 5 harmonics per axis, 10^4 rows, noise in a and omega of 10 % of
                 their RMS: errors in variables against least squares (mean inertia error), and
                 thin-rod payloads (consistency in every trial)
  design         K = 6 poses from 1000 candidates: the predicted standard error of m against the
                 10th percentile of 1000 random 6-pose choices
  regress        random K = 1..7 problems: the criterion against CVXOPT's cone QP (the same
                 objective and LMIs), and the time at K = 7, 20 000 samples x 7 outputs

    SPDFIT_SOURCE_DIR=. PYTHONPATH=build/python /usr/bin/python3 bench/payload_goals.py [--trials N] [--only NAME]

prints a Markdown report (bench/results/payload_goals-*.md keeps one)."""
import argparse
import os
import pathlib
import sys
import time
import warnings

import numpy as np

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(ROOT / "tests" / "support"))
sys.path.insert(0, str(ROOT / "bench"))

from payload_reference import (G, random_quaternions, regressor, rotation_from_quaternion,  # noqa: E402
                               static_log, wrench)
from machine import cpu_model  # noqa: E402

import spdfit  # noqa: E402
import spdfit.payload as pl  # noqa: E402
import spdfit.physical as ph  # noqa: E402

warnings.simplefilter("ignore", spdfit.SpdfitWarning)


def static_estimates(log, **options):
    return pl.identify(wrench=log["wrench"], quaternion=log["quaternion"], **options)


def noise_free():
    rng = np.random.default_rng(1)
    worst_static = 0.0
    for n in (3, 10, 100):
        log = static_log(rng, n, noise=None)
        e = static_estimates(log)
        truth = np.array([1.2, 0.08, 0.0, 0.03, 5.0, -2.0, 1.0, 0.3, -0.1, 0.2])
        got = np.concatenate([[e["mass"]], e["center_of_mass"], e["force_bias"], e["torque_bias"]])
        worst_static = max(worst_static, np.max(np.abs(got - truth) / np.maximum(np.abs(truth), 1e-2)))
    worst_moving = 0.0
    for seed in range(5):
        rng = np.random.default_rng(10 + seed)
        t, omega, alpha, accel, q, w, inertia = moving_log(rng, 500, noise=0.0)
        e = pl.identify(wrench=w, quaternion=q, accel=accel, omega=omega, alpha=alpha)
        truth = np.concatenate([[2.5], [0.02, -0.01, 0.06], inertia.ravel(), BIAS])
        got = np.concatenate([[e["mass"]], e["center_of_mass"], e["inertia"].ravel(), e["force_bias"], e["torque_bias"]])
        worst_moving = max(worst_moving, np.max(np.abs(got - truth) / np.maximum(np.abs(truth), 1e-2)))
    worst_regress = 0.0
    for K in range(1, 8):
        rng = np.random.default_rng(40 + K)
        Y, tau, phi = regress_problem(rng, K, 30 * K, noise=0.0)
        r = ph.regress(Y, tau, bodies=K)
        base = np.array([b["value"] for b in r["base_parameters"]])
        coefficients = np.array([b["coefficients"] for b in r["base_parameters"]])
        worst_regress = max(worst_regress, np.max(np.abs(base - coefficients @ phi) / np.maximum(np.abs(coefficients @ phi), 1e-2)))
    print("## Noise-free data\n")
    print("| problem | worst relative error (|x| floored at 0.01) |\n|---|---|")
    print(f"| static, 3/10/100 orientations: m, c, biases | {worst_static:.1e} |")
    print(f"| moving, 500 rows, 5 trajectories: all 16 | {worst_moving:.1e} |")
    print(f"| regress, K = 1..7: base parameters | {worst_regress:.1e} |\n")


def static(trials):
    rng = np.random.default_rng(2)
    same, worse, count_positive = 0.0, 0, 0
    errors = {"ls": [], "consistent": []}
    for trial in range(trials):
        n = int(rng.integers(3, 101))
        log = static_log(rng, n)
        c = static_estimates(log)
        u = static_estimates(log, consistent=False)
        truth = np.array([1.2, 0.08, 0.0, 0.03])
        if u["mass"] > 0:
            count_positive += 1
            same = max(same, np.max(np.abs(c["parameters"] - u["parameters"]) / np.maximum(np.abs(u["parameters"]), 1e-12)))
        ec = np.linalg.norm(np.concatenate([[c["mass"]], c["center_of_mass"]]) - truth)
        eu = np.linalg.norm(np.concatenate([[u["mass"]], u["center_of_mass"]]) - truth)
        errors["consistent"].append(ec)
        errors["ls"].append(eu)
        worse += ec > eu * (1 + 1e-12)
    print(f"## Static poses ({trials} trials, 3 to 100 random orientations)\n")
    print(f"- unconstrained mass positive in {count_positive} trials; there the consistent fit equals it to "
          f"{same:.1e} (largest relative difference of the 10 parameters)")
    print(f"- trials where the consistent fit's error in (m, c) exceeds least squares': {worse}")
    print(f"- mean error of (m, c): consistent {np.mean(errors['consistent']):.4g}, least squares "
          f"{np.mean(errors['ls']):.4g}\n")


def light(trials):
    rng = np.random.default_rng(3)
    around = np.array([0.0, 0.0, 0.0, 1.0])
    em, ec, um, uc, negative, active, min_mass = [], [], [], [], 0, 0, np.inf
    com = np.array([0.0, 0.0, 0.02])
    for trial in range(trials):
        q = random_quaternions(rng, 20, spread=np.radians(10), around=around)
        log = static_log(rng, 20, mass=0.03, com=com, quaternions=q)
        c = static_estimates(log)
        u = static_estimates(log, consistent=False)
        negative += u["mass"] < 0
        active += c["constraint_active"]
        min_mass = min(min_mass, c["mass"])
        em.append(abs(c["mass"] - 0.03))
        um.append(abs(u["mass"] - 0.03))
        # The centre of mass, where defined (m > 0); at m = 0 the first moment's error instead.
        ec.append(np.linalg.norm(c["parameters"][1:4] - 0.03 * com))
        uc.append(np.linalg.norm(u["parameters"][1:4] - 0.03 * com))
    print(f"## A 30 g tool, orientations within 10 degrees ({trials} trials, 20 poses each)\n")
    print(f"- unconstrained mass negative in {negative} trials; constraint active in {active}; smallest "
          f"consistent mass {min_mass:.3g} kg")
    print(f"- mean error of m: consistent / least squares = {np.mean(em) / np.mean(um):.3f} "
          f"({np.mean(em):.4g} / {np.mean(um):.4g} kg)")
    print(f"- mean error of the first moment m c: consistent / least squares = {np.mean(ec) / np.mean(uc):.3f}\n")


BIAS = np.array([1.0, 2.0, -3.0, 0.1, 0.05, -0.2])


def moving_log(rng, n, noise=0.1, mass=2.5, com=(0.02, -0.01, 0.06), inertia=None):
    """A trajectory of 5 harmonics per axis; noise (fraction of each signal's RMS) in a, omega, alpha;
    wrench noise 0.2 N / 0.01 N m."""
    from payload_reference import trajectory
    t, omega, alpha, accel, q = trajectory(rng, n)
    inertia = np.diag([0.012, 0.02, 0.015]) if inertia is None else inertia
    g_s = np.array([rotation_from_quaternion(qi).T @ G for qi in q])
    w = -wrench(mass, com, inertia, accel - g_s, omega, alpha) + BIAS
    if noise > 0:
        w[:, :3] += 0.2 * rng.standard_normal((n, 3))
        w[:, 3:] += 0.01 * rng.standard_normal((n, 3))
        accel = accel + noise * np.sqrt(np.mean(accel ** 2, axis=0)) * rng.standard_normal(accel.shape)
        omega = omega + noise * np.sqrt(np.mean(omega ** 2, axis=0)) * rng.standard_normal(omega.shape)
        alpha = alpha + noise * np.sqrt(np.mean(alpha ** 2, axis=0)) * rng.standard_normal(alpha.shape)
    return t, omega, alpha, accel, q, w, inertia


def moving(trials, rows=10_000):
    ls_err, eiv_err, rod_consistent, rod_unconstrained_inconsistent, times = [], [], 0, 0, []
    for trial in range(trials):
        rng = np.random.default_rng(1000 + trial)
        t, omega, alpha, accel, q, w, inertia = moving_log(rng, rows)
        std = lambda x: ",".join(map(str, 0.1 * np.sqrt(np.mean(x ** 2, axis=0))))  # noqa: E731
        common = dict(wrench=w, quaternion=q, accel=accel, omega=omega, alpha=alpha, noise_std_wrench=[0.2, 0.01],
                      noise_std_accel=list(0.1 * np.sqrt(np.mean(accel ** 2, axis=0)) / 1.0),
                      noise_std_omega=list(0.1 * np.sqrt(np.mean(omega ** 2, axis=0))),
                      noise_std_alpha=list(0.1 * np.sqrt(np.mean(alpha ** 2, axis=0))))
        del std
        ls = pl.identify(**common)
        start = time.perf_counter()
        eiv = pl.identify(**common, criterion="eiv")
        times.append(time.perf_counter() - start)
        # The noisy signals' own RMS is what the test knows; the truth's is within 1 % of it.
        ls_err.append(np.linalg.norm(ls["inertia"] - inertia))
        eiv_err.append(np.linalg.norm(eiv["inertia"] - inertia))
    for trial in range(trials):
        rng = np.random.default_rng(5000 + trial)
        rod = np.diag([0.02, 0.02, 1e-7])
        t, omega, alpha, accel, q, w, inertia = moving_log(rng, 2000, mass=1.0, com=(0, 0, 0.1), inertia=rod)
        common = dict(wrench=w, quaternion=q, accel=accel, omega=omega, alpha=alpha, noise_std_wrench=[0.2, 0.01],
                      noise_std_accel=list(0.1 * np.sqrt(np.mean(accel ** 2, axis=0))),
                      noise_std_omega=list(0.1 * np.sqrt(np.mean(omega ** 2, axis=0))),
                      noise_std_alpha=list(0.1 * np.sqrt(np.mean(alpha ** 2, axis=0))), criterion="eiv")
        eiv = pl.identify(**common)
        u = pl.identify(**common, consistent=False)
        rod_consistent += eiv["physically_consistent"]
        rod_unconstrained_inconsistent += not u["physically_consistent"]
    print(f"## Moving poses ({trials} trials, {rows} rows, noise 10 % of each signal's RMS in a, omega, alpha)\n")
    print(f"- mean inertia error ||I - I_true||_F: least squares {np.mean(ls_err):.4g}, errors in variables "
          f"{np.mean(eiv_err):.4g} kg m^2: ratio {np.mean(eiv_err) / np.mean(ls_err):.3f} (goal <= 0.8)")
    print(f"- errors-in-variables fit time: median {np.median(times):.3f} s (Python call, {rows} rows)")
    print(f"- thin rod (2000 rows, {trials} trials): consistent in {rod_consistent} of {trials}; the unconstrained "
          f"errors-in-variables fit was inconsistent in {rod_unconstrained_inconsistent}\n")


def design(trials):
    rng = np.random.default_rng(4)
    g = rng.standard_normal((1000, 3))
    g *= 9.80665 / np.linalg.norm(g, axis=1, keepdims=True)
    d = pl.design(gravity_in_sensor=g, poses=6, random=trials, noise_std_wrench=[0.2, 0.01])
    print("## Design (K = 6 from 1000 candidates, noise 0.2 N / 0.01 N m)\n")
    print(f"- predicted standard error of m: chosen {d['se_mass']:.4g} kg; {trials} random choices' 10th / 50th / "
          f"90th percentiles {d['random']['se_mass'][0]:.4g} / {d['random']['se_mass'][1]:.4g} / "
          f"{d['random']['se_mass'][2]:.4g} kg (goal: chosen <= 10th)")
    print(f"- of c: chosen {d['se_center_of_mass_norm']:.4g} m; random 10th percentile "
          f"{d['random']['se_center_of_mass_norm'][0]:.4g} m\n")


def body_parameters(rng, thin=False):
    m = rng.uniform(0.5, 5.0)
    c = rng.uniform(-0.2, 0.2, 3)
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    spread = rng.uniform(0.005, 0.05, 3)  # second moments: >= 0 is the triangle inequality
    if thin:
        spread = np.array([1e-7 * spread[0], 1e-7 * spread[0], spread[0]])  # a rod along one axis
    moments = spread.sum() - spread
    I = Q @ np.diag(moments) @ Q.T + m * (c @ c * np.eye(3) - np.outer(c, c))
    return np.concatenate([[m], m * c, [I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]])


def regress_problem(rng, K, rows, noise=0.5, thin=False):
    phi = np.concatenate([body_parameters(rng, thin) for _ in range(K)])
    Y = rng.standard_normal((rows, 10 * K))
    return Y, Y @ phi + noise * rng.standard_normal(rows), phi


def cvxopt_reference(Y, tau, K):
    from cvxopt import matrix, solvers
    p = Y.shape[1]
    scale = 1.0 / np.linalg.norm(Y, axis=0)
    Ys = Y * scale
    G = np.zeros((16 * K, p))
    for k in range(K):
        for j in range(10):
            phi = np.zeros(10)
            phi[j] = scale[10 * k + j]
            m, h = phi[0], phi[1:4]
            I = np.array([[phi[4], phi[5], phi[6]], [phi[5], phi[7], phi[8]], [phi[6], phi[8], phi[9]]])
            J = np.zeros((4, 4))
            J[:3, :3] = 0.5 * np.trace(I) * np.eye(3) - I
            J[:3, 3] = J[3, :3] = h
            J[3, 3] = m
            G[16 * k:16 * k + 16, 10 * k + j] = -J.ravel(order="F")
    solvers.options.update({"show_progress": False, "abstol": 1e-14, "reltol": 1e-14, "feastol": 1e-14,
                            "maxiters": 300})
    start = time.perf_counter()
    sol = solvers.coneqp(matrix(2 * Ys.T @ Ys), matrix(-2 * Ys.T @ tau), matrix(G), matrix(np.zeros(16 * K)),
                         {"l": 0, "q": [], "s": [4] * K})
    elapsed = time.perf_counter() - start
    phi = np.array(sol["x"]).ravel() * scale
    return np.sum((Y @ phi - tau) ** 2), elapsed


def regress(trials):
    ratios, consistent, total = [], 0, 0
    for K in range(1, 8):
        for trial in range(trials):
            rng = np.random.default_rng(100 * K + trial)
            Y, tau, _ = regress_problem(rng, K, 15 * K, thin=True)
            r = ph.regress(Y, tau, bodies=K)
            f_ref, _ = cvxopt_reference(Y, tau, K)
            ratios.append(r["criterion"] / f_ref)
            consistent += r["physically_consistent"]
            total += 1
    rng = np.random.default_rng(9)
    K, samples, outputs = 7, 20_000, 7
    Y, tau, _ = regress_problem(rng, K, samples * outputs, noise=0.1)
    times = []
    for _ in range(3):
        start = time.perf_counter()
        ph.regress(Y, tau, bodies=K)
        times.append(time.perf_counter() - start)
    print(f"## Regress ({trials} random problems for each K = 1..7, thin bodies, noisy)\n")
    print(f"- criterion / CVXOPT's: largest {max(ratios) - 1:+.2e} (goal <= 1e-6), smallest {min(ratios) - 1:+.2e}")
    print(f"- physically consistent: {consistent} of {total}")
    print(f"- K = 7, {samples} samples x {outputs} outputs ({samples * outputs} x {10 * K}): median "
          f"{np.median(times):.3f} s over 3 calls (Python, Y in memory; goal <= 1 s)\n")


GOALS = {"noise_free": noise_free, "static": static, "light": light, "moving": moving, "design": design,
         "regress": regress}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=None, help="trials per Monte Carlo (default: each goal's)")
    parser.add_argument("--only", choices=sorted(GOALS), action="append")
    args = parser.parse_args()
    defaults = {"static": 1000, "light": 1000, "moving": 100, "design": 1000, "regress": 20}
    print(f"# Payload and regress goals ({time.strftime('%Y-%m-%d')}, {cpu_model()}, spdfit {spdfit.__version__})\n")
    print("Command: `" + " ".join(["SPDFIT_SOURCE_DIR=. PYTHONPATH=build/python /usr/bin/python3"] + sys.argv) + "`\n")
    for name in args.only or GOALS:
        if name == "noise_free":
            noise_free()
        else:
            GOALS[name](args.trials or defaults[name])
    return 0


if __name__ == "__main__":
    sys.exit(main())
