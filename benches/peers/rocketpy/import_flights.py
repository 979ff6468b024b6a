#!/usr/bin/env python3
"""Writes flights/<name>/flight.toml and the flight's data files from RocketPy's examples (issue 36).

Run once, from the repository root, with a RocketPy checkout at d41dd11 (any Python 3.11+,
nothing to install):

    python3 benches/peers/rocketpy/import_flights.py --rocketpy-repo PATH/TO/RocketPy

The inputs below are copied by hand from each flight's notebook,
docs/examples/<name>_flight_sim.ipynb of RocketPy-Team/RocketPy at d41dd11, in RocketPy's
own conventions (its rocket coordinate system, its motor coordinate system, its origins).
This script translates them into ours (docs/flights.md#conventions) and writes them out; the
RocketPy values are kept in the toml's comments. Nothing else reads the notebooks:
benches/peers/rocketpy/flights.py flies flight.toml, so that RocketPy and varmass read one
source, and its apogees agree with the notebooks' own runs (docs/flights.md), which checks
this translation.

Translation (conventions.md: body z from tail to nose, positions relative to a reference
point): the reference point is the rocket's centre of dry mass (the rocket without motor
plus the motor's dry mass), the point whose motion RocketPy integrates. A RocketPy rocket
coordinate p (measured along its axis, from the notebook's origin, toward the nose if
`tail_to_nose`, toward the tail if `nose_to_tail`) becomes z = s (p - p_cdm), s = +1 or -1.
A motor coordinate q (from the motor's origin, toward the combustion chamber if
`nozzle_to_combustion_chamber`, toward the nozzle if `combustion_chamber_to_nozzle`) is at
p = P + s s_m q in rocket coordinates, P the motor's `position` (RocketPy's add_motor).
"""

import argparse
import math
import subprocess
from pathlib import Path


COMMIT = "d41dd11"
PI = math.pi

