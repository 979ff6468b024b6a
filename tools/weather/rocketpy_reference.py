#!/usr/bin/env python3
"""RocketPy 1.13's own atmosphere for each public flight: the reference of cli/tests/weather.rs.

    python3 -m venv target/venv-rocketpy
    target/venv-rocketpy/bin/pip install rocketpy==1.13.0
    target/venv-rocketpy/bin/python tools/weather/rocketpy_reference.py \
        --weather-dir ROCKETPY/data/weather [--only bella_lui]

For each flight of flights.py, builds the flight's Environment as its notebook does
(`Environment(date=..., latitude=..., longitude=..., elevation=..., datum=...,
timezone=...)`, `set_atmospheric_model(type="Reanalysis", file=..., dictionary="ECMWF")`)
and writes, in models/weather/<flight>/:

* rocketpy_1.13.csv: at 21 altitudes h_k = h_0 + k dh (h_0 half a metre above the site,
  dh a multiple of 10 m, the last below the file's top and 12 km), between the levels,
  RocketPy's pressure, temperature, density, speed of sound, wind speed, wind heading
  (degrees, the direction the wind blows toward, clockwise from north) and wind x (east)
  and y (north) components;
* rocketpy_1.13_knots.csv: the knots of its pressure, temperature and wind Functions (the
  levels RocketPy interpolates linearly between), to hold the converted tables to.

CI needs neither RocketPy nor netCDF4: the stored CSVs are the reference.
"""

import argparse
import math
import pathlib
import sys
import warnings

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

from flights import FLIGHTS, ROOT  # noqa: E402


def environment(flight, weather_dir):
    from rocketpy import Environment

    name, file, date, tz, lat, lon, elevation, datum, _ = flight
    day, hour = date.split("T")
    year, month, dd = (int(p) for p in day.split("-"))
    env = Environment(
        date=(year, month, dd, int(hour)),
        latitude=lat,
        longitude=lon,
        elevation=elevation,
        datum=datum,
        timezone=tz,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the legacy files' fallback mapping, announced
        env.set_atmospheric_model(
            type="Reanalysis", file=str(pathlib.Path(weather_dir) / file), dictionary="ECMWF"
        )
    return env


def altitudes(env, elevation):
    top = min(float(env.pressure.x_array[-1]), 12000.0)
    start = elevation + 0.5
    step = math.floor((top - start) / 20 / 10) * 10.0
    return [start + k * step for k in range(21)]


def write(path, header, rows):
    text = header + "\n" + "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows)
    path.write_text(text)


def reference(flight, weather_dir, out_root):
    env = environment(flight, weather_dir)
    out = pathlib.Path(out_root) / flight[0]
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for h in altitudes(env, flight[6]):
        rows.append(
            [
                h,
                env.pressure(h),
                env.temperature(h),
                env.density(h),
                env.speed_of_sound(h),
                env.wind_speed(h),
                env.wind_heading(h),
                env.wind_velocity_x(h),
                env.wind_velocity_y(h),
            ]
        )
    comment = (
        f"# RocketPy 1.13.0's Environment for {flight[0]} (tools/weather/rocketpy_reference.py)\n"
    )
    write(
        out / "rocketpy_1.13.csv",
        comment + "altitude_m,pressure_Pa,temperature_K,density_kg_m3,speed_of_sound_m_s,"
        "wind_speed_m_s,wind_heading_deg,wind_east_m_s,wind_north_m_s",
        rows,
    )
    knots = zip(
        env.pressure.x_array,
        env.pressure.y_array,
        env.temperature.y_array,
        env.wind_velocity_x.y_array,
        env.wind_velocity_y.y_array,
    )
    write(
        out / "rocketpy_1.13_knots.csv",
        comment + "altitude_m,pressure_Pa,temperature_K,wind_east_m_s,wind_north_m_s",
        knots,
    )
    return out, len(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--weather-dir", required=True, help="RocketPy's data/weather")
    parser.add_argument("--out", default=str(ROOT / "models" / "weather"))
    parser.add_argument("--only", action="append", help="a flight's name (repeatable)")
    args = parser.parse_args(argv)
    for flight in FLIGHTS:
        if args.only and flight[0] not in args.only:
            continue
        out, n = reference(flight, args.weather_dir, args.out)
        print(f"{out}: {n} altitudes")


if __name__ == "__main__":
    sys.exit(main())
