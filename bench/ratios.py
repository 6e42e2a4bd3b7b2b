#!/usr/bin/env python3
"""Median time per sample and ratios from ONE nocdyn_bench JSON run (bench/README.md).

usage: bench/ratios.py bench.json
"""
import json
import sys


def main(path):
    run = json.load(open(path))
    med = {}
    for b in run["benchmarks"]:
        if b.get("aggregate_name") == "median":
            med[b["run_name"]] = b
    def per_sample(name):
        b = med.get(name)
        return None if b is None else b.get("per_sample", None)
    print(f"machine: {run['context'].get('host_name', '?')}, {run['context']['num_cpus']} cpus, "
          f"{run['context']['mhz_per_cpu']} MHz, load {run['context'].get('load_avg')}")
    print("| benchmark | median per sample | this / nocdyn | this / nocdyn_full |")
    print("| --- | --- | --- | --- |")
    refs = [per_sample("BM_InverseDynamics/nocdyn"), per_sample("BM_InverseDynamics/nocdyn_full")]
    for name in sorted(med):
        t = per_sample(name)
        if t is None:
            continue
        ratios = [f"{t / r:.1f}x" if r and name.startswith("BM_InverseDynamics/") else "" for r in refs]
        unit, scale = ("us", 1e6) if t >= 1e-6 else ("ns", 1e9)
        print(f"| {name} | {t * scale:.1f} {unit} | {ratios[0]} | {ratios[1]} |")
    for name in sorted(med):
        if per_sample(name) is None:
            b = med[name]
            print(f"| {name} | {b['real_time']:.1f} {b['time_unit']} per iteration (wall) | | |")


if __name__ == "__main__":
    main(sys.argv[1])
