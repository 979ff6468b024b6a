#!/usr/bin/env python3
"""RocketPy 1.13 flies the public flights from flights/<name>/flight.toml (issue 36; not in CI).

Each flight's inputs are read from its flight.toml (docs/flights.md), the file varmass's
scene reads too, and handed to RocketPy in its own terms: a `tail_to_nose` rocket whose
coordinate origin is our reference point (the centre of dry mass), so every `*_z` of the
toml is RocketPy's position unchanged; a `nozzle_to_combustion_chamber` motor with its
origin at the nozzle exit (`add_motor(position = nozzle_z)`, the motor's own positions
`*_z - nozzle_z`). Then `Flight(rocket, env, rail_length, inclination, heading)` at
RocketPy's defaults (LSODA, rtol 1e-6), from the pad to landing, as the notebooks do.

Also writes benches/peers/rocketpy/surfaces.csv: each aerodynamic surface's lift slope
(per radian on the rocket's reference area, Mach 0 and 0.5) and centre of pressure (our z),
and the rocket's, for these flights and Calisto: what a Barrowman component is checked
against. And benches/peers/rocketpy/flights.csv: name, apogee (m above the site, of the centre of
dry mass), its time, rail-exit speed, max speed, static margin (calibers, RocketPy's
`rocket.static_margin`: centre of mass against the Mach-0 centre of pressure) at t = 0 and
at rail exit, the run time of `Flight(...)` (fastest of --repeat), and beside them the
apogees published in docs/examples/index.rst, the notebooks' stored outputs and the
measured ones.

The weather files (`[weather] file`) are RocketPy's; give a RocketPy checkout (a work tree,
or a git directory such as a mirror: the file is then read with `git show`):

    python3 -m venv target/venv-rocketpy
    target/venv-rocketpy/bin/pip install -r benches/peers/rocketpy/requirements.txt
    target/venv-rocketpy/bin/python benches/peers/rocketpy/flights.py \\
        --rocketpy-repo PATH/TO/RocketPy [--only andromeda,astra] [--repeat 3]

`--corrected` flies each flight instead with RocketPy's known errors corrected, as the
Calisto comparison does (docs/flights.md, docs/validation.md#calisto-in-six-degrees-of-freedom):
calisto.py's `all` (the jet damping's l^2, the axial m''(r_NOZ - r_CM) dropped, the propellant
mass tabulated densely, the rail phase's step bounded) and calisto_6dof.py's
`cm_sign_vdot_axial_thomson` (the centre of mass's and the nozzle's offsets with their sign
corrected, -(w' x r_CM) in the translation, T04's r_CM terms dropped, Thomson's internal
flow), at rtol 1e-9 to apogee, the Earth's rotation as the toml says; it writes
flights_corrected.csv (apogee, its time, rail-exit speed and time, max speed to apogee):
what cli/tests/flights.rs checks varmass's scenes against.
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import time
import tomllib
import warnings
from importlib.metadata import version
from pathlib import Path

import numpy as np
from rocketpy import Environment, Flight, Function, Rocket, SolidMotor

ROOT = Path(__file__).resolve().parents[3]
COLUMNS = [
    "name", "apogee", "apogee_time", "rail_exit_speed", "max_speed", "static_margin_0",
    "static_margin_rail_exit", "run_time", "apogee_rtol_1e-9", "published_sim",
    "notebook_output", "measured",
]


def weather_file(repo, path, cache):
    """The path of RocketPy's weather file: in a work tree, or extracted from a git dir."""
    direct = Path(repo) / path
    if direct.exists():
        return str(direct)
    if path not in cache:
        out = Path(tempfile.mkdtemp()) / Path(path).name
        data = subprocess.run(["git", "-C", repo, "show", f"HEAD:{path}"], check=True,
                              capture_output=True).stdout
        out.write_bytes(data)
        cache[path] = str(out)
    return cache[path]


