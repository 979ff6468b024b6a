#!/usr/bin/env python3
"""Convert an ERA5 pressure-level file to the profile tables varmass reads (docs/weather.md).

    python3 tools/weather/era5_to_csv.py FILE.nc --lat 47.213476 --lon 9.003336 \
        --date 2020-02-22T13 [--timezone Europe/Zurich] --out models/weather/bella_lui

writes four CSV files of geometric altitude above sea level, in the format of docs/tables.md:

    temperature.csv   altitude_m,temperature_K   (models/lib/atmosphere_table.vms's air_T_s)
    pressure.csv      altitude_m,pressure_Pa     (its air_p_s)
    wind_east.csv     altitude_m,wind_east_m_s   (models/lib/wind_local.vms's east)
    wind_north.csv    altitude_m,wind_north_m_s  (its north)

one row per pressure level, altitudes increasing, each file opening with `#` lines that
name the source, the site, the time and the grid cell used.

Two methods (``--method``):

* ``rocketpy`` (default) does what RocketPy 1.13's ``Environment.set_atmospheric_model(
  type="Reanalysis", dictionary="ECMWF")`` does (rocketpy/environment/environment.py,
  ``process_forecast_reanalysis``, and the helpers of rocketpy/environment/tools.py and
  rocketpy/tools.py), operation for operation on the same arrays, so that its knots are
  RocketPy's to the last bit: the time of the file NEAREST the launch time (no interpolation
  in time; a tie takes the earlier); the grid cell that brackets the site by RocketPy's
  search; bilinear interpolation in latitude and longitude of the geopotential divided by
  g0 = 9.80665, the temperature and the wind u (east) and v (north) at every level, in the
  file's precision (float32 for the files of the current Copernicus service); the
  geopotential height Z turned into a geometric height by h = R Z/(R - Z), R the distance
  from the Earth's centre to the ellipsoid at the site's latitude; levels with a missing
  value dropped; the pressure in hPa times 100.
* ``physical`` reads every array as float64 and turns Z into h with the gravity of the
  site: Phi = g0 Z = int_0^h g(h') dh' with g = g_phi (R_phi/(R_phi + h))^2, g_phi the
  WGS-84 normal gravity at the ellipsoid (Somigliana) and R_phi = a/(1 + f + m - 2 f sin^2
  phi) the radius of the free-air gradient (the c of models/lib/gravity_somigliana.vms), so
  h = R_phi Z/((g_phi/g0) R_phi - Z). RocketPy's formula takes g_phi = g0 everywhere: its
  heights are (1 - g_phi/g0) too low where g_phi < g0, 0.056 % at 39.4 deg N (5.7 m at
  10 km), and too high where g_phi > g0, 0.016 % at 47.2 deg N (docs/weather.md gives the
  measured differences).

Reading: the netCDF4 package (it reads both formats the ERA5 files come in, NetCDF3 "64-bit
offset" and NetCDF4/HDF5, with a libnetcdf in its wheel), imported only to read; the
arithmetic below needs numpy alone (python/tests/test_weather_converter.py checks it on a
hand example without netCDF4).
"""

import argparse
import datetime
import math
import pathlib
import sys

import numpy as np

STANDARD_G = 9.80665  # m/s^2, RocketPy's standard_g and ERA5's Z = Phi/g0
R_AIR = 287.05287  # J/(kg K), RocketPy's air_gas_constant
WGS84_A = 6378137.0  # m
WGS84_F = 1 / 298.257223563
# WGS-84 (NIMA TR8350.2): Somigliana's constants and m = omega^2 a^2 b/GM.
SOMIGLIANA_GAMMA_E = 9.7803253359
SOMIGLIANA_K = 0.00193185265241
WGS84_E2 = 0.00669437999013
WGS84_M = 0.00344978650684
# RocketPy's ellipsoids by datum (Environment.set_earth_geometry).
DATUMS = {
    "SIRGAS2000": (6378137.0, 1 / 298.257223563),
    "SAD69": (6378160.0, 1 / 298.25),
    "NAD83": (6378137.0, 1 / 298.257024899),
    "WGS84": (6378137.0, 1 / 298.257223563),
}
# The variable names of the ERA5 files: the current service's, then the legacy ones.
NAMES = {
    "time": ("valid_time", "time"),
    "level": ("pressure_level", "level"),
    "latitude": ("latitude",),
    "longitude": ("longitude",),
    "geopotential": ("z",),
    "temperature": ("t",),
    "u": ("u",),
    "v": ("v",),
}


