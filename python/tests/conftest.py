"""Shared fixtures: the repository's model files and the paper's sled and rocket."""

import math
import pathlib

import pytest

import varmass

MODELS = pathlib.Path(__file__).resolve().parents[2] / "models"

#: The paper's sled (Zhang Jiuzhu 2015, §4): m0 = 10 kg, c = 2 kg/m, θ = 30°, f_d = 0.1.
SLED = {"m0": 10.0, "c": 2.0, "g": 9.81, "theta": math.radians(30.0), "f_d": 0.1}


@pytest.fixture(scope="session")
def sled():
    return varmass.Model.from_file(MODELS / "sled.vms", with_=["impact"])


@pytest.fixture(scope="session")
def rocket():
    return varmass.Model.from_file(MODELS / "rocket.vms")
