#!/usr/bin/env python3
"""RocketPy 1.13's getting-started Calisto, and each of its known differences switched off (issue 36).

Not in CI. The inputs are flights/calisto/flight.toml (docs/user/first_simulation.rst of
RocketPy at d41dd11: motor, rocket, nose, airfoil fins with 0.5 degree cant, tail, drag
curves, rail, parachutes), flown through flights.py's reader, with the weather replaced by
one we reproduce exactly: the U.S. Standard Atmosphere 1976 tabulated every 5 m
(flights/calisto/atmosphere.csv, linear between rows) and a constant wind of 3 m/s toward
East and 4 m/s toward South; gravity 9.80665 m/s^2; the Earth not rotating (RocketPy's
`env.earth_rotation_vector` zeroed; the `coriolis` row puts it back).

Printed and written: RocketPy 1.13 as it is at its defaults (LSODA, rtol 1e-6, pad to
landing) and the time of `Flight(...)` (fastest of --repeat); then each known difference
switched off alone, at rtol 1e-9 with the rail phase bounded in every row (RocketPy as it is
stays on the pad at that tolerance, see `pad_hold`), against the first of those rows;
RocketPy as it is against its tolerance; the propellant mass's error; and `all` against
RocketPy's tolerance, the reference varmass compares with. The differences:

- `jet_damping`: RocketPy's nozzle gyration tensor (Rocket.evaluate_nozzle_gyration_tensor,
  rocket/rocket.py) has S_11 = S_22 = r_e^2/4 + l^2/4, l the nozzle's distance from the
  centre of dry mass; the jet-damping moment of a uniform exit disc about a transverse
  axis through that centre has r_e^2/4 + l^2. Corrected by a setting: the rocket's
  `nozzle_gyration_tensor` attribute replaced by the one with l^2 (set after add_motor).
- `axial_mddot`: u_dot_generalized (simulation/flight.py) adds m''(r_noz - r_cm) to the
  body-axis force (its T04), m'' = rocket.total_mass_flow_rate.differentiate_complex_step(t),
  a force no variable-mass derivation has (issue 36). Switched off: that Function
  instance's differentiate_complex_step returns 0 (it is called nowhere else).
- `propellant_exact`: SolidMotor.propellant_mass is the grain volume n rho pi (R^2 - r^2) h
  of a geometry r(t), h(t) that SolidMotor.evaluate_geometry tabulates at the steps of
  scipy's LSODA (rtol 1e-11) and interpolates linearly between them; the mass is then off
  the exact m0 - (1/c) integral of F between the steps. Corrected: the geometry tabulated
  densely from the same solution (solve_ivp's dense output, 20001 instants; the wrapper
  below), so the mass follows the exact integral to the solver's tolerance.
- `pad_hold`: the rail phase (udot_rail1) holds the rocket while the thrust's component
  along the rail is below the weight's (a3 <= 0 returns zero acceleration): a correct pad
  hold. But its derivative is then identically zero, and nothing bounds the steps of the
  rail phase's solver: at tight tolerances, or with a curve that stays below the weight
  long enough, the burn is stepped over and the rocket silently stays on the pad
  (`--pad-demo`). Calisto's curve starts below its weight (100 N at 0.055 s, 1500 N at
  0.092 s against 187.5 N of weight along the rail). Corrected by flights.BoundedRailFlight: `max_step` 0.01 s for the
  rail phase's solver only.
- `all`: the three corrections together (and the pad bound): RocketPy's flight with its
  known differences removed, the reference varmass compares with.
- `coriolis`: `all` with the Earth's rotation back on (its effect, for information).

Each row: apogee (m above the pad, of the centre of dry mass), its time, rail-exit speed,
max speed, static margin (calibers) at t = 0 and at rail exit. Figures: docs/flights.md.

    target/venv-rocketpy/bin/python benches/peers/rocketpy/calisto.py [--repeat 7] [--pad-demo]
"""

import argparse
import csv
import os
import sys
import time
import tomllib
import warnings
from pathlib import Path

import numpy as np
import rocketpy.motors.solid_motor as solid_motor_module
from rocketpy import Flight
from rocketpy.mathutils.vector_matrix import Matrix

sys.path.insert(0, str(Path(__file__).resolve().parent))
import flights as reader  # noqa: E402  (benches/peers/rocketpy/flights.py)
from flights import BoundedRailFlight  # noqa: E402

ROOT = Path(__file__).resolve().parents[3]
FOLDER = ROOT / "flights" / "calisto"
SPEC = tomllib.loads((FOLDER / "flight.toml").read_text())
_SOLVE_IVP = solid_motor_module.integrate.solve_ivp


def dense_solve_ivp(fun, t_span, y0, **kwargs):
    """scipy's solve_ivp with the solution tabulated at 20001 more instants (dense output)."""
    sol = _SOLVE_IVP(fun, t_span, y0, dense_output=True, **kwargs)
    t = np.union1d(sol.t, np.linspace(sol.t[0], sol.t[-1], 20001))
    sol.t, sol.y = t, sol.sol(t)
    return sol


