#!/usr/bin/env python3
"""Writes the scene of each public flight, flights/<name>/<name>.vms and <name>.toml, from its
flight.toml (issue 36, item 6; docs/flights.md#the-scenes), and <name>_ascent.toml, the same
from the rail to the log's apogee without parachutes, which `varmass fit` fits to the log
with the model's thrust scale s_F and drag scale s_D, both 1 as published (issue 37;
docs/sensitivities.md#a-real-flight).

Every scene is Calisto's (flights/calisto/calisto.vms, the template checked against RocketPy
1.13 to 8.2e-7 of apogee) with the flight's own numbers and these differences, each decided
by a key of flight.toml so that a reader sees what differs between two flights:

* weather ([weather] kind = "era5"): the flight's ERA5 profile, models/weather/<name>/
  (pressure, temperature, wind east and north against the altitude above sea level), LINEAR
  tables held outside as RocketPy reads them (models/lib/atmosphere_gas.vms's header), the
  air's molar mass set to RocketPy's R = 287.05287 J/(kg K) (`air_M0 = 0.02896442`);
* gravity ([site] gravity): a constant, or "somigliana": models/lib/gravity_somigliana.vms
  at the site's latitude and the altitude above sea level (RocketPy's default);
* the Earth's rotation ([site] earth_rotation = true): RocketPy's Coriolis acceleration
  -2 Omega x v of the reference point (Flight.u_dot_generalized and u_dot_parachute; not on
  the rail), Omega = Omega_E (0, cos(lat), sin(lat)) in east-north-up axes, Omega_E = 2 pi /
  86164.1 s (RocketPy's sidereal day). In a Lagrangian model a velocity-dependent force: here
  -2 m Omega x v on the whole mass, applied at the centre of mass (no moment, as RocketPy's
  acceleration of the reference point adds none);
* the wind at each surface's height: RocketPy 1.13 (Flight.u_dot_generalized) takes each
  aerodynamic surface's stream velocity with the wind at that surface's centre of pressure's
  altitude, z + (K r_cp).z, not the reference point's; so does each Barrowman component here
  (its lateral airspeed u, v less the wind's change between the two heights, in body axes).
  Calisto's wind is the same at every height, so calisto.vms has no such term; NDRT's shear
  (1.6–2.0 m/s per 100 m near its pad) makes it 0.4 m of apogee (docs/validation.md);
* the nose ([nose] kind): "vonKarman" -> barrowman_nose_haack.vms (C = 0), "tangent" ->
  barrowman_nose_ogive.vms (a tangent ogive: RocketPy's centre of pressure L - V/A(L) is the
  library's);
* a tail ([tail]) only where the flight has one; the fins' body radius ([fins] body_radius);
* drag ([drag]): one table when power-on and power-off are the same file, a constant when a
  number (NDRT's 0.44), else Calisto's power-on while burning and power-off after;
* the thrust clipped to [0, burn_time] (RocketPy clips it: Bella Lui's curve runs to 2.50 s,
  its burn_time is 2.43 s);
* recovery ([[parachutes]]): a phase at apogee (z' falls through 0), where a drogue's
  deployment time is set to apogee + lag; a main's phase at its height on the way down, the
  drogue cut as it opens (RocketPy flies one parachute at a time); models/lib/parachute.vms
  at the reference point; from the first canopy's opening the airframe's aerodynamic forces
  are off (`aero_off`), as RocketPy then flies the rocket as a particle under its canopy.
  The landing: the last phase stops where z falls through 0. A flight without parachutes
  falls ballistically, airframe on, as RocketPy's does.

    python3 tools/flights/make_scenes.py            # writes flights/<name>/<name>{.vms,.toml,_ascent.toml}
    python3 tools/flights/make_scenes.py --out DIR  # into DIR/<name>/ (the pytest's check)

Plain Python (stdlib tomllib); python/tests/test_flight_scenes.py regenerates into a temporary
folder and asserts the committed files are identical.
"""

import argparse
import math
import sys
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_ascents import apogee_time  # noqa: E402  (the log's apogee, one definition)

ROOT = Path(__file__).resolve().parents[2]
FLIGHTS = ["bella_lui", "ndrt_2020", "andromeda", "astra", "erebus", "cavour", "genesis",
           "lince"]
