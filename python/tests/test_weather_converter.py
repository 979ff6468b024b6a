"""The ERA5 converter's arithmetic (tools/weather/era5_to_csv.py, docs/weather.md) on hand
examples: one grid cell, one pressure level, the numbers worked out in the comments. It
needs numpy only; reading a NetCDF file (netCDF4) is not tested here, and nothing here
needs RocketPy (cli/tests/weather.rs holds the converted files to RocketPy's values)."""

import datetime
import importlib.util
import math
import pathlib

import numpy as np
import pytest

TOOL = pathlib.Path(__file__).resolve().parents[2] / "tools" / "weather" / "era5_to_csv.py"
_spec = importlib.util.spec_from_file_location("era5_to_csv", TOOL)
era5 = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(era5)

G0 = 9.80665
A = 6378137.0
F = 1 / 298.257223563


def cell(z11, z12, z21, z22):
    """One level's 2x2 cell, [:, 0, 0] at (lat1, lon1) … as the file's slice gives it."""
    return np.array([[[z11, z12], [z21, z22]]], dtype=np.float64)


def test_one_level_of_one_cell_by_hand():
    # The cell latitudes (40.0, 39.75) (descending, as ERA5's), longitudes (-8.5, -8.25);
    # the site (39.8, -8.4). Bilinear weights: latitude 40.0 gets (39.75 - 39.8)/(39.75 -
    # 40.0) = 0.2, 39.75 gets 0.8; longitude -8.5 gets (-8.25 + 8.4)/0.25 = 0.6, -8.25 0.4.
    # Geopotential heights Z = 1000, 1100, 1200, 1300 m at the corners (Phi = g0 Z):
    # Z = 0.2 (0.6*1000 + 0.4*1100) + 0.8 (0.6*1200 + 0.4*1300) = 208 + 992 = 1200 m.
    # Temperatures 280, 282, 284, 286 K: 0.2*280.8 + 0.8*284.8 = 284.0 K. u = 1, 2, 3, 4:
    # 0.2*1.4 + 0.8*3.4 = 3.0 m/s. v = -1 everywhere: -1. The level 850 hPa: 85000 Pa.
    cells = {
        "geopotential": cell(*(G0 * z for z in (1000.0, 1100.0, 1200.0, 1300.0))),
        "temperature": cell(280.0, 282.0, 284.0, 286.0),
        "u": cell(1.0, 2.0, 3.0, 4.0),
        "v": cell(-1.0, -1.0, -1.0, -1.0),
    }
    # The geocentric radius of the ellipsoid at 39.8 deg, written from the ellipse
    # x = a cos(beta), z = b sin(beta) with tan(beta) = (b/a) tan(phi) (reduced latitude):
    # R = sqrt(x^2 + z^2), an independent form of RocketPy's expression.
    b = A * (1 - F)
    beta = math.atan(b / A * math.tan(math.radians(39.8)))
    radius = math.hypot(A * math.cos(beta), b * math.sin(beta))
    assert abs(radius - float(era5.earth_radius(39.8))) < 1e-6  # m, of 6.37e6
    table = era5.profile(
        cells, np.array([85000.0]), 39.8, -8.4, (40.0, 39.75), (-8.5, -8.25), radius
    )
    # h = R Z/(R - Z) = 1200 + 1200^2/(R - 1200) = 1200.2261... m at R = 6369.5 km.
    h = 1200.0 + 1200.0**2 / (radius - 1200.0)
    assert table.shape == (1, 5)
    expected = [h, 85000.0, 284.0, 3.0, -1.0]
    assert np.allclose(table[0], expected, rtol=1e-13, atol=1e-12), table[0]
    assert 1200.22 < h < 1200.23


def test_rocketpys_float32_arithmetic_is_kept_and_physical_reads_float64():
    # The current files are float32: RocketPy's arithmetic stays in float32 (NumPy 2 keeps
    # an array's precision against a Python float), so its temperature 284.0 + 1/3 of a
    # float32 unit; the physical method casts to float64 first.
    t = np.float32(284.1)
    cells = {
        "geopotential": cell(*([np.float32(G0 * 1200.0)] * 4)).astype(np.float32),
        "temperature": cell(t, t, t, t).astype(np.float32),
        "u": cell(0, 0, 0, 0).astype(np.float32),
        "v": cell(0, 0, 0, 0).astype(np.float32),
    }
    args = (np.array([85000.0]), 39.8, -8.4, (40.0, 39.75), (-8.5, -8.25), 6.37e6)
    rocketpy = era5.profile(cells, *args, method="rocketpy")
    physical = era5.profile(cells, *args, method="physical")
    # float32's unit at 284 is 2^-15 = 3.05e-5 K: both within a few units of the value.
    assert abs(rocketpy[0, 2] - float(t)) <= 4 * 2.0**-15
    assert abs(physical[0, 2] - float(t)) <= 1e-12