class Integrate:  # stands for scipy.integrate inside rocketpy.motors.solid_motor
    solve_ivp = staticmethod(dense_solve_ivp)


def build(propellant_exact):
    """The Calisto rocket and environment, the motor's geometry dense if asked."""
    solid_motor_module.integrate = Integrate if propellant_exact else _scipy_integrate()
    try:
        env = reader.environment(SPEC, "", {}, FOLDER)
        rk = reader.rocket(SPEC, FOLDER)
    finally:
        solid_motor_module.integrate = _scipy_integrate()
    return env, rk


def _scipy_integrate():
    import scipy.integrate

    return scipy.integrate


def correct_jet_damping(rk):
    r_e, l = rk.motor.nozzle_radius, rk.nozzle_to_cdm
    s11 = 0.25 * r_e**2 + l**2
    rk.nozzle_gyration_tensor = Matrix([[s11, 0, 0], [0, s11, 0], [0, 0, 0.5 * r_e**2]])


def drop_axial_mddot(rk):
    rk.total_mass_flow_rate.differentiate_complex_step = lambda *a, **k: 0.0


def fly(config, rtol=1e-6, terminate_on_apogee=False, bound_rail=None):
    """One Calisto flight: `config` names the corrections (see the module's doc)."""
    corrected = config in ("all", "coriolis")
    env, rk = build(propellant_exact=corrected or config == "propellant_exact")
    if config == "coriolis":
        lat = np.radians(SPEC["site"]["latitude"])
        w = 2 * np.pi / 86164.1
        env.earth_rotation_vector = [0, w * np.cos(lat), w * np.sin(lat)]
    if corrected or config == "jet_damping":
        correct_jet_damping(rk)
    if corrected or config == "axial_mddot":
        drop_axial_mddot(rk)
    if bound_rail is None:
        bound_rail = corrected or config == "pad_hold"
    cls = BoundedRailFlight if bound_rail else Flight
    rail = SPEC["rail"]
    kwargs = {} if rtol == 1e-6 else {"rtol": rtol, "atol": [rtol * 1e3] * 6 + [rtol] * 4
                                      + [rtol * 1e3] * 3}
    np.random.seed(36)
    t0 = time.perf_counter()
    f = cls(rocket=rk, environment=env, rail_length=rail["length"],
            inclination=rail["inclination"], heading=rail["heading"],
            terminate_on_apogee=terminate_on_apogee, **kwargs)
    elapsed = time.perf_counter() - t0
    return f, rk, env, elapsed


def summary(config, f, rk, env):
    return {
        "config": config,
        "apogee": f.apogee - env.elevation,
        "apogee_time": f.apogee_time,
        "rail_exit_speed": f.out_of_rail_velocity,
        "rail_exit_time": f.out_of_rail_time,
        "max_speed": f.max_speed,
        "static_margin_0": rk.static_margin(0),
        "static_margin_rail_exit": rk.static_margin(f.out_of_rail_time),
    }


def propellant_error():
    """Largest error of RocketPy's propellant mass against m0 - (1/c) integral of F, both
    motors (as is, dense geometry), on 40001 instants over the burn."""
    out = []
    for exact in (False, True):
        _, rk = build(propellant_exact=exact)
        m = rk.motor
        ts = np.linspace(0, m.burn_out_time, 40001)
        # the thrust is linear between its points: integrate it exactly on a grid holding them
        grid = np.union1d(ts, m.thrust.x_array)
        fgrid = np.array([m.thrust(t) for t in grid])
        cum = np.concatenate(([0.0], np.cumsum(np.diff(grid) * (fgrid[1:] + fgrid[:-1]) / 2)))
        impulse = np.interp(ts, grid, cum)
        c = m.total_impulse / m.propellant_initial_mass
        exact_mass = m.propellant_initial_mass - impulse / c
        got = np.array([m.propellant_mass(t) for t in ts])
        out.append(np.max(np.abs(got - exact_mass)) / m.propellant_initial_mass)
    return out


