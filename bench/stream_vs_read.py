"""Streaming .npy against reading the same files from the page cache (issue 19, item 4's target:
spdfit fit --stream at most 3 times the read), timed in one run, alternating, so that both see the
same machine state. Each command is run `--runs` times; the first two of each are warm-up.

    /usr/bin/python3 bench/stream_vs_read.py A.npy B.npy [--spdfit build/apps/spdfit] [--other OLD_SPDFIT]

prints the median, minimum and maximum wall time of: cat A B > /dev/null; dd of A and of B
(bs=1M); spdfit fit --method spde --stream A B (and the same with --other, an older build, when
given); and the ratio of each spdfit to cat."""
import argparse
import statistics
import subprocess
import time


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
    times = {name: [] for name in commands}
    for _ in range(args.runs):
        for name, steps in commands.items():
            start = time.perf_counter()
            for step in steps:
                subprocess.run(step, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            times[name].append(time.perf_counter() - start)
    medians = {}
    for name, values in times.items():
        kept = values[2:]
        medians[name] = statistics.median(kept)
        print(f"{name}: median {medians[name]:.3f} s, min {min(kept):.3f}, max {max(kept):.3f} ({len(kept)} runs)")
    for name in ("spdfit", "other spdfit"):
        if name in medians:
            print(f"{name} / cat: {medians[name] / medians['cat A B']:.2f}")


if __name__ == "__main__":
    main()
