#!/usr/bin/env python3
"""Forward sensitivities: varmass against heyoka's variational equations (issue 37; not in CI).

Two problems, each with its sensitivities at the end of the run:
- the paper's sled (m = m0 + c x, from rest) to a fixed time, 7.18 s, when it is near 50 m
  (no event), the derivatives of (x, p) with respect to the scooping rate c and the initial
  momentum p0;
- Kepler e = 0.5 over three orbits in polar coordinates (r, θ, p_r, p_θ), the derivatives of
  the final state with respect to the initial one (the state-transition matrix).

heyoka: `var_ode_sys(sys, args, order=1)` and `taylor_adaptive` (Taylor's method on the
variational equations heyoka derives), c a runtime parameter. Ours: `Sensitive` on the Taylor
stepper (the recurrences over tangents) and on DOP853, by our binary `peers_sensitivities`
(benches/peers/ours_sensitivities.rs) kept running. Both sides integrate the same ODE (the
state rates of benches/peers/heyoka.py, checked there against ours).

Timing as benches/peers/heyoka.py times the plain runs: heyoka from Python around
`propagate_until`, the integrator made once and reset before each run, the fastest of 3 to
1000 runs over about 0.15 s, *less* its fastest empty call (`propagate_until(0.0)`,
interleaved): heyoka net, a lower bound on its cost; ours inside Rust, nothing subtracted.
Every round runs all points (problem × tolerance × side) in a shuffled order; each point
keeps its fastest round.

Error: the largest entry of |S − S_ref| over the largest |S_ref| (normwise relative, as one
norm over state and columns measures: small columns' relative errors do not show). The
references are independent of both codes: the sled's variational equations derived by hand
(below) integrated by mpmath's Taylor solver (`odefun`) at 30 digits; Kepler's from the
exact orbit (orbital elements, Kepler's equation) at 60 digits, differentiated by central
differences of step 1e-25. A method's time at a target error is read off its own curve
(log time interpolated linearly in log error between the two tolerances that bracket it).

Setup, from the repository root:

    python3 -m venv target/venv-heyoka
    target/venv-heyoka/bin/pip install heyoka numpy mpmath
    target/venv-heyoka/bin/python benches/peers/heyoka_sensitivities.py [--rounds 3] [--seed N]

It writes docs/bench/heyoka_sensitivities.md.
"""

import argparse
import math
import platform
import random
import subprocess
import sys
import time
from pathlib import Path

# This directory holds heyoka.py: keep it off the path, or `import heyoka` imports that.
sys.path = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import heyoka as hy  # noqa: E402
import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PAGE = ROOT / "docs" / "bench" / "heyoka_sensitivities.md"

TARGETS = [1e-6, 1e-9, 1e-12]
HEYOKA_TOLERANCES = [10.0**-k for k in range(4, 17)]
OUR_METHODS = {"taylor": 15, "dop853": 13}

# The sled of benches/peers/heyoka.py (common::problems::SledProblem::standard).
M0, C, G, THETA, FD = 20.0, 4.0, 9.81, 0.5, 0.1
DRIVE = G * (math.sin(THETA) - FD * math.cos(THETA))
# Kepler (common::problems::KeplerProblem::standard).
MK, K, A, E = 1.5, 1.0, 1.0, 0.5