NOSES = {"vonkarman": "barrowman_nose_haack.vms", "tangent": "barrowman_nose_ogive.vms"}
OMEGA_EARTH = 2 * math.pi / 86164.1  # rad/s, RocketPy's Environment (sidereal day)
R_AIR_ROCKETPY_M0 = 0.02896442  # kg/mol: R*/M0 = 287.05287 J/(kg K), RocketPy's air


def num(x):
    """A number as the model writes it: the shortest repr that reads back exactly."""
    return repr(float(x)) if not float(x).is_integer() else f"{float(x):.1f}"


def grains_inertia(motor):
    """The propellant's squared radii of gyration about the grains' centre (transverse k_a^2,
    axial k_c^2) at ignition and burnout, RocketPy's SolidMotor: n hollow cylinders on the fixed
    spacing h0 + separation, the bore r and height h = h0 - 2 (r - r0) regressing;
    k_a^2 = (R^2 + r^2)/4 + h^2/12 + sum d_i^2/n, sum d_i^2/n = (h0 + s)^2 (n^2 - 1)/12."""
    g = motor["grains"]
    n, big_r, r0, h0, sep = (g["number"], g["outer_radius"], g["inner_radius"], g["height"],
                             g["separation"])
    spread = (h0 + sep) ** 2 * (n * n - 1) / 12

    def ka2(r, h):
        return (big_r**2 + r**2) / 4 + h**2 / 12 + spread

    h1 = h0 - 2 * (big_r - r0)
    assert h1 > 0, "the grains burn through their height before their bore"
    return (ka2(r0, h0), ka2(big_r, h1), (big_r**2 + r0**2) / 2, big_r**2)


def attitude(rail):
    """RocketPy's initial quaternion (3-1-3 Euler angles psi = -heading, theta = inclination
    - 90 deg, phi = button_angle), checked: its body z is the rail's direction."""
    psi, theta, phi = (math.radians(-rail["heading"]), math.radians(rail["inclination"] - 90),
                       math.radians(rail["button_angle"]))
    q = (math.cos(theta / 2) * math.cos((phi + psi) / 2),
         math.sin(theta / 2) * math.cos((phi - psi) / 2),
         -math.sin(theta / 2) * math.sin((phi - psi) / 2),
         math.cos(theta / 2) * math.sin((phi + psi) / 2))
    e0, e1, e2, e3 = q
    axis = (2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2)
    i, h = math.radians(rail["inclination"]), math.radians(rail["heading"])
    rail_dir = (math.cos(i) * math.sin(h), math.cos(i) * math.cos(h), math.sin(i))
    assert max(abs(a - b) for a, b in zip(axis, rail_dir)) < 1e-12, (axis, rail_dir)
    return q


def chutes(spec):
    """(drogue, main): the parachute at apogee and the one at a height, either may be None."""
    drogue = main = None
    for c in spec.get("parachutes", []):
        if c["trigger"] == "apogee":
            assert drogue is None
            drogue = c
        else:
            assert main is None and isinstance(c["trigger"], (int, float))
            main = c
    return drogue, main


def drag_lines(spec):
    """The drag coefficient's declarations and its `cd` law (RocketPy's R3: power-on curve
    while burning, power-off after)."""
    d = spec["drag"]
    on, off = d["power_on"], d["power_off"]
    if isinstance(on, (int, float)) and on == off:
        return ([f"parameter cd_const = {num(on)}", "units cd_const: 1"],
                "let cd = cd_const")
    if on == off:
        return ([f'table cd_mach(mach) = "{on}", outside hold', "units cd_mach: 1"],
                "let cd = cd_mach(mach)")
    return ([f'table cd_on(mach) = "{on}", outside hold',
             f'table cd_off(mach) = "{off}", outside hold', "units cd_on: 1, cd_off: 1"],
            "let cd = burning*cd_on(mach) + (1 - burning)*cd_off(mach)")


