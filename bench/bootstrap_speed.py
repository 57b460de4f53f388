"""Speed of the bootstrap (issue 15), measured through the CLI, best of `repeats` runs each.

1. `fit --bootstrap 1000 --json` on the data of `spdfit hexapod simulate --samples 200 --seed 1`
   (6x6, m = 200), every method, against the same fit without --bootstrap (goal: < 0.5 s on 2 cores).
2. `fit --stream --bootstrap 1000` on 10^7 rows (n = 6, .npy written here) against the plain
   `fit --stream` (goal: < 3x).

    /usr/bin/python3 bench/bootstrap_speed.py build/apps/spdfit [scratch-dir] [repeats]
"""
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

from machine import cpu_model


def best(command, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    cli = sys.argv[1]
    scratch = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/spdfit-bootstrap-bench")
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    scratch.mkdir(parents=True, exist_ok=True)
    cpu = cpu_model()
    print(f"# Bootstrap speed: {time.strftime('%Y-%m-%d')}, {cpu}, {os.cpu_count()} cores\n")
    print(f"`/usr/bin/python3 bench/bootstrap_speed.py {cli} {scratch} {repeats}`: wall time, best of "
          f"{repeats} runs of the CLI (process start and file reading included).\n")

    sim = scratch / "hexapod200"
    subprocess.run([cli, "hexapod", "simulate", "--samples", "200", "--seed", "1", "--noise-var", "0.86", "--out",
                    str(sim)], check=True, stdout=subprocess.DEVNULL)
    files = [str(sim / "A.csv"), str(sim / "B.csv")]
    print("## 6 x 6, m = 200 (`hexapod simulate --samples 200 --seed 1 --noise-var 0.86`), 1000 replicates\n")
    print("| method | fit alone (s) | --bootstrap 1000 (s) |")
    print("|---|---|---|")
    for method in ["ls", "procrustes", "tls", "tls-sym", "spde", "spd-tls", "psd-ls", "auto"]:
        plain = best([cli, "fit", "-m", method, "--json", *files], repeats)
        boot = best([cli, "fit", "-m", method, "--json", "--bootstrap", "1000", *files], repeats)
        print(f"| {method} | {plain:.3f} | {boot:.3f} |", flush=True)

    m = 10**7
    a_path, b_path = scratch / "A7.npy", scratch / "B7.npy"
    if not (a_path.exists() and b_path.exists()):
        rng = np.random.default_rng(1)
        X = np.loadtxt(sim / "truth.csv", delimiter=",")
        A0 = rng.uniform(-5, 5, (m, 6))
        np.save(a_path, A0 + 0.3 * rng.standard_normal(A0.shape))
        np.save(b_path, A0 @ X + 0.3 * rng.standard_normal(A0.shape))
    print(f"\n## --stream, 10^7 rows x 6 columns (.npy, {2 * a_path.stat().st_size / 1e6:.0f} MB, page cache warm)\n")
    print("| method | --stream (s) | --stream --bootstrap 1000 (s) | ratio |")
    print("|---|---|---|---|")
    for method in ["spde", "spd-tls"]:
        plain = best([cli, "fit", "-m", method, "--stream", "--json", str(a_path), str(b_path)], repeats)
        boot = best([cli, "fit", "-m", method, "--stream", "--json", "--bootstrap", "1000", str(a_path), str(b_path)],
                    repeats)
        print(f"| {method} | {plain:.2f} | {boot:.2f} | {boot / plain:.2f} |", flush=True)


if __name__ == "__main__":
    main()
