#!/usr/bin/env python3
"""Prints each benchmark's median time as a ratio to the memcpy benchmark of the same run."""
import json
import sys

TO_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def main(path):
    with open(path) as f:
        data = json.load(f)
    medians = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name", "median") != "median":
            continue
        name = b.get("run_name", b["name"]).replace("_median", "")
        medians[name] = (b["real_time"] * TO_NS[b.get("time_unit", "ns")], b.get("label", ""))
    # A memcpy of the same size when the run has one per size (".../200"), else the run's only memcpy.
    memcpys = {k: t for k, (t, _) in medians.items() if "Memcpy" in k}

    def baseline(name):
        arg = name.split("/", 1)[1] if "/" in name else None
        for k, t in memcpys.items():
            if arg is not None and k.endswith("/" + arg):
                return t
        return next(iter(memcpys.values()), None)

    print(f"{'benchmark':44s} {'median':>12s} {'x memcpy':>9s}")
    for name, (t, label) in medians.items():
        base = baseline(name)
        ratio = f"{t / base:9.2f}" if base else "      n/a"
        print(f"{name:44s} {t / 1e6:10.3f}ms {ratio}  {label}")


if __name__ == "__main__":
    main(sys.argv[1])
