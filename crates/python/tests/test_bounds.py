"""The command line's bounds and messages at the Python entry points, so
that one input gets one answer from both: complex arrays, speeds
outside the data reader's range, copies of rows without sigma, absurd
loads, films and E1_max."""

import numpy as np
import pytest

import rollfit


def sls_scene(**kwargs):
    return rollfit.Scene(
        shape="sphere", radius=0.01, load=1.0, material=rollfit.SLS(1e6, 1e8, 1e-2), **kwargs
    )


def test_complex_arrays_are_refused_naming_the_argument():
    scene = sls_scene()
    # pyo3 names the argument after the message ("while processing 'v'").
    with pytest.raises(TypeError, match=r"complex values: give real numbers[\s\S]*'v'"):
        scene.mu(np.array([1e-3 + 1e-3j, 1e-2]))
    with pytest.raises(TypeError, match=r"complex values: give real numbers[\s\S]*'omega'"):
        rollfit.SLS(1e6, 1e8, 1e-2).modulus(np.array([1.0 + 0j]))
    # Real arrays of any real dtype still pass.
    assert scene.mu(np.array([1, 2], dtype=np.int64) * 1e-3).shape == (2,)


def test_speeds_have_the_data_reader_s_bounds():
    scene = sls_scene()
    with pytest.raises(ValueError, match=r"v\[0\] = 1e300: must be at most 1000 m/s"):
        scene.mu([1e300])
    with pytest.raises(ValueError, match=r"v\[1\] = 1e-20: must be at least 1e-15 m/s"):
        scene.mu([1e-3, 1e-20])
    with pytest.raises(ValueError, match=r"v\[0\] = NaN: must be a finite number"):
        scene.mu_and_jacobian([float("nan")])


def test_copied_rows_without_sigma_say_what_was_given():
    scene = rollfit.Scene.from_toml("data/hn-rubber.toml")
    v = np.logspace(-6, -2, 11)
    mu = scene.mu(v)
    with pytest.raises(ValueError, match=r"repeat 11 speeds .* give a sigma column \(sigma= in Python\)"):
        rollfit.fit(scene, np.tile(v, 30), np.tile(mu, 30))


def test_absurd_set_up_values_name_their_key():
    with pytest.raises(ValueError, match=r"load = 1e300: must lie between 1e-9 and 1e8 N"):
        rollfit.Scene(shape="sphere", radius=0.01, load=1e300)
    with pytest.raises(ValueError, match=r"load = 1e-300: must lie between 1e-9 and 1e8 N"):
        rollfit.Scene(shape="sphere", radius=0.01, load=1e-300)
    with pytest.raises(ValueError, match=r"thickness = 1e-300: must lie between 1e-9 m and 1000 m"):
        rollfit.Scene(shape="cylinder", radius=0.01, load=100.0, thickness=1e-300)
    scene = rollfit.Scene.from_toml("data/hn-rubber.toml")
    v = np.logspace(-6, -2, 11)
    with pytest.raises(ValueError, match=r"E1_max.*1e-300 Pa must lie between 1e3 and 1e12 Pa"):
        rollfit.fit(scene, v, scene.mu(v), E1_max=1e-300)
