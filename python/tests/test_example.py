"""The notebook-style example runs headless from start to end: it derives, flies one rocket
against its closed form, runs its ensemble on a two-worker Dask LocalCluster and writes the
histogram. CI runs it with 4 000 members (VARMASS_MEMBERS) instead of 10⁵ to stay quick."""

import os
import pathlib
import subprocess
import sys

import pytest

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "dispersion.py"


def test_the_dispersion_example_runs_headless(tmp_path):
    pytest.importorskip("dask.distributed")
    pytest.importorskip("matplotlib")
    figure = tmp_path / "apex.png"
    env = dict(os.environ, VARMASS_MEMBERS="4000", VARMASS_FIGURE=str(figure), MPLBACKEND="Agg")
    done = subprocess.run(
        [sys.executable, str(EXAMPLE)],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert "<varmass.EnsembleResult: 4000 members (0 failed)" in done.stdout
    assert "apex: mean" in done.stdout
    assert figure.stat().st_size > 10_000
