#!/usr/bin/env python3
"""The median of NASA's simulations, and their spread, for the check-cases varmass flies.

Source: E. A. Murri, E. B. Jackson, R. A. Shelton et al., "Check-cases for verification of
6-degree-of-freedom flight vehicle simulations", NASA/TM-2015-218675 (NASA Engineering and
Safety Center, 2015), volumes I and II: the atmospheric check-cases, each flown by up to six
of NASA's simulations, whose trajectories NASA published as CSV files. This script reads
the copy of those files in the GitHub repository onurtuncer/Aetherion, directory data/, at
commit 9a495bf (`fix(cmake): fix AETHERION_INSTALL=ON export failures ...`); the raw files
are 58 MB and stay out of this repository.

For each case it writes validation/nasa/case_NN.csv: at every time all the case's
simulations share (every 0.1 s from 0 to 30 s), for each quantity below, the median of the
simulations that record it (the mean of the middle two when their number is even) and the
spread, the largest |simulation - median| among them. SI units; angles in radians. For
cases 1, 2, 3 and 6-10 it also writes case_NN_sims.csv, a few quantities of single
simulations (SINGLE below).
A simulation published only in US units (case 2's sims 2, 4, 5 and 6) is converted with
ft = 0.3048 m exactly and deg = pi/180 rad. Euler angles are aligned to the first
simulation's value modulo 2*pi before the median, which is then wrapped to (-pi, pi].

Usage (stdlib only):
    python3 validation/nasa/extract.py [--mirror GIT_DIR] [--commit 9a495bf] [--out DIR]
"""
import argparse
import csv
import io
import math
import os
import subprocess
import sys

CASES = {
    1: "Atmos_01_DroppedSphere",
    2: "Atmos_02_TumblingBrickNoDamping",
    3: "Atmos_03_TumblingBrickWithDamping",
    6: "Atmos_06_SphereWithDrag",
    7: "Atmos_07_DroppedSphereSteadyWind",
    8: "Atmos_08_DroppedSphere2DWindShear",
    9: "Atmos_09_EastwardCannonball",
    10: "Atmos_10_NorthwardCannonball",
}

FT = 0.3048  # m, exact
DEG = math.pi / 180.0

# (output name, SI column, US column, factor from US to SI, is an angle to wrap)
QUANTITIES = [
    ("x_eci", "eiPosition_m_X", "eiPosition_ft_X", FT, False),
    ("y_eci", "eiPosition_m_Y", "eiPosition_ft_Y", FT, False),
    ("z_eci", "eiPosition_m_Z", "eiPosition_ft_Z", FT, False),
    ("vx_eci", "eiVelocity_m_s_X", "eiVelocity_ft_s_X", FT, False),
    ("vy_eci", "eiVelocity_m_s_Y", "eiVelocity_ft_s_Y", FT, False),
    ("vz_eci", "eiVelocity_m_s_Z", "eiVelocity_ft_s_Z", FT, False),
    ("x_ecef", "gePosition_m_X", "gePosition_ft_X", FT, False),
    ("y_ecef", "gePosition_m_Y", "gePosition_ft_Y", FT, False),
    ("z_ecef", "gePosition_m_Z", "gePosition_ft_Z", FT, False),
    ("v_north", "feVelocity_m_s_X", "feVelocity_ft_s_X", FT, False),
    ("v_east", "feVelocity_m_s_Y", "feVelocity_ft_s_Y", FT, False),
    ("v_down", "feVelocity_m_s_Z", "feVelocity_ft_s_Z", FT, False),
    ("altitude", "altitudeMsl_m", "altitudeMsl_ft", FT, False),
    ("longitude", "longitude_rad", "longitude_deg", DEG, False),
    ("latitude", "latitude_rad", "latitude_deg", DEG, False),
    ("gravity", "localGravity_m_s2", "localGravity_ft_s2", FT, False),
    ("yaw", "eulerAngle_rad_Yaw", "eulerAngle_deg_Yaw", DEG, True),
    ("pitch", "eulerAngle_rad_Pitch", "eulerAngle_deg_Pitch", DEG, False),
    ("roll", "eulerAngle_rad_Roll", "eulerAngle_deg_Roll", DEG, True),
    ("p", "bodyAngularRateWrtEi_rad_s_Roll", "bodyAngularRateWrtEi_deg_s_Roll", DEG, False),
    ("q", "bodyAngularRateWrtEi_rad_s_Pitch", "bodyAngularRateWrtEi_deg_s_Pitch", DEG, False),
    ("r", "bodyAngularRateWrtEi_rad_s_Yaw", "bodyAngularRateWrtEi_deg_s_Yaw", DEG, False),
]


# Single simulations kept beside the medians, where ours agrees with some of them far more
# closely than with the median (docs/validation.md#nasa-check-cases): {case: [(sim, names)]}.
SINGLE = {
    1: [(5, ["x_eci", "y_eci", "vx_eci", "vy_eci"])],
    2: [
        (1, ["yaw", "pitch", "roll", "p", "q", "r"]),
        (4, ["yaw", "pitch", "roll", "p", "q", "r"]),
    ],
    3: [(4, ["p", "q", "r"])],
    7: [(4, ["x_eci", "vx_eci"])],
    8: [(4, ["x_eci", "vx_eci"])],
}