# One dict per flight: RocketPy's inputs as the notebook gives them.
# env: local date/hour and its time zone (RocketPy's set_date: the date is local time).
FLIGHTS = {
    "andromeda": dict(
        title="Andromeda (2022)",
        notebook="andromeda_flight_sim.ipynb",
        published=(3614.95, 3415),
        notebook_output=3614.946,
        env=dict(lat=39.388692, lon=-8.287814, elevation=160, date=(2022, 10, 14, 14),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1, gravity=9.80665,
                 weather="data/weather/euroc_2022_all_windows.nc", max_height=4000),
        motor=dict(thrust="data/rockets/andromeda/thrust_curve.csv", burn_time=3.76,
                   grain_number=1, grain_density=1468.9079097925262,
                   grain_inner_radius=0.01875, grain_outer_radius=0.0375,
                   grain_height=0.893, grain_separation=0,
                   grains_cm=0.5613903872259161, nozzle_radius=0.028125, nozzle=0,
                   throat_radius=0.01875, dry_mass=0, dry_cm=0.5, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=0),
        rocket=dict(radius=0.07535, mass=20.9767, inertia=(11.249, 0.12377), cm=1.3998,
                    csys="tail_to_nose",
                    drag=("data/rockets/andromeda/drag_coefficient.csv",
                          "data/rockets/andromeda/drag_coefficient.csv")),
        buttons=(1.5998, 0.8998, 45),
        nose=dict(length=0.3, kind="vonKarman", position=2.4996),
        fins=dict(n=3, span=0.185, root=0.23, tip=0.11, position=0.3546),
        tail=None,
        chutes=[dict(name="Drogue", cd_s=0.84665922014, trigger="apogee", rate=100, lag=0,
                     noise=(0, 0, 0)),
                dict(name="Main", cd_s=8.362919643856031, trigger=500, rate=100, lag=0,
                     noise=(0, 0, 0))],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/andromeda/flight_data.csv", time="t(s)", alt="alt(m)",
                 scale=1.0, every=1),
    ),
    "astra": dict(
        title="Astra (2022)",
        notebook="astra_flight_sim.ipynb",
        published=(3043.07, 3250),
        notebook_output=3043.066,
        env=dict(lat=39.3897, lon=-8.2889639, elevation=160, date=(2022, 10, 13, 16),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1, gravity=9.80665,
                 weather="data/weather/euroc_2022_all_windows.nc", max_height=4000),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_4263L1350-P.eng", burn_time=3.284,
                   grain_number=1, grain_density=1256.7753406541794,
                   grain_inner_radius=0.01875, grain_outer_radius=0.0375,
                   grain_height=0.486, grain_separation=0, grains_cm=0.243,
                   nozzle_radius=0.028125, nozzle=0, throat_radius=0.01875, dry_mass=0,
                   dry_cm=0, dry_inertia=(0, 0, 0), csys="nozzle_to_combustion_chamber",
                   position=0.7146163949),
        rocket=dict(radius=0.047, mass=10.6462, inertia=(6.6986, 0.040824), cm=1.3957,
                    csys="tail_to_nose",
                    drag=("data/rockets/astra/drag_coefficient.csv",
                          "data/rockets/astra/drag_coefficient.csv")),
        buttons=(1.5957, 1.1957, 45),
        nose=dict(length=0.27, kind="vonKarman", position=2.5214),
        fins=dict(n=4, span=0.117, root=0.2, tip=0.118, position=0.9134),
        tail=None,
        chutes=[],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/astra/flight_data.csv", time="t", alt="alt", scale=1.0,
                 every=1),
    ),
    "erebus": dict(
        title="Erebus (2022)",
        notebook="erebus_flight_sim.ipynb",
        published=(2750.90, 3020),
        notebook_output=2750.904,
        env=dict(lat=39.3897, lon=-8.2889639, elevation=160, date=(2022, 10, 15, 16),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1, gravity=9.80665,
                 weather="data/weather/euroc_2022_all_windows.nc", max_height=4000),
        motor=dict(thrust="data/rockets/erebus11/thrust_source.csv", burn_time=3.657,
                   grain_number=1, grain_density=1196.6353410211093,
                   grain_inner_radius=0.0135, grain_outer_radius=0.027, grain_height=0.572,
                   grain_separation=0, grains_cm=0.3, nozzle_radius=0.02025, nozzle=0,
                   throat_radius=0.0135, dry_mass=0, dry_cm=0, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=0.211668),
        rocket=dict(radius=0.04575, mass=5.82, inertia=(2.571, 0.0056233), cm=1.192,
                    csys="tail_to_nose",
                    drag=("data/rockets/erebus11/drag_curve.csv",
                          "data/rockets/erebus11/drag_curve.csv")),
        buttons=(1.392, 0.692, 45),
        nose=dict(length=0.391113, kind="vonKarman", position=2.3841),
        fins=dict(n=4, span=0.08, root=0.12, tip=0.05, position=0.395787),
        tail=dict(top=0.04575, bottom=0.03575, length=0.079119, position=0.290787),
        chutes=[],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/erebus11/flight_data_filtered.csv", time="t", alt="alt",
                 scale=1.0, every=1),
    ),
    "cavour": dict(
        title="Cavour (2023)",
        notebook="cavour_flight_sim.ipynb",
        published=(2818.90, 2789),
        notebook_output=2817.405,
        env=dict(lat=39.388692, lon=-8.287814, elevation=150, date=(2023, 10, 13, 13),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1, gravity=9.80665,
                 weather="data/weather/euroc_2023_all_windows.nc", max_height=4000),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_3618L995-P.eng", burn_time=3.8,
                   grain_number=3, grain_density=1653.53, grain_inner_radius=0.011375,
                   grain_outer_radius=0.0325, grain_height=0.13244, grain_separation=0.001,
                   grains_cm=0.19966000000000006, nozzle_radius=0.0335, nozzle=0,
                   throat_radius=0.0114, dry_mass=0, dry_cm=1.1994, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=0),
        rocket=dict(radius=0.052, mass=8.219, inertia=(4.449, 0.014634), cm=1.1994,
                    csys="tail_to_nose",
                    drag=("data/rockets/polito/drag_coefficient_power_off.csv",
                          "data/rockets/polito/drag_coefficient_power_on.csv")),
        buttons=(1.0954, 0.005400000000000071, 45),
        nose=dict(length=0.52, kind="vonKarman", position=2.7224),
        fins=dict(n=4, span=0.1, root=0.2, tip=0.07, position=0.2104),
        tail=None,
        chutes=[],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/polito/altimeter_cavour.csv", time="ts",
                 alt="altitude[m]", scale=1.0, every=1),
    ),
    "genesis": dict(
        title="Genesis (2023)",
        notebook="genesis_flight_sim.ipynb",
        published=(3076.45, 2916),
        notebook_output=3044.091,
        env=dict(lat=39.38895, lon=-8.28837, elevation=160, date=(2023, 10, 12, 14),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1, gravity=9.80665,
                 weather="data/weather/euroc_2023_all_windows.nc", max_height=4000),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_3618L995-P.eng", burn_time=3.8,
                   grain_number=3, grain_density=1815, grain_inner_radius=0.015,
                   grain_outer_radius=0.033, grain_height=0.12, grain_separation=0.005,
                   grains_cm=0.243, nozzle_radius=0.042354, nozzle=0, throat_radius=0.00925,
                   dry_mass=0, dry_cm=0.895, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=0.0),
        rocket=dict(radius=0.047, mass=9.214, inertia=(7.5046, 0.042241), cm=0.895,
                    csys="tail_to_nose",
                    drag=("data/rockets/genesis/drag_coefficient_power_off.csv",
                          "data/rockets/genesis/drag_coefficient_power_on.csv")),
        buttons=(0.98, 0.095, 45),
        nose=dict(length=0.27, kind="vonKarman", position=2.372),
        fins=dict(n=4, span=0.105, root=0.2, tip=0.11, position=0.25),
        tail=None,
        chutes=[dict(name="Drogue", cd_s=0.285005285533666, trigger="apogee", rate=105,
                     lag=1, noise=(0, 8.3, 0.5)),
                dict(name="Main", cd_s=1.1, trigger=870, rate=105, lag=1,
                     noise=(0, 8.3, 0.5))],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/genesis/flight_data_faraday.csv", time="ts",
                 alt="filtered_altitude_AGL", scale=1.0, every=20),
    ),
    "lince": dict(
        title="Lince (2023)",
        notebook="lince_flight_sim.ipynb",
        published=(3284.12, 3587),
        notebook_output=3284.107,
        env=dict(lat=39.3897, lon=-8.288964, elevation=158, date=(2023, 10, 12, 11),
                 timezone="Europe/Lisbon", tz_note="Portugal", utc_offset=1,
                 gravity="somigliana", weather="data/weather/euroc_2023_all_windows.nc",
                 max_height=4000),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_M1101.eng", burn_time=4.736,
                   grain_number=4, grain_density=1363, grain_inner_radius=0.01,
                   grain_outer_radius=0.035, grain_height=0.16, grain_separation=0.00,
                   grains_cm=0.315533, nozzle_radius=0.0335, nozzle=0, throat_radius=0.0114,
                   dry_mass=0, dry_cm=1.061, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=0),
        rocket=dict(radius=0.052, mass=10.6851352, inertia=(4.9939475, 0.0213204),
                    cm=1.061, csys="tail_to_nose",
                    drag=("data/rockets/lince/drag_coefficient_power_off.csv",
                          "data/rockets/lince/drag_coefficient_power_on.csv")),
        buttons=(1.54049, 0.13549, 45),
        nose=dict(length=0.28, kind="vonKarman", position=2.109417),
        fins=dict(n=4, span=0.0825, root=0.17, tip=0.0425, position=0.17),
        tail=dict(top=0.052, bottom=0.04852, length=0.022, position=0),
        chutes=[dict(name="Main", cd_s=3.9, trigger="apogee", rate=150, lag=0,
                     noise=(0, 0, 0))],
        rail=dict(length=12, inclination=84, heading=133),
        log=dict(path="data/rockets/lince/main_data.csv", time="ts",
                 alt="filtered_altitude_AGL", scale=1.0, every=20),
        note="The notebook flies LincePreDeploy to apogee and on (max_time 399.35159 s), "
        "then splits it into two bodies after apogee (LincePostDeploy, Payload); the "
        "apogee is the first flight's, which is what this file holds.",
    ),
    "bella_lui": dict(
        title="Bella Lui (2020)",
        notebook="bella_lui_flight_sim.ipynb",
        published=(460.50, 458.97),
        notebook_output=460.540,
        env=dict(lat=47.213476, lon=9.003336, elevation=407, date=(2020, 2, 22, 13),
                 timezone="UTC", tz_note="UTC", utc_offset=0, gravity=9.81,
                 weather="data/weather/bella_lui_weather_data_ERA5.nc", max_height=1000),
        motor=dict(thrust="data/motors/aerotech/AeroTech_K828FJ.eng", burn_time=2.43,
                   grain_number=3, grain_density=782.4, grain_inner_radius=33.147 / 1000,
                   grain_outer_radius=85.598 / 2000, grain_height=152.4 / 1000,
                   grain_separation=3 / 1000, grains_cm=0.3, nozzle_radius=44.45 / 1000,
                   nozzle=0, throat_radius=21.4376 / 1000, dry_mass=0.001, dry_cm=0.3,
                   dry_inertia=(0, 0, 0), csys="nozzle_to_combustion_chamber",
                   position=-1.1356),
        rocket=dict(radius=156 / 2000, mass=18.227 - 0.001, inertia=(0.78267, 0.064244),
                    cm=0, csys="tail_to_nose",
                    drag=([(0.01, 0.51), (0.02, 0.46), (0.04, 0.43), (0.28, 0.43),
                           (0.29, 0.44), (0.45, 0.44), (0.49, 0.46)],) * 2),
        buttons=(0.1, -0.5, 45),
        nose=dict(length=0.242, kind="tangent", position=1.3 + 0.242),
        fins=dict(n=3, span=0.200, root=0.280, tip=0.125, position=-0.75),
        tail=dict(top=156 / 2000, bottom=135 / 2000, length=0.050, position=-1.0856),
        chutes=[dict(name="Drogue", cd_s=PI / 4, trigger="apogee", rate=105, lag=1,
                     noise=(0, 8.3, 0.5))],
        rail=dict(length=4.2, inclination=89, heading=45),
        log=dict(path="data/rockets/EPFL_Bella_Lui/bella_lui_flight_data_filtered.csv",
                 time="time aprox (s)", alt="z (m)", scale=1.0, every=1),
        note="The notebook's drag is the table power_off_drag below (RocketPy Function, "
        "linear, held outside), multiplied by 1; its flight-data comparison uses the "
        "log's first 573 rows.",
    ),
    "ndrt_2020": dict(
        title="NDRT (2020)",
        notebook="ndrt_2020_flight_sim.ipynb",
        published=(1296.77, 1316.75),
        notebook_output=1293.430,
        env=dict(lat=41.775447, lon=-86.572467, elevation=206, date=(2020, 2, 23, 16),
                 timezone="UTC", tz_note="UTC", utc_offset=0, gravity=9.81,
                 weather="data/weather/ndrt_2020_weather_data_ERA5.nc", max_height=None),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_4895L1395-P.eng", burn_time=3.433,
                   grain_number=5, grain_density=1519.708, grain_inner_radius=0.015,
                   grain_outer_radius=0.033, grain_height=0.12, grain_separation=0.003,
                   grains_cm=-0.35, nozzle_radius=0.02475, nozzle=0, throat_radius=0.01075,
                   dry_mass=1.848, dry_cm=-0.35, dry_inertia=(0, 0, 0),
                   csys="combustion_chamber_to_nozzle", position=3.391),
        rocket=dict(radius=0.1015, mass=18.998, inertia=(73.316, 0.15982), cm=1.3,
                    csys="nose_to_tail", drag=(0.44, 0.44)),
        buttons=(1.5, 2, 45),
        nose=dict(length=0.610, kind="tangent", position=0),
        fins=dict(n=4, span=0.165, root=0.152, tip=0.0762, position=3.050, sweep_angle=13,
                  radius=0.0775),
        tail=dict(top=0.1015, bottom=0.0775, length=0.127, position=1.2),
        chutes=[dict(name="Drogue", cd_s=1.5 * PI * (24 * 25.4 / 1000) ** 2 / 4,
                     trigger="apogee", rate=105, lag=1, noise=(0, 8.3, 0.5)),
                dict(name="Main", cd_s=2.2 * PI * (120 * 25.4 / 1000) ** 2 / 4,
                     trigger=167.64, rate=105, lag=1, noise=(0, 8.3, 0.5))],
        rail=dict(length=3.353, inclination=90, heading=181),
        log=dict(path="data/rockets/NDRT_2020/ndrt_2020_flight_data.csv", time=" Time (s)",
                 alt=" Altitude (Ft-AGL)", scale=1 / 3.281, every=1),
        note="The 'tail' is a transition in mid-body (RocketPy add_tail) from the 0.1015 m "
        "body to 0.0775 m; the fins sit on the 0.0775 m section (their `body_radius`).",
    ),
    "valetudo": dict(
        title="Valetudo (2019)",
        notebook="valetudo_flight_sim.ipynb",
        published=(825.39, 860),
        notebook_output=815.260,
        env=dict(lat=-23.363611, lon=-48.011389, elevation=668, date=(2019, 8, 10, 21),
                 timezone="UTC", tz_note="UTC", utc_offset=0, gravity="somigliana",
                 weather=None, max_height=None),
        motor=dict(thrust="data/motors/projeto-jupiter/keron_thrust_curve.csv",
                   burn_time=5.274, grain_number=6, grain_density=1707,
                   grain_inner_radius=9.65 / 1000, grain_outer_radius=21.4 / 1000,
                   grain_height=120 / 1000, grain_separation=6 / 1000, grains_cm=0.42,
                   nozzle_radius=21.642 / 1000, nozzle=0, throat_radius=8 / 1000,
                   dry_mass=0.001, dry_cm=0.42, dry_inertia=(0, 0, 0),
                   csys="nozzle_to_combustion_chamber", position=-1.024),
        rocket=dict(radius=40.45 / 1000, mass=8.257, inertia=(3.675, 0.007), cm=0,
                    csys="tail_to_nose",
                    drag=("data/rockets/valetudo/Cd_PowerOff_RASAero.csv",
                          "data/rockets/valetudo/Cd_PowerOn_RASAero.csv")),
        buttons=(0.224, -0.93, 30),
        nose=dict(length=0.274, kind="tangent", position=1.134),
        fins=dict(n=3, span=0.077, root=0.058, tip=0.018, position=-0.906),
        tail=None,
        chutes=[dict(name="Drogue", cd_s=0.349 * 1.3, trigger="apogee", rate=105, lag=1,
                     noise=(0, 8.3, 0.5))],
        rail=dict(length=5.7, inclination=84.7, heading=53),
        log=None,
        note="No weather file: the notebook leaves RocketPy's default atmosphere (the "
        "International Standard Atmosphere, no wind). The flight log was lost; the "
        "measured apogee (860 m AGL) and drift are all that is known.",
    ),
    "calisto": dict(
        title="Calisto (getting started)",
        notebook="docs/user/first_simulation.rst",
        published=None,
        notebook_output=None,
        env=dict(lat=32.990254, lon=-106.974998, elevation=1400, date=(2026, 1, 1, 12),
                 timezone="UTC", tz_note="UTC", utc_offset=0, gravity=9.80665,
                 weather=None, max_height=None, us1976_wind=(3.0, -4.0),
                 earth_rotation=False),
        motor=dict(thrust="data/motors/cesaroni/Cesaroni_M1670.eng", burn_time=3.9,
                   grain_number=5, grain_density=1815, grain_inner_radius=15 / 1000,
                   grain_outer_radius=33 / 1000, grain_height=120 / 1000,
                   grain_separation=5 / 1000, grains_cm=0.397, nozzle_radius=33 / 1000,
                   nozzle=0, throat_radius=11 / 1000, dry_mass=1.815, dry_cm=0.317,
                   dry_inertia=(0.125, 0.125, 0.002), csys="nozzle_to_combustion_chamber",
                   position=-1.255),
        rocket=dict(radius=127 / 2000, mass=14.426, inertia=(6.321, 0.034), cm=0,
                    csys="tail_to_nose",
                    drag=("data/rockets/calisto/powerOffDragCurve.csv",
                          "data/rockets/calisto/powerOnDragCurve.csv")),
        buttons=(0.0818, -0.6182, 45),
        nose=dict(length=0.55829, kind="von karman", position=1.278),
        fins=dict(n=4, span=0.110, root=0.120, tip=0.060, position=-1.04956, cant=0.5,
                  airfoil=("data/airfoils/NACA0012-radians.txt", "radians")),
        tail=dict(top=0.0635, bottom=0.0435, length=0.060, position=-1.194656),
        chutes=[dict(name="main", cd_s=10.0, trigger=800, rate=105, lag=1.5,
                     noise=(0, 8.3, 0.5), radius=1.5, height=1.5),
                dict(name="drogue", cd_s=1.0, trigger="apogee", rate=105, lag=1.5,
                     noise=(0, 8.3, 0.5), radius=1.5, height=1.5)],
        rail=dict(length=5.2, inclination=85, heading=0),
        log=None,
        note="RocketPy's getting-started rocket (docs/user/first_simulation.rst at d41dd11) "
        "with its weather (a GFS forecast for tomorrow) replaced by one we reproduce "
        "exactly: the U.S. Standard Atmosphere 1976 tabulated every 5 m (pressure and "
        "temperature, linear between) and a constant wind of 3 m/s toward East and 4 m/s "
        "toward South at every height; gravity constant. benches/peers/rocketpy/calisto.py "
        "flies it with each of RocketPy's known differences switched off in turn.",
    ),
}


