"""A scene's flight from Python (``sol.flight_summary()``, ``sol.plot_flight()``): the
tool's own summary (cli/tests/flight_summary.rs checks every field against closed forms)
against the burn-and-coast rocket's closed form, and the panels drawn with Matplotlib (a
test extra: the plot test runs in CI, never skipped)."""

import math
import pickle
import sys

import numpy as np
import pytest

import varmass
from conftest import MODELS

G = 9.81


def burn_scene(tmp_path, flight=""):
    """``models/rocket.vms`` on its pad (m0 = 100 kg, 2 kg/s at u_e = 400 m/s), burning to
    m = 40 kg at t_b = 30 s, coasting drag-free to its apex and falling to y = 0."""
    path = tmp_path / "burn.toml"
    path.write_text(
        f'model = "{MODELS / "rocket.vms"}"\nsupport = "y"\nuntil = 200.0\n'
        'method = "dop853"\ntol = 1e-12\nstop_when = "y = 0"\n'
        "set = { mu = 2.0, u_e = 400.0, g = 9.81 }\ninit = { y = 0.0, m = 100.0 }\n\n"
        '[[phase]]\nwhen = "m = 40"\nset = { mu = 0.0 }\n\n'
        f'[flight]\naltitude = "y"\nstatic_margin = "2 - m/100"\nthrust = "mu*u_e"\n{flight}\n'
    )
    return path


def closed_form():
    """Lift-off where 800 N = m g; Tsiolkovsky with gravity from there to t_b; the coast's
    apex y_b + v_b²/(2g) at t_b + v_b/g (cli/tests/flight_summary.rs derives each)."""
    m0, mu, u_e, m_b = 100.0, 2.0, 400.0, 40.0
    m_lift = mu * u_e / G
    t_lift = (m0 - m_lift) / mu
    tau = 30.0 - t_lift
    v_b = u_e * math.log(m_lift / m_b) - G * tau
    y_b = u_e * (tau - m_b / mu * math.log(m_lift / m_b)) - 0.5 * G * tau * tau
    return t_lift, v_b, y_b + v_b * v_b / (2 * G), 30.0 + v_b / G


def test_the_flight_summary_is_the_closed_form(tmp_path):
    sol = varmass.Scene.from_file(burn_scene(tmp_path)).run()
    s = sol.flight_summary()
    t_lift, v_b, h_a, t_a = closed_form()
    # Measured through the tool at tolerance 1e-12: 1e-13 relative; bound 1e-9.
    assert abs(s["apogee"]["altitude"] - h_a) <= 1e-9 * h_a
    assert abs(s["apogee"]["time"] - t_a) <= 1e-9 * t_a
    assert abs(s["lift_off"] - t_lift) <= 1e-12 * t_lift
    assert abs(s["burnout"] - 30.0) <= 1e-12 * 30.0
    assert abs(s["static_margin"]["at_burnout"] - 1.6) <= 1e-12
    assert s["roles"]["vertical_speed"] == "y'"
    (change,) = s["phases"]
    assert change["phase"] == 2 and abs(change["speed"] - v_b) <= 1e-9 * v_b
    landing = s["landing"]
    assert abs(landing["vertical_speed"] + math.sqrt(2 * G * h_a)) <= 1e-9 * h_a
    assert s["end"]["stopped_by"] == "y = 0"
    # The same dict after a pickle (a Dask task's result), and a fresh one each call.
    assert pickle.loads(pickle.dumps(sol)).flight_summary() == s
    s["apogee"] = None
    assert sol.flight_summary()["apogee"] is not None
    assert "apogee: altitude" in sol.summary


def test_a_solution_without_a_flight_says_so(rocket):
    sol = varmass.Scene.from_file(MODELS / "two_stage_rocket.toml").run()
    with pytest.raises(ValueError, match=r"\[flight\]"):
        sol.flight_summary()
    run = rocket.run(set={"mu": 1.0, "u_e": 100.0, "g": 9.81}, init={"y": 0, "m": 10}, until=1)
    with pytest.raises(ValueError, match=r"\[flight\]"):
        run.plot_flight()


