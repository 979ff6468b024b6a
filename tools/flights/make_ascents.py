#!/usr/bin/env python3
"""Writes flights/NAME/ascent.vms for every flight with a log: the flight's ascent reduced to
one vertical coordinate, with a thrust scale s_F and a drag scale s_D to fit to its log
(docs/sensitivities.md#a-real-flight), from flight.toml (the numbers the 6-DOF models of
make_scenes.py use). With --fit, also runs `varmass fit` on each (target/debug/varmass, or
$VARMASS) and prints the table of docs/sensitivities.md#a-real-flight.

    python3 tools/flights/make_ascents.py [--fit]

What the reduction leaves out: the rail (flown as vertical from rest: 84 deg rails make it
cruder than Bella Lui's 89 deg), the wind, the attitude and the airframe's normal forces, the
Earth's rotation. Its own error, not the fit's, sets what a fitted apogee is worth.
"""
import csv
import pathlib
import subprocess
import sys
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[2]
FLIGHTS = ROOT / "flights"


def num(x):
    return repr(float(x))


def thrust_curve(path):
    """(t, F) points of a RASP .eng (a (0, 0) point before its first) or a CSV."""
    text = path.read_text().splitlines()
    if path.suffix == ".eng":
        lines = [l.split(";")[0].strip() for l in text]
        rows = [l.split() for l in lines if l][1:]
        points = [(0.0, 0.0)] + [(float(t), float(f)) for t, f in rows]
    else:
        rows = list(csv.reader(text))[1:]
        points = [(float(t), float(f)) for t, f in rows]
    return points


def lift_off(points, weight):
    """The first time the linear thrust curve reaches `weight`, rounded up to 1e-4 s."""
    for (t0, f0), (t1, f1) in zip(points, points[1:]):
        if f1 >= weight:
            t = t0 if f0 >= weight else t0 + (weight - f0) / (f1 - f0) * (t1 - t0)
            return (int(t * 1e4) + 1) / 1e4
    raise ValueError("the thrust never exceeds the weight")


def gravity(site):
    """The site's g: a number, or "somigliana" (the normal gravity at the site's latitude,
    at sea level: WGS-84's Somigliana formula)."""
    g = site["gravity"]
    if g != "somigliana":
        return float(g)
    import math
    s2 = math.sin(math.radians(float(site["latitude"]))) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999014 * s2)


def drag_lines(spec):
    d = spec["drag"]
    on, off = d["power_on"], d["power_off"]
    if isinstance(on, (int, float)) and on == off:
        return [f"parameter cd_const = {num(on)}", "units cd_const: 1", "let cd = cd_const"]
    if on == off:
        return [f'table cd_mach(mach) = "{on}", outside hold', "units cd_mach: 1",
                "let cd = cd_mach(mach)"]
    return [f'table cd_on(mach) = "{on}", outside hold',
            f'table cd_off(mach) = "{off}", outside hold', "units cd_on: 1, cd_off: 1",
            "let cd = burning*cd_on(mach) + (1 - burning)*cd_off(mach)"]


