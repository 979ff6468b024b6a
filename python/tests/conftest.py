"""Shared fixtures: the repository's model files and the paper's sled and rocket."""

import math
import os
import pathlib

import pytest

import varmass

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"


def tool():
    """The ``varmass`` command line tool that ``cargo test``/``cargo build`` left in the
    target directory (``CARGO_TARGET_DIR``, else the repository's ``target/``; CI builds it
    before the Python tests), or ``None``."""
    targets = [os.environ.get("CARGO_TARGET_DIR"), str(ROOT / "target")]
    for target in filter(None, targets):
        for profile in ("debug", "release"):
            path = pathlib.Path(target) / profile / "varmass"
            if path.is_file():
                return path
    return None

#: The paper's sled (Zhang Jiuzhu 2015, §4): m0 = 10 kg, c = 2 kg/m, θ = 30°, f_d = 0.1.
SLED = {"m0": 10.0, "c": 2.0, "g": 9.81, "theta": math.radians(30.0), "f_d": 0.1}


@pytest.fixture(scope="session")
def sled():
    return varmass.Model.from_file(MODELS / "sled.vms", with_=["impact"])


@pytest.fixture(scope="session")
def rocket():
    return varmass.Model.from_file(MODELS / "rocket.vms")
