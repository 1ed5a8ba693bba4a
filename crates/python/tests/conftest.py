"""Shared fixtures: the repository, the `rollfit` binary the Python results
are compared with, and running it."""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


def rollfit_binary() -> Path:
    """target/release/rollfit, honouring CARGO_TARGET_DIR (or ROLLFIT_BIN)."""
    if "ROLLFIT_BIN" in os.environ:
        return Path(os.environ["ROLLFIT_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    if not target.is_absolute():
        target = REPO / target
    return target / "release" / "rollfit"


@pytest.fixture(scope="session")
def cli():
    """Runs `rollfit ARGS` in the repository; returns the CompletedProcess."""
    binary = rollfit_binary()
    if not binary.exists():
        pytest.fail(
            f"{binary} is missing: build it with `cargo build --release -p rollfit-cli` "
            "(the tests compare the module with it)"
        )

    def run(*args, check=True):
        done = subprocess.run(
            [str(binary), *map(str, args)],
            cwd=REPO,
            capture_output=True,
            text=True,
        )
        if check and done.returncode != 0:
            raise AssertionError(f"rollfit {' '.join(map(str, args))} failed:\n{done.stderr}")
        return done

    return run


@pytest.fixture(autouse=True)
def in_repo(monkeypatch):
    """Relative paths as the CLI is given them (fit.json records them)."""
    monkeypatch.chdir(REPO)