def header(name, spec):
    site = spec["site"]
    return f"""# {spec['source']['name']}: RocketPy's public flight (flight.toml, docs/flights.md) in six
# degrees of freedom, from the rail to apogee, under its parachutes to landing. WRITTEN BY
# tools/flights/make_scenes.py from flight.toml: edit the generator, not this file. The
# model is flights/calisto/calisto.vms's (its header explains every part; checked against
# RocketPy 1.13 to 8.2e-7 of apogee) with this flight's numbers; what differs between the
# flights is listed in the generator's doc. {name}.toml flies it; cli/tests/flights.rs
# checks its ascent against RocketPy 1.13 with its known errors corrected
# (benches/peers/rocketpy/flights_corrected.csv), docs/validation.md#the-public-flights.
#
# World x = East, y = North, z = Up at the launch site ({num(site['latitude'])} deg,
# {num(site['longitude'])} deg, elevation {num(site['elevation'])} m); [x, y, z] is the reference
# point, the centre of dry mass; `altitude` is z, above the launch site. Body z toward the
# nose; every `z_*` is a body-z coordinate from the reference point (flight.toml's `*_z`).
"""


def site_lines(name, spec):
    site, lines = spec["site"], []
    lines += [f"parameter elevation = {num(site['elevation'])}", "units elevation: m"]
    w = f"../../models/weather/{name}"
    assert spec["weather"]["kind"] == "era5", "only the ERA5 flights have a scene"
    lines += [
        "# the air and the wind: the ERA5 profile, linear, held outside (RocketPy's)",
        f'table weather_T(h) = "{w}/temperature.csv", linear, outside hold',
        f'table weather_p(h) = "{w}/pressure.csv", linear, outside hold',
        f'table weather_e(h) = "{w}/wind_east.csv", linear, outside hold',
        f'table weather_n(h) = "{w}/wind_north.csv", linear, outside hold',
        "units weather_T: K, weather_p: Pa, weather_e: m/s, weather_n: m/s",
        "let h_asl = elevation + z",
        "units h_asl: m",
        'use "../../models/lib/atmosphere_gas.vms" as air: temperature = weather_T(h_asl), '
        "pressure = weather_p(h_asl)",
        "let wind_east = weather_e(h_asl)",
        "let wind_north = weather_n(h_asl)",
        "units wind_east: m/s, wind_north: m/s",
    ]
    return lines


def gravity_lines(spec):
    """Gravity on the whole mass, its centre at z_c: m g (z + z_c cos(tilt)); the offset's
    term with the pad's g (g varies by 3e-7 over a metre)."""
    site = spec["site"]
    tilt = "m_p*z_g*(e0^2 - e1^2 - e2^2 + e3^2)/(e0^2 + e1^2 + e2^2 + e3^2)"
    if site["gravity"] == "somigliana":
        lat = math.radians(site["latitude"])
        s2 = math.sin(lat) ** 2
        g_pad = 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 6.69437999014e-3 * s2)
        a_e, f, m_r = 6378137.0, 0.0033528106647474805, 0.00344978650684
        h = site["elevation"]
        g_pad *= 1 - 2 * (1 + f + m_r - 2 * f * s2) * h / a_e + 3 * h * h / a_e**2
        return [
            "# gravity: Somigliana's normal gravity at the latitude and the height above sea level",
            f"parameter latitude = {num(lat)}",
            f"parameter g_pad = {num(g_pad)}",
            "units latitude: rad, g_pad: m/s^2",
            'use "../../models/lib/gravity_somigliana.vms" as gravity: mass = m, h = h_asl, '
            "phi = latitude",
            f"potential g_pad*{tilt}",
        ]
    return [
        f"parameter g = {num(site['gravity'])}",
        "units g: m/s^2",
        f"potential g*(m*z + {tilt})",
    ]


def coriolis_lines(spec):
    site = spec["site"]
    if not site.get("earth_rotation", False):
        return []
    lat = math.radians(site["latitude"])
    return [
        "# the Earth's rotation: RocketPy's Coriolis acceleration -2 Omega x v of the reference",
        "# point, Omega = Omega_E (0, cos(lat), sin(lat)) (east, north, up), on the whole mass",
        f"parameter omega_north = {num(OMEGA_EARTH * math.cos(lat))}",
        f"parameter omega_up = {num(OMEGA_EARTH * math.sin(lat))}",
        "units omega_north: rad/s, omega_up: rad/s",
        "let coriolis_x = -2*m*(omega_north*z' - omega_up*y')",
        "let coriolis_y = -2*m*omega_up*x'",
        "let coriolis_z = 2*m*omega_north*x'",
        "units coriolis_x: N, coriolis_y: N, coriolis_z: N",
        "force rocket: [coriolis_x, coriolis_y, coriolis_z] at [0, 0, z_c]",
    ]