def earth_radius(lat_deg, semi_major_axis=WGS84_A, flattening=WGS84_F):
    """The distance from the centre to the ellipsoid at geodetic latitude lat_deg (m), as
    RocketPy's Environment.calculate_earth_radius writes it."""
    b = semi_major_axis * (1 - flattening)
    lat = lat_deg * np.pi / 180
    return np.sqrt(
        ((np.cos(lat) * (semi_major_axis**2)) ** 2 + (np.sin(lat) * (b**2)) ** 2)
        / ((np.cos(lat) * semi_major_axis) ** 2 + (np.sin(lat) * b) ** 2)
    )


def geometric_height(geopotential_height, radius):
    """RocketPy's h = R Z/(R - Z) (rocketpy.tools.geopotential_height_to_geometric_height)."""
    return radius * geopotential_height / (radius - geopotential_height)


def normal_gravity(lat_deg):
    """WGS-84 normal gravity on the ellipsoid (Somigliana), m/s^2."""
    s2 = math.sin(math.radians(lat_deg)) ** 2
    return SOMIGLIANA_GAMMA_E * (1 + SOMIGLIANA_K * s2) / math.sqrt(1 - WGS84_E2 * s2)


def physical_height(geopotential_height, lat_deg):
    """h of Phi = g0 Z = g_phi R_phi h/(R_phi + h): h = R_phi Z/((g_phi/g0) R_phi - Z)."""
    s2 = math.sin(math.radians(lat_deg)) ** 2
    radius = WGS84_A / (1 + WGS84_F + WGS84_M - 2 * WGS84_F * s2)
    ratio = normal_gravity(lat_deg) / STANDARD_G
    return radius * geopotential_height / (ratio * radius - geopotential_height)


def bilinear(x, y, x1, x2, y1, y2, z11, z12, z21, z22):
    """rocketpy.tools.bilinear_interpolation, term for term: z11 at (x1, y1), z12 at
    (x1, y2), z21 at (x2, y1), z22 at (x2, y2)."""
    return (
        z11 * (x2 - x) * (y2 - y)
        + z21 * (x - x1) * (y2 - y)
        + z12 * (x2 - x) * (y - y1)
        + z22 * (x - x1) * (y - y1)
    ) / ((x2 - x1) * (y2 - y1))


def normalize_longitude(lon, first, last):
    """A longitude in the grid's convention, [-180, 180) or [0, 360) (RocketPy's)."""
    if first < 0 or last < 0:
        return lon if lon < 180 else -180 + lon % 180
    return lon % 360


def bracket(value, coords):
    """The index i such that coords[i - 1] and coords[i] bracket value, coords ascending or
    descending (RocketPy's binary search and its boundary rule); ValueError outside."""
    coords = [float(c) for c in coords]
    ascending = coords[0] < coords[-1]
    low, high = 0, len(coords)
    while low < high:
        mid = (low + high) // 2
        if (coords[mid] < value) if ascending else (coords[mid] > value):
            low = mid + 1
        else:
            high = mid
    if low == 0 and math.isclose(coords[0], value):
        low = 1
    if low == len(coords) and coords[-1] == value:
        low -= 1
    if low in (0, len(coords)):
        raise ValueError(f"{value} is outside the grid, {coords[0]} to {coords[-1]}")
    return low


def nearest_time_index(target, times):
    """The index of the time nearest target (a tie takes the earlier), as RocketPy's
    find_time_index; ValueError before the first or after the last."""
    times = [float(t) for t in times]
    low, high = 0, len(times)
    while low < high:
        mid = (low + high) // 2
        if times[mid] < target:
            low = mid + 1
        else:
            high = mid
    right = min(max(low, 0), len(times) - 1)
    left = min(max(right - 1, 0), len(times) - 1)
    index = left if abs(target - times[left]) <= abs(times[right] - target) else right
    if (index == 0 and target < times[0]) or (index == len(times) - 1 and target > times[-1]):
        raise ValueError(f"the time {target} is outside the file's, {times[0]} to {times[-1]}")
    return index


