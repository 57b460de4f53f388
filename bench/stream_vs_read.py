"""Streaming .npy against reading the same files from the page cache (issue 19, item 4's target:
spdfit fit --stream at most 3 times the read), timed in one run, alternating, so that both see the
same machine state. Each command is run `--runs` times; the first two of each are warm-up.

    /usr/bin/python3 bench/stream_vs_read.py A.npy B.npy [--spdfit build/apps/spdfit] [--other OLD_SPDFIT]

prints, for each of: cat A B > /dev/null; dd of A and of B (bs=1M); spdfit fit --method spde
--stream A B (and the same with --other, an older build, when given), the median, minimum and
maximum wall time and the median and minimum CPU time (user + system, of the command and its
threads); then the ratio of each spdfit to cat, of the medians and of the best runs, wall and CPU.
The load average before and after is printed too: on a shared machine the CPU times are the
steadier comparison."""
import argparse
import os
import resource
import statistics
import subprocess
import time


def cpu_of_children():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--spdfit", default="build/apps/spdfit")
    parser.add_argument("--other", help="another spdfit build to time alongside")
    parser.add_argument("--runs", type=int, default=12)
    args = parser.parse_args()
    commands = {
        "cat A B": [["cat", args.a, args.b]],
        "dd A; dd B (bs=1M)": [["dd", f"if={args.a}", "of=/dev/null", "bs=1M"],
                               ["dd", f"if={args.b}", "of=/dev/null", "bs=1M"]],
        "spdfit": [[args.spdfit, "fit", "--method", "spde", "--stream", args.a, args.b]],
    }
    if args.other:
        commands["other spdfit"] = [[args.other, "fit", "--method", "spde", "--stream", args.a, args.b]]
    print("load average before: %.2f %.2f %.2f" % os.getloadavg())
    walls = {name: [] for name in commands}
    cpus = {name: [] for name in commands}
    for _ in range(args.runs):
        for name, steps in commands.items():
            cpu = cpu_of_children()
            start = time.perf_counter()
            for step in steps:
                subprocess.run(step, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            walls[name].append(time.perf_counter() - start)
            cpus[name].append(cpu_of_children() - cpu)
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())
    median, best, median_cpu, best_cpu = {}, {}, {}, {}
    for name in commands:
        wall, cpu = walls[name][2:], cpus[name][2:]
        median[name], best[name] = statistics.median(wall), min(wall)
        median_cpu[name], best_cpu[name] = statistics.median(cpu), min(cpu)
        print(f"{name}: wall median {median[name]:.3f} s, min {best[name]:.3f}, max {max(wall):.3f}; "
              f"CPU median {median_cpu[name]:.3f} s, min {best_cpu[name]:.3f} ({len(wall)} runs)")
    for name in ("spdfit", "other spdfit"):
        if name in median:
            print(f"{name} / cat: wall {median[name] / median['cat A B']:.2f} (medians), "
                  f"{best[name] / best['cat A B']:.2f} (best); "
                  f"CPU {median_cpu[name] / median_cpu['cat A B']:.2f} (medians), "
                  f"{best_cpu[name] / best_cpu['cat A B']:.2f} (best)")


if __name__ == "__main__":
    main()