def environment(spec, repo, cache, folder=None):
    site, weather = spec["site"], spec["weather"]
    gravity = None if site["gravity"] == "somigliana" else site["gravity"]
    date = spec["site"]["date_utc"]
    y, mo, d, h = int(date[0:4]), int(date[5:7]), int(date[8:10]), int(date[11:13])
    env = Environment(gravity=gravity, date=(y, mo, d, h), latitude=site["latitude"],
                      longitude=site["longitude"], elevation=site["elevation"],
                      timezone="UTC")
    if weather["kind"] == "era5":
        env.set_atmospheric_model(type="Reanalysis",
                                  file=weather_file(repo, weather["file"], cache),
                                  dictionary="ECMWF")
        if "max_expected_height" in weather:
            env.max_expected_height = weather["max_expected_height"]
    elif weather["kind"] == "us1976":
        table = np.loadtxt(folder / weather["table"], delimiter=",", skiprows=1)
        u, v = weather["wind"]
        env.set_atmospheric_model(type="custom_atmosphere",
                                  pressure=table[:, [0, 1]], temperature=table[:, [0, 2]],
                                  wind_u=u, wind_v=v)
    elif weather["kind"] != "standard":
        raise ValueError(f"weather kind {weather['kind']!r}")
    if not site.get("earth_rotation", True):
        env.earth_rotation_vector = [0.0, 0.0, 0.0]
    return env


def curve(path, outside):
    """A two-column CSV with a header line (Mach and Cd, time and thrust, angle and lift
    coefficient) as a RocketPy Function, linear between its points as RocketPy reads a
    headerless file (its own CSV reader would take a header for a multi-variable table)."""
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return Function(data, interpolation="linear", extrapolation=outside)


def motor(spec, folder):
    m, g = spec["motor"], spec["motor"]["grains"]
    noz = m["nozzle_z"]
    return SolidMotor(
        thrust_source=(str(folder / m["thrust"]) if m["thrust"].endswith(".eng")
                       else np.loadtxt(folder / m["thrust"], delimiter=",", skiprows=1)),
        burn_time=m["burn_time"],
        dry_mass=m["dry_mass"],
        dry_inertia=(m["dry_inertia"][0], m["dry_inertia"][0], m["dry_inertia"][1]),
        center_of_dry_mass_position=m["dry_cg_z"] - noz,
        grains_center_of_mass_position=g["cg_z"] - noz,
        grain_number=g["number"],
        grain_separation=g["separation"],
        grain_density=g["density"],
        grain_outer_radius=g["outer_radius"],
        grain_initial_inner_radius=g["inner_radius"],
        grain_initial_height=g["height"],
        nozzle_radius=m["nozzle_radius"],
        throat_radius=m["throat_radius"],
        nozzle_position=0,
        interpolation_method="linear",
        coordinate_system_orientation="nozzle_to_combustion_chamber",
    )


def drag(value, folder):
    return value if isinstance(value, (int, float)) else curve(folder / value, "constant")


def rocket(spec, folder):
    r, dr = spec["rocket"], spec["drag"]
    rk = Rocket(
        radius=r["radius"], mass=r["mass"],
        inertia=(r["inertia"][0], r["inertia"][0], r["inertia"][1]),
        power_off_drag=drag(dr["power_off"], folder),
        power_on_drag=drag(dr["power_on"], folder),
        center_of_mass_without_motor=r["cg_z"],
        coordinate_system_orientation="tail_to_nose",
    )
    mt = motor(spec, folder)
    # the toml's derived impulse against RocketPy's: the thrust file is read alike
    rel = abs(mt.total_impulse / spec["motor"]["total_impulse"] - 1)
    if rel > 1e-9:
        raise ValueError(f"total impulse {mt.total_impulse} against the toml's, {rel:.1e}")
    rk.add_motor(mt, position=spec["motor"]["nozzle_z"])
    rail = spec["rail"]
    rk.set_rail_buttons(rail["upper_button_z"], rail["lower_button_z"], rail["button_angle"])
    nose = spec["nose"]
    rk.add_nose(length=nose["length"], kind=nose["kind"], position=nose["tip_z"],
                base_radius=nose["base_radius"])
    fins = spec["fins"]
    airfoil = None
    if fins["airfoil"] != "none":
        airfoil = (np.loadtxt(folder / fins["airfoil"], delimiter=",", skiprows=1),
                   fins["airfoil_unit"])
    rk.add_trapezoidal_fins(
        n=fins["n"], root_chord=fins["root_chord"], tip_chord=fins["tip_chord"],
        span=fins["span"], position=fins["root_leading_edge_z"],
        cant_angle=fins["cant"], sweep_length=fins["sweep_length"],
        radius=fins["body_radius"], airfoil=airfoil,
    )
    if "tail" in spec:
        t = spec["tail"]
        rk.add_tail(top_radius=t["top_radius"], bottom_radius=t["bottom_radius"],
                    length=t["length"], position=t["top_z"])
    for c in spec.get("parachutes", []):
        rk.add_parachute(c["name"], cd_s=c["cd_s"], trigger=c["trigger"],
                         sampling_rate=c["sampling_rate"], lag=c["lag"],
                         noise=tuple(c["noise"]), radius=c.get("radius"),
                         height=c.get("height"))
    return rk