class Ours:
    """Our binary, one point per request."""

    def __init__(self):
        self.proc = subprocess.Popen(
            ["cargo", "bench", "-q", "-p", "varmass-benches", "--bench", "peers_sensitivities"],
            cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def point(self, problem, method, tol):
        self.proc.stdin.write(f"{problem} {method} {tol:e}\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline().rstrip("\n").split("\t")
        if len(line) < 7:
            sys.exit(f"our binary did not answer {problem} {method} {tol:e}: {line}")
        end, seconds, steps = float(line[3]), float(line[4]), int(line[5])
        return end, seconds, steps, np.array([float(x) for x in line[6:]])

    def close(self):
        self.proc.stdin.close()
        self.proc.wait()


# ------------------------------------------------------------------------------ problems
def sled_system():
    x, p = hy.make_vars("x", "p")
    m = M0 + hy.par[0] * x
    # ẋ = p/m; the true ṗ = m g (sin θ − f_d cos θ) (impact −c ẋ² and flux +c ẋ² cancel).
    sys_ = [(x, p / m), (p, m * DRIVE)]
    return hy.var_ode_sys(sys_, [hy.par[0], p], order=1), [0.0, 0.0], [C]


def kepler_system():
    r, th, pr, pth = hy.make_vars("r", "th", "pr", "pth")
    rhs = [pr / MK, pth / (MK * r * r), pth * pth / (MK * r**3) - K * MK / (r * r), 0.0 * r]
    start = [A * (1 - E), 0.0, 0.0, MK * math.sqrt(K * A * (1 - E * E))]
    return hy.var_ode_sys(list(zip([r, th, pr, pth], rhs)), hy.var_args.vars, order=1), start, []


def sled_reference(end):
    """∂(x, p)/∂(c, p0) at `end` in 30 digits. With m = m0 + c x, ẋ = p/m, ṗ = m D:
    ∂ẋ/∂x = −p c/m², ∂ẋ/∂p = 1/m, ∂ẋ/∂c = −p x/m², ∂ṗ/∂x = c D, ∂ṗ/∂c = x D; the columns
    s' = J s (+ ∂f/∂c for c), s(0) = 0 for c and e_p for p0."""
    mp.mp.dps = 30
    drive = mp.mpf(DRIVE)

    def rates(t, y):
        x, p, xc, pc, xp, pp = y
        m = M0 + C * x
        dxx, dxp, dxc = -p * C / m**2, 1 / m, -p * x / m**2
        dpx, dpc = C * drive, x * drive
        return [p / m, m * drive, dxx * xc + dxp * pc + dxc, dpx * xc + dpc,
                dxx * xp + dxp * pp, dpx * xp]

    y = mp.odefun(rates, 0, [mp.mpf(0)] * 5 + [mp.mpf(1)])(mp.mpf(end))
    return np.array([float(v) for v in (y[2], y[4], y[3], y[5])])


def kepler_propagate(state, end):
    """(r, θ, p_r, p_θ) at `end` on the exact orbit through `state` (mpmath numbers; θ
    unwrapped), through the orbital elements and Kepler's equation."""
    r, th, pr, pth = state
    m, mu = mp.mpf(MK), mp.mpf(K)
    rdot, h = pr / m, pth / m
    energy = (rdot**2 + (h / r) ** 2) / 2 - mu / r
    a = -mu / (2 * energy)
    ecos, esin = h * h / (mu * r) - 1, h * rdot / mu
    e = mp.sqrt(ecos**2 + esin**2)
    f0 = mp.atan2(esin, ecos)
    beta = e / (1 + mp.sqrt(1 - e * e))
    e0 = 2 * mp.atan2(mp.sqrt(1 - e) * mp.sin(f0 / 2), mp.sqrt(1 + e) * mp.cos(f0 / 2))
    mean = e0 - e * mp.sin(e0) + mp.sqrt(mu / a**3) * end
    anomaly = mp.findroot(lambda x: x - e * mp.sin(x) - mean, mean)
    f = anomaly + 2 * mp.atan(beta * mp.sin(anomaly) / (1 - beta * mp.cos(anomaly)))
    f0 = e0 + 2 * mp.atan(beta * mp.sin(e0) / (1 - beta * mp.cos(e0)))
    radius = a * (1 - e * mp.cos(anomaly))
    rate = mp.sqrt(mu * a) / radius * e * mp.sin(anomaly)
    return [radius, th + f - f0, m * rate, pth]


def kepler_reference(start, end):
    """The state-transition matrix ∂y(end)/∂y(0), row by row, by central differences of the
    exact orbit at 60 digits, step 1e-25 (truncation ~1e-50, rounding ~1e-35)."""
    mp.mp.dps = 60
    y0, h = [mp.mpf(x) for x in start], mp.mpf("1e-25")
    end = mp.mpf(end)
    columns = []
    for j in range(4):
        up, down = list(y0), list(y0)
        up[j] += h
        down[j] -= h
        a, b = kepler_propagate(up, end), kepler_propagate(down, end)
        columns.append([(u - d) / (2 * h) for u, d in zip(a, b)])
    return np.array([float(columns[j][i]) for i in range(4) for j in range(4)])


def error(ours, reference):
    return float(np.max(np.abs(ours - reference)) / np.max(np.abs(reference)))


# ------------------------------------------------------------------------------ timing
def time_heyoka(ta, initial, n, end, budget=0.15):
    """The fastest run, the fastest empty call, and the final sensitivities, each run from
    `initial` (the state and the variational equations' initial values, as heyoka set them
    when the integrator was made; `n` the state's length)."""
    best, empty, runs, began = math.inf, math.inf, 0, time.perf_counter()
    while runs < 3 or (time.perf_counter() - began < budget and runs < 1000):
        ta.time = 0.0
        ta.state[:] = initial
        t0 = time.perf_counter()
        outcome = ta.propagate_until(0.0)
        empty = min(empty, time.perf_counter() - t0)
        if outcome[3] != 0:
            sys.exit("heyoka's empty call took a step")
        ta.time = 0.0
        ta.state[:] = initial
        t0 = time.perf_counter()
        outcome = ta.propagate_until(end)
        best = min(best, time.perf_counter() - t0)
        if outcome[0] != hy.taylor_outcome.time_limit:
            sys.exit(f"heyoka's run ended with {outcome[0]}")
        runs += 1
    return best, empty, outcome[3], ta.state[n:].copy()


def at_error(points, target):
    """Seconds at `target` from (tolerance, error, seconds) points: a number, or why not."""
    points = sorted(points, key=lambda p: -p[0])
    for (t1, e1, s1), (t2, e2, s2) in zip(points, points[1:]):
        if e1 >= target >= e2 and e1 > e2 > 0:
            w = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(s1) + w * (math.log(s2) - math.log(s1)))
    if points and target > points[0][1]:
        return "looser"
    return "not reached"


def measure(ours, rounds, rng):
    """Every point, `rounds` times in shuffled orders: the best (seconds, error, steps)."""
    systems = {"sled": sled_system(), "kepler": kepler_system()}
    # Our end times: heyoka runs to them and the references are taken there.
    ends = {name: ours.point(name, "taylor", 1e-9)[0] for name in systems}
    references = {"sled": sled_reference(ends["sled"]),
                  "kepler": kepler_reference(systems["kepler"][1], ends["kepler"])}
    integrators = {}
    for name, (var_sys, start, pars) in systems.items():
        for tol in HEYOKA_TOLERANCES:
            ta = hy.taylor_adaptive(var_sys, start, pars=pars, tol=tol)
            integrators[name, tol] = (ta, ta.state.copy(), len(start))
    points = [(name, "heyoka", tol) for name in systems for tol in HEYOKA_TOLERANCES]
    points += [(name, method, 10.0**-k) for name in systems
               for method, tightest in OUR_METHODS.items() for k in range(4, tightest + 1)]
    best = {}
    for _ in range(rounds):
        rng.shuffle(points)
        for name, side, tol in points:
            if side == "heyoka":
                ta, initial, n = integrators[name, tol]
                run, empty, steps, s = time_heyoka(ta, initial, n, ends[name])
                # Net, and raw as a second side of its own.
                keep(best, (name, "heyoka raw", tol), (run, error(s, references[name]), steps))
                seconds = max(run - empty, 1e-9)
            else:
                _, seconds, steps, s = ours.point(name, side, tol)
            keep(best, (name, side, tol), (seconds, error(s, references[name]), steps))
    return best, ends


def keep(best, key, point):
    """Keeps the fastest round of a point."""
    if key not in best or point[0] < best[key][0]:
        best[key] = point


# ------------------------------------------------------------------------------ the page
def show(x):
    return f"{x * 1e6:.1f} µs" if isinstance(x, float) else x


def tables(best):
    lines = []
    for name in ["sled", "kepler"]:
        lines += [f"### {name}", "", "| target error | heyoka net (raw) | ours Taylor | ratio "
                  "to net (raw) | ours DOP853 | ratio to net |", "|---|---|---|---|---|---|"]
        sides = ["heyoka", "heyoka raw", "taylor", "dop853"]
        curve = {side: [(tol, e, s) for (n, sd, tol), (s, e, _) in best.items()
                        if n == name and sd == side] for side in sides}
        ratio = lambda a, b: f"{a / b:.2f}" if isinstance(a, float) and isinstance(b, float) \
            else "–"  # noqa: E731
        for target in TARGETS:
            h, raw = at_error(curve["heyoka"], target), at_error(curve["heyoka raw"], target)
            taylor, dop = at_error(curve["taylor"], target), at_error(curve["dop853"], target)
            row = [f"{target:.0e}", f"{show(h)} ({show(raw)})", show(taylor),
                   f"{ratio(taylor, h)} ({ratio(taylor, raw)})", show(dop), ratio(dop, h)]
            lines.append("| " + " | ".join(row) + " |")
        lines += ["", "| side | tolerance | error | steps | time |", "|---|---|---|---|---|"]
        for (n, side, tol), (s, e, steps) in sorted(best.items()):
            if n == name:
                lines.append(f"| {side} | {tol:.0e} | {e:.1e} | {steps} | {show(s)} |")
        lines.append("")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seed", type=int, default=random.randrange(2**32))
    args = parser.parse_args()
    rng = random.Random(args.seed)
    ours = Ours()
    try:
        best, ends = measure(ours, args.rounds, rng)
    finally:
        ours.close()
    head = [
        "# Forward sensitivities: varmass against heyoka's variational equations",
        "",
        "Made by `benches/peers/heyoka_sensitivities.py` (its docstring: the method, the "
        "references, how each side is timed); do not edit by hand.",
        "",
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, heyoka {hy.__version__}, "
        f"Python {platform.python_version()}, {args.rounds} rounds, seed {args.seed}; "
        f"sled to t = {ends['sled']:.6f} s (x ≈ 50 m), Kepler to t = {ends['kepler']:.6f}.",
        "",
        "Time at a target error (normwise relative error of the sensitivities at the end): "
        "heyoka net of its empty call (raw in brackets: its run as timed from Python); "
        "ratio = ours ÷ heyoka (below 1: ours faster).",
        "",
    ]
    PAGE.write_text("\n".join(head + tables(best)) + "\n")
    print(PAGE.read_text())


if __name__ == "__main__":
    main()