def git_show(repo, path):
    return subprocess.run(
        ["git", "-C", str(repo), "show", f"HEAD:{path}"], check=True, capture_output=True
    ).stdout


def csys_sign(name):
    return {"tail_to_nose": 1, "nose_to_tail": -1, "nozzle_to_combustion_chamber": 1,
            "combustion_chamber_to_nozzle": -1}[name]


def translate(f):
    """Positions along the body in our convention: z from the centre of dry mass, + to the nose."""
    r, m = f["rocket"], f["motor"]
    s, sm = csys_sign(r["csys"]), csys_sign(m["csys"])

    def motor_point(q):
        return m["position"] + s * sm * q

    dry_total = r["mass"] + m["dry_mass"]
    cdm = (r["mass"] * r["cm"] + m["dry_mass"] * motor_point(m["dry_cm"])) / dry_total
    z = lambda p: s * (p - cdm)  # noqa: E731
    out = dict(cdm=cdm, s=s, z=z, rocket_origin=z(0.0))
    out["cg"] = z(r["cm"])
    out["nozzle"] = z(motor_point(m["nozzle"]))
    out["grains"] = z(motor_point(m["grains_cm"]))
    out["motor_dry"] = z(motor_point(m["dry_cm"]))
    out["motor_origin"] = z(m["position"])
    up, low, ang = f["buttons"]
    out["buttons"] = (z(up), z(low), ang if s == 1 else (360 - ang) % 360)
    out["nose_tip"] = z(f["nose"]["position"])
    out["fins_le"] = z(f["fins"]["position"])
    if f["tail"]:
        out["tail_top"] = z(f["tail"]["position"])
    # dry inertia about the centre of dry mass (parallel axes)
    i11 = r["inertia"][0] + r["mass"] * out["cg"] ** 2
    i11 += m["dry_inertia"][0] + m["dry_mass"] * out["motor_dry"] ** 2
    out["dry_inertia"] = (i11, r["inertia"][1] + m["dry_inertia"][2])
    g = m
    out["propellant_mass"] = (g["grain_number"] * g["grain_density"] * PI
                              * (g["grain_outer_radius"] ** 2 - g["grain_inner_radius"] ** 2)
                              * g["grain_height"])
    return out


