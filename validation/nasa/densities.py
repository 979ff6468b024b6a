#!/usr/bin/env python3
"""How far each NASA simulation's air density is from the 1976 standard's formulas.

For check-cases 6, 9 and 10 (NASA/TM-2015-218675, drag in the 1976 standard atmosphere),
reads every simulation's recorded altitude and air density from the copy of NASA's CSVs in
onurtuncer/Aetherion (data/, commit 9a495bf; as extract.py) and prints, per simulation, the
largest relative difference of its density from the standard's formulas at its own
altitude (models/atmosphere/us_standard_1976.py, the formulas models/lib/atmosphere_1976.vms
writes). Sims 1, 2 and 3 differ by 3.5e-4 to 2.8e-3 (the size of a table's interpolation
error), sims 4, 5 and 6 by < 3e-5: the main reason their trajectories split
(docs/validation.md#check-cases-6-9-and-10-drag-on-a-rotating-earth).

Usage (stdlib only): python3 validation/nasa/densities.py [--mirror GIT_DIR]
"""
import argparse
import csv
import io
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "models", "atmosphere"))
import extract  # noqa: E402
import us_standard_1976  # noqa: E402

SLUG_FT3 = 0.45359237 * 9.80665 / 0.3048 / 0.3048**3  # kg/m^3


def worst(mirror, commit, case, sim, layers):
    """(largest relative density difference, the altitude there) of one simulation, or None."""
    base = f"data/{extract.CASES[case]}/Atmos_{case:02d}_sim_{sim:02d}"
    text = extract.git_show(mirror, commit, base + "_si_units.csv")
    us = text is None
    if us:
        text = extract.git_show(mirror, commit, base + ".csv")
    if text is None:
        return None
    rows = list(csv.reader(io.StringIO(text)))
    header = [h.strip() for h in rows[0]]
    names = ("altitudeMsl_ft", "airDensity_slug_ft3") if us else ("altitudeMsl_m", "airDensity_kg_m3")
    if not all(n in header for n in names):
        return None
    at, rho_at = (header.index(n) for n in names)
    found = (0.0, 0.0)
    for row in rows[1:]:
        if len(row) <= rho_at or not row[0].strip():
            continue
        z, rho = float(row[at]), float(row[rho_at])
        if us:
            z, rho = z * extract.FT, rho * SLUG_FT3
        z = max(z, 0.0)  # a start a rounding below the ground reads sea level
        standard = us_standard_1976.density(z, layers)
        difference = (rho - standard) / standard
        if abs(difference) > abs(found[0]):
            found = (difference, z)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mirror", default="/work/.mirror/onurtuncer+Aetherion/repo")
    parser.add_argument("--commit", default="9a495bf")
    args = parser.parse_args()
    layers = us_standard_1976.bases()
    for case in (6, 9, 10):
        for sim in range(1, 7):
            found = worst(args.mirror, args.commit, case, sim, layers)
            if found is not None:
                print(f"case {case} sim {sim}: density {found[0]:+.2e} of the standard's at {found[1]:.0f} m")


if __name__ == "__main__":
    main()
