"""`spdfit payload identify --robust` against gross errors: the parameter error of least squares,
Huber and Tukey over the clean fit's, on static logs of tests/cli/test_payload.py's kind (200 poses,
noise 0.2 N / 0.01 N m, 2 % of the samples with a 40 N spike on one force axis), one row per seed.

    SPDFIT_SOURCE_DIR=. /usr/bin/python3 bench/payload_robust.py build/apps/spdfit [FIRST_SEED] [SEEDS]
"""
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "support"))
from payload_reference import static_log, write_log  # noqa: E402

FORCE = ["fx", "fy", "fz", "tx", "ty", "tz"]
QUAT = ["qx", "qy", "qz", "qw"]
TRUTH = np.array([1.2, 1.2 * 0.08, 0.0, 1.2 * 0.03, 5.0, -2.0, 1.0, 0.3, -0.1, 0.2])


def parameters(cli, path, *options):
    run = subprocess.run([cli, "payload", "identify", str(path), "--json", "--wrench-cols", "fx:tz", "--quat-cols",
                          "qx:qw", "--noise-std-wrench", "0.2,0.01", *options], capture_output=True, text=True, check=True)
    return np.array(json.loads(run.stdout)["parameters"])


def main():
    cli = sys.argv[1]
    first = int(sys.argv[2]) if len(sys.argv) > 2 else 21
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 6
    print("| seed | clean error | least squares / clean | huber / clean | tukey / clean |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(first, first + seeds):
            # The test's draws, in its order (tests/cli/test_payload.py, seed 21).
            rng = np.random.default_rng(seed)
            clean = static_log(rng, 200)
            log = {key: value.copy() for key, value in clean.items()}
            bad = rng.choice(200, 4, replace=False)
            log["wrench"][bad, rng.integers(0, 3, 4)] += 40.0
            clean_path = write_log(pathlib.Path(tmp) / "clean.csv", [(FORCE, clean["wrench"]), (QUAT, clean["quaternion"])])
            bad_path = write_log(pathlib.Path(tmp) / "bad.csv", [(FORCE, log["wrench"]), (QUAT, log["quaternion"])])
            error = lambda p: np.linalg.norm(p - TRUTH)  # noqa: E731
            reference = error(parameters(cli, clean_path))
            ratios = [error(parameters(cli, bad_path, *o)) / reference
                      for o in ([], ["--robust", "huber"], ["--robust", "tukey"])]
            print(f"| {seed} | {reference:.4g} | " + " | ".join(f"{r:.2f}" for r in ratios) + " |")


if __name__ == "__main__":
    main()