def mass_lines(spec):
    r, m = spec["rocket"], spec["motor"]
    ka2_0, ka2_1, kc2_0, kc2_1 = grains_inertia(m)
    table = m["thrust"]
    return [
        f'table F(t) = "{table}", outside zero',
        "units F: N",
        "# the dry rocket (rocket + unloaded motor) about the reference point",
        f"parameter m_d = {num(r['dry_mass'])}",
        f"parameter A_d = {num(r['dry_inertia'][0])}",
        f"parameter C_d = {num(r['dry_inertia'][1])}",
        "units m_d: kg, A_d: kg*m^2, C_d: kg*m^2",
        "# the motor: exhaust speed, burnout, nozzle, the grains' centre and their inertia radii",
        f"parameter c = {num(m['exhaust_speed'])}",
        f"parameter t_burnout = {num(m['burn_time'])}",
        f"parameter z_nozzle = {num(m['nozzle_z'])}",
        f"parameter z_g = {num(m['grains']['cg_z'])}",
        f"parameter m_p0 = {num(m['propellant_mass'])}",
        f"parameter ka2_0 = {num(ka2_0)}",
        f"parameter ka2_1 = {num(ka2_1)}",
        f"parameter kc2_0 = {num(kc2_0)}",
        f"parameter kc2_1 = {num(kc2_1)}",
        "units c: m/s, t_burnout: s, z_nozzle: m, z_g: m, m_p0: kg",
        "units ka2_0: m^2, ka2_1: m^2, kc2_0: m^2, kc2_1: m^2",
        "# the burn: RocketPy clips the thrust curve to [0, burn_time]; s_F scales the thrust",
        "# through the exhaust speed (the propellant and its burn rate are the motor's): 1 as",
        "# published, a free unknown of `varmass fit` (docs/sensitivities.md#a-real-flight)",
        "parameter s_F = 1",
        "units s_F: 1",
        "let burning = (1 + sign(t_burnout - t))/2",
        "let mu = burning*F(t)/c",
        "let thrust = s_F*burning*F(t)",
        "units burning: 1, thrust: N, mu: kg/s",
        "# the propellant plus a constant m_held that never burns (calisto.vms)",
        "parameter m_held = 1",
        "units m_held: kg",
        "mass m_s: state, rate -mu",
        "let m_p = m_s - m_held",
        "units m_p: kg",
        "mass m = m_d + m_p",
        "let ka2 = ka2_1 + (ka2_0 - ka2_1)*m_p/m_p0",
        "let kc2 = kc2_1 + (kc2_0 - kc2_1)*m_p/m_p0",
        "let z_c = z_g*m_p/m",
        "units ka2: m^2, kc2: m^2, z_c: m",
        "inertia A = A_d + m_p*ka2 + m_d*m_p*z_g^2/m",
        "inertia C = C_d + m_p*kc2",
        "rigid rocket: mass m, inertia [A, A, C], position [x, y, z], "
        "orientation quaternion(e0, e1, e2, e3), centre [0, 0, z_c]",
        "outflow rocket: rate mu, at [0, 0, z_nozzle], relative_velocity body [0, 0, -s_F*c]",
    ]


def air_lines(spec):
    return [
        "# the airspeed in body axes; the airframe's forces off from the first canopy's opening",
        "parameter aero_off = 1e30",
        "units aero_off: s",
        "let aero = 1 - sign(max(t - aero_off, 0))",
        "let rho_aero = aero*air_rho",
        "units aero: 1, rho_aero: kg/m^3",
        "let air_vx = x' - wind_east",
        "let air_vy = y' - wind_north",
        "let air_vz = z'",
        "let airspeed = sqrt(air_vx^2 + air_vy^2 + air_vz^2)",
        "let mach = airspeed/air_a",
        "let qbar = air_rho*airspeed^2/2",
        "let altitude = z",
        "let speed = sqrt(x'^2 + y'^2 + z'^2)",
        "units air_vx: m/s, air_vy: m/s, air_vz: m/s, airspeed: m/s, mach: 1, qbar: Pa",
        "units altitude: m, speed: m/s",
        'use "../../models/lib/body_axes_quaternion.vms" as axes: e0 = e0, e1 = e1, '
        "e2 = e2, e3 = e3, vx = air_vx, vy = air_vy, vz = air_vz",
        "let alpha = atan2(sqrt(axes_u^2 + axes_v^2), axes_w)",
        "units alpha: rad",
    ]


