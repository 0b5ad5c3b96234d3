#!/usr/bin/env python3
"""Prints each benchmark's median and minimum time as ratios to the memcpy benchmark of the same run.

The median is what the README's tables quote; the minimum (the same statistic as costmap_tool
--repeat's update_ms_min, tool/run_timing.hpp) is the least disturbed by other processes on a shared
machine, so its ratio moves less between runs.
"""
import json
import sys

TO_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def main(path):
    with open(path) as f:
        data = json.load(f)
    stats = {"median": {}, "min": {}}
    labels = {}
    for b in data["benchmarks"]:
        agg = b.get("aggregate_name", "median")
        if agg not in stats:
            continue
        name = b.get("run_name", b["name"])
        for suffix in ("_median", "_min"):
            name = name.replace(suffix, "")
        stats[agg][name] = b["real_time"] * TO_NS[b.get("time_unit", "ns")]
        labels[name] = b.get("label", "")
    medians, mins = stats["median"], stats["min"]
    # A memcpy of the same size when the run has one per size (".../200"), else the run's first memcpy.
    memcpys = [k for k in medians if "Memcpy" in k]

    def baseline(name):
        arg = name.split("/", 1)[1] if "/" in name else None
        for k in memcpys:
            if arg is not None and k.endswith("/" + arg):
                return k
        return memcpys[0] if memcpys else None

    print(f"{'benchmark':44s} {'median':>11s} {'x memcpy':>9s} {'min':>11s} {'x memcpy':>9s}")
    for name, t in medians.items():
        base = baseline(name)
        ratio = f"{t / medians[base]:9.2f}" if base else "      n/a"
        tmin = mins.get(name)
        if tmin is not None and base in mins:
            min_text = f"{tmin / 1e6:9.3f}ms {tmin / mins[base]:9.2f}"
        else:
            min_text = f"{'':11s} {'':9s}"
        print(f"{name:44s} {t / 1e6:9.3f}ms {ratio} {min_text}  {labels.get(name, '')}")


if __name__ == "__main__":
    main(sys.argv[1])