def apogee_time(log):
    """The time and altitude of the log's highest point, of its five-sample running median:
    a logger's spike or dropout is no apogee (Lince's log jumps to 3668.5 m at 28.89 s,
    off its 0.2 s grid, between 3030.7 and 3553.1; its top is 3586.9 m at 26.05 s,
    flight.toml's measured 3587)."""
    rows = [(float(r["time"]), float(r["altitude"])) for r in csv.DictReader(log.open())]
    median = [sorted(z for _, z in rows[max(i - 2, 0):i + 3])[len(rows[max(i - 2, 0):i + 3]) // 2]
              for i in range(len(rows))]
    i = max(range(len(rows)), key=lambda i: median[i])
    return rows[i][0], median[i]


def ascent(name, spec):
    """The model's text and the `varmass fit` arguments that fit it."""
    motor, rocket, site = spec["motor"], spec["rocket"], spec["site"]
    m_p0 = float(motor["propellant_mass"])
    dry = float(rocket["dry_mass"])
    points = thrust_curve(FLIGHTS / name / motor["thrust"])
    # 1.5 times the weight: the thrust scale is fitted down to 0.67 without the rocket
    # sinking at the start (no pad holds it; the propellant burnt meanwhile is grams).
    t_off = lift_off(points, 1.5 * (dry + m_p0) * gravity(site))
    t_apogee, _ = apogee_time(FLIGHTS / name / "flight_log.csv")
    s0 = m_p0 + 1.0
    lines = [
        f"# {spec['source']['name']}'s ascent reduced to one vertical coordinate, with a thrust",
        "# scale s_F and a drag scale s_D to fit to its log. WRITTEN BY",
        "# tools/flights/make_ascents.py from flight.toml (its doc says what the reduction",
        "# leaves out); flights/bella_lui/ascent.vms explains every line. Fitted by",
        "#",
        f"#   varmass fit flights/{name}/ascent.vms --data flights/{name}/flight_log.csv \\",
        f"#       --time time --column \"z=altitude\" --from {t_off} --until {t_apogee} \\",
        "#       --fit s_F=0.7:1.5 --fit s_D=0.2:5 --fit data:offset=-1:1 --predict \"z' < 0\" \\",
        f"#       --init z=0 --init \"z'=0\" --init m_s={num(s0)} --method dop853 --tol 1e-10",
        "#",
        f"# (--from {t_off}: where the thrust first reaches 1.5 times the weight, so that a",
        "# thrust scale down to 0.67 lifts the rocket at once; before it a pad would hold it).",
        "coordinates z",
        "units z: m",
        f'table F(t) = "{motor["thrust"]}", outside zero',
        f'table weather_T(h) = "../../models/weather/{name}/temperature.csv", linear, outside hold',
        f'table weather_p(h) = "../../models/weather/{name}/pressure.csv", linear, outside hold',
        "units F: N, weather_T: K, weather_p: Pa",
        f"parameter m_d = {num(dry)}",
        f"parameter c = {num(motor['exhaust_speed'])}",
        f"parameter t_burnout = {num(motor['burn_time'])}",
        f"parameter d_ref = {num(2 * float(rocket['radius']))}",
        f"parameter elevation = {num(site['elevation'])}",
        f"parameter g = {num(gravity(site))}",
        "parameter s_F = 1",
        "parameter s_D = 1",
        "parameter m_held = 1",
        "units m_d: kg, c: m/s, t_burnout: s, d_ref: m, elevation: m, g: m/s^2, s_F: 1, s_D: 1",
        "units m_held: kg",
        "let burning = (1 + sign(t_burnout - t))/2",
        "let mu = burning*F(t)/c",
        "units burning: 1, mu: kg/s",
        "mass m_s: state, rate -mu",
        "let m_p = m_s - m_held",
        "units m_p: kg",
        "mass m = m_d + m_p",
        "body rocket: mass m, position [z]",
        "outflow rocket: rate mu, relative_velocity [-s_F*c]",
        "potential m*g*z",
        'use "../../models/lib/atmosphere_gas.vms" as air: temperature = '
        "weather_T(elevation + z), pressure = weather_p(elevation + z)",
        "let mach = abs(z')/air_a",
        "units mach: 1",
        *drag_lines(spec),
        "let drag = s_D*cd*air_rho*z'*abs(z')/2*3.141592653589793*d_ref^2/4",
        "let altitude = z",
        "units cd: 1, drag: N, altitude: m",
        "force rocket: [-drag]",
    ]
    args = [
        "fit", f"flights/{name}/ascent.vms", "--data", f"flights/{name}/flight_log.csv",
        "--time", "time", "--column", "z=altitude", "--from", str(t_off),
        "--until", str(t_apogee), "--fit", "s_F=0.7:1.5", "--fit", "s_D=0.2:5",
        "--fit", "data:offset=-1:1", "--predict", "z' < 0", "--init", "z=0",
        "--init", "z'=0", "--init", f"m_s={num(s0)}", "--method", "dop853", "--tol", "1e-10",
    ]
    return "\n".join(lines) + "\n", args


def reported(text, name):
    for line in text.splitlines():
        line = line.strip()
        if line.startswith(f"{name} = "):
            return line.split(" = ", 1)[1].split(" (")[0]
    return "?"


def main():
    fit = "--fit" in sys.argv
    varmass = str(ROOT / "target/debug/varmass")
    rows = []
    for toml in sorted(FLIGHTS.glob("*/flight.toml")):
        name = toml.parent.name
        if name == "bella_lui" or not (toml.parent / "flight_log.csv").exists():
            # Bella Lui's is written by hand (the model the others follow).
            if name != "bella_lui":
                continue
        spec = tomllib.loads(toml.read_text())
        text, args = ascent(name, spec)
        if name != "bella_lui":
            (toml.parent / "ascent.vms").write_text(text)
        if fit:
            done = subprocess.run([varmass, *args], cwd=ROOT, capture_output=True, text=True)
            out = done.stdout + done.stderr
            apogee = spec["apogee"]
            top = apogee_time(toml.parent / "flight_log.csv")[1]
            rows.append((spec["source"]["name"], top, apogee.get("published_sim"),
                         reported(out, "z"), reported(out, "s_F"), reported(out, "s_D"),
                         reported(out, "data:offset"),
                         next((l.split("rms ")[1].split(" ")[0] for l in out.splitlines()
                               if l.startswith("residuals of z")), "?")))
    if fit:
        print("| flight | log's apogee (m) | RocketPy's (m) | fitted (m) | s_F | s_D | offset (s) | rms (m) |")
        print("|---|---|---|---|---|---|---|---|")
        for r in rows:
            rms = r[7] if r[7] == "?" else f"{float(r[7]):.2f}"
            print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]} | {r[5]} | {r[6]} | {rms} |")


if __name__ == "__main__":
    main()
