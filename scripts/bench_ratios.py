#!/usr/bin/env python3
"""Prints each benchmark's median time as a ratio to the memcpy benchmark of the same run."""
import json
import sys


def main(path):
    with open(path) as f:
        data = json.load(f)
    medians = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name", "median") != "median":
            continue
        name = b.get("run_name", b["name"]).replace("_median", "")
        medians[name] = b["real_time"]
    base = [v for k, v in medians.items() if "Memcpy" in k]
    if not base:
        print("(no memcpy baseline in this run)")
        return
    unit = data["benchmarks"][0].get("time_unit", "ms")
    print(f"{'benchmark':48s} {'median':>12s} {'x memcpy':>9s}")
    for name, t in medians.items():
        print(f"{name:48s} {t:10.3f}{unit:>2s} {t / base[0]:9.2f}")


if __name__ == "__main__":
    main(sys.argv[1])