class BoundedRailFlight(Flight):
    """Flight whose rail phase (only) has its solver's step bounded by `rail_max_step` (s).

    On the rail RocketPy holds the rocket while the thrust along the rail is below the
    weight's component (Flight.udot_rail1: a3 <= 0 gives zero acceleration); the state's
    derivative is then identically zero, LSODA's error estimate too, and its steps grow
    unbounded: at tight tolerances (rtol <= 1e-9 for Calisto and Andromeda) or with a curve
    that stays below the weight long enough, it steps over the thrust and the rocket stays on
    the pad, silently. Bounding the rail phase's steps (Flight's own max_time_step would
    bound every phase) makes it see the thrust.
    """

    rail_max_step = 0.01

    def _Flight__simulate(self, verbose):  # noqa: N802  (name-mangled private method)
        original = self._solver

        def solver(fun, t0, y0, t_bound, **kwargs):
            if fun == self.udot_rail1:
                kwargs["max_step"] = min(kwargs.get("max_step", np.inf), self.rail_max_step)
            return original(fun, t0, y0, t_bound, **kwargs)

        self._solver = solver
        try:
            return Flight._Flight__simulate(self, verbose)
        finally:
            self._solver = original


def fly(spec, env, rk, rtol=None):
    kwargs = {}
    if "max_time" in spec.get("run", {}):
        kwargs["max_time"] = spec["run"]["max_time"]
    cls = Flight
    if rtol is not None:  # tight: RocketPy stays on the pad unless the rail phase is bounded
        kwargs.update(rtol=rtol, atol=[rtol * 1e3] * 6 + [rtol] * 4 + [rtol * 1e3] * 3,
                      terminate_on_apogee=True)
        cls = BoundedRailFlight
    rail = spec["rail"]
    return cls(rocket=rk, environment=env, rail_length=rail["length"],
               inclination=rail["inclination"], heading=rail["heading"], **kwargs)


def run(name, repo, repeat, cache):
    folder = ROOT / "flights" / name
    spec = tomllib.loads((folder / "flight.toml").read_text())
    env = environment(spec, repo, cache, folder)
    best, flight = math.inf, None
    for _ in range(repeat):
        np.random.seed(36)  # the parachutes' pressure noise: no effect before apogee
        rk = rocket(spec, folder)
        t0 = time.perf_counter()
        flight = fly(spec, env, rk)
        best = min(best, time.perf_counter() - t0)
    ap = spec["apogee"]
    tight = fly(spec, env, rocket(spec, folder), rtol=1e-9)
    return {
        "apogee_rtol_1e-9": tight.apogee - env.elevation,
        "name": name,
        "apogee": flight.apogee - env.elevation,
        "apogee_time": flight.apogee_time,
        "rail_exit_speed": flight.out_of_rail_velocity,
        "max_speed": flight.max_speed,
        "static_margin_0": rk.static_margin(0),
        "static_margin_rail_exit": rk.static_margin(flight.out_of_rail_time),
        "run_time": best,
        "published_sim": ap["published_sim"],
        "notebook_output": ap["notebook_output"],
        "measured": ap["measured"],
    }