def centres_of_pressure(spec):
    """Each surface's centre of pressure (body z), the library's formulas (barrowman_*.vms):
    the height at which its wind is read. Checked against RocketPy's (surfaces.csv)."""
    nose, fins = spec["nose"], spec["fins"]
    kind = nose["kind"].replace(" ", "").lower()
    length = nose["length"]
    if kind == "vonkarman":
        x_nose = length / 2
    else:  # tangent ogive: L - V/(pi R^2)
        big_r = nose["base_radius"]
        rho_o = (big_r**2 + length**2) / (2 * big_r)
        vol = math.pi * (rho_o**2 * length - length**3 / 3
                         - (rho_o - big_r) * rho_o**2 * math.asin(length / rho_o))
        x_nose = length - vol / (math.pi * big_r**2)
    cr, ct, sweep = fins["root_chord"], fins["tip_chord"], fins["sweep_length"]
    x_fins = sweep / 3 * (cr + 2 * ct) / (cr + ct) + (cr**2 + ct**2 + cr * ct) / (6 * (cr + ct))
    cps = {"nose": nose["tip_z"] - x_nose, "fins": fins["root_leading_edge_z"] - x_fins}
    if "tail" in spec:
        t = spec["tail"]
        d1, d2 = t["top_radius"], t["bottom_radius"]
        cps["tail"] = t["top_z"] - t["length"] * (d1 + 2 * d2) / (3 * (d1 + d2))
    return cps


def check_against_rocketpy(name, cps):
    path = ROOT / "benches" / "peers" / "rocketpy" / "surfaces.csv"
    kinds = {"NoseCone": "nose", "TrapezoidalFins": "fins", "Tail": "tail"}
    checked = set()
    for line in path.read_text().splitlines()[1:]:
        f = line.split(",")
        if f[0] == name and f[1] in kinds:
            assert abs(cps[kinds[f[1]]] - float(f[4])) < 1e-8, (name, f, cps)
            checked.add(kinds[f[1]])
    # Every surface the scene has is checked: a flight missing from surfaces.csv is an error.
    assert checked == set(cps), (name, sorted(checked), sorted(cps))


def local_wind_lines(spec):
    """Each surface's lateral airspeed with the wind at its own height (RocketPy's)."""
    lines = ["# each surface's airspeed with the wind at its centre of pressure's height (RocketPy's)"]
    for label, z in centres_of_pressure(spec).items():
        lines += [
            f"parameter z_cp_{label} = {num(z)}",
            f"units z_cp_{label}: m",
            f"let h_{label} = h_asl + z_cp_{label}*axes_R33",
            f"let dwe_{label} = weather_e(h_{label}) - wind_east",
            f"let dwn_{label} = weather_n(h_{label}) - wind_north",
            f"let u_{label} = axes_u - axes_R11*dwe_{label} - axes_R21*dwn_{label}",
            f"let v_{label} = axes_v - axes_R12*dwe_{label} - axes_R22*dwn_{label}",
            f"units h_{label}: m, dwe_{label}: m/s, dwn_{label}: m/s, u_{label}: m/s, "
            f"v_{label}: m/s",
        ]
    return lines


