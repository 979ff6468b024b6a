"""SciPy's values of `pchip` and `spline` for the tests of varmass-table (tests/scipy.rs).

For each data set, 5000 arguments (evenly spaced over the data, and every knot) and, at each,
the value and first derivative of SciPy's PchipInterpolator and CubicSpline(bc_type='natural').
Numbers are written with repr(), which round-trips exactly.

    python3 -m venv .venv && .venv/bin/pip install scipy      # at the worktree's root
    .venv/bin/python table/tests/data/scipy_reference.py      # rewrites the *_scipy.csv files

Made with SciPy 1.17.1, NumPy 2.4.6.
"""

from pathlib import Path

import numpy as np
import scipy
from scipy.interpolate import CubicSpline, PchipInterpolator

HERE = Path(__file__).parent
ROOT = HERE.parent.parent.parent
SAMPLES = 5000


def read_rasp(path):
    """Times and thrusts of a RASP .eng file, from (0, 0) as the Rust reader reads them."""
    rows = []
    lines = [l.split(";")[0].split() for l in path.read_text().splitlines()]
    lines = [l for l in lines if l]
    for fields in lines[1:]:  # lines[0] is the header
        rows.append((float(fields[0]), float(fields[1])))
    if rows[0][0] > 0:
        rows.insert(0, (0.0, 0.0))
    x, y = zip(*rows)
    return np.array(x), np.array(y)


def write_wiggle(path):
    """A data set that exercises every branch of PCHIP: uneven spacing, flat runs, turns,
    chords of both signs, a steep end; values rounded to 6 digits so the file reads well."""
    rng = np.random.default_rng(20261126)
    x = np.round(np.cumsum(rng.uniform(0.05, 1.0, 40)) - 3.0, 6)
    y = np.round(rng.normal(0.0, 50.0, 40).cumsum(), 6)
    y[10:13] = y[10]  # a flat run: zero chords
    y[20] = y[19]  # one flat chord between turns
    y[-1] = y[-2] + 400.0  # a steep last chord
    with path.open("w") as f:
        f.write("# Made by scipy_reference.py (seeded); see there.\nargument,value\n")
        for a, b in zip(x, y):
            f.write(f"{float(a)!r},{float(b)!r}\n")
    return x, y


def write_reference(path, x, y):
    knots = set(x.tolist())
    # The two ends are knots: the union has SAMPLES arguments unless a grid point hits a knot.
    grid = np.linspace(x[0], x[-1], SAMPLES - len(x) + 2)
    samples = np.array(sorted(knots.union(grid.tolist())))
    assert len(samples) == SAMPLES, len(samples)
    pchip = PchipInterpolator(x, y)
    spline = CubicSpline(x, y, bc_type="natural")
    columns = [samples, pchip(samples), pchip(samples, 1), spline(samples), spline(samples, 1)]
    with path.open("w") as f:
        f.write(f"# SciPy {scipy.__version__}, NumPy {np.__version__}: made by scipy_reference.py\n")
        f.write("x,pchip,pchip_slope,spline,spline_slope\n")
        for row in zip(*columns):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def main():
    x, y = read_rasp(ROOT / "models" / "motors" / "Cesaroni_M1670.eng")
    write_reference(HERE / "m1670_scipy.csv", x, y)
    x, y = write_wiggle(HERE / "wiggle.csv")
    write_reference(HERE / "wiggle_scipy.csv", x, y)


if __name__ == "__main__":
    main()
