"""The public flights' scenes (flights/<name>/<name>.vms and .toml, docs/flights.md#the-scenes)
are what tools/flights/make_scenes.py writes from each flight.toml: regenerated into a
temporary folder, every committed file is identical. Plain Python (the generator needs only
the standard library); cli/tests/flights.rs flies the scenes against RocketPy."""

import importlib.util
import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("tomllib")  # the generator reads flight.toml with Python >= 3.11's tomllib

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "flights" / "make_scenes.py"
_spec = importlib.util.spec_from_file_location("make_scenes", TOOL)
make_scenes = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(make_scenes)


def test_the_committed_scenes_are_the_generators(tmp_path):
    subprocess.run([sys.executable, str(TOOL), "--out", str(tmp_path)], check=True,
                   capture_output=True)
    for name in make_scenes.FLIGHTS:
        for suffix in (".vms", ".toml", "_ascent.toml"):
            written = (tmp_path / name / f"{name}{suffix}").read_text()
            committed = (ROOT / "flights" / name / f"{name}{suffix}").read_text()
            assert written == committed, f"flights/{name}/{name}{suffix}: rerun {TOOL.name}"


def test_the_initial_attitude_puts_body_z_on_the_rail():
    # Calisto's quaternion (calisto.toml, checked there against RocketPy) from its rail:
    # 85 deg, heading 0, buttons at 45 deg
    q = make_scenes.attitude({"inclination": 85.0, "heading": 0.0, "button_angle": 45.0})
    expected = (0.9230002039112792, -0.04029905920751535, 0.01669241687462921,
                0.38231920253318413)
    assert max(abs(a - b) for a, b in zip(q, expected)) < 1e-15


def test_the_grains_radii_of_gyration_are_calistos():
    # calisto.vms's ka2_0, ka2_1, kc2_0, kc2_1, worked by hand in its header
    motor = {"grains": {"number": 5, "outer_radius": 0.033, "inner_radius": 0.015,
                        "height": 0.12, "separation": 0.005}}
    got = make_scenes.grains_inertia(motor)
    for a, b in zip(got, (0.0327785, 0.0323825, 0.000657, 0.001089)):
        assert abs(a - b) < 1e-15