def fmt(x):
    if isinstance(x, str):
        return f'"{x}"'
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        r = repr(round(x, 12))
        return r if ("." in r or "e" in r) else r + ".0"
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(fmt(v) for v in x) + "]"
    raise TypeError(x)


NUDGE = 1e-9  # moves a repeated argument with another value just past the first


def increasing(rows):
    """Rows sorted by their first column (stable, as RocketPy's Function keeps a sorted
    file's order), strictly increasing as varmass's tables need: a row repeating the one
    before it is dropped; a repeated argument with another value (a jump) is moved NUDGE
    past the first, which RocketPy interpolates the same way to within NUDGE times the
    jump's slope. Returns the rows, how many were dropped and how many moved."""
    rows = sorted(rows, key=lambda r: r[0])
    out, dropped, moved = [], 0, 0
    for a, b in rows:
        if out and a <= out[-1][0]:
            if a == out[-1][0] and b == out[-1][1]:
                dropped += 1
                continue
            a = out[-1][0] + NUDGE
            moved += 1
        out.append((a, b))
    return out, dropped, moved


def read_pairs(text):
    rows = []
    for line in text.splitlines():
        parts = [p for p in line.replace(";", ",").split(",") if p.strip()]
        if len(parts) < 2:
            continue
        try:
            rows.append((float(parts[0]), float(parts[1])))
        except ValueError:
            continue  # a header
    return rows


