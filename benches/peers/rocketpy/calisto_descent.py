#!/usr/bin/env python3
"""Calisto's full flight in RocketPy 1.13 (ascent, drogue, main, landing), the noise off (issue 36).

Not in CI. calisto_6dof.py's rows flown past apogee to landing, the parachutes' pressure
noise switched off (flight.toml's `noise` set to (0, 0, 0): RocketPy's trigger then reads
the exact pressure's height), LSODA at rtol 1e-9, the rail phase's step bounded:

- `all`: calisto.py's `all` (RocketPy's jet damping, axial m'' force and propellant mass
  corrected), its sign errors of r_CM and r_NOZ kept;
- `cm_sign_vdot_axial_thomson`: those corrected too, the internal flow's Coriolis force
  Thomson's: the ascent varmass's calisto.vms meets to 8.2e-7 of apogee (calisto_6dof.csv),
  the reference cli/tests/calisto_flight.rs compares the descent with;
- `defaults_noise_off`: RocketPy as it is at its defaults (rtol 1e-6), the noise off.

RocketPy checks each trigger at its parachute's sampling instants k/105 s (from t = 0):
the drogue's (vertical speed < 0) at the first after apogee, the main's (vertical speed
< 0 and height above the pad < 800 m) at the first after the crossing; each canopy opens
`lag` (1.5 s) later, at once, and from then Flight.u_dot_parachute flies the centre of dry
mass as a particle: a = (D + W)/(m + m_a), D = -1/2 rho CdS |V| V with V the free-stream
airspeed, W = -m g z, m_a the canopy's added mass (1.068 (1 - 1.465 p - 0.25975 p^2 +
1.2626 p^3) rho (2/3) pi R^2 h, p = 0.0432, R = h = 1.5 m), the attitude frozen.

Each row: apogee (m above the pad) and its time, the drogue's and main's trigger times
(RocketPy's parachute_events), the landing time, the landing point x (East), y (North) (m
from the pad, of the centre of dry mass), the vertical speed at landing and at the main's
trigger, the height above the pad there (a node of the solution: its value exact). The
sampling delays are then drogue_trigger - apogee_time and (800 - main_trigger_height) /
main_trigger_vz (the 800 m crossing extrapolated over < 1/105 s, near the terminal speed).
Written to calisto_descent.csv.

    target/venv-rocketpy/bin/python benches/peers/rocketpy/calisto_descent.py
"""

import csv
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import calisto  # noqa: E402  (benches/peers/rocketpy/calisto.py)
import calisto_6dof  # noqa: E402

ROWS = [
    ("cm_sign_vdot_axial_thomson", ("sign", "vdot", "axial", "thomson"), calisto.TIGHT),
    ("all", (), calisto.TIGHT),
    ("defaults_noise_off", None, 1e-6),
]
COLS = ["apogee", "apogee_time", "drogue_trigger", "main_trigger", "landing_time",
        "landing_x", "landing_y", "landing_vz", "main_trigger_vz",
        "main_trigger_height"]


def fly(switches, rtol):
    """One flight to landing, the noise off; `switches` as calisto_6dof.py's (None: as is)."""
    from rocketpy.simulation.flight import Flight

    saved = [dict(c) for c in calisto.SPEC["parachutes"]]
    for c in calisto.SPEC["parachutes"]:
        c["noise"] = [0, 0, 0]
    build = calisto.build
    try:
        if switches is None:
            f, rk, env, _ = calisto.fly("rocketpy", rtol=rtol)
        else:
            calisto.build = lambda propellant_exact: _switched_build(switches, propellant_exact)
            Flight.u_dot_generalized = calisto_6dof.patched(switches)
            f, rk, env, _ = calisto.fly("all", rtol=rtol)
    finally:
        calisto.build = build
        Flight.u_dot_generalized = calisto_6dof.ORIGINAL
        calisto.SPEC["parachutes"] = saved
    return f, env


def _switched_build(switches, exact):
    env, rk = calisto_6dof._BUILD(exact)
    if "sign" in switches:
        rk.com_to_cdm_function = -1 * rk.com_to_cdm_function
        rk.nozzle_to_cdm = -rk.nozzle_to_cdm
    return env, rk


def figures(f, env):
    events = {p.name: t for t, p in f.parachute_events}
    t_main = events["main"]
    return {
        "apogee": f.apogee - env.elevation,
        "apogee_time": f.apogee_time,
        "drogue_trigger": events["drogue"],
        "main_trigger": t_main,
        "landing_time": f.t_final,
        "landing_x": f.x_impact,
        "landing_y": f.y_impact,
        "landing_vz": f.impact_velocity,
        "main_trigger_vz": float(f.vz(t_main)),
        "main_trigger_height": float(f.z(t_main)) - env.elevation,
    }


def main():
    warnings.simplefilter("ignore")
    np.random.seed(36)
    out = Path(__file__).with_name("calisto_descent.csv")
    with open(out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["config", "rtol"] + COLS)
        for name, switches, rtol in ROWS:
            row = figures(*fly(switches, rtol))
            print(f"{name:28s} " + "  ".join(f"{c} {row[c]:.6f}" for c in COLS), flush=True)
            w.writerow([name, f"{rtol:g}"] + [f"{row[c]:.10g}" for c in COLS])
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