def test_the_physical_height_uses_the_sites_gravity():
    # WGS-84's normal gravity (NIMA TR8350.2): 9.7803253359 m/s^2 at the equator,
    # 9.8321849378 at the poles (printed to 10 digits); at 45 deg Somigliana's
    # gamma_e (1 + k/2)/sqrt(1 - e^2/2) = 9.80619777 m/s^2. The free-air radius there is
    # a/(1 + f + m - 2 f sin^2 45) = a/(1 + m).
    assert abs(era5.normal_gravity(0.0) - 9.7803253359) < 1e-12
    assert abs(era5.normal_gravity(90.0) - 9.8321849378) < 1e-10
    gamma45 = 9.7803253359 * (1 + 0.00193185265241 / 2) / math.sqrt(1 - 0.00669437999013 / 2)
    assert abs(gamma45 - 9.80619777) < 1e-8
    assert abs(era5.normal_gravity(45.0) - gamma45) < 1e-14
    radius = A / (1 + 0.00344978650684)
    z = 10000.0
    # g0 Z = gamma R h/(R + h): h = R Z/((gamma/g0) R - Z).
    h = radius * z / (gamma45 / G0 * radius - z)
    assert abs(era5.physical_height(z, 45.0) - h) < 1e-8
    # Against RocketPy's h = R Z/(R - Z) (R = 6367.49 km, the geocentric radius): with
    # h ~ Z g0/gamma + Z^2/R, gamma45/g0 - 1 = -4.611e-5 puts the physical height 0.462 m
    # higher at Z = 10 km, and its smaller radius R' = 6356.21 km another Z^2 (1/R' - 1/R)
    # = 0.028 m: 0.490 m (measured 0.4906).
    rocketpy = era5.geometric_height(z, float(era5.earth_radius(45.0)))
    assert 0.485 < h - rocketpy < 0.495, h - rocketpy


def test_the_grid_search_and_the_nearest_time_follow_rocketpy():
    lats = [40.0, 39.75, 39.5]  # descending
    assert era5.bracket(39.8, lats) == 1
    assert era5.bracket(39.6, lats) == 2
    assert era5.bracket(40.0, lats) == 1  # on the first knot: the first cell
    with pytest.raises(ValueError):
        era5.bracket(40.1, lats)
    assert era5.bracket(-8.4, [-9.0, -8.75, -8.5, -8.25]) == 3
    assert era5.normalize_longitude(350.0, -10.0, 10.0) == -10.0
    assert era5.normalize_longitude(-8.4, 0.0, 359.75) == pytest.approx(351.6)
    times = [0.0, 1.0, 2.0, 3.0]
    assert era5.nearest_time_index(1.4, times) == 1
    assert era5.nearest_time_index(1.5, times) == 1  # a tie: the earlier
    assert era5.nearest_time_index(1.6, times) == 2
    with pytest.raises(ValueError):
        era5.nearest_time_index(3.5, times)


def test_a_site_below_the_lowest_level_gets_a_row_at_the_floor():
    table = np.array(
        [[200.0, 100000.0, 290.0, 1.0, 2.0], [400.0, 97700.0, 288.7, 3.0, 4.0]]
    )
    held = era5.extend_below(table, 0.0, "rocketpy")
    assert held[0].tolist() == [0.0, 100000.0, 290.0, 1.0, 2.0]
    # Physical: the lapse (288.7 - 290)/200 = -0.0065 K/m, so 291.3 K at 0 m, and
    # p = 1e5 (290/291.3)^(g0/(R L)) with g0/(R L) = -5.2558...: 1e5 * 1.023577... Pa.
    physical = era5.extend_below(table, 0.0, "physical")
    assert physical[0, 2] == pytest.approx(291.3, abs=1e-12)
    exponent = G0 / (287.05287 * -0.0065)
    assert physical[0, 1] == pytest.approx(1e5 * (290 / 291.3) ** exponent, rel=1e-14)
    # Against an isothermal layer at the mean temperature 290.65 K, p = p0 exp(g0 dz/(R T)):
    # 2378.664 Pa over 200 m; the lapse changes that only in the second order (measured
    # 1.7e-6 relative; bound 1e-5).
    isothermal = 1e5 * (math.exp(G0 * 200 / (287.05287 * 290.65)) - 1)
    assert physical[0, 1] - 1e5 == pytest.approx(isothermal, rel=1e-5)
    assert era5.extend_below(table, 300.0, "rocketpy") is table


def test_a_launch_time_in_a_time_zone_is_turned_into_utc():
    try:
        when = era5.utc("2022-10-14T14", "Portugal")
    except Exception as e:  # no time zone database on this machine
        pytest.skip(f"zoneinfo: {e}")
    # October in Portugal is summer time, UTC+1.
    assert when == datetime.datetime(2022, 10, 14, 13)
    assert era5.utc("2020-02-22T13", "UTC") == datetime.datetime(2020, 2, 22, 13)


def test_the_tables_are_written_as_the_tables_read_them(tmp_path):
    table = np.array([[0.5, 100000.0, 290.0, 1.0, -2.0], [100.25, 98800.0, 289.5, 1.5, -2.5]])
    era5.write_tables(tmp_path, table, ["a note"])
    text = (tmp_path / "wind_north.csv").read_text()
    assert text == "# a note\naltitude_m,wind_north_m_s\n0.5,-2.0\n100.25,-2.5\n"
    assert (tmp_path / "pressure.csv").read_text().splitlines()[2] == "0.5,100000.0"
