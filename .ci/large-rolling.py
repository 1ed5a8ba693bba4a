#!/usr/bin/env python3
"""A rolling-friction logger file of a given size for the memory benchmark
(BENCHMARKS.md, "rolling data reader"): rows of `v,mu` at log-uniform speeds
over the bundled data's range, μ interpolated in log-log between the bundled
rows of data/hn-rubber.csv, 2 % Gaussian noise, seed 1.

Usage: .ci/large-rolling.py OUT.csv MEGABYTES
"""
import bisect
import math
import os
import random
import sys


def main():
    out, megabytes = sys.argv[1], float(sys.argv[2])
    here = os.path.dirname(os.path.abspath(__file__))
    rows = [
        line.strip().split(",")
        for line in open(os.path.join(here, "..", "data", "hn-rubber.csv"))
        if line[0].isdigit()
    ]
    v = [float(r[0]) for r in rows]
    mu = [float(r[1]) for r in rows]
    lo, hi = math.log(min(v)), math.log(max(v))
    random.seed(1)
    with open(out, "w") as f:
        f.write("v,mu\n")
        while f.tell() < megabytes * 1e6:
            x = math.exp(random.uniform(lo, hi))
            j = min(max(bisect.bisect(v, x), 1), len(v) - 1)
            w = (math.log(x) - math.log(v[j - 1])) / (math.log(v[j]) - math.log(v[j - 1]))
            m = math.exp(math.log(mu[j - 1]) * (1 - w) + math.log(mu[j]) * w)
            m *= 1 + 0.02 * random.gauss(0, 1)
            f.write(f"{x:.6g},{m:.6g}\n")


if __name__ == "__main__":
    main()