def pad_demo():
    """A thrust curve below the weight for its first 0.3 s, flown with RocketPy as is and
    with the rail phase's step bounded."""
    env, rk = build(False)
    motor = rk.motor
    t = motor.thrust.x_array
    weight = rk.total_mass(0) * 9.80665
    # Calisto's curve delayed by 0.3 s, with 0.3 s at a tenth of the weight in front of it
    src = np.column_stack(([0.0, 0.3], [0.1 * weight, 0.1 * weight]))
    shifted = np.column_stack((t + 0.3, motor.thrust.y_array))
    path = Path(os.environ.get("TMPDIR", "/tmp")) / "calisto_pad_demo.csv"
    np.savetxt(path, np.vstack((src, shifted[1:])), delimiter=",")
    spec = dict(SPEC)
    spec["motor"] = dict(SPEC["motor"], thrust=str(path), burn_time=float(t[-1] + 0.3))
    for cls in (Flight, BoundedRailFlight):
        rk = reader.rocket(spec, FOLDER)
        rail = SPEC["rail"]
        f = cls(rocket=rk, environment=env, rail_length=rail["length"],
                inclination=rail["inclination"], heading=rail["heading"],
                terminate_on_apogee=True, max_time=60)
        print(f"pad demo, {cls.__name__:17s}: apogee {f.apogee - env.elevation:9.3f} m, "
              f"rail exit at {getattr(f, 'out_of_rail_time', float('nan')):.4f} s, "
              f"solution points {len(f.solution)}")


KEYS = ["apogee", "apogee_time", "rail_exit_speed", "max_speed"]
TIGHT = 1e-9


def line(row, base=None):
    text = f"{row['config']:24s}"
    units = {"apogee": "m", "apogee_time": "s", "rail_exit_speed": "m/s", "max_speed": "m/s"}
    for k in KEYS:
        text += f"  {k} {row[k]:.6f} {units[k]}"
        if base is not None:
            text += f" ({row[k] - base[k]:+.6f})"
    return text + f"  margin {row['static_margin_0']:.4f}/{row['static_margin_rail_exit']:.4f}"


def effects():
    """Each difference's effect at rtol 1e-9, the rail phase's step bounded in every row
    (RocketPy as is stays on the pad at tight tolerances, see pad_hold)."""
    rows = []
    for config in ("rocketpy", "jet_damping", "axial_mddot", "propellant_exact", "all",
                   "coriolis"):
        f, rk, env, _ = fly(config, rtol=TIGHT, terminate_on_apogee=True, bound_rail=True)
        name = "bounded_as_is" if config == "rocketpy" else config
        rows.append(summary(name, f, rk, env))
        print(line(rows[-1], rows[0]), flush=True)
    return rows


def pad_rows():
    """RocketPy as is, rail phase not bounded, against tolerance: it leaves the pad or not."""
    rows = []
    for rtol in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
        f, rk, env, _ = fly("rocketpy", rtol=rtol, terminate_on_apogee=True, bound_rail=False)
        rows.append(summary(f"as_is_rtol_{rtol:g}", f, rk, env))
        print(line(rows[-1]), flush=True)
    return rows


def convergence():
    rows = []
    for rtol in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
        f, rk, env, el = fly("all", rtol=rtol, terminate_on_apogee=True)
        rows.append(summary(f"all_rtol_{rtol:g}", f, rk, env))
        print(line(rows[-1], None) + f"  ({el:.2f} s to apogee)", flush=True)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--pad-demo", action="store_true")
    ap.add_argument("--out", default=str(Path(__file__).with_name("calisto.csv")))
    args = ap.parse_args()
    warnings.simplefilter("ignore")
    if args.pad_demo:
        pad_demo()
        return
    print("RocketPy 1.13 as is, Flight(...) at its defaults (LSODA, rtol 1e-6), to landing:")
    f, rk, env, _ = fly("rocketpy")
    defaults = summary("rocketpy_defaults", f, rk, env)
    print(line(defaults))
    times = [fly("rocketpy")[3] for _ in range(args.repeat)]
    print(f"  its time: fastest of {args.repeat} {min(times):.3f} s"
          f" (median {sorted(times)[len(times) // 2]:.3f} s)")
    print(f"each known difference at rtol {TIGHT:g} (rail phase step <= "
          f"{BoundedRailFlight.rail_max_step} s in every row), change from the first row:")
    eff = effects()
    print("RocketPy as is, rail phase not bounded, against its tolerance:")
    pad = pad_rows()
    err_asis, err_dense = propellant_error()
    print(f"propellant mass, largest relative error over the burn: RocketPy {err_asis:.2e},"
          f" dense geometry {err_dense:.2e}")
    print("all corrections, against RocketPy's tolerance (the reference for varmass):")
    conv = convergence()
    cols = ["config"] + KEYS + ["rail_exit_time", "static_margin_0", "static_margin_rail_exit"]
    with open(args.out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols + ["d_" + k for k in KEYS])
        for row in [defaults] + eff + pad + conv:
            base = eff[0] if row in eff else None
            d = [f"{row[k] - base[k]:.6g}" if base else "" for k in KEYS]
            w.writerow([row["config"]] + [f"{row[c]:.10g}" for c in cols[1:]] + d)
        w.writerow(["flight_time_defaults_s", f"{min(times):.4f}"] + [""] * (len(cols) + 2))
        w.writerow(["propellant_rel_error_asis", f"{err_asis:.3g}"] + [""] * (len(cols) + 2))
        w.writerow(["propellant_rel_error_dense", f"{err_dense:.3g}"] + [""] * (len(cols) + 2))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
