#!/usr/bin/env python3
"""Two builds of nocdyn_bench in one run: the same benchmarks, alternating between the two
binaries round after round (so that both see the same machine load), and the median per
sample of each with their ratio.

usage: bench/before_after.py BEFORE_BINARY AFTER_BINARY --filter REGEX [--rounds 3] [--min-time 0.3]

Prints a Markdown table: benchmark, median per sample before and after, after / before.
"""
import argparse
import json
import statistics
import subprocess
import sys


def one_run(binary, pattern, min_time):
    out = subprocess.run([binary, f"--benchmark_filter={pattern}", f"--benchmark_min_time={min_time}",
                          "--benchmark_format=json"], check=True, capture_output=True, text=True, timeout=3600)
    run = json.loads(out.stdout)
    return run, {b["name"]: b["per_sample"] for b in run["benchmarks"] if "per_sample" in b}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--filter", required=True, help="the benchmarks (a --benchmark_filter regex)")
    parser.add_argument("--rounds", type=int, default=3, help="runs of each binary, alternating (1..20)")
    parser.add_argument("--min-time", type=float, default=0.3, help="--benchmark_min_time of each run, s")
    args = parser.parse_args()
    if not 1 <= args.rounds <= 20:
        sys.exit("before_after.py: --rounds must be 1..20")
    times = {"before": {}, "after": {}}
    context = None
    for _ in range(args.rounds):
        for side, binary in (("before", args.before), ("after", args.after)):
            run, per_sample = one_run(binary, args.filter, args.min_time)
            context = context or run["context"]
            for name, t in per_sample.items():
                times[side].setdefault(name, []).append(t)
    common = [name for name in times["before"] if name in times["after"]]
    if not common:
        sys.exit("before_after.py: no benchmark matched the filter in both binaries")
    print(f"{args.rounds} alternating rounds of each binary; {context['num_cpus']} cpus, "
          f"load {context.get('load_avg')} at the start")
    print()
    print("| benchmark | before (median) | after (median) | after / before |")
    print("| --- | --- | --- | --- |")
    for name in common:
        b, a = statistics.median(times["before"][name]), statistics.median(times["after"][name])
        unit, scale = ("us", 1e6) if b >= 1e-6 else ("ns", 1e9)
        print(f"| {name} | {b * scale:.1f} {unit} | {a * scale:.1f} {unit} | {a / b:.3f} |")


if __name__ == "__main__":
    main()