def airframe_lines(spec):
    r, nose, fins = spec["rocket"], spec["nose"], spec["fins"]
    kind = nose["kind"].replace(" ", "").lower()
    if fins["airfoil"] != "none" and "airfoil_cl_alpha" not in fins:
        raise ValueError(f"fins with the airfoil {fins['airfoil']!r} need airfoil_cl_alpha")
    cl_alpha = fins["airfoil_cl_alpha"] if fins["airfoil"] != "none" else 2 * math.pi
    lines = [
        "# the airframe (flight.toml's [rocket], [nose], [fins], [tail])",
        f"parameter d_ref = {num(2 * r['radius'])}",
        f"parameter l_nose = {num(nose['length'])}",
        f"parameter d_nose = {num(2 * nose['base_radius'])}",
        f"parameter z_nose = {num(nose['tip_z'])}",
        f"parameter fin_root = {num(fins['root_chord'])}",
        f"parameter fin_tip = {num(fins['tip_chord'])}",
        f"parameter fin_span = {num(fins['span'])}",
        f"parameter fin_sweep = {num(fins['sweep_length'])}",
        f"parameter r_fins = {num(fins['body_radius'])}",
        f"parameter z_fins = {num(fins['root_leading_edge_z'])}",
        f"parameter fin_cant = {num(math.radians(fins['cant']))}",
        f"parameter fin_cl_alpha = {num(cl_alpha)}",
        "units d_ref: m, l_nose: m, d_nose: m, z_nose: m, fin_root: m, fin_tip: m, "
        "fin_span: m, fin_sweep: m",
        "units r_fins: m, z_fins: m, fin_cant: rad, fin_cl_alpha: 1",
        "# the normal forces (Barrowman), each at its centre of pressure, local airspeed",
        f'use "../../models/lib/{NOSES[kind]}" as nose: on = rocket, rho = rho_aero, '
        "speed = airspeed, u = u_nose, v = v_nose, p = axes_p, q = axes_q, d_ref = d_ref, "
        "length = l_nose, d = d_nose, z = z_nose",
        'use "../../models/lib/barrowman_fins_trapezoidal.vms" as fins: on = rocket, '
        "rho = rho_aero, speed = airspeed, u = u_fins, v = v_fins, p = axes_p, q = axes_q, "
        f"r = axes_r, d_ref = d_ref, N = {fins['n']}, root = fin_root, tip = fin_tip, "
        "span = fin_span, sweep = fin_sweep, radius = r_fins, z = z_fins, mach = mach, "
        "cant = fin_cant, cl_alpha = fin_cl_alpha",
    ]
    if "tail" in spec:
        t = spec["tail"]
        lines += [
            f"parameter l_tail = {num(t['length'])}",
            f"parameter d_tail_fore = {num(2 * t['top_radius'])}",
            f"parameter d_tail_aft = {num(2 * t['bottom_radius'])}",
            f"parameter z_tail = {num(t['top_z'])}",
            "units l_tail: m, d_tail_fore: m, d_tail_aft: m, z_tail: m",
            'use "../../models/lib/barrowman_transition.vms" as tail: on = rocket, '
            "rho = rho_aero, speed = airspeed, u = u_tail, v = v_tail, p = axes_p, "
            "q = axes_q, d_ref = d_ref, length = l_tail, d_fore = d_tail_fore, "
            "d_aft = d_tail_aft, z = z_tail",
        ]
    return lines


def roll_lines(spec):
    n = spec["fins"]["n"]
    pi = "3.141592653589793"
    return [
        "# the fins' roll moment as RocketPy 1.13 has it (calisto.vms: Barrowman's K_f, K_d),",
        "# r_t the body radius under the fins",
        "let tau = (fin_span + r_fins)/r_fins",
        "let lam = fin_tip/fin_root",
        "let ka = asin((tau^2 - 1)/(tau^2 + 1))",
        f"let k_f = (({pi}^2/4)*(tau + 1)^2/tau^2 + {pi}*(tau^2 + 1)^2/(tau^2*(tau - 1)^2)*ka"
        f" - 2*{pi}*(tau + 1)/(tau*(tau - 1)) + (tau^2 + 1)^2/(tau^2*(tau - 1)^2)*ka^2"
        f" - 4*(tau + 1)/(tau*(tau - 1))*ka + 8/(tau - 1)^2*ln((tau^2 + 1)/(2*tau)))/{pi}^2",
        "let k_d = 1 + ((tau - lam)/tau - (1 - lam)/(tau - 1)*ln(tau))/((tau + 1)*(tau - lam)/2"
        " - (1 - lam)*(tau^3 - 1)/(3*(tau - 1)))",
        f"let roll_forcing = aero*qbar*fins_area_ref*k_f*{n}*(fins_y_mac + r_fins)*"
        "fins_cn_alpha_1*fin_cant",
        f"let roll_damping = rho_aero*airspeed/2*k_d*{n}*fins_cn_alpha_1*cos(fin_cant)*"
        "fins_roll_sum*axes_r",
        "units tau: 1, lam: 1, ka: 1, k_f: 1, k_d: 1, roll_forcing: N*m, roll_damping: N*m",
        "torque rocket: body [0, 0, roll_forcing - roll_damping - fins_roll]",
    ]


