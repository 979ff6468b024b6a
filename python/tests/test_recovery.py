"""Recovery through ``varmass.Scene`` (docs/scenes.md#a-recovery): the scene keys of the
tool — a ``[[phase]]`` that sets a canopy's opening time to the time of its change plus a
lag — work from Python, with the tool's numbers (cli/tests/recovery.rs holds them to the
closed forms)."""

import math

import numpy as np
import pytest

import varmass

from conftest import MODELS

G, RHO, M0 = 9.81, 1.225, 2.0


def terminal(cds):
    """v_t = √(2 m g/(ρ C)): where the canopy's ½ρC v² equals the weight."""
    return math.sqrt(2 * M0 * G / (RHO * cds))


def test_a_drogue_opens_a_lag_after_apogee_and_falls_as_the_closed_form(tmp_path):
    # Up at 50 m/s, the drogue (v_t 30 m/s) at apogee + 1.5 s, opening at once. Before it
    # opens the fall is free; after, from v₁ = −g·1.5 at t₁ (|v₁| < v_t), the closed form
    # of v̇ = −g (1 − v²/v_t²): v = −v_t tanh(atanh(−v₁/v_t) + g (t − t₁)/v_t).
    model = MODELS / "recovery_descent.vms"
    path = tmp_path / "drogue.toml"
    path.write_text(
        f'model = "{model}"\nuntil = 20.0\nstop_when = "z < 0"\nmethod = "dop853"\n'
        'tol = 1e-12\nrecord = ["z", "z\'", "drogue_cds"]\n'
        "set = { m0 = 2.0, g = 9.81, rho = 1.225, CdS_drogue = 0.0356, CdS_main = 1.0 }\n"
        'init = { z = 0.0, "z\'" = 50.0 }\n\n'
        '[[phase]]\nwhen = "z\' < 0"\nset = { drogue_t_open = "t + 1.5" }\n'
    )
    sol = varmass.Scene.from_file(path).run()
    (change,) = sol.changes
    apogee = 50.0 / G
    # Located to the last bits (1e-13 s).
    assert abs(change.time - apogee) < 1e-13
    t_open = change.time + 1.5
    assert change.set == {"drogue_t_open": t_open}
    assert "set drogue_t_open = " in sol.summary
    t, v, cds = sol.t, sol["z'"], sol["drogue_cds"]
    assert np.all(cds[t <= t_open] == 0.0) and np.all(cds[t > t_open] == 0.0356)
    vt = terminal(0.0356)
    v1 = -G * 1.5
    a = math.atanh(-v1 / vt)
    after = t > t_open
    exact = -vt * np.tanh(a + G * (t[after] - t_open) / vt)
    # Measured 2e-13 of v_t (DOP853 at 1e-12); 1e-10.
    assert np.max(np.abs(v[after] - exact)) < 1e-10 * vt
    assert sol.stopped_by == "z < 0" and abs(sol.end_state[0]) < 1e-9


def test_a_non_finite_value_set_at_a_change_is_refused(tmp_path):
    model = MODELS / "recovery_descent.vms"
    path = tmp_path / "bad.toml"
    path.write_text(
        f'model = "{model}"\nuntil = 20.0\n'
        "set = { m0 = 2.0, g = 9.81, rho = 1.225, CdS_drogue = 0.0356, CdS_main = 1.0 }\n"
        'init = { z = 0.0, "z\'" = 50.0 }\n\n'
        '[[phase]]\nwhen = "z\' < 0"\nset = { drogue_t_open = "t + 1/0" }\n'
    )
    with pytest.raises(ValueError, match="finite"):
        varmass.Scene.from_file(path).run()