def copy_curve(repo, src, dest, header):
    """A curve (argument, value) from a RocketPy data file, written with a header line and
    strictly increasing arguments (`increasing`), the form both readers take."""
    rows, dropped, moved = increasing(read_pairs(git_show(repo, src).decode()))
    dest.write_text(header + "\n" + "".join(f"{a!r},{b!r}\n" for a, b in rows))
    note = f"{len(rows)} points, sorted"
    if dropped:
        note += f", {dropped} repeated rows dropped"
    if moved:
        note += f", {moved} repeated Mach values with another Cd moved {NUDGE:g} up"
    return note


def copy_log(repo, log, dest):
    import csv
    import io

    text = git_show(repo, log["path"]).decode()
    reader = csv.DictReader(io.StringIO(text))
    rows = [(float(r[log["time"]]), float(r[log["alt"]]) * log["scale"]) for r in reader]
    imax = max(range(len(rows)), key=lambda i: rows[i][1])
    kept = [r for i, r in enumerate(rows) if i % log["every"] == 0 or i == imax]
    # times strictly increasing as written (6 digits): a row that does not pass the last is dropped
    mono = []
    for t, a in kept:
        if not mono or float(f"{t:.6g}") > float(f"{mono[-1][0]:.6g}"):
            mono.append((t, a))
    dest.write_text("time,altitude\n" + "".join(f"{t:.6g},{a:.6g}\n" for t, a in mono))
    return len(rows), len(mono), rows[imax]


def rasp_with_header(text, f):
    """The RASP file as it is, unless its first line that is not a comment is no header (7
    fields): RocketPy takes any first line for the header, varmass's reader wants one. That
    line is replaced by a header (RocketPy reads the same curve: it ignores the header's
    numbers and starts the curve from (0, 0) either way)."""
    text = text.lstrip("\ufeff")
    lines = text.splitlines()
    for i, line in enumerate(lines):
        content = line.split(";")[0].strip()
        if not content:
            continue
        if len(content.split()) >= 7:
            return text
        m = f["motor"]
        prop = (m["grain_number"] * m["grain_density"] * PI
                * (m["grain_outer_radius"] ** 2 - m["grain_inner_radius"] ** 2) * m["grain_height"])
        name = Path(m["thrust"]).stem.split("_")[-1]
        lines[i:i + 1] = [
            f"; import_flights.py: {m['thrust']} has no header line; its first line",
            f"; ({content!r}) was read by RocketPy as the header and is replaced by one.",
            "; diameter and length unknown (0); masses: the grains' propellant, no casing.",
            f"{name} 0 0 0 {prop:.6f} {prop + m['dry_mass']:.6f} unknown",
        ]
        return "\n".join(lines) + "\n"
    return text


def thrust_points(text, ext):
    """The thrust curve as RocketPy reads it: a RASP file gets (0, 0) in front of its points
    (Motor.import_eng); a CSV is taken as it is."""
    pts = [(0.0, 0.0)] if ext == ".eng" else []
    header_seen = False
    for line in text.splitlines():
        line = line.split(";")[0].strip()
        if not line:
            continue
        if ext == ".eng" and not header_seen:
            header_seen = True
            continue
        a, b = line.replace(",", " ").split()[:2]
        pts.append((float(a), float(b)))
    return pts


def impulse(pts, t_end):
    """The integral of the linear interpolant of pts over [0, t_end] (RocketPy clips there)."""
    total = 0.0
    for (t0, f0), (t1, f1) in zip(pts, pts[1:]):
        if t0 >= t_end:
            break
        if t1 > t_end:
            f1 = f0 + (f1 - f0) * (t_end - t0) / (t1 - t0)
            t1 = t_end
        total += (t1 - t0) * (f0 + f1) / 2
    return total


def us1976(h):
    """U.S. Standard Atmosphere 1976 below 11 km geopotential (NOAA-S/T 76-1562 eqs. 18, 23, 33a)."""
    r0, g0, rs, m0 = 6356766.0, 9.80665, 8.31432, 0.0289644
    hg = r0 * h / (r0 + h)
    assert hg < 11000.0
    t = 288.15 - 0.0065 * hg
    return 101325.0 * (288.15 / t) ** (g0 * m0 / (rs * -0.0065)), t


def write_us1976(path, lo, hi, step):
    n = int(round((hi - lo) / step))
    rows = []
    for i in range(n + 1):
        h = lo + i * step
        p, t = us1976(h)
        rows.append(f"{h:.1f},{p:.10g},{t:.10g}\n")
    path.write_text("height,pressure,temperature\n" + "".join(rows))


def utc_string(date, offset):
    y, mo, d, h = date
    return f"{y:04d}-{mo:02d}-{d:02d}T{h - offset:02d}:00:00Z"


