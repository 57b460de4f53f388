"""Mean, median and max error of the estimators against the number of samples m (issue 14).

The thesis model (M_p of eq. 6.1, n = 6, accelerations uniform of variance 25/3) with uniform
noise of width nm in every entry of A and B (variance nm^2 / 12), nm = 1 and 3.2, m = 12, 30,
100, 1000; `spdfit experiment thesis` for each point. Prints a Markdown table and the command.

    /usr/bin/python3 bench/methods_vs_m.py build/apps/spdfit [trials]
"""
import json
import subprocess
import sys
import time

from machine import cpu_model

METHODS = ["procrustes", "tls-sym", "spde", "spd-tls", "psd-ls", "auto"]
WIDTHS = [1.0, 3.2]
SIZES = [12, 30, 100, 1000]


def main():
    cli = sys.argv[1]
    trials = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
    cpu = cpu_model()
    print(f"# Estimators against m: {time.strftime('%Y-%m-%d')}, {cpu}\n")
    print(f"`/usr/bin/python3 bench/methods_vs_m.py {cli} {trials}`; each point is `spdfit experiment thesis "
          f"--noise-var nm^2/12 --samples m --trials {trials} --seed 1 --methods {','.join(METHODS)}`.\n")
    print("Cells: mean / median / max of ||M_p - M_hat||_F (failures in brackets); auto/best is auto's mean "
          "over the lowest mean of the other methods.\n")
    print("| nm | m | " + " | ".join(METHODS) + " | auto/best | seconds |")
    print("|---|---|" + "---|" * (len(METHODS) + 2))
    for width in WIDTHS:
        for m in SIZES:
            start = time.perf_counter()
            out = subprocess.run([cli, "experiment", "thesis", "--noise-var", repr(width * width / 12),
                                  "--samples", str(m), "--trials", str(trials), "--seed", "1",
                                  "--methods", ",".join(METHODS), "--json"],
                                 check=True, capture_output=True, text=True).stdout
            seconds = time.perf_counter() - start
            results = json.loads(out)["methods"]
            best = min(results[name]["mean"] for name in METHODS if name != "auto")
            cells = []
            for name in METHODS:
                r = results[name]
                cell = f"{r['mean']:.3f} / {r['median']:.3f} / {r['max']:.2f}"
                if r["failures"]:
                    cell += f" ({r['failures']})"
                cells.append(f"**{cell}**" if name != "auto" and r["mean"] == best else cell)
            print(f"| {width:g} | {m} | " + " | ".join(cells) +
                  f" | {results['auto']['mean'] / best:.3f} | {seconds:.2f} |")


if __name__ == "__main__":
    main()
