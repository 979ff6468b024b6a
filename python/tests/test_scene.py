"""Scene files from Python (``varmass.Scene``, ``varmass.run_scene``): the tool's phases,
messages and numbers, checked against the two-stage rocket's closed form."""

import math

import numpy as np
import pytest

import varmass
from conftest import MODELS

TWO_STAGE = MODELS / "two_stage_rocket.toml"


def test_the_two_stage_rocket_scene_reaches_its_closed_form_speed():
    sol = varmass.Scene.from_file(TWO_STAGE).run()
    # Stage 1 burns 10 kg/s at u_e = 2500 m/s from 1000 kg to 500 kg (t = 50 s), stage 2
    # 2 kg/s at 3000 m/s from 300 kg to 100 kg (t = 150 s), g = 9.81; Tsiolkovsky with
    # gravity loss: v(150) = 2500 ln 2 − 9.81·50 + 3000 ln 3 − 9.81·100.
    exact = 2500 * math.log(2) - 9.81 * 50 + 3000 * math.log(3) - 9.81 * 100
    assert sol.t[-1] == 150.0 and sol.stopped_by is None
    error = abs(sol["y'"][-1] - exact) / exact
    assert error <= 1e-12, error  # measured 6.3e-15 (the tool's run: cli/tests/scene.rs)
    assert abs(sol["m"][-1] - 100.0) <= 1e-9
    # The phase column: 1 up to the separation, 2 after; the change appears twice at
    # t = 50 s (m = 500 kg before, 300 kg after, the same velocity).
    assert sol.keys()[:2] == ["t", "phase"]
    phase = sol["phase"]
    assert phase[0] == 1.0 and phase[-1] == 2.0
    assert np.all(np.diff(phase) >= 0)
    k = int(np.argmax(phase == 2.0))
    assert sol.t[k - 1] == sol.t[k] and abs(sol.t[k] - 50.0) < 1e-9
    assert abs(sol["m"][k - 1] - 500.0) < 1e-9 and sol["m"][k] == 300.0
    # One change: the 200 kg dry stage leaves with v(50) = 2500 ln 2 − 9.81·50, taking
    # ½·200·v(50)² of kinetic energy.
    (change,) = sol.changes
    assert isinstance(change, varmass.PhaseChange)
    assert (change.phase, change.rule) == (2, "separation")
    assert change.time == sol.t[k]
    v_50 = 2500 * math.log(2) - 9.81 * 50
    taken = 0.5 * 200 * v_50**2
    assert abs(change.kinetic_energy_removed - taken) <= 1e-9 * taken
    assert "kinetic energy removed" in sol.summary
    assert sol.statistics["accepted_steps"] > 0
    assert sol.end_time == 150.0 and len(sol.end_state) == 3
    # run_scene is the same run, bit for bit.
    again = varmass.run_scene(str(TWO_STAGE))
    assert again["y'"].tobytes() == sol["y'"].tobytes()
    assert again.changes == sol.changes


def test_a_scene_ending_on_its_stop_when_names_it(tmp_path):
    model = MODELS / "two_stage_rocket.vms"
    path = tmp_path / "apex.toml"
    path.write_text(
        f'model = "{model}"\nuntil = 1000.0\nstop_when = "y\' < 0"\n'
        "set = { mu = 10.0, u_e = 2500.0, g = 9.81 }\ninit = { y = 0.0, m = 1000.0 }\n\n"
        '[[phase]]\nwhen = "m = 500"\nset = { mu = 2.0, u_e = 3000.0 }\n'
        "masses = { m = 300.0 }\n\n"
        '[[phase]]\nwhen = "t = 150"\nset = { mu = 0.0 }\n'
    )
    sol = varmass.Scene.from_file(path).run()
    assert sol.stopped_by == "y' < 0"
    assert [c.phase for c in sol.changes] == [2, 3]
    # The apex: t = 150 + v(150)/g = 512.610073129887 s (cli/tests/scene.rs); tolerance
    # 1e-9 (default), bound 1e-6 relative.
    assert abs(sol.end_time - 512.610073129887) <= 1e-6 * 512.6
    assert sol["phase"][-1] == 3.0


