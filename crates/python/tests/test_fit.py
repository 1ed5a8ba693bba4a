"""Fits from Python against `rollfit fit` on the same inputs: the folder
`save` writes is the CLI's byte for byte, except the fields that
legitimately differ: `wall_time_s` (of the fit and of each run, in
fit.json), which measure the clock. Also the errors of bad settings and
data, `compare` against `rollfit compare`, and Ctrl-C."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import rollfit

# (scene, data) of the bundled examples, as `rollfit fit` is given them.
EXAMPLES = [
    ("data/hn-rubber.toml", "data/hn-rubber.csv"),
    ("data/hn-rubber-tset.toml", "data/hn-rubber-tset.csv"),
    ("data/lab-ball.toml", "data/lab-ball.csv"),
]

# The one field that measures the clock, not the fit.
CLOCK = "wall_time_s"


def without_clock(value):
    """fit.json with every `wall_time_s` removed."""
    if isinstance(value, dict):
        return {k: without_clock(v) for k, v in value.items() if k != CLOCK}
    if isinstance(value, list):
        return [without_clock(v) for v in value]
    return value


def lines_without_clock(path):
    return [line for line in path.read_bytes().splitlines() if CLOCK.encode() not in line]


def python_fit(scene, data, **settings):
    d = rollfit.read_data(data)
    return rollfit.fit(
        rollfit.Scene.from_toml(scene), d["v"], d["mu"], d["sigma"], d["T"],
        data_file=data, **settings,
    )


@pytest.mark.parametrize("scene,data", EXAMPLES)
def test_saved_folder_is_the_cli_s(cli, tmp_path, scene, data):
    cli("fit", scene, data, "-o", tmp_path / "cli", "--allow-poor-fit")
    result = python_fit(scene, data)
    result.save(tmp_path / "py")
    for name in ["mu.csv", "modulus.csv"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    ours, theirs = tmp_path / "py" / "fit.json", tmp_path / "cli" / "fit.json"
    assert lines_without_clock(ours) == lines_without_clock(theirs)
    cli_json = json.loads(theirs.read_text())
    assert without_clock(result.to_dict()) == without_clock(cli_json)
    # The accessors read the same result.
    assert result.window == (cli_json["window"]["omega_min"], cli_json["window"]["omega_max"])
    assert result.warnings == cli_json["warnings"]
    assert result.shift == cli_json.get("shift")
    assert result.converged == cli_json["converged"]


def test_curve_band_and_modulus(cli, tmp_path):
    scene, data = EXAMPLES[0]
    cli("fit", scene, data, "-o", tmp_path / "cli")
    result = python_fit(scene, data)
    table = np.genfromtxt(tmp_path / "cli" / "modulus.csv", delimiter=",", names=True)
    curve = result.curve
    for name in table.dtype.names:
        assert np.array_equal(curve[name], table[name]), name
    # At modulus.csv's frequencies the band is modulus.csv's rows.
    band = result.band(table["omega"])
    for name in ["E_storage", "E_loss", "tan_delta", "abs_E", "tan_delta_sigma", "abs_E_sigma"]:
        assert np.array_equal(band[name], table[name]), name
    # Between rows it lies between them; outside the window it is unknown.
    mid = np.sqrt(table["omega"][:-1] * table["omega"][1:])
    inner = result.band(mid)["tan_delta_sigma"]
    lo = np.minimum(table["tan_delta_sigma"][:-1], table["tan_delta_sigma"][1:])
    hi = np.maximum(table["tan_delta_sigma"][:-1], table["tan_delta_sigma"][1:])
    assert np.all((inner >= lo) & (inner <= hi))
    assert np.isnan(result.band([table["omega"][0] / 2])["tan_delta"][0])
    # The Prony series of fit.json gives the curve's E′, E″ and tan δ.
    e = result.modulus(table["omega"])
    assert np.allclose(e.real, table["E_storage"], rtol=1e-12, atol=0)
    assert np.allclose(e.imag, table["E_loss"], rtol=1e-12, atol=0)
    assert np.allclose(result.tan_delta(table["omega"]), table["tan_delta"], rtol=1e-12, atol=0)
    mu_csv = np.genfromtxt(tmp_path / "cli" / "mu.csv", delimiter=",", names=True)
    assert np.array_equal(result.mu_fit, mu_csv["mu_fit"])


def test_settings_by_keyword_are_the_flags(cli, tmp_path):
    scene, data = EXAMPLES[0]
    cli("fit", scene, data, "-o", tmp_path / "cli", "--starts", "1", "--terms", "3/decade",
        "--lambda", "auto", "--method", "lbfgs", "--allow-unconverged", "--allow-poor-fit")
    result = python_fit(scene, data, starts=1, terms="3/decade", method="lbfgs", **{"lambda": "auto"})
    result.save(tmp_path / "py")
    assert lines_without_clock(tmp_path / "py" / "fit.json") == lines_without_clock(
        tmp_path / "cli" / "fit.json"
    )
    assert (tmp_path / "py" / "modulus.csv").read_bytes() == (
        tmp_path / "cli" / "modulus.csv"
    ).read_bytes()


def test_compare_is_the_cli_s(cli, tmp_path):
    scene, data = EXAMPLES[0]
    dma = "data/hn-rubber-dma.csv"
    cli("fit", scene, data, "-o", tmp_path / "cli")
    cli("compare", tmp_path / "cli", dma)
    theirs = json.loads((tmp_path / "cli" / "compare.json").read_text())
    result = python_fit(scene, data)
    assert rollfit.compare(result, dma) == theirs
    assert rollfit.compare(str(tmp_path / "cli"), dma) == theirs
    assert rollfit.compare(result, rollfit.read_dma(dma, result.to_dict()["poisson"])) == theirs
    read = rollfit.read_dma(dma)
    assert read.format == theirs["dma_format"] and read.modulus_kind == theirs["modulus_kind"]
    assert len(read.omega) == theirs["dma_points"]


# Bad values: ValueError with the message `rollfit fit` prints.
@pytest.mark.parametrize(
    "key,value,flag",
    [
        ("starts", 0, "0"),
        ("method", "newton", "newton"),
        ("terms", "3/decennium", "3/decennium"),
        ("lambda", "-1", "-1"),
        ("physics", "exakt", "exakt"),
    ],
)
def test_bad_setting_messages_are_the_cli_s(cli, key, value, flag):
    scene, data = EXAMPLES[0]
    done = cli("fit", scene, data, "-o", "/nonexistent/never", f"--{key}", flag, check=False)
    assert done.returncode != 0
    with pytest.raises(ValueError) as caught:
        python_fit(scene, data, **{key: value})
    message = str(caught.value)
    assert f"`{key}`" in message
    if f"command line: --{key}: " in done.stderr:
        # Checked against the set-up: the CLI names the flag before the text.
        assert done.stderr.strip() == f"error: command line: --{key}: {message}"
    else:
        # Refused by clap while parsing the flag: the problem, after clap's
        # own words, is the text after "fit setting `KEY`: ".
        problem = message.split(f"fit setting `{key}`: ", 1)[1]
        assert problem in done.stderr


def test_setting_and_data_errors():
    scene = rollfit.Scene.from_toml("data/hn-rubber.toml")
    d = rollfit.read_data("data/hn-rubber.csv")
    with pytest.raises(ValueError, match="`colour`"):
        rollfit.fit(scene, d["v"], d["mu"], colour="red")
    with pytest.raises(ValueError, match="`seed`"):
        rollfit.fit(scene, d["v"], d["mu"], seed="many")
    with pytest.raises(ValueError, match="at least 4 distinct speeds"):
        rollfit.fit(scene, d["v"][:3], d["mu"][:3])
    with pytest.raises(ValueError, match="lengths"):
        rollfit.fit(scene, d["v"], d["mu"][:-1])
    with pytest.raises(ValueError, match="one scale anchor"):
        rollfit.fit(scene, d["v"], d["mu"], E0=2e6, E_at={"omega": 10.0, "E": 6e7})
    with pytest.raises(OSError):
        rollfit.read_data("data/no-such-file.csv")


def test_data_error_message_is_the_cli_s(cli, tmp_path):
    rows = tmp_path / "three.csv"
    rows.write_text("v,mu\n1e-3,0.1\n1e-2,0.2\n1e-1,0.3\n")
    done = cli("fit", "data/hn-rubber.toml", rows, "-o", tmp_path / "out", check=False)
    with pytest.raises(ValueError) as caught:
        rollfit.fit(rollfit.Scene.from_toml("data/hn-rubber.toml"), [1e-3, 1e-2, 1e-1], [0.1, 0.2, 0.3])
    assert done.stderr.strip() == f"error: data file {rows}: {caught.value}"


def test_python_scene_fit_starts_like_the_file(tmp_path):
    """A Scene made in Python fits as the same scene file without [fit]."""
    toml = tmp_path / "ball.toml"
    toml.write_text('[geometry]\nshape = "sphere"\nradius = 0.005\nload = 1.0\n')
    d = rollfit.read_data("data/hn-rubber.csv")
    from_file = rollfit.fit(rollfit.Scene.from_toml(toml), d["v"], d["mu"], d["sigma"], starts=1)
    made = rollfit.Scene(shape="sphere", radius=0.005, load=1.0)
    ours = rollfit.fit(made, d["v"], d["mu"], d["sigma"], starts=1)
    a, b = without_clock(from_file.to_dict()), without_clock(ours.to_dict())
    a.pop("input"), b.pop("input")
    assert a == b


def test_ctrl_c_interrupts_a_fit():
    """SIGINT during a long fit raises KeyboardInterrupt within a second, and
    the fit's worker stops (the process uses no CPU afterwards)."""
    script = textwrap.dedent(
        """
        import os, signal, threading, time, rollfit
        d = rollfit.read_data("data/hn-rubber-tset.csv")
        scene = rollfit.Scene.from_toml("data/hn-rubber-tset.toml")
        threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        start = time.monotonic()
        try:
            rollfit.fit(scene, d["v"], d["mu"], d["sigma"], d["T"], starts=40)
            print("finished", time.monotonic() - start)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic() - start)
        # CPU time of the process while the main thread sleeps: the
        # cancelled worker's last solver run at most.
        time.sleep(0.5)
        cpu = time.process_time()
        time.sleep(1.5)
        print("cpu", time.process_time() - cpu)
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    word, seconds, _, cpu = done.stdout.split()
    assert word == "interrupted", done.stdout + done.stderr
    assert float(seconds) < 2.0
    assert float(cpu) < 0.3, f"the worker went on: {cpu} s of CPU in 1.5 s"
