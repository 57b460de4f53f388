"""The speed of `spdfit payload identify` on 10^5 rows (static least squares; moving errors in
variables) and of `spdfit physical regress` at K = 7, 20 000 samples x 7 outputs, through the
command line (the file read included), each beside `cat` of the same file as the floor of
reading it: wall time and CPU time (user + system of the child), medians and spread over
interleaved runs, with the load average (the machine is shared).

    SPDFIT_SOURCE_DIR=. /usr/bin/python3 bench/payload_speed.py build/apps/spdfit [--runs 7] [--dir /tmp/payload_speed]
"""
import argparse
import os
import pathlib
import resource
import subprocess
import sys
import time

import numpy as np

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(ROOT / "tests" / "support"))
sys.path.insert(0, str(ROOT / "bench"))
from machine import cpu_model  # noqa: E402
from payload_reference import G, random_quaternions, rotation_from_quaternion, trajectory, wrench  # noqa: E402


def write_logs(directory, rows=100_000):
    rng = np.random.default_rng(1)
    directory.mkdir(parents=True, exist_ok=True)
    static = directory / "static.npy"
    moving = directory / "moving.npy"
    if not static.exists():
        q = random_quaternions(rng, rows)
        g_s = np.einsum("nji,j->ni", np.array([rotation_from_quaternion(qi) for qi in q]), G)
        w = -wrench(1.2, [0.08, 0, 0.03], np.zeros((3, 3)), -g_s) + [5, -2, 1, 0.3, -0.1, 0.2]
        w += np.hstack([0.2 * rng.standard_normal((rows, 3)), 0.01 * rng.standard_normal((rows, 3))])
        np.save(static, np.hstack([w, q]))
        np.savetxt(directory / "static.csv", np.hstack([w, q]), delimiter=",", fmt="%.9g")
    if not moving.exists():
        t, omega, alpha, accel, q = trajectory(rng, rows, duration=rows / 1000.0)
        R = np.array([rotation_from_quaternion(qi) for qi in q])
        g_s = np.einsum("nji,j->ni", R, G)
        w = -wrench(2.5, [0.02, -0.01, 0.06], np.diag([0.012, 0.02, 0.015]), accel - g_s, omega, alpha)
        w += np.hstack([0.2 * rng.standard_normal((rows, 3)), 0.01 * rng.standard_normal((rows, 3))])
        noisy = [x + 0.1 * np.sqrt(np.mean(x ** 2, axis=0)) * rng.standard_normal(x.shape) for x in (accel, omega, alpha)]
        np.save(moving, np.hstack([w, q, *noisy]))
        np.savetxt(directory / "moving.csv", np.hstack([w, q, *noisy]), delimiter=",", fmt="%.9g")
    return directory


def regress_files(directory):
    y = directory / "Y.npy"
    if not y.exists():
        rng = np.random.default_rng(2)
        Y = rng.standard_normal((140_000, 70))
        phi = rng.standard_normal(70)
        np.save(y, Y)
        np.save(directory / "tau.npy", (Y @ phi + 0.1 * rng.standard_normal(140_000))[:, None])
    return y, directory / "tau.npy"


def timed(command):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--dir", default="/tmp/payload_speed")
    args = parser.parse_args()
    d = write_logs(pathlib.Path(args.dir))
    y, tau = regress_files(d)
    static_cols = ["--wrench-cols", "1:6", "--quat-cols", "7:10"]
    moving_cols = static_cols + ["--accel-cols", "11:13", "--omega-cols", "14:16", "--alpha-cols", "17:19"]
    noise = ["--noise-std-wrench", "0.2,0.01", "--noise-std-accel", "0.2", "--noise-std-omega", "0.1",
             "--noise-std-alpha", "0.5", "--criterion", "eiv"]
    cases = {
        "static ls, .npy": [args.cli, "payload", "identify", str(d / "static.npy"), *static_cols],
        "static ls, .csv": [args.cli, "payload", "identify", str(d / "static.csv"), *static_cols],
        "cat static.csv": ["cat", str(d / "static.csv")],
        "moving eiv, .npy": [args.cli, "payload", "identify", str(d / "moving.npy"), *moving_cols, *noise],
        "moving eiv, .csv": [args.cli, "payload", "identify", str(d / "moving.csv"), *moving_cols, *noise],
        "moving ls, .npy": [args.cli, "payload", "identify", str(d / "moving.npy"), *moving_cols],
        "cat moving.csv": ["cat", str(d / "moving.csv")],
        "regress K=7, 140000 x 70, .npy": [args.cli, "physical", "regress", str(y), str(tau), "--bodies", "7"],
    }
    results = {name: [] for name in cases}
    for _ in range(args.runs):
        for name, command in cases.items():  # interleaved
            results[name].append(timed(command))
    print(f"# payload_speed ({time.strftime('%Y-%m-%d')}, {cpu_model()}, load average "
          f"{os.getloadavg()[0]:.1f})\n")
    print("Command: `" + " ".join(["SPDFIT_SOURCE_DIR=. /usr/bin/python3"] + sys.argv) + "`\n")
    print("| case | wall median (min-max) s | CPU median (min-max) s |\n|---|---|---|")
    for name, runs in results.items():
        wall = np.array([r[0] for r in runs])
        cpu = np.array([r[1] for r in runs])
        print(f"| {name} | {np.median(wall):.3f} ({wall.min():.3f}-{wall.max():.3f}) | "
              f"{np.median(cpu):.3f} ({cpu.min():.3f}-{cpu.max():.3f}) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