def test_a_failing_scene_raises_run_error_with_its_points(tmp_path):
    # Stage 2 burns 2 kg/s from 300 kg: its mass reaches 0 at t = 200 s, before until.
    model = MODELS / "two_stage_rocket.vms"
    path = tmp_path / "runs_out.toml"
    path.write_text(
        f'model = "{model}"\nuntil = 250.0\n'
        "set = { mu = 10.0, u_e = 2500.0, g = 9.81 }\ninit = { y = 0.0, m = 1000.0 }\n\n"
        '[[phase]]\nwhen = "m = 500"\nset = { mu = 2.0, u_e = 3000.0 }\n'
        "masses = { m = 300.0 }\n"
    )
    with pytest.raises(varmass.RunError) as caught:
        varmass.run_scene(path)
    error = caught.value
    assert error.reason == "the mass `m` is not positive"
    assert abs(error.time - 200.0) < 1e-6, error.time
    points = error.points
    assert points["phase"][0] == 1.0 and points["phase"][-1] == 2.0
    # Empty at t = 200 exactly; the refused step is retried by halves down to a rounding of
    # t, so the last point lies within a few roundings of 200 (measured 3 ulps): 1e-12.
    assert abs(points["t"][-1] - 200.0) <= 1e-12, points["t"][-1]


def test_a_bad_scene_file_is_the_tools_message_at_its_line(tmp_path):
    path = tmp_path / "bad.toml"
    model = MODELS / "two_stage_rocket.vms"
    path.write_text(
        f'model = "{model}"\nuntil = 150.0\nset = {{ mu = 10.0, u_e = 2500.0, g = 9.81 }}\n'
        'init = { y = 0.0, m = 1000.0 }\nmethod = "dop8"\n'
    )
    with pytest.raises(ValueError, match=r":5:10.*unknown method `dop8`|unknown method `dop8`"):
        varmass.Scene.from_file(path).run()
    with pytest.raises(FileNotFoundError):
        varmass.Scene.from_file(tmp_path / "none.toml")
    with pytest.raises(TypeError, match="path"):
        varmass.Scene.from_file(3)


def test_a_scene_derives_its_model_once_and_runs_again_the_same():
    """``Scene.run`` keeps the models it derived (one per set of tags its phases select):
    a second run derives nothing, and flies bit for bit as the first. A rewritten model
    file is derived again."""
    scene = varmass.Scene.from_file(TWO_STAGE)
    first = scene.run()
    derived = scene._native.derivations()
    assert derived >= 1
    again = scene.run()
    assert scene._native.derivations() == derived
    assert again["y'"].tobytes() == first["y'"].tobytes()
    assert again.changes == first.changes


def test_a_scene_derives_again_a_model_file_rewritten(tmp_path):
    model = tmp_path / "rocket.vms"
    model.write_text((MODELS / "two_stage_rocket.vms").read_text())
    path = tmp_path / "scene.toml"
    text = TWO_STAGE.read_text()
    path.write_text(text.replace('"two_stage_rocket.vms"', f'"{model}"'))
    scene = varmass.Scene.from_file(path)
    scene.run()
    derived = scene._native.derivations()
    model.write_text(model.read_text() + "\n# rewritten\n")
    scene.run()
    assert scene._native.derivations() == 2 * derived


def test_a_scenes_sensitivities_follow_its_separation():
    # At t = 150 s, with t₁ = (m0 − 500)/10 and m₂ = 300 − 2(150 − t₁):
    # v = 2500 ln(m0/500) − g t₁ + 3000 ln(300/m₂) − g (150 − t₁), so ∂v/∂g = −150,
    # ∂v/∂v₀ = 1, ∂v/∂m0 = 2500/m0 − 3000/m₂ · 2/10 = 2.5 − 6 = −3.5 (the g terms of t₁
    # cancel), and ∂m/∂m0 = 2/10 (the separation sets m = 300 kg at a time that moves).
    sol = varmass.Scene.from_file(TWO_STAGE).run(sensitivity=["g", "init:m", "init:y'"])
    assert sol.t[-1] == 150.0
    expected = {
        ("y'", "g"): -150.0,
        ("y'", "init:y'"): 1.0,
        ("y'", "init:m"): -3.5,
        ("m", "init:m"): 0.2,
    }
    for (quantity, wrt), value in expected.items():
        got = sol.sensitivity(quantity, wrt)[-1]
        assert abs(got - value) <= 1e-9 * max(1.0, abs(value)), (quantity, wrt, got)
    with pytest.raises(ValueError, match="sets `u_e`"):
        varmass.Scene.from_file(TWO_STAGE).run(sensitivity="u_e")


def two_stage_altitude(g, m0, t):
    """The two-stage scene's altitude from rest (Tsiolkovsky with gravity in each burn:
    y = y₀ + v₀τ + u(τ − (m/μ) ln(m₀/m)) − ½gτ², v = v₀ + u ln(m₀/m) − gτ)."""

    def burn(y0, v0, mass0, mu, u, tau):
        m = mass0 - mu * tau
        ln = math.log(mass0 / m)
        return (
            y0 + v0 * tau + u * (tau - m / mu * ln) - 0.5 * g * tau * tau,
            v0 + u * ln - g * tau,
        )

    t1 = (m0 - 500.0) / 10.0
    if t <= t1:
        return burn(0.0, 0.0, m0, 10.0, 2500.0, t)[0]
    y1, v1 = burn(0.0, 0.0, m0, 10.0, 2500.0, t1)
    return burn(y1, v1, 300.0, 2.0, 3000.0, t - t1)[0]