def drag_and_margin_lines(spec):
    decl, cd = drag_lines(spec)
    tail = ", cn3 = tail_cn_alpha, z3 = tail_z_cp" if "tail" in spec else ""
    return decl + [
        "# drag: axial, through the axis (RocketPy's R3); s_D scales it (1 as published, a",
        "# free unknown of `varmass fit`)",
        cd,
        "parameter s_D = 1",
        "let drag = s_D*aero*qbar*fins_area_ref*cd",
        "units cd: 1, s_D: 1, drag: N",
        "force rocket: body [0, 0, -drag]",
        "# the static margin at the flight's Mach number, and at Mach 0 (RocketPy's)",
        'use "../../models/lib/barrowman_margin.vms" as margin: z_cg = z_c, d_ref = d_ref, '
        "cn1 = nose_cn_alpha, z1 = nose_z_cp, cn2 = fins_cn_alpha, z2 = fins_z_cp" + tail,
        f"let fins_cn0 = fins_interference*{spec['fins']['n']}/2*6.283185307179586*fin_span^2/"
        "fins_area_ref/"
        "(1 + sqrt(1 + (6.283185307179586*fin_span*fins_mid_chord/(fins_area_fin*"
        "fin_cl_alpha))^2))",
        "units fins_cn0: 1",
        'use "../../models/lib/barrowman_margin.vms" as margin0: z_cg = z_c, d_ref = d_ref, '
        "cn1 = nose_cn_alpha, z1 = nose_z_cp, cn2 = fins_cn0, z2 = fins_z_cp" + tail,
        "let static_margin = margin_static_margin",
        "let static_margin_0 = margin0_static_margin",
        "units static_margin: 1, static_margin_0: 1",
    ]


def parachute_lines(spec):
    drogue, main = chutes(spec)
    lines = []
    for label, c in (("drogue", drogue), ("main", main)):
        if c is None:
            continue
        lines += [
            f"# the {label} ({c['name']}): closed until its phase sets {label}_t_open",
            f"parameter cds_{label} = {num(c['cd_s'])}",
            f"units cds_{label}: m^2",
            f'use "../../models/lib/parachute.vms" as {label}: on = rocket, vx = air_vx, '
            f"vy = air_vy, vz = air_vz, rho = air_rho, CdS = cds_{label}",
        ]
    return lines


def model(name, spec):
    parts = [
        [header(name, spec).rstrip("\n")],
        ["coordinates x, y, z, e0, e1, e2, e3",
         "units x: m, y: m, z: m, e0: 1, e1: 1, e2: 1, e3: 1"],
        mass_lines(spec),
        site_lines(name, spec),
        gravity_lines(spec),
        coriolis_lines(spec),
        air_lines(spec),
        local_wind_lines(spec),
        airframe_lines(spec),
        roll_lines(spec),
        drag_and_margin_lines(spec),
        parachute_lines(spec),
    ]
    return "\n".join(line for part in parts for line in part) + "\n"


def phases(spec):
    """The [[phase]] tables: apogee, then a main's height on the way down."""
    drogue, main = chutes(spec)
    apogee = {}
    if drogue is not None:
        apogee = {"drogue_t_open": f"t + {num(drogue['lag'])}",
                  "aero_off": f"t + {num(drogue['lag'])}"}
    out = ["[[phase]]", "when = \"z' < 0\"                 # apogee"]
    if apogee:
        out.append("set = { " + ", ".join(f'{k} = "{v}"' for k, v in apogee.items()) + " }")
    if main is not None:
        lag = num(main["lag"])
        sets = {"main_t_open": f"t + {lag}"}
        if drogue is not None:
            sets["drogue_t_cut"] = f"t + {lag}"
        else:
            sets["aero_off"] = f"t + {lag}"
        out += ["", "[[phase]]",
                f'when = "z < {num(main["trigger"])}"            # the main, on the way down',
                "set = { " + ", ".join(f'{k} = "{v}"' for k, v in sets.items()) + " }"]
    return out