def test_plot_flight_draws_the_panels_and_the_log(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    log = tmp_path / "log.csv"
    _, _, h_a, t_a = closed_form()
    log.write_text("Time (s),Altitude (m)\n" + "".join(
        f"{t},{0.98 * h_a * (1 - ((t - t_a) / t_a) ** 2)}\n" for t in np.linspace(0, 2 * t_a, 50)
    ))
    sol = varmass.Scene.from_file(burn_scene(tmp_path, f'log = {{ file = "{log}" }}')).run()
    fig = sol.plot_flight()
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["altitude", "speed", "static margin"]
    altitude = fig.axes[0]
    labels = [line.get_label() for line in altitude.get_lines()]
    assert labels == ["altitude", "measured log"]
    measured = altitude.get_lines()[1].get_ydata()
    assert max(measured) == pytest.approx(0.98 * h_a, rel=1e-3)
    # The simulated altitude is the flight's own column.
    assert np.array_equal(altitude.get_lines()[0].get_ydata(), sol["y"])
    assert sol.flight_summary()["log"]["apogee"]["value"] == max(measured)
    # log=False draws none; a pair of arrays draws that.
    assert len(sol.plot_flight(log=False).axes[0].get_lines()) == 1
    pair = sol.plot_flight(log=([0.0, 1.0], [0.0, 5.0])).axes[0].get_lines()[1]
    assert list(pair.get_ydata()) == [0.0, 5.0]


def test_plot_flight_without_matplotlib_says_how_to_get_it(tmp_path, monkeypatch):
    sol = varmass.Scene.from_file(burn_scene(tmp_path)).run()
    # A module set to None in sys.modules cannot be imported: matplotlib absent.
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    with pytest.raises(ImportError, match=r"pip install 'varmass\[plot\]'"):
        sol.plot_flight()


def test_a_rail_scene_gives_its_lift_off_and_exit(tmp_path):
    """``models/rocket_on_rail.toml``: 550 kg on a rail 80° above the horizontal, 5000 N of
    thrust (μ = 5 kg/s at u_e = 1000 m/s) against 5396 N of weight along it. It rests until
    μ u_e = m g sin i, m = 550 − μ t: t_l = (550 − μ u_e/(g sin i))/μ; then the frozen-mass
    equation along the rail m s̈ = μ u_e − m g sin i gives, with m_l = 550 − μ t_l and
    m = m_l − μ τ, ṡ = u_e ln(m_l/m) − g sin i τ and s = u_e (τ + (m/μ) ln(m/m_l)) −
    g sin i τ²/2; the exit is where s = 5 m (Newton on the closed form below, as
    tests/rail_support/mod.rs does)."""
    sol = varmass.Scene.from_file(MODELS / "rocket_on_rail.toml").run()
    mu, u_e, gs = 5.0, 1000.0, G * math.sin(math.radians(80.0))
    t_l = (550.0 - mu * u_e / gs) / mu
    m_l = 550.0 - mu * t_l

    def slide(tau):
        m = m_l - mu * tau
        s = u_e * (tau + m / mu * math.log(m / m_l)) - 0.5 * gs * tau * tau
        return s, u_e * math.log(m_l / m) - gs * tau

    tau = 7.0
    for _ in range(50):
        s, v = slide(tau)
        tau -= (s - 5.0) / v
    time, speed = sol.rail_exit
    # tests/rail.rs measures the lift-off 2.5e-14 s off, the exit 1.1e-12 s (the events'
    # location tolerance), the speed 1.1e-14 relative: bounds 1e-10 s and 1e-9.
    assert abs(sol.lift_off - t_l) <= 1e-10
    assert abs(time - (t_l + tau)) <= 1e-10
    assert abs(speed - slide(tau)[1]) <= 1e-9 * speed
    assert pickle.loads(pickle.dumps(sol)).rail_exit == sol.rail_exit
    # A scene without a rail or support, and a plain run, have neither.
    staged = varmass.Scene.from_file(MODELS / "two_stage_rocket.toml").run()
    assert staged.rail_exit is None and staged.lift_off is None
