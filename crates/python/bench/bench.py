"""Timings of the Python module against the Rust sweep and `rollfit fit`
(BENCHMARKS.md, "Python").

  python crates/python/bench/bench.py [sweep] [fits]   # both by default

1. scene.mu(v) for 4001 log-spaced speeds (1e-6 … 1 m/s) on the scene of
   the criterion bench `sweep4001_sphere` (crates/model/benches/forward.rs):
   median and best of 30 repeats of timeit's autorange, per call.
2. rollfit.fit on data/hn-rubber.* and data/hn-rubber-tset.* in a fresh
   interpreter against the CLI's `rollfit fit` on the same files (wall clock
   of the process, best of 5), the binary at
   $CARGO_TARGET_DIR/release/rollfit.
"""

import os
import subprocess
import tempfile
import time
import timeit
from pathlib import Path

import numpy as np

import rollfit

ROOT = Path(__file__).resolve().parents[3]
os.chdir(ROOT)


def sweep():
    # The criterion bench's 15-term Prony series (prony15), one term per
    # decade from 1e-9 s to 1e5 s, and its sphere.
    k = np.arange(15)
    tau = 10.0 ** (k - 9)
    h = 3e6 * np.exp(-(((k - 5.0) / 4.0) ** 2)) * 20.0 + 1e5
    material = rollfit.Prony(E1=2e6 + h.sum(), H=h, tau=tau)
    scene = rollfit.Scene(shape="sphere", radius=0.005, load=1.0, material=material)
    v = 1e-6 * 10.0 ** (np.arange(4001) * 6.0 / 4000.0)
    timer = timeit.Timer(lambda: scene.mu(v))
    number, _ = timer.autorange()
    times = np.array(timer.repeat(repeat=30, number=number)) / number
    # The median is what criterion's estimate of the mean is compared with;
    # the best run is the least disturbed by other work on the machine.
    print(
        f"scene.mu(v), 4001 speeds: median {1e3 * np.median(times):.3f} ms, "
        f"best {1e3 * times.min():.3f} ms per call (30 repeats of {number} calls)"
    )


def binary():
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "rollfit"


# One fit in a fresh interpreter (numpy imported and the data read before
# the clock starts), so that both sides build the kernel tables once.
FRESH = """
import sys, time, numpy, rollfit
scene, data = sys.argv[1], sys.argv[2]
d = rollfit.read_data(data)
s = rollfit.Scene.from_toml(scene)
start = time.perf_counter()
rollfit.fit(s, d["v"], d["mu"], d["sigma"], d["T"])
print(time.perf_counter() - start)
"""


def fits():
    """rollfit.fit in a fresh process (best of 5) against the `rollfit fit`
    process's wall clock (best of 5; it also reads the files and writes the
    folder) and the fit's own wall_time_s in its fit.json."""
    import json
    import sys

    for stem in ["hn-rubber", "hn-rubber-tset"]:
        scene, data = f"data/{stem}.toml", f"data/{stem}.csv"
        python, cli, inner = [], [], []
        for _ in range(5):
            done = subprocess.run([sys.executable, "-c", FRESH, scene, data], check=True,
                                  capture_output=True, text=True)
            python.append(float(done.stdout))
            with tempfile.TemporaryDirectory() as out:
                start = time.perf_counter()
                subprocess.run([binary(), "fit", scene, data, "-o", out], check=True,
                               capture_output=True)
                cli.append(time.perf_counter() - start)
                inner.append(json.loads((Path(out) / "fit.json").read_text())["wall_time_s"])
        print(f"fit {stem}: rollfit.fit {min(python):.3f} s; rollfit fit process {min(cli):.3f} s, "
              f"its fit.json wall_time_s {min(inner):.3f} s (best of 5 each)")


if __name__ == "__main__":
    import sys

    parts = sys.argv[1:] or ["sweep", "fits"]
    if "sweep" in parts:
        sweep()
    if "fits" in parts:
        fits()