def scene(name, spec):
    drogue_main = chutes(spec)
    names = [c["name"] for c in drogue_main if c is not None] or ["none"]
    head = [
        f"# {spec['source']['name']}: {name}.vms from the rail to apogee, then its parachutes",
        f"# ({', '.join(names)}) to landing. WRITTEN BY tools/flights/make_scenes.py from",
    ]
    end = [
        "# phase stops where z falls through 0: the landing (above the pad's level).",
        "# cli/tests/flights.rs flies the first phase only, to apogee.",
        f'model = "{name}.vms"',
        "until = 2000.0",
        'stop_when = "z < 0"',
    ]
    return "\n".join(scene_lines(spec, head, end) + phases(spec)) + "\n"


def ascent_scene(name, spec, log):
    """The flight's scene from the rail to the log's apogee, without its parachutes: what
    `varmass fit` fits to the log's ascent (docs/sensitivities.md#a-real-flight)."""
    until, _ = apogee_time(log)
    head = [
        f"# {spec['source']['name']}'s ascent: {name}.vms from the rail to the log's apogee (its",
        "# five-sample running median's top), without parachutes. WRITTEN BY",
        "# tools/flights/make_scenes.py from",
    ]
    end = [
        "# phase ends at the log's apogee time; `varmass fit` runs it past that when a fitted",
        "# offset of the log's clock asks (docs/sensitivities.md#a-real-flight).",
        f'model = "{name}.vms"',
        f"until = {num(until)}",
    ]
    return "\n".join(scene_lines(spec, head, end)[:-1]) + "\n"


def scene_lines(spec, head, end):
    """A scene's lines from its header's first lines `head` and the lines `end` that end
    the header and name the model, to its `[flight]` table (then an empty line)."""
    q = attitude(spec["rail"])
    rail = spec["rail"]
    lines = head + [
        "# flight.toml. The body starts at rest on the rail with RocketPy's attitude (3-1-3 Euler",
        f"# angles psi = -heading = {num(-rail['heading'])} deg, theta = inclination - 90 = "
        f"{num(rail['inclination'] - 90)} deg,",
        f"# phi = button_angle = {num(rail['button_angle'])} deg); the rail's exit_travel is "
        "flight.toml's. The last",
    ] + end + [
        'method = "dop853"',
        "tol = 1e-10",
        'record = ["altitude", "speed", "airspeed", "mach", "qbar", "alpha", "static_margin", '
        '"static_margin_0", "m_p", "x", "y", "z", "z\'", "cd", "thrust"]',
        "",
        "[set]",
        f"air_M0 = {R_AIR_ROCKETPY_M0}   # RocketPy's air constant R = 287.05287 J/(kg K)",
        "",
        "[rail]",
        'position = ["x", "y", "z"]',
        f"inclination = {num(rail['inclination'])}",
        f"heading = {num(rail['heading'])}",
        f"exit_travel = {num(rail['exit_travel'])}",
        "",
        "[init]",
        "x = 0.0", "y = 0.0", "z = 0.0",
        *(f"e{i} = {num(v)}" for i, v in enumerate(q)),
        f"m_s = {num(spec['motor']['propellant_mass'] + 1)}",
        "",
        "[flight]",
        "log = { file = \"flight_log.csv\", time = \"time\", altitude = \"altitude\" }",
        "",
    ]
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "flights"))
    args = ap.parse_args()
    for name in FLIGHTS:
        spec = tomllib.loads((ROOT / "flights" / name / "flight.toml").read_text())
        check_against_rocketpy(name, centres_of_pressure(spec))
        folder = Path(args.out) / name
        folder.mkdir(parents=True, exist_ok=True)
        (folder / f"{name}.vms").write_text(model(name, spec))
        (folder / f"{name}.toml").write_text(scene(name, spec))
        log = ROOT / "flights" / name / "flight_log.csv"
        (folder / f"{name}_ascent.toml").write_text(ascent_scene(name, spec, log))
    print(f"wrote {len(FLIGHTS)} scenes and their ascents into {args.out}")


if __name__ == "__main__":
    main()