def profile(cells, levels_pa, lat, lon, lats, lons, radius, method="rocketpy"):
    """The site's profile from each field's 2x2 cell at every level.

    cells: {"geopotential", "temperature", "u", "v"} -> arrays (levels, 2, 2), [:, 0, 0] at
    (lats[0], lons[0]), [:, 0, 1] at (lats[0], lons[1]), [:, 1, 0] at (lats[1], lons[0]);
    the geopotential in m^2/s^2. Returns the columns altitude (m above sea level, geometric),
    pressure (Pa), temperature (K), east and north wind (m/s), rows by increasing altitude,
    rows with a missing value dropped."""
    x1, x2 = lats
    y1, y2 = lons
    if method == "physical":
        cells = {k: np.ma.asarray(v, dtype=np.float64) for k, v in cells.items()}
    columns = {}
    for name in ("geopotential", "temperature", "u", "v"):
        c = cells[name] / STANDARD_G if name == "geopotential" else cells[name]
        columns[name] = bilinear(
            lat, lon, x1, x2, y1, y2, c[:, 0, 0], c[:, 0, 1], c[:, 1, 0], c[:, 1, 1]
        )
    z = columns["geopotential"]
    height = geometric_height(z, radius) if method == "rocketpy" else physical_height(z, lat)
    table = np.ma.column_stack(
        [height, levels_pa, columns["temperature"], columns["u"], columns["v"]]
    )
    if np.any(np.ma.getmaskarray(table)):
        table = np.ma.compress_rows(table)
    table = np.asarray(table, dtype=np.float64)
    table = table[table[:, 0].argsort()]
    if np.any(np.diff(table[:, 0]) <= 0):
        raise ValueError("two levels at one altitude: the tables need increasing altitudes")
    return table


def extend_below(table, floor, method="rocketpy"):
    """The table with a first row at the altitude `floor` when its lowest level lies above it
    (a site below the file's lowest level, as the EuroC sites are on some days). RocketPy
    holds every value constant below its lowest level (its Functions' constant
    extrapolation), and so does the `rocketpy` row: linear tables then give RocketPy's
    values down to `floor`. The `physical` row extrapolates the lowest layer: the
    temperature on its lapse rate L, the pressure hydrostatic, p = p0 (T0/T)^(g0/(R L)) (an
    exponential where L = 0); the wind held."""
    h0, p0, t0, u0, v0 = table[0]
    if floor >= h0:
        return table
    if method == "rocketpy":
        row = [floor, p0, t0, u0, v0]
    else:
        lapse = (table[1, 2] - t0) / (table[1, 0] - h0)
        t = t0 + lapse * (floor - h0)
        if abs(lapse) < 1e-9:
            p = p0 * math.exp(-STANDARD_G * (floor - h0) / (R_AIR * t0))
        else:
            p = p0 * (t0 / t) ** (STANDARD_G / (R_AIR * lapse))
        row = [floor, p, t, u0, v0]
    return np.vstack([np.array(row, dtype=np.float64), table])


def variable(data, key):
    for name in NAMES[key]:
        if name in data.variables:
            return data.variables[name]
    raise ValueError(f"no {key} variable ({' or '.join(NAMES[key])}) in the file")


