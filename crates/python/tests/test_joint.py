"""The joint fit of DMA isotherms and rolling friction from
Python: the keyword `dma` and a scene file's `[fit] dma` give the fit
`rollfit fit` gives with `--dma` and with the same scene, fit.json's
`joint` record is the result's `joint`, and the joint settings without DMA
data are refused naming the key."""

import json
from pathlib import Path

import pytest

import rollfit

SCENE, DATA = "data/hn-rubber-tset.toml", "data/hn-rubber-tset.csv"
JOINT_SCENE = "data/hn-rubber-joint.toml"
DMA = "data/hn-rubber-dma-isotherms.csv"


def python_fit(scene, **settings):
    d = rollfit.read_data(DATA)
    return rollfit.fit(
        rollfit.Scene.from_toml(scene), d["v"], d["mu"], d["sigma"], d["T"],
        data_file=DATA, **settings,
    )


def without_clock(value):
    if isinstance(value, dict):
        return {k: without_clock(v) for k, v in value.items() if k != "wall_time_s"}
    if isinstance(value, list):
        return [without_clock(v) for v in value]
    return value


def test_dma_keyword_is_the_cli_s_dma_flag(cli, tmp_path):
    cli("fit", SCENE, DATA, "-o", tmp_path / "cli", "--dma", DMA, "--friction-factor", "free")
    theirs = json.loads((tmp_path / "cli" / "fit.json").read_text())
    result = python_fit(SCENE, dma=Path(DMA), friction_factor="free")
    assert without_clock(result.to_dict()) == without_clock(theirs)
    joint = result.joint
    assert joint == theirs["joint"]
    assert joint["dma_source"] == DMA and joint["dma_points"] == 117
    assert joint["compatibility"]["compatible"] is True
    assert abs(joint["friction_factor"]["value"] - 1.0) < 0.1


def test_scene_dma_is_the_cli_s(cli, tmp_path):
    cli("fit", JOINT_SCENE, DATA, "-o", tmp_path / "cli")
    theirs = json.loads((tmp_path / "cli" / "fit.json").read_text())
    result = python_fit(JOINT_SCENE)
    assert without_clock(result.to_dict()) == without_clock(theirs)
    # Relative to the scene file's folder, not to the current one.
    assert result.joint["dma_source"] == DMA
    assert "friction_factor" not in result.joint
    assert python_fit(SCENE, starts=1, dma=None, friction_factor=None).joint is None


def test_joint_settings_and_files_are_checked():
    with pytest.raises(ValueError, match="`friction_factor`.*DMA"):
        python_fit(SCENE, friction_factor="free")
    with pytest.raises(ValueError, match="`dma_sigma`"):
        python_fit(SCENE, dma_sigma=0.01)
    with pytest.raises(ValueError, match="`friction_factor`"):
        python_fit(SCENE, dma=DMA, friction_factor="kappa")
    with pytest.raises(OSError, match="DMA file data/absent.csv does not exist"):
        python_fit(SCENE, dma="data/absent.csv")
