#!/usr/bin/env python3
"""The weather of RocketPy's public flights: convert each flight's ERA5 file (docs/weather.md).

    python3 tools/weather/flights.py --weather-dir ROCKETPY/data/weather [--only bella_lui]

writes models/weather/<flight>/{temperature,pressure,wind_east,wind_north}.csv with
era5_to_csv.py. ROCKETPY is a checkout of RocketPy-Team/RocketPy (the files below were read
at commit d41dd11); the .nc files are not committed here. Each flight's site, date, time
zone, datum and file are those of its notebook, docs/examples/<notebook>_flight_sim.ipynb,
as its `Environment(...)` and `set_atmospheric_model(type="Reanalysis", file=...,
dictionary="ECMWF")` cells give them; the elevation is the notebook's too (Hedy's the
160 m its Open-Elevation look-up printed).
"""

import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import era5_to_csv  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
ROCKETPY_COMMIT = "d41dd11e"
# A site below the file's lowest level (Andromeda, Astra, Camoes, Cavour, Halcyon, Lince:
# 13 to 62 m below it) gets a first row at sea level (era5_to_csv.extend_below), held as
# RocketPy holds it.
FLOOR = 0.0

# name, ERA5 file, local date-time, time zone, latitude, longitude, elevation (m), datum,
# notebook.
FLIGHTS = [
    ("bella_lui", "bella_lui_weather_data_ERA5.nc", "2020-02-22T13", "UTC",
     47.213476, 9.003336, 407.0, "SIRGAS2000", "bella_lui"),
    ("ndrt_2020", "ndrt_2020_weather_data_ERA5.nc", "2020-02-23T16", "UTC",
     41.775447, -86.572467, 206.0, "SIRGAS2000", "ndrt_2020"),
    ("andromeda", "euroc_2022_all_windows.nc", "2022-10-14T14", "Portugal",
     39.388692, -8.287814, 160.0, "WGS84", "andromeda"),
    ("astra", "euroc_2022_all_windows.nc", "2022-10-13T16", "Portugal",
     39.3897, -8.2889639, 160.0, "WGS84", "astra"),
    ("erebus", "euroc_2022_all_windows.nc", "2022-10-15T16", "Portugal",
     39.3897, -8.2889639, 160.0, "WGS84", "erebus"),
    ("camoes", "euroc_2023_all_windows.nc", "2023-10-14T14", "Portugal",
     39.3900032043457, -8.2895383834838, 107.0, "WGS84", "camoes"),
    ("cavour", "euroc_2023_all_windows.nc", "2023-10-13T13", "Portugal",
     39.388692, -8.287814, 150.0, "WGS84", "cavour"),
    ("genesis", "euroc_2023_all_windows.nc", "2023-10-12T14", "Portugal",
     39.38895, -8.28837, 160.0, "WGS84", "genesis"),
    ("halcyon", "euroc_2023_all_windows.nc", "2023-10-13T14", "Portugal",
     39.388692, -8.287814, 130.0, "WGS84", "halcyon"),
    ("lince", "euroc_2023_all_windows.nc", "2023-10-12T11", "Portugal",
     39.3897, -8.288964, 158.0, "WGS84", "lince"),
    ("hedy", "hedy_euroc_2025_weather_data.nc", "2025-10-12T17", "Europe/Lisbon",
     39.39046096801758, -8.288534164428711, 160.0, "SIRGAS2000", "hedy"),
]


def convert(flight, weather_dir, out_root, method="rocketpy"):
    name, file, date, tz, lat, lon, elevation, datum, notebook = flight
    when = era5_to_csv.utc(date, tz)
    table, notes = era5_to_csv.read_era5(
        pathlib.Path(weather_dir) / file, when, lat, lon, datum, method
    )
    lowest = table[0, 0]
    if elevation < lowest:
        table = era5_to_csv.extend_below(table, FLOOR, method)
        kind = "held" if method == "rocketpy" else "extrapolated"
        notes.append(f"first row at {FLOOR} m {kind} below the lowest level, {lowest} m")
    header = [
        f"ERA5 pressure levels: RocketPy-Team/RocketPy data/weather/{file} at {ROCKETPY_COMMIT}",
        f"flight {name} (docs/examples/{notebook}_flight_sim.ipynb): latitude {lat}, "
        f"longitude {lon}, elevation {elevation} m, launch {date} {tz}",
        *notes,
        "written by tools/weather/flights.py (docs/weather.md); altitude above sea level",
    ]
    out = pathlib.Path(out_root) / name
    era5_to_csv.write_tables(out, table, header)
    return out, table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--weather-dir", required=True, help="RocketPy's data/weather")
    parser.add_argument("--out", default=str(ROOT / "models" / "weather"))
    parser.add_argument("--method", default="rocketpy", choices=("rocketpy", "physical"))
    parser.add_argument("--only", action="append", help="a flight's name (repeatable)")
    args = parser.parse_args(argv)
    for flight in FLIGHTS:
        if args.only and flight[0] not in args.only:
            continue
        out, table = convert(flight, args.weather_dir, args.out, args.method)
        print(f"{out}: {len(table)} rows, {table[0, 0]:.1f} to {table[-1, 0]:.1f} m")


if __name__ == "__main__":
    sys.exit(main())
