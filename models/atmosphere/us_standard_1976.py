"""The density of the U.S. Standard Atmosphere, 1976, from 0 to 86 km geometric altitude,
computed from the standard's defining formulas (NOAA-S/T 76-1562, part 1, sections 1.2-1.3):

* geopotential altitude H = r0 Z / (r0 + Z), r0 = 6356.766 km (eq. 18);
* seven layers of linear molecular-scale temperature in H, T = Tb + Lb (H - Hb) (eq. 23),
  with the base altitudes and lapse rates of Table 4;
* pressure by hydrostatic integration (eqs. 33a, 33b):
  P = Pb [Tb / (Tb + Lb (H - Hb))]^(g0' M0 / (R* Lb))   if Lb != 0,
  P = Pb exp(-g0' M0 (H - Hb) / (R* Tb))                if Lb == 0;
* density rho = P M0 / (R* T) (eq. 42), with M0 constant below 86 km.

It also writes the temperature and the pressure (`temperature.csv`, `pressure.csv`), the
default sounding of models/lib/atmosphere_table.vms.

Constants as the standard gives them: g0' = 9.80665 m^2/(s^2 m'), R* = 8.31432 J/(mol K),
M0 = 28.9644 g/mol, P0 = 101325 Pa, T0 = 288.15 K.

    python3 models/atmosphere/us_standard_1976.py    # rewrites the three CSVs beside it
"""

import math
from pathlib import Path

G0 = 9.80665  # m^2 / (s^2 m'), standard gravity over geopotential metres
R_STAR = 8.31432  # J / (mol K), the 1976 standard's gas constant
M0 = 28.9644e-3  # kg / mol, sea-level mean molecular weight
R0 = 6356.766e3  # m, the effective Earth radius of the geopotential
P0 = 101325.0  # Pa
T0 = 288.15  # K

# Table 4: base geopotential altitude (m'), lapse rate (K/m').
LAYERS = [
    (0.0, -6.5e-3),
    (11000.0, 0.0),
    (20000.0, 1.0e-3),
    (32000.0, 2.8e-3),
    (47000.0, 0.0),
    (51000.0, -2.8e-3),
    (71000.0, -2.0e-3),
    (84852.0, None),  # the top of the seven layers
]

STEP = 500.0  # m
TOP = 86000.0  # m geometric = 84852 m' geopotential


def bases():
    """Temperature and pressure at each layer's base, carried up from sea level."""
    temperature, pressure = T0, P0
    result = []
    for (base, lapse), (top, _) in zip(LAYERS, LAYERS[1:]):
        result.append((base, lapse, temperature, pressure))
        temperature, pressure = state(top - base, lapse, temperature, pressure)
    return result


def state(dh, lapse, tb, pb):
    """Temperature and pressure dh geopotential metres above a base at (tb, pb)."""
    if lapse == 0.0:
        return tb, pb * math.exp(-G0 * M0 * dh / (R_STAR * tb))
    t = tb + lapse * dh
    return t, pb * (tb / t) ** (G0 * M0 / (R_STAR * lapse))


def temperature_pressure(z, layers):
    """Temperature (K) and pressure (Pa) at geometric altitude z (m)."""
    h = R0 * z / (R0 + z)
    base, lapse, tb, pb = next(layer for layer in reversed(layers) if layer[0] <= h)
    return state(h - base, lapse, tb, pb)


def density(z, layers):
    """Density at geometric altitude z (m)."""
    t, p = temperature_pressure(z, layers)
    return p * M0 / (R_STAR * t)


def write(name, header, value, layers):
    """One CSV of altitude against value(z, layers), every STEP to TOP."""
    path = Path(__file__).with_name(name)
    with path.open("w") as f:
        f.write(f"# U.S. Standard Atmosphere 1976: {header[1]} against geometric altitude,\n")
        f.write("# computed by us_standard_1976.py from the standard's formulas.\n")
        f.write(f"altitude_m,{header[0]}\n")
        for k in range(int(TOP / STEP) + 1):
            z = k * STEP
            f.write(f"{z:.0f},{value(z, layers):.{header[2]}e}\n")


def main():
    layers = bases()
    write("density.csv", ("density_kg_m3", "density", 6), density, layers)
    temperature = lambda z, layers: temperature_pressure(z, layers)[0]
    pressure = lambda z, layers: temperature_pressure(z, layers)[1]
    write("temperature.csv", ("temperature_K", "temperature", 9), temperature, layers)
    write("pressure.csv", ("pressure_Pa", "pressure", 9), pressure, layers)


if __name__ == "__main__":
    main()