def read_era5(path, when, lat, lon, datum="SIRGAS2000", method="rocketpy", floor=None):
    """The profile (see profile) of the ERA5 file at `path` at the UTC datetime `when` and
    the site (lat, lon in degrees), extended down to `floor` (m) if given (extend_below),
    with what was used, as (table, notes)."""
    import netCDF4  # only here: the arithmetic above runs without it

    with netCDF4.Dataset(path) as data:
        time = variable(data, "time")
        target = netCDF4.date2num(when, time.units, calendar="gregorian")
        t = nearest_time_index(target, time[:])
        lats, lons = variable(data, "latitude"), variable(data, "longitude")
        lon_n = normalize_longitude(lon, float(lons[0]), float(lons[-1]))
        i, j = bracket(lat, lats[:]), bracket(lon_n, lons[:])
        level = variable(data, "level")
        levels_pa = 100 * level[:]
        cells = {
            key: variable(data, key)[t, :, (i - 1, i), (j - 1, j)]
            for key in ("geopotential", "temperature", "u", "v")
        }
        corner_lats = (float(lats[i - 1]), float(lats[i]))
        corner_lons = (float(lons[j - 1]), float(lons[j]))
        radius = earth_radius(lat, *DATUMS[datum])
        table = profile(cells, levels_pa, lat, lon_n, corner_lats, corner_lons, radius, method)
        used = netCDF4.num2date(float(time[t]), time.units, calendar="gregorian")
    lowest = table[0, 0]
    if floor is not None:
        table = extend_below(table, floor, method)
    notes = [
        f"time used {used} UTC (nearest to {when:%Y-%m-%d %H:%M} UTC), index {t}",
        f"grid cell latitudes {corner_lats}, longitudes {corner_lons}, bilinear",
        f"method {method}, datum {datum}, {len(table)} rows",
    ]
    if len(table) and table[0, 0] < lowest:
        kind = "held" if method == "rocketpy" else "extrapolated"
        notes.append(f"first row at {table[0, 0]} m {kind} below the lowest level, {lowest} m")
    return table, notes


COLUMNS = (
    ("temperature.csv", "temperature_K", 2),
    ("pressure.csv", "pressure_Pa", 1),
    ("wind_east.csv", "wind_east_m_s", 3),
    ("wind_north.csv", "wind_north_m_s", 4),
)


def write_tables(out, table, header):
    """The four CSV files of `table` in the directory `out`, each opening with `header`."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    comment = "".join(f"# {line}\n" for line in header)
    for name, column, k in COLUMNS:
        rows = "".join(f"{float(r[0])!r},{float(r[k])!r}\n" for r in table)
        (out / name).write_text(f"{comment}altitude_m,{column}\n{rows}")


def utc(date, timezone):
    """The UTC datetime of an ISO date-time `date` (2020-02-22T13) in `timezone` (an IANA
    name, as RocketPy's set_date(date, timezone) takes it)."""
    import zoneinfo

    local = datetime.datetime.fromisoformat(date)
    if local.tzinfo is None:
        local = local.replace(tzinfo=zoneinfo.ZoneInfo(timezone))
    return local.astimezone(datetime.timezone.utc).replace(tzinfo=None)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("file", help="an ERA5 pressure-level NetCDF file")
    parser.add_argument("--lat", type=float, required=True, help="latitude, degrees north")
    parser.add_argument("--lon", type=float, required=True, help="longitude, degrees east")
    parser.add_argument("--date", required=True, help="launch date-time, 2020-02-22T13")
    parser.add_argument("--timezone", default="UTC", help="the date's time zone (IANA)")
    parser.add_argument("--datum", default="SIRGAS2000", choices=sorted(DATUMS))
    parser.add_argument("--method", default="rocketpy", choices=("rocketpy", "physical"))
    parser.add_argument("--floor", type=float, help="extend the tables down to this altitude")
    parser.add_argument("--source", help="the file's origin, written in the header")
    parser.add_argument("--out", required=True, help="the directory of the four CSV files")
    args = parser.parse_args(argv)
    when = utc(args.date, args.timezone)
    try:
        table, notes = read_era5(
            args.file, when, args.lat, args.lon, args.datum, args.method, args.floor
        )
    except (ValueError, OSError) as e:
        print(f"error: {args.file}: {e}", file=sys.stderr)
        return 2
    header = [
        f"ERA5 pressure levels: {args.source or pathlib.Path(args.file).name}",
        f"site latitude {args.lat}, longitude {args.lon}; launch {args.date} {args.timezone}",
        *notes,
        "written by tools/weather/era5_to_csv.py (docs/weather.md); altitude above sea level",
    ]
    write_tables(args.out, table, header)
    print(f"{args.out}: {len(table)} rows, {table[0, 0]:.1f} to {table[-1, 0]:.1f} m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
