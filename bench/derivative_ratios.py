#!/usr/bin/env python3
"""Ratios of the derivatives' cost to the dynamics' from ONE nocdyn_derivatives_bench JSON run.

usage: bench/derivative_ratios.py derivatives.json
(the run: build/bench/nocdyn_derivatives_bench --benchmark_repetitions=5 \
 --benchmark_out=derivatives.json --benchmark_out_format=json)
"""
import json
import sys


def main(path):
    run = json.load(open(path))
    per_sample = {}
    for b in run["benchmarks"]:
        if b.get("aggregate_name") in (None, "median") and "per_sample" in b:
            name = b["run_name"]
            if b.get("aggregate_name") == "median" or name not in per_sample:
                per_sample[name] = b["per_sample"]
    robots = sorted({name.split("/")[1] for name in per_sample})
    print("| robot | d tau/d(p,dp,ddp) | / inverse dynamics (full) | / inverse dynamics (lean) "
          "| d ddp/d(p,dp,tau) | / forward dynamics |")
    print("| --- | --- | --- | --- | --- | --- |")
    for robot in robots:
        t = {what: per_sample.get(f"BM_Derivatives/{robot}/{what}") for what in
             ("inverse_dynamics_fast", "inverse_dynamics", "inverse_derivatives", "forward_dynamics",
              "forward_derivatives")}
        if None in t.values():
            continue
        print(f"| {robot} | {t['inverse_derivatives'] * 1e9:.0f} ns | "
              f"{t['inverse_derivatives'] / t['inverse_dynamics']:.1f}x | "
              f"{t['inverse_derivatives'] / t['inverse_dynamics_fast']:.1f}x | "
              f"{t['forward_derivatives'] * 1e9:.0f} ns | "
              f"{t['forward_derivatives'] / t['forward_dynamics']:.1f}x |")
    print()
    print("| robot | u, du, ddu and derivatives | / inverse dynamics (full) | as one batch (1 thread) "
          "| / inverse dynamics (full) |")
    print("| --- | --- | --- | --- | --- |")
    for robot in robots:
        t = {what: per_sample.get(f"BM_Derivatives/{robot}/{what}") for what in
             ("inverse_dynamics", "actuator_derivatives", "actuator_batch")}
        if None in t.values():
            continue
        print(f"| {robot} | {t['actuator_derivatives'] * 1e9:.0f} ns | "
              f"{t['actuator_derivatives'] / t['inverse_dynamics']:.1f}x | "
              f"{t['actuator_batch'] * 1e9:.0f} ns | "
              f"{t['actuator_batch'] / t['inverse_dynamics']:.1f}x |")


if __name__ == "__main__":
    main(sys.argv[1])
