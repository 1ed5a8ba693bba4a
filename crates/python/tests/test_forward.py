"""μ(v) from Python against `rollfit forward` on the same scene, bit for
bit, and the Jacobian against finite differences of μ."""

import csv
import io

import numpy as np
import pytest

import rollfit


def forward_columns(cli, scene):
    """v and mu of `rollfit forward SCENE` (stdout CSV; numbers written
    with the shortest digits that round-trip, so float() gives the f64)."""
    rows = list(csv.DictReader(io.StringIO(cli("forward", scene).stdout)))
    return (
        np.array([float(r["v"]) for r in rows]),
        np.array([float(r["mu"]) for r in rows]),
    )


def same_bits(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


@pytest.mark.parametrize(
    "scene",
    [
        "data/example-sphere.toml",
        "data/hn-rubber.toml",
        "data/paper-fig2-cylinder.toml",
        "data/paper-fig2-sphere.toml",
    ],
)
def test_scene_file_mu_is_the_cli_s(cli, scene):
    v, mu = forward_columns(cli, scene)
    s = rollfit.Scene.from_toml(scene)
    assert same_bits(s.speeds, v)
    assert same_bits(s.mu(v), mu)
    # A list is an array-like too.
    assert same_bits(s.mu(list(v)), mu)


def test_python_scene_is_the_file_s(cli):
    """data/example-sphere.toml written as Python objects."""
    v, mu = forward_columns(cli, "data/example-sphere.toml")
    material = rollfit.Prony(
        E1=1.0e9,
        H=[5.0e8, 3.0e8, 1.2e8, 5.0e7, 1.8e7, 6.0e6, 2.5e6, 1.5e6],
        tau=[1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0],
    )
    s = rollfit.Scene(shape="sphere", radius=0.005, load=1.0, poisson=0.5, material=material)
    assert same_bits(s.mu(v), mu)


def test_havriliak_negami_is_the_file_s(cli):
    v, mu = forward_columns(cli, "data/hn-rubber.toml")
    hn = rollfit.HavriliakNegami(E0=2.0e6, E1=2.0e9, tau=1.0e-3, alpha=0.55, beta=0.4)
    s = rollfit.Scene(shape="sphere", radius=0.005, load=1.0, material=hn)
    assert same_bits(s.mu(v), mu)
    omega = np.logspace(-3, 3, 7)
    assert same_bits(s.modulus(omega).real, hn.modulus(omega).real)


def test_sls_modulus_closed_form():
    """The standard linear solid's limits: E*(0) = E0, E*(∞) = E1."""
    sls = rollfit.SLS(E0=1e6, E1=1e8, tau=1e-2)
    e = sls.modulus([0.0, 1e12])
    assert e[0].real == pytest.approx(1e6, rel=1e-12) and abs(e[0].imag) < 1e-3
    assert e[1].real == pytest.approx(1e8, rel=1e-6)
    assert sls.static_modulus == 1e6


def test_jacobian_against_finite_differences():
    e1 = 1.0e9
    h = np.array([5.0e8, 3.0e8, 1.2e8, 5.0e7, 1.8e7, 6.0e6, 2.5e6, 1.5e6])
    tau = np.logspace(-5, 2, 8)
    v = np.logspace(-5, -1, 9)

    def scene(e1, h):
        return rollfit.Scene(
            shape="sphere", radius=0.005, load=1.0, material=rollfit.Prony(e1, h, tau),
            tolerance=1e-10,
        )

    mu, jac = scene(e1, h).mu_and_jacobian(v)
    assert jac.shape == (len(v), 1 + len(h))
    assert np.allclose(mu, scene(e1, h).mu(v), rtol=1e-9, atol=0)
    for j in range(1 + len(h)):
        p = np.concatenate([[e1], h])
        # Every parameter moves E0 = E1 − ΣH (2 MPa), which μ is most
        # sensitive to: the step is relative to E0.
        step = 1e-4 * (e1 - h.sum())
        up, down = p.copy(), p.copy()
        up[j] += step
        down[j] -= step
        fd = (scene(up[0], up[1:]).mu(v) - scene(down[0], down[1:]).mu(v)) / (2 * step)
        scale = np.max(np.abs(fd))
        assert np.max(np.abs(jac[:, j] - fd)) <= 1e-5 * scale, j


def test_bad_scene_values_raise_value_error():
    with pytest.raises(ValueError, match="radius"):
        rollfit.Scene(shape="sphere", radius=-1.0, load=1.0, material=rollfit.SLS(1e6, 1e8, 1.0))
    with pytest.raises(ValueError, match="poisson"):
        rollfit.Scene(shape="sphere", radius=0.01, load=1.0, poisson=0.7)
    with pytest.raises(ValueError, match="ball"):
        rollfit.Scene(shape="ball", radius=0.01, load=1.0)
    with pytest.raises(ValueError):
        rollfit.SLS(E0=1e8, E1=1e6, tau=1.0)
    s = rollfit.Scene(shape="sphere", radius=0.01, load=1.0)
    with pytest.raises(ValueError, match="no material"):
        s.mu([1e-3])
    hn = rollfit.Scene(
        shape="sphere", radius=0.01, load=1.0,
        material=rollfit.HavriliakNegami(2e6, 2e9, 1e-3, 0.5, 0.5),
    )
    with pytest.raises(ValueError, match="Prony"):
        hn.mu_and_jacobian([1e-3])
    with pytest.raises(ValueError):
        hn.mu([-1.0])


def test_scene_file_errors_are_the_cli_s(cli, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[geometry]\nshape = "sphere"\nradius = 0.01\nload = 1.0\nwheel = 3\n'
        '[material]\nmodel = "sls"\nE0 = 1e6\nE1 = 1e8\ntau = 1.0\n'
        "[sweep]\nv_min = 1e-6\nv_max = 1.0\n"
    )
    done = cli("forward", bad, check=False)
    assert done.returncode != 0
    with pytest.raises(ValueError) as caught:
        rollfit.Scene.from_toml(bad)
    assert done.stderr.strip() == f"error: {caught.value}"
    with pytest.raises(OSError):
        rollfit.Scene.from_toml(tmp_path / "missing.toml")


def test_quickstart_runs_as_a_script(tmp_path):
    """examples/python/quickstart.py, as the README runs it (the picture, if
    matplotlib is installed, lands in the working folder)."""
    import subprocess
    import sys

    from conftest import REPO

    done = subprocess.run(
        [sys.executable, str(REPO / "examples" / "python" / "quickstart.py")],
        cwd=tmp_path, capture_output=True, text=True, timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert "largest error" in done.stdout
