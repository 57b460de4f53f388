"""Strong scaling of `mpirun -n K spdfit fit --stream` (issue 20), through the CLI, best of
`repeats` runs each, files in the page cache (one untimed run first).

- .npy, n = 6, 10^7 rows (2 x 480 MB); CSV, n = 6, 2 * 10^6 rows (about 2 x 220 MB); .npy,
  n = 50, 10^6 rows (2 x 400 MB: the arithmetic, not the reading, is the limit);
- spdfit alone (no mpirun), then mpirun with K = 1, 2 and 4 processes (4 oversubscribes this
  2-core machine: for correctness, not speed), each process on cores / K threads (the default);
- and the same with --threads 1, which shows what K processes give over one, thread for thread.

    /usr/bin/python3 bench/scale_mpi.py build/apps/spdfit [scratch-dir] [repeats]
"""
import os
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np

from machine import cpu_model


def best(command, repeats):
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)  # page cache, untimed
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return min(times)


def make(scratch, name, m, n, kind):
    a, b = scratch / f"A-{name}.{kind}", scratch / f"B-{name}.{kind}"
    if a.exists() and b.exists():
        return a, b
    rng = np.random.default_rng(1)
    X = rng.standard_normal((n, n))
    X = X @ X.T + n * np.eye(n)
    chunk = 10**6
    with open(a, "wb") as fa, open(b, "wb") as fb:
        if kind == "npy":
            A = np.lib.format.open_memmap(a, mode="w+", dtype=np.float64, shape=(m, n))
            B = np.lib.format.open_memmap(b, mode="w+", dtype=np.float64, shape=(m, n))
            for start in range(0, m, chunk):
                rows = min(chunk, m - start)
                A[start:start + rows] = rng.standard_normal((rows, n))
                B[start:start + rows] = A[start:start + rows] @ X + 0.01 * rng.standard_normal((rows, n))
            A.flush()
            B.flush()
        else:
            for start in range(0, m, chunk):
                rows = min(chunk, m - start)
                A = rng.standard_normal((rows, n))
                np.savetxt(fa, A, delimiter=",", fmt="%.17g")
                np.savetxt(fb, A @ X + 0.01 * rng.standard_normal((rows, n)), delimiter=",", fmt="%.17g")
    return a, b


def main():
    cli = sys.argv[1]
    scratch = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/spdfit-scale-bench")
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    scratch.mkdir(parents=True, exist_ok=True)
    mpirun = [shutil.which("mpirun"), "-q", "--oversubscribe"]
    if os.geteuid() == 0:
        mpirun.insert(1, "--allow-run-as-root")
    print(f"# Scale-out: mpirun -n K spdfit fit --stream ({time.strftime('%Y-%m-%d')}, {cpu_model()}, "
          f"{os.cpu_count()} cores)\n")
    print(f"`/usr/bin/python3 bench/scale_mpi.py {cli} {scratch} {repeats}`: wall time in seconds, best of "
          f"{repeats} runs of the CLI after one untimed run (files in the page cache), --method spde.\n")
    print("| data | threads per process | spdfit alone | K = 1 | K = 2 | K = 4 (oversubscribed) |")
    print("|---|---|---|---|---|---|")
    for name, m, n, kind in [("npy6", 10**7, 6, "npy"), ("csv6", 2 * 10**6, 6, "csv"), ("npy50", 10**6, 50, "npy")]:
        a, b = make(scratch, name, m, n, kind)
        size = (a.stat().st_size + b.stat().st_size) / 1e6
        for threads in [None, 1]:
            extra = [] if threads is None else ["--threads", str(threads)]
            fit = [cli, "fit", "--method", "spde", "--stream", *extra, str(a), str(b)]
            row = [best(fit, repeats)] + [best(mpirun + ["-n", str(k)] + fit, repeats) for k in (1, 2, 4)]
            label = "cores / K" if threads is None else "1"
            print(f"| {kind}, n = {n}, m = {m:.0e} ({size:.0f} MB) | {label} | " +
                  " | ".join(f"{t:.2f}" for t in row) + " |", flush=True)


if __name__ == "__main__":
    main()