def write_toml(name, f, t, files, log_info):
    r, m, e = f["rocket"], f["motor"], f["env"]
    s = t["s"]
    o = []
    w = o.append
    w(f"# {f['title']}: RocketPy's example flight, translated to varmass's conventions.")
    w("# Written by benches/peers/rocketpy/import_flights.py; schema in docs/flights.md.")
    w("#")
    w("# Conventions (docs/flights.md#conventions): world axes x = East, y = North, z = Up at")
    w("# the launch site; body z along the rocket's axis from tail to NOSE. Every position `*_z`")
    w("# is a body-z coordinate in metres from the REFERENCE POINT, the centre of dry mass")
    w("# (rocket without motor + the motor's dry mass), positive toward the nose. RocketPy")
    w("# integrates the motion of that same point (its state x, y, z), so its altitudes are")
    w("# that point's.")
    w(f"# RocketPy's notebook uses coordinate_system_orientation=\"{r['csys']}\" (s = {s:+d}) with")
    w(f"# its origin at our z = {t['rocket_origin']:.10g}; a notebook position p is our")
    w(f"# z = {s:+d} (p - p_cdm), p_cdm = {t['cdm']:.10g} m in the notebook's coordinates.")
    if f.get("note"):
        w("#")
        for line in wrap(f["note"]):
            w("# " + line)
    w("")
    w("[source]")
    w(f"name = {fmt(f['title'])}")
    nb = f["notebook"] if "/" in f["notebook"] else "docs/examples/" + f["notebook"]
    w(f'notebook = "{nb}"  # in RocketPy-Team/RocketPy')
    w(f'rocketpy_commit = "{COMMIT}"')
    w("")
    if f["published"]:
        w("[apogee]  # metres above the launch site (AGL)")
        w(f"published_sim = {fmt(f['published'][0])}  # docs/examples/index.rst at {COMMIT}")
        w(f"measured = {fmt(f['published'][1])}  # docs/examples/index.rst at {COMMIT}")
        w(f"notebook_output = {fmt(f['notebook_output'])}  # the notebook's stored output at {COMMIT}")
    if log_info:
        n_all, n_kept, (tmax, amax) = log_info
        w('log = "flight_log.csv"  # time (s), altitude AGL (m)')
        w(f'log_source = "{f["log"]["path"]}"  # columns "{f["log"]["time"].strip()}",'
          f' "{f["log"]["alt"].strip()}"' + (" (feet, / 3.281)" if f["log"]["scale"] != 1 else ""))
        if n_kept != n_all:
            every = f["log"]["every"]
            kept = f"every {every}th row and the highest one, " if every > 1 else ""
            w(f"# log: {n_kept} of {n_all} rows ({kept}times strictly increasing)")
        w(f"log_max = {fmt(round(amax, 3))}  # highest altitude in the log, at {tmax:g} s")
    w("")
    w("[site]")
    w(f"latitude = {fmt(e['lat'])}  # degrees")
    w(f"longitude = {fmt(e['lon'])}  # degrees")
    w(f"elevation = {fmt(float(e['elevation']))}  # m above sea level: the launch altitude")
    w(f"date_utc = \"{utc_string(e['date'], e['utc_offset'])}\"")
    y, mo, d, h = e["date"]
    w(f"# RocketPy: date=({y}, {mo}, {d}, {h}) in time zone \"{e['tz_note']}\" (local time,"
      f" UTC{'+' if e['utc_offset'] >= 0 else ''}{e['utc_offset']})")
    if isinstance(e["gravity"], str):
        w('gravity = "somigliana"  # RocketPy\'s default: Somigliana\'s normal gravity at the')
        w("# latitude, reduced with height (Environment(gravity=None))")
    else:
        w(f"gravity = {fmt(float(e['gravity']))}  # m/s^2, constant")
    if e.get("earth_rotation", True):
        w("earth_rotation = true  # RocketPy adds the Coriolis acceleration -2 Omega x v")
    else:
        w("earth_rotation = false  # a flat, non-rotating Earth: RocketPy's earth_rotation_vector")
        w("# set to zero (its Coriolis acceleration -2 Omega x v off; calisto.py measures it)")
    w("")
    w("[weather]")
    if e["weather"]:
        w('kind = "era5"')
        w(f'file = "{e["weather"]}"  # in RocketPy-Team/RocketPy; RocketPy\'s "Reanalysis", dictionary "ECMWF"')
        w("# RocketPy takes the time step nearest date_utc and interpolates the pressure-level")
        w("# profiles bilinearly between the four grid points around (latitude, longitude)")
        if e["max_height"]:
            w(f"max_expected_height = {fmt(float(e['max_height']))}  # m ASL, RocketPy's env.max_expected_height")
    elif e.get("us1976_wind"):
        u, v = e["us1976_wind"]
        w('kind = "us1976"  # the U.S. Standard Atmosphere 1976 (models/lib/atmosphere_1976.vms)')
        w('table = "atmosphere.csv"  # height ASL (m), pressure (Pa), temperature (K), every 5 m')
        w("# RocketPy reads the table (custom_atmosphere, linear between rows; density p/(R T),")
        w("# R = 287.05287 J/(kg K), RocketPy's air constant (the 1976 R*/M0 is 287.05307: RocketPy's")
        w("# density 7.0e-7 above the standard's), sound speed sqrt(1.4 R T)); the closed form differs")
        w("# from the table by < 1e-7 relative")
        w(f"wind = {fmt([u, v])}  # m/s [East, North], the same at every height")
    else:
        w('kind = "standard"  # RocketPy\'s default: the ISA standard atmosphere, no wind')
    w("")
    up, low, ang = t["buttons"]
    rail = f["rail"]
    ci, hi = math.radians(rail["inclination"]), math.radians(rail["heading"])
    w("[rail]")
    w(f"length = {fmt(float(rail['length']))}  # m")
    w(f"inclination = {fmt(float(rail['inclination']))}  # degrees above the horizontal")
    w(f"heading = {fmt(float(rail['heading']))}  # degrees from North toward East")
    w("# the rail's direction in world (ENU) axes: [cos(incl) sin(head), cos(incl) cos(head), sin(incl)]")
    w(f"# = [{math.cos(ci) * math.sin(hi):.9f}, {math.cos(ci) * math.cos(hi):.9f}, {math.sin(ci):.9f}]")
    w(f"upper_button_z = {fmt(up)}  # RocketPy upper_button_position = {f['buttons'][0]!r}")
    w(f"lower_button_z = {fmt(low)}  # RocketPy lower_button_position = {f['buttons'][1]!r}")
    w(f"button_angle = {fmt(float(ang))}  # degrees about body z from body x; RocketPy angular_position = {f['buttons'][2]}")
    w("# RocketPy starts the rocket with its nozzle at the rail's lower end and its roll angle")
    w("# equal to button_angle (3-1-3 Euler angles psi = -heading, theta = inclination - 90)")
    w("# and releases it when the reference point has moved")
    exit_d = rail["length"] - abs(up - t["nozzle"])
    w(f"exit_travel = {fmt(exit_d)}  # m = length - (upper_button_z - nozzle_z): the upper button leaves the rail")
    w("")
    w("[rocket]  # without motor")
    w(f"radius = {fmt(float(r['radius']))}  # m, reference radius (area pi r^2, caliber 2 r)")
    w(f"mass = {fmt(float(r['mass']))}  # kg")
    w(f"cg_z = {fmt(t['cg'])}  # RocketPy center_of_mass_without_motor = {r['cm']!r}")
    w(f"inertia = {fmt([float(v) for v in r['inertia']])}  # kg m^2, [I_xx = I_yy, I_zz] about cg_z")
    w("# derived: the dry rocket (rocket + motor dry mass) about the reference point")
    w(f"dry_mass = {fmt(float(r['mass'] + m['dry_mass']))}  # kg")
    w(f"dry_inertia = {fmt(list(t['dry_inertia']))}  # kg m^2, [I_xx, I_zz] about z = 0")
    w("")
    w("[motor]")
    w('kind = "solid"  # RocketPy SolidMotor')
    w(f'thrust = "{files["thrust"]}"  # from {m["thrust"]}; linear between points')
    w(f"burn_time = {fmt(float(m['burn_time']))}  # s: RocketPy clips the curve to [0, burn_time] (value at the end interpolated)")
    w(f"nozzle_z = {fmt(t['nozzle'])}  # nozzle exit; RocketPy motor position = {m['position']!r}, nozzle_position = {m['nozzle']!r}")
    w(f"nozzle_radius = {fmt(float(m['nozzle_radius']))}  # m")
    w(f"throat_radius = {fmt(float(m['throat_radius']))}  # m")
    w(f"dry_mass = {fmt(float(m['dry_mass']))}  # kg")
    w(f"dry_cg_z = {fmt(t['motor_dry'])}  # RocketPy center_of_dry_mass_position = {m['dry_cm']!r}")
    w(f"dry_inertia = {fmt([float(m['dry_inertia'][0]), float(m['dry_inertia'][2])])}  # kg m^2, [I_xx, I_zz] about dry_cg_z")
    w(f"# RocketPy motor coordinate_system_orientation = \"{m['csys']}\"")
    w(f"propellant_mass = {fmt(t['propellant_mass'])}  # kg, derived: n rho pi (R^2 - r^2) h")
    w(f"total_impulse = {fmt(files['impulse'])}  # N s, derived: the linear thrust over [0, burn_time]")
    w(f"exhaust_speed = {fmt(files['impulse'] / t['propellant_mass'])}  # m/s, derived: c = total_impulse / propellant_mass")
    w("# RocketPy burns the propellant at F(t)/c")
    w("")
    w("[motor.grains]  # RocketPy's grain geometry (sets the propellant's inertia as it burns)")
    w(f"number = {m['grain_number']}")
    w(f"density = {fmt(float(m['grain_density']))}  # kg/m^3")
    w(f"outer_radius = {fmt(float(m['grain_outer_radius']))}  # m")
    w(f"inner_radius = {fmt(float(m['grain_inner_radius']))}  # m, initial")
    w(f"height = {fmt(float(m['grain_height']))}  # m, initial, each grain")
    w(f"separation = {fmt(float(m['grain_separation']))}  # m")
    w(f"cg_z = {fmt(t['grains'])}  # fixed; RocketPy grains_center_of_mass_position = {m['grains_cm']!r}")
    w("# RocketPy regresses each grain on its bore and both ends: dr/dt = -V'/A_burn,")
    w("# dh/dt = -2 dr/dt, A_burn = 2 pi (R^2 - r^2 + r h), V' = mdot/(n rho)")
    w("")
    nose = f["nose"]
    w("[nose]")
    w(f'kind = "{nose["kind"]}"  # RocketPy kind')
    w(f"length = {fmt(float(nose['length']))}  # m")
    w(f"tip_z = {fmt(t['nose_tip'])}  # RocketPy position = {nose['position']!r}")
    w(f"base_radius = {fmt(float(r['radius']))}  # m (RocketPy default: the rocket's radius)")
    w("")
    fins = f["fins"]
    w("[fins]")
    w('kind = "trapezoidal"')
    w(f"n = {fins['n']}")
    w(f"root_chord = {fmt(float(fins['root']))}  # m")
    w(f"tip_chord = {fmt(float(fins['tip']))}  # m")
    w(f"span = {fmt(float(fins['span']))}  # m")
    w(f"root_leading_edge_z = {fmt(t['fins_le'])}  # RocketPy position = {fins['position']!r}")
    if "sweep_angle" in fins:
        sweep = fins["span"] * math.tan(math.radians(fins["sweep_angle"]))
        w(f"sweep_length = {fmt(sweep)}  # m = span tan({fins['sweep_angle']} deg), RocketPy sweep_angle = {fins['sweep_angle']}")
    else:
        w(f"sweep_length = {fmt((fins['root'] - fins['tip']) / 1.0)}  # m, RocketPy's default: root - tip (trailing edge square)")
    w(f"cant = {fmt(float(fins.get('cant', 0.0)))}  # degrees (RocketPy cant_angle)")
    w(f"body_radius = {fmt(float(fins.get('radius', r['radius'])))}  # m, the body under the fins")
    if fins.get("airfoil"):
        w(f'airfoil = "{files["airfoil"]}"  # lift coefficient against angle of attack ({fins["airfoil"][1]}), from {fins["airfoil"][0]}')
        w(f'airfoil_unit = "{fins["airfoil"][1]}"')
        w(f"airfoil_cl_alpha = {fmt(files['cl_alpha'])}  # 1/rad: RocketPy uses only the slope at 0 (its derivative at 1e-3,")
        w("# step 1e-3, of the linear table), in place of the flat plate's 2 pi, then Prandtl-Glauert")
        w("# and Diederich's planform correlation as for the flat plate")
    else:
        w('airfoil = "none"  # flat plate (Barrowman): 2 pi per radian')
    w("")
    if f["tail"]:
        tl = f["tail"]
        w("[tail]  # a conical transition (RocketPy add_tail)")
        w(f"top_radius = {fmt(float(tl['top']))}  # m")
        w(f"bottom_radius = {fmt(float(tl['bottom']))}  # m")
        w(f"length = {fmt(float(tl['length']))}  # m")
        w(f"top_z = {fmt(t['tail_top'])}  # its forward end; RocketPy position = {tl['position']!r}")
        w("")
    w("[drag]  # Cd(Mach) on the reference area; linear, held outside (RocketPy Function)")
    for key, val in zip(("power_off", "power_on"), files["drag"]):
        w(f"{key} = {fmt(val)}")
    for line in files["drag_note"]:
        w("# " + line)
    w("")
    for c in f["chutes"]:
        w("[[parachutes]]")
        w(f'name = "{c["name"]}"')
        w(f"cd_s = {fmt(float(c['cd_s']))}  # m^2")
        if c["trigger"] == "apogee":
            w('trigger = "apogee"  # RocketPy: vertical speed < 0')
        else:
            w(f"trigger = {fmt(float(c['trigger']))}  # m AGL on the way down (RocketPy: vz < 0 and the height its noisy pressure signal gives < this)")
        w(f"lag = {fmt(float(c['lag']))}  # s from trigger to full opening (RocketPy: drag area switched at once)")
        w(f"sampling_rate = {fmt(float(c['rate']))}  # Hz, the trigger is checked at these instants")
        w(f"noise = {fmt([float(v) for v in c['noise']])}  # Pa: RocketPy's pressure noise (mean, sd, time correlation)")
        if "radius" in c:
            w(f"radius = {fmt(float(c['radius']))}  # m, canopy (RocketPy: for the added mass only)")
            w(f"height = {fmt(float(c['height']))}  # m, canopy (RocketPy: for the added mass only)")
        w("# RocketPy 1.13 adds the canopy's added mass 1.068 (1 - 1.465 p - 0.25975 p^2 + 1.2626 p^3)")
        w("# rho (2/3) pi R^2 h with porosity p = 0.0432, R = h = sqrt(cd_s / (1.4 pi)) unless given; under a")
        w("# parachute it flies the reference point as a particle (3 degrees of freedom)")
        w("")
    w("[run]  # how RocketPy's Flight is called")
    w('solver = "LSODA"  # RocketPy default; rtol 1e-6, its default atol')
    if name == "lince":
        w("max_time = 399.35159  # s")
    return "\n".join(o).rstrip() + "\n"