CORRECTED_COLUMNS = ["name", "apogee", "apogee_time", "rail_exit_speed", "rail_exit_time",
                     "max_speed", "static_margin_0"]


STEPS = [  # cumulative: each row adds one correction to the row before
    ("as_is", ()),
    ("all", ("all",)),
    ("cm_sign", ("all", "sign")),
    ("vdot", ("all", "sign", "vdot")),
    ("axial", ("all", "sign", "vdot", "axial")),
    ("thomson", ("all", "sign", "vdot", "axial", "thomson")),
]


def run_corrected(name, repo, cache, switches=("all", "sign", "vdot", "axial", "thomson")):
    """One flight with RocketPy's known errors corrected (calisto.py's `all` plus
    calisto_6dof.py's cm_sign, vdot, axial and thomson; `switches` says which), rtol 1e-9
    (the rail phase bounded), to apogee."""
    import calisto  # noqa: PLC0415  (benches/peers/rocketpy/calisto.py: the corrections)
    import calisto_6dof  # noqa: PLC0415
    import rocketpy.motors.solid_motor as solid_motor_module  # noqa: PLC0415

    folder = ROOT / "flights" / name
    spec = tomllib.loads((folder / "flight.toml").read_text())
    env = environment(spec, repo, cache, folder)
    if "all" in switches:  # the propellant mass tabulated densely
        solid_motor_module.integrate = calisto.Integrate
    try:
        rk = rocket(spec, folder)
    finally:
        solid_motor_module.integrate = calisto._scipy_integrate()
    if "all" in switches:
        calisto.correct_jet_damping(rk)
        calisto.drop_axial_mddot(rk)
    if "sign" in switches:
        rk.com_to_cdm_function = -1 * rk.com_to_cdm_function
        rk.nozzle_to_cdm = -rk.nozzle_to_cdm
    original = Flight.u_dot_generalized
    Flight.u_dot_generalized = calisto_6dof.patched(switches)
    try:
        np.random.seed(36)
        f = fly(spec, env, rk, rtol=1e-9)
    finally:
        Flight.u_dot_generalized = original
    return {
        "name": name, "apogee": f.apogee - env.elevation, "apogee_time": f.apogee_time,
        "rail_exit_speed": f.out_of_rail_velocity, "rail_exit_time": f.out_of_rail_time,
        "max_speed": f.max_speed, "static_margin_0": rk.static_margin(0),
    }


def steps(names, repo, out):
    """Each flight's apogee with the corrections added one by one (STEPS), rtol 1e-9."""
    rows, cache = [], {}
    for name in names:
        row = [name] + [run_corrected(name, repo, cache, sw)["apogee"] for _, sw in STEPS]
        rows.append(row)
        print("  ".join([name] + [f"{s} {a:.4f}" for (s, _), a in zip(STEPS, row[1:])]),
              flush=True)
    with open(out, "w", newline="") as fh:
        fh.write(f"# RocketPy {version('rocketpy')}: apogee (m above the pad) at rtol 1e-9 to apogee "
                 "(rail phase bounded), the corrections added one by one:\n"
                 "# target/venv-rocketpy/bin/python benches/peers/rocketpy/flights.py "
                 "--rocketpy-repo PATH/TO/RocketPy --corrected --steps\n")
        w = csv.writer(fh)
        w.writerow(["name"] + [s for s, _ in STEPS])
        for row in rows:
            w.writerow([row[0]] + [f"{a:.10g}" for a in row[1:]])
    print(f"wrote {out}")