# Cases 6, 9 and 10 (drag): sim 4, whose atmosphere is the 1976 standard's formulas (its
# density within 4e-7 of them, validation/nasa/densities.py), as ours is.
SINGLE.update(
    {
        6: [(4, ["x_eci", "vx_eci", "altitude", "v_down"])],
        9: [(4, ["altitude", "v_east", "v_down", "longitude"])],
        10: [(4, ["altitude", "v_north", "v_down", "latitude", "pitch"])],
    }
)


def git_show(mirror, commit, path):
    """The text of `path` at `commit`, or None when the file is not there."""
    result = subprocess.run(
        ["git", "-C", mirror, "show", f"{commit}:{path}"],
        capture_output=True,
        check=False,
    )
    return result.stdout.decode() if result.returncode == 0 else None


def read_simulation(mirror, commit, case, sim):
    """{quantity: {time key (ms): value}} for one simulation, in SI, or None."""
    base = f"data/{CASES[case]}/Atmos_{case:02d}_sim_{sim:02d}"
    text = git_show(mirror, commit, base + "_si_units.csv")
    us = text is None
    if us:
        text = git_show(mirror, commit, base + ".csv")
    if text is None:
        return None
    rows = list(csv.reader(io.StringIO(text)))
    header = [h.strip() for h in rows[0]]
    series = {}
    for name, si_column, us_column, factor, _ in QUANTITIES:
        column = us_column if us else si_column
        if column not in header:
            continue
        index = header.index(column)  # the first, where a column is repeated
        scale = factor if us else 1.0
        values = {}
        for row in rows[1:]:
            if len(row) <= index or not row[0].strip():
                continue
            t = float(row[0])
            key = round(t * 1000.0)
            if abs(t - key / 1000.0) < 1e-6:
                values[key] = float(row[index]) * scale
        series[name] = values
    return series


def median(values):
    ordered = sorted(values)
    n = len(ordered)
    return ordered[n // 2] if n % 2 else 0.5 * (ordered[n // 2 - 1] + ordered[n // 2])


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


def statistics(values, is_angle):
    """(median, spread) of one quantity at one time across simulations."""
    if is_angle:
        reference = values[0]
        values = [reference + wrap(v - reference) for v in values]
    middle = median(values)
    spread = max(abs(v - middle) for v in values)
    return (wrap(middle) if is_angle else middle), spread


def extract(mirror, commit, case, out_dir):
    sims = {}
    for sim in range(1, 7):
        series = read_simulation(mirror, commit, case, sim)
        if series is not None:
            sims[sim] = series
    names = [q for q in QUANTITIES if any(q[0] in s for s in sims.values())]
    shared = None
    for series in sims.values():
        keys = set.intersection(*(set(v) for v in series.values()))
        shared = keys if shared is None else shared & keys
    times = sorted(shared)
    path = os.path.join(out_dir, f"case_{case:02d}.csv")
    with open(path, "w", newline="") as out:
        out.write(f"# NASA/TM-2015-218675 check-case {case} ({CASES[case]}): median and spread\n")
        out.write(f"# of NASA's simulations, from onurtuncer/Aetherion data/ at {commit};\n")
        out.write("# written by validation/nasa/extract.py. SI units, angles in rad.\n")
        for name, *_ in names:
            which = [str(k) for k, s in sims.items() if name in s]
            out.write(f"# {name}: sims {' '.join(which)}\n")
        columns = ["t"] + [f"{n}{s}" for n, *_ in names for s in ("", "_spread")]
        out.write(",".join(columns) + "\n")
        for key in times:
            row = [f"{key / 1000.0:g}"]
            for name, _, _, _, is_angle in names:
                values = [s[name][key] for s in sims.values() if name in s]
                middle, spread = statistics(values, is_angle)
                row += [repr(middle), f"{spread:.3e}"]
            out.write(",".join(row) + "\n")
    size = os.path.getsize(path)
    print(f"case {case}: sims {sorted(sims)}, {len(times)} times, {size} bytes -> {path}")
    if case in SINGLE:
        write_single(case, commit, sims, times, out_dir)


def write_single(case, commit, sims, times, out_dir):
    """case_NN_sims.csv: the quantities of SINGLE[case], simulation by simulation."""
    columns = [(sim, name) for sim, names in SINGLE[case] for name in names]
    path = os.path.join(out_dir, f"case_{case:02d}_sims.csv")
    with open(path, "w", newline="") as out:
        out.write(f"# NASA/TM-2015-218675 check-case {case}: single simulations, from\n")
        out.write(f"# onurtuncer/Aetherion data/ at {commit}; validation/nasa/extract.py.\n")
        header = ["t"] + [f"sim{sim}_{name}" for sim, name in columns]
        out.write(",".join(header) + "\n")
        for key in times:
            row = [f"{key / 1000.0:g}"] + [repr(sims[sim][name][key]) for sim, name in columns]
            out.write(",".join(row) + "\n")
    print(f"case {case}: single simulations, {os.path.getsize(path)} bytes -> {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mirror", default="/work/.mirror/onurtuncer+Aetherion/repo")
    parser.add_argument("--commit", default="9a495bf")
    parser.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("cases", nargs="*", type=int, default=sorted(CASES))
    args = parser.parse_args()
    for case in args.cases:
        if case not in CASES:
            sys.exit(f"unknown case {case}: one of {sorted(CASES)}")
        extract(args.mirror, args.commit, case, args.out)


if __name__ == "__main__":
    main()