def wrap(text, width=88):
    words, lines, cur = text.split(), [], ""
    for word in words:
        if len(cur) + len(word) + 1 > width - 2:
            lines.append(cur)
            cur = word
        else:
            cur = f"{cur} {word}" if cur else word
    return lines + [cur]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rocketpy-repo", required=True, help="a RocketPy checkout at d41dd11")
    ap.add_argument("--out", default="flights")
    args = ap.parse_args()
    repo, out = Path(args.rocketpy_repo), Path(args.out)
    for name, f in FLIGHTS.items():
        d = out / name
        d.mkdir(parents=True, exist_ok=True)
        t = translate(f)
        files = {}
        src = f["motor"]["thrust"]
        ext = Path(src).suffix
        if ext == ".eng":
            (d / "thrust.eng").write_text(rasp_with_header(git_show(repo, src).decode(), f))
        else:
            copy_curve(repo, src, d / "thrust.csv", "time,thrust")
        files["thrust"] = f"thrust{ext}"
        pts = thrust_points(git_show(repo, src).decode(), ext)
        files["impulse"] = impulse(pts, f["motor"]["burn_time"])
        drag, notes = [], []
        off, on = f["rocket"]["drag"]
        for key, val in (("power_off", off), ("power_on", on)):
            if isinstance(val, (int, float)):
                drag.append(float(val))
            elif isinstance(val, list):
                fn = "drag.csv"
                (d / fn).write_text("mach,cd\n" + "".join(f"{a!r},{b!r}\n" for a, b in val))
                drag.append(fn)
                if key == "power_off":
                    notes.append("drag.csv: the notebook's inline table (a RocketPy Function)")
            else:
                fn = "drag.csv" if off == on else f"drag_{key}.csv"
                note = copy_curve(repo, val, d / fn, "mach,cd")
                drag.append(fn)
                if key == "power_off" or off != on:
                    notes.append(f"{fn}: from {val} ({note})")
        files["drag"], files["drag_note"] = drag, notes
        fins = f["fins"]
        if fins.get("airfoil"):
            src = fins["airfoil"][0]
            copy_curve(repo, src, d / "airfoil.csv", "alpha,cl")
            pts = read_pairs((d / "airfoil.csv").read_text())
            cl = lambda a: next(y0 + (y1 - y0) * (a - x0) / (x1 - x0)  # noqa: E731
                                for (x0, y0), (x1, y1) in zip(pts, pts[1:]) if x0 <= a <= x1)
            slope = (cl(2e-3) - cl(0.0)) / 2e-3
            files["airfoil"], files["cl_alpha"] = "airfoil.csv", slope
        if f["env"].get("us1976_wind"):
            write_us1976(d / "atmosphere.csv", 1000.0, 6000.0, 5.0)
        log_info = copy_log(repo, f["log"], d / "flight_log.csv") if f["log"] else None
        (d / "flight.toml").write_text(write_toml(name, f, t, files, log_info))
        print(name, f"cdm {t['cdm']:.6f}", f"propellant {t['propellant_mass']:.6f} kg")


if __name__ == "__main__":
    main()