def corrected(names, repo, out):
    rows, cache = [], {}
    for name in names:
        row = run_corrected(name, repo, cache)
        rows.append(row)
        print("  ".join(f"{c} {row[c]}" for c in CORRECTED_COLUMNS), flush=True)
    with open(out, "w", newline="") as fh:
        fh.write(f"# RocketPy {version('rocketpy')}, known errors corrected, rtol 1e-9, to apogee:\n"
                 "# target/venv-rocketpy/bin/python benches/peers/rocketpy/flights.py "
                 "--rocketpy-repo PATH/TO/RocketPy --corrected\n")
        w = csv.writer(fh)
        w.writerow(CORRECTED_COLUMNS)
        for row in rows:
            w.writerow([row["name"]] + [f"{row[c]:.10g}" for c in CORRECTED_COLUMNS[1:]])
    print(f"wrote {out} ({len(rows)} flights)")


def surfaces(name):
    """RocketPy's lift slope (per radian, on the rocket's reference area, at Mach 0 and 0.5)
    and centre of pressure (our z) of each aerodynamic surface of a flight, and the rocket's."""
    folder = ROOT / "flights" / name
    spec = tomllib.loads((folder / "flight.toml").read_text())
    rk = rocket(spec, folder)
    rows = []
    for surface, _ in rk.aerodynamic_surfaces:
        factor = (surface.rocket_radius / rk.radius) ** 2
        rows.append([name, type(surface).__name__, factor * surface.clalpha(0.0),
                     factor * surface.clalpha(0.5), rk.surfaces_cp_to_cdm[surface].z])
    rows.append([name, "rocket", rk.total_lift_coeff_der(0.0), rk.total_lift_coeff_der(0.5),
                 rk.cp_position(0.0)])
    rows.append([name, "static_margin_0", rk.static_margin(0), "", ""])
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rocketpy-repo", required=True)
    ap.add_argument("--only", default="")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=None)
    ap.add_argument("--corrected", action="store_true",
                    help="RocketPy's known errors corrected, rtol 1e-9 → flights_corrected.csv")
    ap.add_argument("--steps", action="store_true",
                    help="with --corrected: the corrections one by one → flights_corrections.csv")
    args = ap.parse_args()
    names = sorted(p.parent.name for p in (ROOT / "flights").glob("*/flight.toml")
                   if p.parent.name != "calisto")  # calisto.py flies Calisto
    if args.only:
        names = [n for n in names if n in args.only.split(",")]
    os.environ.setdefault("MPLBACKEND", "Agg")
    warnings.simplefilter("ignore")
    sys.path.insert(0, str(Path(__file__).resolve().parent))  # calisto.py, calisto_6dof.py
    if args.corrected and args.steps:
        steps(names, args.rocketpy_repo,
              args.out or str(Path(__file__).with_name("flights_corrections.csv")))
        return
    if args.corrected:
        corrected(names, args.rocketpy_repo,
                  args.out or str(Path(__file__).with_name("flights_corrected.csv")))
        return
    args.out = args.out or str(Path(__file__).with_name("flights.csv"))
    rows, cache = [], {}
    for name in names:
        row = run(name, args.rocketpy_repo, args.repeat, cache)
        rows.append(row)
        print(f"{name:10s} apogee {row['apogee']:9.2f} m at {row['apogee_time']:6.2f} s"
              f"  rail exit {row['rail_exit_speed']:6.2f} m/s  max {row['max_speed']:7.2f} m/s"
              f"  margin {row['static_margin_0']:.3f}/{row['static_margin_rail_exit']:.3f}"
              f"  {row['run_time']:.2f} s  rtol 1e-9: {row['apogee_rtol_1e-9']:.2f} m  (published {row['published_sim']},"
              f" notebook {row['notebook_output']}, measured {row['measured']})",
              flush=True)
    with open(args.out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        for row in rows:
            w.writerow([row["name"]] + [f"{row[c]:.6g}" if c != "run_time" else
                                        f"{row[c]:.3f}" for c in COLUMNS[1:]])
    print(f"wrote {args.out} ({len(rows)} flights), rocketpy {version('rocketpy')}")
    out = Path(args.out).with_name("surfaces.csv")
    with open(out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["name", "surface", "cn_alpha_mach_0", "cn_alpha_mach_0.5", "cp_z"])
        for name in names + ["calisto"]:
            for row in surfaces(name):
                w.writerow(row[:2] + [f"{v:.10g}" if v != "" else "" for v in row[2:]])
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