def test_a_scene_is_fitted_to_its_flights_altitude():
    # Exact altitudes of g = 9.5, m0 = 1020 kg (separation at 52 s) every 2.5 s, and one
    # at 160 s, after the scene's end (left out, with a warning): from the scene's own
    # 9.81 and 1000 kg the fit lands on the truth (the tool's run: cli/tests/fit_scene.rs,
    # 8.4e-15 and 9.9e-15 relative).
    t = np.append(2.5 * np.arange(1, 61), 160.0)
    altitude = np.array([two_stage_altitude(9.5, 1020.0, x) for x in t])
    scene = varmass.Scene.from_file(TWO_STAGE)
    with pytest.warns(UserWarning, match="1 data outside"):
        fit = scene.fit({"y": (t, altitude)}, {"g": None, "init:m": (600.0, 2000.0)})
    assert fit.converged
    assert abs(fit.values["g"] - 9.5) <= 9.5e-8, fit
    assert abs(fit.values["init:m"] - 1020.0) <= 1020e-8, fit
    assert len(fit.residuals["y"]) == 60


def test_a_scenes_log_offset_is_fitted():
    # The same flight logged on a clock 0.8 s ahead (t_log = t + 0.8): the offset's
    # column is each quantity's rate, which the scene records for the fit (the tool's run:
    # cli/tests/fit_scene.rs, about 1e-14). The offset's bounds (0.2, 2) keep 0 out: the
    # data's window starts at the bound nearest 0, so the datum logged at 160 s (model
    # time 159.8 s at δ = 0.2) is still past the scene's 150 s and left out.
    t = np.append(2.5 * np.arange(1, 61), 160.0)
    altitude = np.array([two_stage_altitude(9.5, 1020.0, x - 0.8) for x in t])
    scene = varmass.Scene.from_file(TWO_STAGE)
    unknowns = {"g": None, "init:m": (600.0, 2000.0), "data:offset": (0.2, 2.0)}
    with pytest.warns(UserWarning, match="1 data outside"):
        fit = scene.fit({"y": (t, altitude)}, unknowns)
    assert fit.converged
    assert abs(fit.values["g"] - 9.5) <= 9.5e-8, fit
    assert abs(fit.values["init:m"] - 1020.0) <= 1020e-8, fit
    assert abs(fit.values["data:offset"] - 0.8) <= 1e-8, fit


def test_a_scene_fit_predicts_stage_twos_mass_on_the_datas_clock():
    # The offset log above, fitted and run on to stage 2's m = 200 kg: from the separation
    # at t₁ = (1020 − 500)/10 = 52 s, 100 kg at μ₂ = 2 kg/s take 50 s, so t = 102 s (the
    # log's clock: 102.8 s) and y = two_stage_altitude(9.5, 1020, 102); all to 1e-9
    # relative (measured 4.2e-15, 2.0e-15 and 5.1e-15, as the tool's run in
    # cli/tests/fit_scene.rs). Exact data: the errors are the integration's scatter, tiny
    # but positive (1.5e-13 s, 1.1e-13 s, 2.4e-10 m).
    t = 2.5 * np.arange(1, 61)
    altitude = np.array([two_stage_altitude(9.5, 1020.0, x - 0.8) for x in t])
    scene = varmass.Scene.from_file(TWO_STAGE)
    unknowns = {"g": None, "init:m": (600.0, 2000.0), "data:offset": (-2.0, 2.0)}
    fit = scene.fit({"y": (t, altitude)}, unknowns, predict="m < 200")
    p = fit.prediction
    expected = two_stage_altitude(9.5, 1020.0, 102.0)
    assert abs(p.t - 102.0) <= 102e-9, p
    assert abs(p.clock - 102.8) <= 102e-9, p
    assert abs(p.values["y"] - expected) <= expected * 1e-9, p
    for error in (p.t_error, p.clock_error, p.errors["y"]):
        assert 0.0 < error < 1e-6, p
    # A condition the last phase never meets before predict_until: the fit is kept.
    with pytest.raises(varmass.RunError, match="did not reach `m < 50`") as e:
        scene.fit({"y": (t, altitude)}, unknowns, predict="m < 50", predict_until=110)
    assert e.value.fit.converged and abs(e.value.fit.values["g"] - 9.5) <= 9.5e-8
    with pytest.raises(ValueError, match="--predict-until -1: the prediction's run would end"):
        scene.fit({"y": (t, altitude)}, unknowns, predict="m < 200", predict_until=-1)
