"""The noise-model table of docs/guide.md ("Units and noise") with an independent reference.

For each row (data set, m) it runs build/bench/spdfit_noise_table (the thesis experiment with
per-channel Gaussian noise: spdfit's mean errors of auto and psd-ls without a noise model and of
spd-tls and auto with the true and the rest segment's covariances), has it dump every trial's data
and spdfit's maximum-likelihood estimate, and computes the maximum-likelihood estimate with the
true covariances independently (tests/reference/noise_reference.py: SciPy BFGS on a Cholesky
factor). It prints the table, the ratio of spdfit's rest-segment estimate's mean error to the
reference's, and checks on every trial that spdfit's criterion is no larger than the reference's.

    /usr/bin/python3 bench/noise_table.py --program build/bench/spdfit_noise_table [--trials 40]
"""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "reference"))
import noise_reference as ref  # noqa: E402

ROWS = [("both", 100), ("both", 1000), ("kn", 1000), ("b-only", 1000)]
LABELS = {"both": "std in A (0.2, 0.4, 0.8, ...), in B (3, 1, 0.3, ...)", "kn": "same, B in kN (B/1000)",
          "b-only": "noise only in B (A exact)"}
# spdfit's criterion may exceed the reference's only by rounding.
CRITERION_RTOL = 1e-10


def run_row(program, case, m, trials, seed, rest, directory):
    out = subprocess.run([program, "--case", case, "--samples", str(m), "--trials", str(trials), "--seed", str(seed),
                          "--rest-samples", str(rest), "--dump", str(directory)],
                         check=True, capture_output=True, text=True).stdout
    means = {}
    for line in out.splitlines():
        match = re.match(r"(\S+)\s+noise model (\S+)\s+([0-9.]+) \(([0-9.]+)\)\s+failures (\d+)", line)
        if match:
            means[(match[1], match[2])] = (float(match[3]), float(match[4]), int(match[5]))
    return means


def reference_errors(directory, trials):
    d = pathlib.Path(directory)
    truth = np.load(d / "truth.npy")
    cov_a, cov_b = np.load(d / "cov_a.npy"), np.load(d / "cov_b.npy")
    scale_b = float((d / "scale_b.txt").read_text())
    errors, spdfit_errors, worst = [], [], 0.0
    for k in range(trials):
        A, B = np.load(d / f"trial{k}_A.npy"), np.load(d / f"trial{k}_B.npy")
        X_ref, f_ref = ref.ml_estimate(A, B, cov_a, cov_b)
        errors.append(np.linalg.norm(X_ref / scale_b - truth))
        X = np.load(d / f"trial{k}_X_ml_true.npy")
        spdfit_errors.append(np.linalg.norm(X / scale_b - truth))
        f = ref.criterion(A, B, X, cov_a, cov_b)
        worst = max(worst, f / f_ref - 1.0)
    return np.array(errors), np.array(spdfit_errors), worst


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", default="build/bench/spdfit_noise_table")
    parser.add_argument("--trials", type=int, default=40)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--rest-samples", type=int, default=2000)
    args = parser.parse_args()
    print(f"{args.trials} trials per row, seed {args.seed}, rest segment {args.rest_samples} rows; "
          "mean ||M - M_hat||_F (standard error)\n")
    print("| data | m | auto, no model | psd-ls, no model | ML, true covariances (SciPy) | spd-tls, true "
          "| spd-tls, rest | auto, rest | rest / ML | spdfit f / SciPy f - 1 (worst) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    failed = False
    for case, m in ROWS:
        with tempfile.TemporaryDirectory() as directory:
            means = run_row(args.program, case, m, args.trials, args.seed, args.rest_samples, directory)
            errors, spdfit_errors, worst = reference_errors(directory, args.trials)

        def cell(key):
            mean, se, failures = means[key]
            return f"{mean:.3f} ({se:.3f})" + (f", {failures} failed" if failures else "")

        ref_mean = errors.mean()
        ref_se = errors.std(ddof=1) / np.sqrt(len(errors))
        # The dumped estimates are the experiment's (the same draws): their mean is its mean.
        assert abs(spdfit_errors.mean() - means[("spd-tls", "true")][0]) < 1e-3, "dump and experiment disagree"
        ratio = means[("spd-tls", "rest")][0] / ref_mean
        print(f"| {LABELS[case]} | {m} | {cell(('auto', 'none'))} | {cell(('psd-ls', 'none'))} | "
              f"{ref_mean:.3f} ({ref_se:.3f}) | {cell(('spd-tls', 'true'))} | {cell(('spd-tls', 'rest'))} | "
              f"{cell(('auto', 'rest'))} | {ratio:.3f} | {worst:.1e} |")
        failed |= worst > CRITERION_RTOL
    if failed:
        print(f"\nspdfit's criterion exceeded the reference's by more than {CRITERION_RTOL} on some trial")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
