"""rollfit from Python: forward μ(v) of the bundled sphere, a fit of the
bundled measurement, and the recovered tan δ against the truth.

Run from the repository's root after `pip install ./crates/python`:

    python examples/python/quickstart.py

Units are SI (Pa, m, N, s, rad/s, m/s). The picture needs matplotlib
(`pip install matplotlib`); without it the script prints the numbers only.
"""

from pathlib import Path

import numpy as np

import rollfit

ROOT = Path(__file__).resolve().parents[2]

# 1. Forward: μ(v) of a steel ball (R = 5 mm, F_N = 1 N) on an 8-term Prony
#    rubber, the scene of data/example-sphere.toml.
scene = rollfit.Scene.from_toml(ROOT / "data" / "example-sphere.toml")
v = scene.speeds  # the file's [sweep]: 41 speeds, 1e-6 … 1 m/s
mu = scene.mu(v)
k = int(np.argmax(mu))
print(f"example sphere: μ peaks at {mu[k]:.4f} near v = {v[k]:.2e} m/s")

# The same scene built in Python gives the same numbers.
rubber = rollfit.Prony(
    E1=1.0e9,
    H=[5.0e8, 3.0e8, 1.2e8, 5.0e7, 1.8e7, 6.0e6, 2.5e6, 1.5e6],
    tau=[1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0],
)
ball = rollfit.Scene(shape="sphere", radius=0.005, load=1.0, poisson=0.5, material=rubber)
assert np.array_equal(ball.mu(v), mu)

# 2. Inverse: the master curve from data/hn-rubber.csv (41 speeds, 1 % noise,
#    a Havriliak–Negami rubber), with the anchor of data/hn-rubber.toml's [fit].
data = rollfit.read_data(ROOT / "data" / "hn-rubber.csv")
fit_scene = rollfit.Scene.from_toml(ROOT / "data" / "hn-rubber.toml")
result = rollfit.fit(fit_scene, data["v"], data["mu"], data["sigma"])
lo, hi = result.window
print(f"fit: {result!r}")
for w in result.warnings:
    print("warning:", w)

# 3. Recovered against true tan δ (the truth: data/README.md, the [material]
#    of data/hn-rubber.toml).
truth = rollfit.HavriliakNegami(E0=2.0e6, E1=2.0e9, tau=1.0e-3, alpha=0.55, beta=0.4)
omega = np.logspace(np.log10(lo), np.log10(hi), 61)
recovered, true = result.tan_delta(omega), truth.tan_delta(omega)
band = result.band(omega)
error = np.abs(recovered / true - 1)
print(f"tan δ over the window {lo:.2e} … {hi:.2e} rad/s: largest error {100 * error.max():.2f} %")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no picture (pip install matplotlib)")
else:
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.loglog(v, mu, "o-", ms=3)
    left.set(xlabel="v (m/s)", ylabel="μ", title="forward: example sphere")
    wide = np.logspace(-5, 5, 201)
    right.semilogx(wide, truth.tan_delta(wide), "k--", label="true")
    right.semilogx(omega, recovered, "C1", label="recovered")
    right.fill_between(
        omega,
        recovered - band["tan_delta_sigma"],
        recovered + band["tan_delta_sigma"],
        color="C1",
        alpha=0.3,
        label="1σ",
    )
    right.set(xlabel="ω (rad/s)", ylabel="tan δ", title="fit: hn-rubber")
    right.legend()
    fig.tight_layout()
    out = Path("quickstart.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
