#!/usr/bin/env python3
"""heyoka against varmass at equal achieved error (issues 25 and 38; not in CI).

Runs heyoka (Taylor's method, LLVM JIT) and our bench binary `peers` (the Taylor stepper on
the emitted recurrences, and DOP853; on Kepler also the Taylor stepper with its
double-double head, `taylor-head`, in rows of its own) on the same four problems in one
session. Every round shuffles all points (problem × tolerance × side; the seed is printed
and written to the page) and runs them in that order, our points answered one by one by
our binary kept running (`peers -- serve`); each point keeps its fastest round.

How each side is timed (issue 38):
- heyoka: from Python, `time.perf_counter()` around `ta.propagate_until(end)`, the
  integrator made once (before the rounds) and its time and state reset before each run;
  the fastest of 3 to 1000 runs over about 0.15 s. Interleaved with those runs, the same
  integrator's *empty call*, `ta.propagate_until(0.0)` at t = 0 (no step: the outcome's
  step count is checked to be 0), timed the same way. "heyoka net" is the fastest run less
  the fastest empty call: the binding's entry and exit, the timer and heyoka's own set-up
  of a propagation are all taken off, so heyoka net is a lower bound on its cost as a
  caller in C++ would see it, and the equalised ratio leans heyoka's way; the raw ratio
  leans ours.
- ours: inside Rust (benches/common/timing.rs), `Instant` around one run of a stepper made
  once and restarted (restart, stop time, steps), the fastest of 3 to 1000 runs over about
  0.15 s; DOP853 is made afresh in each run (it allocates nothing). Nothing is subtracted.
Each method's time at a target error is read off its own curve (log time interpolated
linearly in log error between the two tolerances that bracket the target, the first such
pair as the tolerance tightens).

References, none from varmass: the sled's closed form v(x) (eq. 24) at the numerical x, in
40 digits; the rocket's closed form at 15 s, in 40 digits; Kepler's exact orbit through the initial state as stored, in 40 digits; the
3-link pendulum's final state from benches/peers/pendulum3_reference.txt, made by
benches/peers/pendulum3_reference.py (sympy from the Lagrangian, heyoka's Taylor in 256-bit
arithmetic). Our order-30 Taylor reference (`peers -- rates`) is compared with it and the
gap printed.

Construction: heyoka JIT-compiles one integrator per problem and tolerance, and caches the
code in memory and (heyoka.py ≥ 7.10) on disk. Timed: in a new Python process (after
`import heyoka`, not timed) with the on-disk cache off, and again reading an on-disk cache
a first new process wrote; in this session, with the on-disk cache off, the first
construction of each integrator (made before the rounds, in shuffled order) and a second
one at once (from the in-memory cache). Ours is compiled ahead
(benches/peers/compile_cost.sh times it; its last result is put on the page).

The ODEs typed into heyoka here are our derived state rates; before timing, heyoka's
right-hand side is evaluated at a state our binary prints (`peers -- rates`) and must agree
to 1e-14, and so must the pendulum's independent sympy derivation.

Setup, from the repository root:

    python3 -m venv target/venv-heyoka
    target/venv-heyoka/bin/pip install heyoka numpy mpmath sympy
    target/venv-heyoka/bin/python benches/peers/heyoka.py [--rounds 5] [--seed N]
    target/venv-heyoka/bin/python benches/peers/heyoka.py --kepler-floor  # heyoka alone

Problems: the paper's sled to 50 m (m = m0 + c x; error |v − v(x)|/v(x)), Kepler e = 0.5
over three orbits (error: position over a, velocity over √(k/a)), the vertical rocket
m = m0 − μ t to 15 s (error: largest relative error of height, speed and mass), the planar
3-link pendulum over 10 s (error: largest state difference).

Kepler's reference is the exact orbit through the initial state as stored (mpmath):
p_θ = m √(k a (1 − e²)) rounds by 2.8e-17 relative, which moves the energy by 1.7e-16 and
the phase after three orbits by 4.7e-15, 8e-15 in position at the periapsis where the run
ends. Against the nominal orbit (a = 1, e = 0.5, the row "nominal") that rounding of the
start, common to every method, is a floor near 1e-14 that hides the integrators' own
errors; the equal-error table uses the exact reference for both methods alike.
"""

import argparse
import math
import os
import random
import subprocess
import sys
import time
from pathlib import Path

# This file is named heyoka.py: keep its own directory off the path, or it imports itself.
sys.path = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import heyoka as hy  # noqa: E402
import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

TARGETS = [1e-6, 1e-9, 1e-12, 1e-14]
HEAD_TARGETS = [1e-12, 1e-14, 5e-15]
HEYOKA_TOLERANCES = [10.0**-k for k in range(4, 17)]
# Ours: method -> tightest k of 10⁻ᵏ (Taylor refuses a relative tolerance below 1e-15,
# DOP853 below 100 machine epsilons); taylor-head on Kepler only.
OUR_METHODS = {"taylor": 15, "dop853": 13, "taylor-head": 15}
CONSTRUCT_TOLERANCES = [1e-9, 1e-12, 1e-15]


def ours(*args):
    """Runs our bench binary and returns its tab-separated lines."""
    out = subprocess.run(
        ["cargo", "bench", "-q", "-p", "varmass-benches", "--bench", "peers", "--", *args],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return [line.split("\t") for line in out.splitlines() if "\t" in line]


class Ours:
    """Our binary in `serve` mode: one point per request."""

    def __init__(self):
        self.proc = subprocess.Popen(
            ["cargo", "bench", "-q", "-p", "varmass-benches", "--bench", "peers", "--",
             "serve"],
            cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def point(self, problem, method, tol):
        self.proc.stdin.write(f"{problem} {method} {tol:e}\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline().rstrip("\n").split("\t")
        if len(line) < 7:
            sys.exit(f"our binary did not answer {problem} {method} {tol:e}: {line}")
        return np.array([float(x) for x in line[6:]]), float(line[4])

    def close(self):
        self.proc.stdin.close()
        self.proc.wait()


# ------------------------------------------------------------------------------ problems
# The sled's DRIVE is a double computed as our Rust side computes g (sin θ − f_d cos θ); the
# closed form is then evaluated in 40 digits with it.
M0, C, G, THETA, FD = 20.0, 4.0, 9.81, 0.5, 0.1
DRIVE = G * (math.sin(THETA) - FD * math.cos(THETA))


def sled_speed(x):
    eps = C * x / M0
    return math.sqrt(x * 2.0 / 3.0 * DRIVE * (3 + 3 * eps + eps * eps) / (1 + eps) ** 2)


def sled_time_to(distance, panels=2048):
    top = math.sqrt(distance)
    h = top / panels

    def f(u):
        x = u * u
        eps = C * x / M0
        return 2.0 / math.sqrt(2.0 / 3.0 * DRIVE * (3 + 3 * eps + eps * eps) / (1 + eps) ** 2)

    interior = sum((4 if i % 2 else 2) * f(i * h) for i in range(1, panels))
    return h / 3 * (f(0) + interior + f(top))


def sled():
    x, p = hy.make_vars("x", "p")
    m = M0 + C * x
    # ẋ = p/m; the true ṗ = m g (sin θ − f_d cos θ) (impact −c ẋ² and flux +c ẋ² cancel).
    rhs = [p / m, m * DRIVE]

    def error(y):
        # In 40 digits: v = p/m at the numerical x against the closed form v(x) there.
        import mpmath as mp

        mp.mp.dps = 40
        x, p = mp.mpf(float(y[0])), mp.mpf(float(y[1]))
        eps = C * x / M0
        exact = mp.sqrt(x * 2 / mp.mpf(3) * mp.mpf(DRIVE) * (3 + 3 * eps + eps * eps)
                        / (1 + eps) ** 2)
        return float(abs(p / (M0 + C * x) - exact) / exact)

    return dict(vars=[x, p], rhs=rhs, start=[0.0, 0.0], end=sled_time_to(50.0), error=error)


MK, K, A, E = 1.5, 1.0, 1.0, 0.5


def kepler_cartesian_exact(t):
    n = math.sqrt(K / A**3)
    mean = n * t
    anomaly = mean
    for _ in range(50):
        step = (anomaly - E * math.sin(anomaly) - mean) / (1 - E * math.cos(anomaly))
        anomaly -= step
        if abs(step) < 1e-16:
            break
    rate = n / (1 - E * math.cos(anomaly))
    b = A * math.sqrt(1 - E * E)
    return np.array(
        [A * (math.cos(anomaly) - E), b * math.sin(anomaly),
         -A * math.sin(anomaly) * rate, b * math.cos(anomaly) * rate]
    )


def kepler_exact_through(start, end):
    """(x, y, ẋ, ẏ) at `end` on the orbit through the polar `start` as stored (doubles, at
    periapsis: θ = 0, p_r = 0), to 40 digits, as mpmath numbers."""
    import mpmath as mp

    mp.mp.dps = 40
    r0, th0, pr0, pth0 = (mp.mpf(x) for x in start)
    assert th0 == 0 and pr0 == 0, "the reference starts at periapsis"
    m, k = mp.mpf(MK), mp.mpf(K)
    h = pth0 / m  # angular momentum per unit mass
    a = -k / (2 * (h * h / (2 * r0 * r0) - k / r0))
    e = 1 - r0 / a
    n = mp.sqrt(k / a**3)
    mean = n * mp.mpf(end)
    anomaly = mp.findroot(lambda x: x - e * mp.sin(x) - mean, mean)
    rate = n / (1 - e * mp.cos(anomaly))
    b = a * mp.sqrt(1 - e * e)
    return [a * (mp.cos(anomaly) - e), b * mp.sin(anomaly),
            -a * mp.sin(anomaly) * rate, b * mp.cos(anomaly) * rate]


def kepler():
    r, th, pr, pth = hy.make_vars("r", "th", "pr", "pth")
    rhs = [pr / MK, pth / (MK * r * r), pth * pth / (MK * r**3) - K * MK / (r * r), 0.0 * r]
    end = 3 * 2 * math.pi * math.sqrt(A**3 / K)

    start = [A * (1 - E), 0.0, 0.0, MK * math.sqrt(K * A * (1 - E * E))]
    exact = kepler_exact_through(start, end)

    def error(y):
        import mpmath as mp

        mp.mp.dps = 40
        rr, t = mp.mpf(float(y[0])), mp.mpf(float(y[1]))
        dr, dth = mp.mpf(float(y[2])) / MK, mp.mpf(float(y[3])) / (MK * rr * rr)
        cart = [rr * mp.cos(t), rr * mp.sin(t),
                dr * mp.cos(t) - rr * dth * mp.sin(t),
                dr * mp.sin(t) + rr * dth * mp.cos(t)]
        d = [float(c - x) for c, x in zip(cart, exact)]
        return max(math.hypot(d[0], d[1]) / A, math.hypot(d[2], d[3]) / math.sqrt(K / A))

    def nominal(y):
        rr, t, dr, dth = y[0], y[1], y[2] / MK, y[3] / (MK * y[0] ** 2)
        cart = np.array([rr * math.cos(t), rr * math.sin(t),
                         dr * math.cos(t) - rr * dth * math.sin(t),
                         dr * math.sin(t) + rr * dth * math.cos(t)])
        d = cart - kepler_cartesian_exact(end)
        return max(np.linalg.norm(d[:2]) / A, np.linalg.norm(d[2:]) / math.sqrt(K / A))

    return dict(vars=[r, th, pr, pth], rhs=rhs, start=start, end=end, error=error,
                nominal=nominal)


MU, UE, M_ROCKET, T_ROCKET = 0.05, 300.0, 1.0, 15.0


def rocket():
    """The vertical rocket from rest, m = m0 − μ t (issue 38's fourth scalar problem), state
    (y, p = m ẏ, m) as ours: ẏ = p/m, ṗ = −μ p/m + μ u_e − m g, ṁ = −μ, to 15 s (three
    quarters of the mass burnt). Error: the largest relative error of y, v = p/m and m
    against the closed form v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t²,
    in 40 digits."""
    y, p, m = hy.make_vars("y", "p", "m")
    rhs = [p / m, -MU * (p / m) + MU * UE - m * G, -MU + 0.0 * m]

    def error(state):
        import mpmath as mp

        mp.mp.dps = 40
        t, mu, ue, g, m0 = (mp.mpf(x) for x in (T_ROCKET, MU, UE, G, M_ROCKET))
        mass = m0 - mu * t
        log_ratio = mp.log(m0 / mass)
        exact = [ue * (t - mass / mu * log_ratio) - g * t * t / 2, ue * log_ratio - g * t, mass]
        yy, pp, mm = (mp.mpf(float(x)) for x in state)
        return float(max(abs(n - e) / abs(e) for n, e in zip([yy, pp / mm, mm], exact)))

    return dict(vars=[y, p, m], rhs=rhs, start=[0.0, 0.0, M_ROCKET], end=T_ROCKET, error=error)


def pendulum3(reference):
    a = hy.make_vars("a1", "a2", "a3")
    p = hy.make_vars("p1", "p2", "p3")
    m, l, g = 1.0, 1.0, 9.81
    w = [[3 - max(i, j) for j in range(3)] for i in range(3)]
    M = [[m * l * l * w[i][j] * hy.cos(a[i] - a[j]) if i != j else m * l * l * w[i][i]
          for j in range(3)] for i in range(3)]
    # q̇ = M⁻¹ p by the adjugate.
    cof = [[M[(j + 1) % 3][(i + 1) % 3] * M[(j + 2) % 3][(i + 2) % 3]
            - M[(j + 1) % 3][(i + 2) % 3] * M[(j + 2) % 3][(i + 1) % 3]
            for j in range(3)] for i in range(3)]
    det = M[0][0] * cof[0][0] + M[0][1] * cof[1][0] + M[0][2] * cof[2][0]
    v = [sum(cof[i][j] * p[j] for j in range(3)) / det for i in range(3)]
    # ṗ_k = ∂L/∂a_k = −m l² ȧ_k Σ_j w_kj sin(a_k − a_j) ȧ_j − m g l (3 − k) sin a_k.
    pdot = [-m * l * l * v[k] * sum(w[k][j] * hy.sin(a[k] - a[j]) * v[j]
                                    for j in range(3) if j != k)
            - m * g * l * (3 - k) * hy.sin(a[k]) for k in range(3)]

    def error(y):
        # The largest state difference, in 40 digits, against the independent reference.
        import mpmath as mp

        mp.mp.dps = 40
        return float(max(abs(mp.mpf(float(x)) - r) for x, r in zip(y, reference)))

    start = [0.6, -0.4, 0.3, 0.0, 0.0, 0.0]
    return dict(vars=[*a, *p], rhs=v + pdot, start=start, end=10.0, error=error)




def independent_pendulum3():
    """The independent reference (benches/peers/pendulum3_reference.txt, made by
    pendulum3_reference.py) as mpmath numbers, and that script as a module."""
    import importlib.util

    import mpmath as mp

    mp.mp.dps = 40
    lines = (HERE / "pendulum3_reference.txt").read_text().splitlines()
    values = [mp.mpf(x) for x in lines if x.strip() and not x.startswith("#")]
    spec = importlib.util.spec_from_file_location("pendulum3_reference",
                                                  HERE / "pendulum3_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return values, module


# ------------------------------------------------------------------------------ session
def check_rates(name, problem, rates):
    """heyoka's right-hand side against ours at the state our binary printed."""
    state = np.array([float(x) for x in rates[(name, "state")]])
    expected = np.array([float(x) for x in rates[(name, "rate")]])
    make = getattr(hy, "cfunc", None) or hy.make_cfunc
    try:
        cf = make(problem["rhs"], problem["vars"])
    except TypeError:
        cf = make(problem["rhs"], vars=problem["vars"])
    got = np.asarray(cf(state))
    gap = float(np.max(np.abs(got - expected)) / max(1.0, float(np.max(np.abs(expected)))))
    print(f"{name}: heyoka's rate vs ours at a test state: relative gap {gap:.1e}")
    if gap > 1e-14:
        sys.exit(f"{name}: the ODEs differ")
    return gap


def build(problem, tol):
    """heyoka's integrator for `problem` at `tol`, and the seconds its construction took."""
    began = time.perf_counter()
    ta = hy.taylor_adaptive(list(zip(problem["vars"], problem["rhs"])), problem["start"], tol=tol)
    return ta, time.perf_counter() - began


def time_heyoka(ta, problem, budget=0.15):
    """The fastest run and the fastest empty call (interleaved), and the last final state."""
    best, empty, runs, began = math.inf, math.inf, 0, time.perf_counter()
    while runs < 3 or (time.perf_counter() - began < budget and runs < 1000):
        ta.time = 0.0
        ta.state[:] = problem["start"]
        t0 = time.perf_counter()
        outcome = ta.propagate_until(0.0)
        empty = min(empty, time.perf_counter() - t0)
        if outcome[3] != 0:
            sys.exit("heyoka's empty call took a step")
        ta.time = 0.0
        ta.state[:] = problem["start"]
        t0 = time.perf_counter()
        ta.propagate_until(problem["end"])
        best = min(best, time.perf_counter() - t0)
        runs += 1
    return ta.state.copy(), best, empty


def bare_call(ta, runs=2000):
    """The fastest read of `ta.time` (a property: one binding call, no work), timed as the
    runs are: what of the empty call is the binding's and the timer's."""
    best = math.inf
    for _ in range(runs):
        t0 = time.perf_counter()
        ta.time
        best = min(best, time.perf_counter() - t0)
    return best


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


def kepler_floor():
    """heyoka's Kepler errors from 1e-14 to 1e-18 (issue 25's ≤ 5e-15; ours in
    `tests/kepler_floor.rs`): below 1e-14 they wander with rounding, as ours do."""
    problem = kepler()
    for tol in [10.0**-k for k in range(14, 19)]:
        ta = hy.taylor_adaptive(list(zip(problem["vars"], problem["rhs"])), problem["start"],
                                tol=tol)
        ta.propagate_until(problem["end"])
        print(f"kepler heyoka {tol:.0e}: order {ta.order}, error {problem['error'](ta.state):.1e}"
              f" (nominal orbit {problem['nominal'](ta.state):.1e})")


def construct_once(name, tol, cache):
    """`--construct NAME TOL CACHE`: one construction in this (fresh) process, heyoka's
    on-disk cache at CACHE (or disabled if CACHE is "off"); prints seconds."""
    if cache == "off":
        hy.llvm_state.set_diskcache_enabled(False)
    else:
        hy.llvm_state.set_diskcache_enabled(True)
        hy.llvm_state.set_diskcache_path(cache)
    problem = {"sled": sled, "kepler": kepler, "rocket": rocket,
               "pendulum3": lambda: pendulum3(independent_pendulum3()[0])}[name]()
    _, seconds = build(problem, tol)
    print(seconds)


def fresh_constructions(names, rng):
    """(problem, tol) -> (seconds in a new process with no on-disk cache, seconds in a new
    process reading the on-disk cache a first such process wrote)."""
    import shutil
    import tempfile

    keys = [(n, t) for n in names for t in CONSTRUCT_TOLERANCES]
    rng.shuffle(keys)
    out = {}
    for name, tol in keys:
        cache = tempfile.mkdtemp(prefix="heyoka-cache-", dir=ROOT / "target")
        seconds = []
        for where in ["off", cache, cache]:
            run = subprocess.run([sys.executable, __file__, "--construct", name, repr(tol), where],
                                 check=True, capture_output=True, text=True)
            seconds.append(float(run.stdout.split()[-1]))
        shutil.rmtree(cache)
        # seconds[1] wrote the cache (a cold build too); seconds[2] read it.
        out[(name, tol)] = (min(seconds[0], seconds[1]), seconds[2])
    return out


def measure(problems, rounds, rng):
    """The shuffled session: constructions, then the rounds. Returns best, nominal,
    construction, orders and loads."""
    tasks = [(n, "heyoka", t) for n in problems for t in HEYOKA_TOLERANCES]
    tasks += [(n, m, 10.0**-k) for n in problems for m, top in OUR_METHODS.items()
              for k in range(4, top + 1) if m != "taylor-head" or n == "kepler"]
    integrators, construction, orders = {}, {}, {}
    # No on-disk cache in this process: its first construction of an integrator is a JIT,
    # the second comes from heyoka's in-memory cache.
    hy.llvm_state.set_diskcache_enabled(False)
    keys = [(n, t) for n in problems for t in HEYOKA_TOLERANCES]
    rng.shuffle(keys)
    for key in keys:
        integrators[key], first = build(problems[key[0]], key[1])
        _, cached = build(problems[key[0]], key[1])
        construction[key] = (first, cached)
        orders[key] = integrators[key].order
    best = {}  # (problem, method, tol) -> (error, seconds, heyoka's empty call)
    nominal = {}  # (method, tol) -> Kepler's error against the nominal orbit
    ours_bin = Ours()
    load = [os.getloadavg()[0]]
    for round_ in range(rounds):
        rng.shuffle(tasks)
        for name, method, tol in tasks:
            problem = problems[name]
            if method == "heyoka":
                state, seconds, empty = time_heyoka(integrators[(name, tol)], problem)
            else:
                (state, seconds), empty = ours_bin.point(name, method, tol), 0.0
            key = (name, method, tol)
            error = problem["error"](state)
            if key not in best:
                best[key] = (error, seconds, empty)
            else:
                e, s, em = best[key]
                if seconds < s:
                    e, s = error, seconds
                best[key] = (e, s, min(em, empty))
            if "nominal" in problem:
                nominal[(method, tol)] = problem["nominal"](state)
        load.append(os.getloadavg()[0])
        print(f"round {round_ + 1} of {rounds} done", file=sys.stderr)
    ours_bin.close()
    bare = {name: bare_call(integrators[(name, 1e-12)]) for name in problems}
    return best, nominal, construction, orders, load, bare


def show(x):
    return x if isinstance(x, str) else f"{x * 1e6:.2f}"


def ratio(x, h):
    return "–" if isinstance(x, str) or isinstance(h, str) else f"{x / h:.2f}"


def speed_table(problems, best, nominal):
    rows = ["| problem | error | heyoka µs | heyoka's empty call µs | heyoka net µs | Taylor µs "
            "| Taylor ÷ heyoka, raw | Taylor ÷ heyoka, equalised | DOP853 ÷ heyoka, raw "
            "| DOP853 ÷ heyoka, equalised |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for name in problems:
        curves, net = {}, []
        for (p, method, tol), (error, seconds, empty) in best.items():
            if p == name:
                curves.setdefault(method, []).append((tol, error, seconds))
                if method == "heyoka":
                    net.append((tol, error, seconds - empty))
        curves["heyoka net"] = net

        def line(label, targets, taylor):
            for target in targets:
                t = {m: at_error(c, target) for m, c in curves.items()}
                h, n = t["heyoka"], t["heyoka net"]
                empty = "–" if isinstance(h, str) or isinstance(n, str) else show(h - n)
                d = t.get("dop853", "–") if taylor == "taylor" else "–"
                rows.append(f"| {label} | {target:.0e} | {show(h)} | {empty} | {show(n)} | "
                            f"{show(t[taylor])} | {ratio(t[taylor], h)} | {ratio(t[taylor], n)} | "
                            f"{ratio(d, h)} | {ratio(d, n)} |")

        line(name, TARGETS, "taylor")
        if "taylor-head" in curves:
            # The Taylor stepper with its double-double head (Kepler only), at the tight
            # targets, 5e-15 being issue 25's "reached to".
            line(f"{name}, Taylor with its head", HEAD_TARGETS, "taylor-head")
        floor = {m: min(e for _, e, _ in c) for m, c in curves.items() if m != "heyoka net"}
        rows.append(f"| {name} | smallest error reached | "
                    + ", ".join(f"{m} {e:.1e}" for m, e in sorted(floor.items()))
                    + " | | | | | | | |")
        if name == "kepler":
            worst = {}
            for (m, _), e in nominal.items():
                worst[m] = min(worst.get(m, math.inf), e)
            rows.append("| kepler | smallest error against the nominal orbit | "
                        + ", ".join(f"{m} {e:.1e}" for m, e in sorted(worst.items()))
                        + " | | | | | | | |")
    return "\n".join(rows)


def construction_table(problems, construction, orders, fresh):
    rows = ["| problem | heyoka tolerance | order | heyoka, new process, no cache ms "
            "| heyoka, new process, on-disk cache ms | heyoka, first in this session ms "
            "| heyoka, in-memory cache ms |",
            "|---|---|---|---|---|---|---|"]
    for name in problems:
        for tol in CONSTRUCT_TOLERANCES:
            first, cached = construction[(name, tol)]
            cold, disk = fresh[(name, tol)]
            rows.append(f"| {name} | {tol:.0e} | {orders[(name, tol)]} | {cold * 1e3:.1f} | "
                        f"{disk * 1e3:.1f} | {first * 1e3:.1f} | {cached * 1e3:.1f} |")
        firsts = [construction[(name, t)][0] for t in HEYOKA_TOLERANCES]
        cached = [construction[(name, t)][1] for t in HEYOKA_TOLERANCES]
        rows.append(f"| {name} | all 1e-4 … 1e-16 | "
                    f"{min(orders[(name, t)] for t in HEYOKA_TOLERANCES)}–"
                    f"{max(orders[(name, t)] for t in HEYOKA_TOLERANCES)} | | | "
                    f"{min(firsts) * 1e3:.1f}–{max(firsts) * 1e3:.1f} | "
                    f"{min(cached) * 1e3:.1f}–{max(cached) * 1e3:.1f} |")
    return "\n".join(rows)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=None)
    parser.add_argument("--kepler-floor", action="store_true",
                        help="print heyoka's Kepler errors at 1e-14 … 1e-18 and stop")
    parser.add_argument("--construct", nargs=3, metavar=("PROBLEM", "TOL", "CACHE"),
                        help="time one construction of heyoka's integrator and stop")
    parser.add_argument("--no-write", action="store_true", help="print, do not write the page")
    args = parser.parse_args()
    if args.kepler_floor:
        kepler_floor()
        return
    if args.construct:
        construct_once(args.construct[0], float(args.construct[1]), args.construct[2])
        return
    # No on-disk JIT cache in this session (see `measure`).
    hy.llvm_state.set_diskcache_enabled(False)
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(2**32)
    print(f"seed {seed}")
    rng = random.Random(seed)
    rates = {(r[0], r[1]): r[2:] for r in ours("rates")}
    reference, derivation = independent_pendulum3()
    problems = {"sled": sled(), "kepler": kepler(), "rocket": rocket(),
                "pendulum3": pendulum3(reference)}
    gaps = {name: check_rates(name, problem, rates) for name, problem in problems.items()}
    # The independent derivation's rates against ours.
    state = [float(x) for x in rates[("pendulum3", "state")]]
    expected = np.array([float(x) for x in rates[("pendulum3", "rate")]])
    sympy_gap = float(np.max(np.abs(np.array(derivation.rates_at(state)) - expected))
                      / max(1.0, float(np.max(np.abs(expected)))))
    print(f"pendulum3: sympy's Lagrangian derivation vs ours at a test state: {sympy_gap:.1e}")
    if sympy_gap > 1e-14:
        sys.exit("pendulum3: the independent derivation differs")
    ours_reference = [float(x) for x in rates[("pendulum3", "reference")]]
    ref_gap = problems["pendulum3"]["error"](ours_reference)
    print(f"pendulum3: our order-30 Taylor reference against the independent one: {ref_gap:.2e}")
    fresh = fresh_constructions(problems, rng)
    best, nominal, construction, orders, load, bare = measure(problems, args.rounds, rng)
    bare_text = ", ".join(f"{n} {b * 1e6:.2f}" for n, b in bare.items())
    print(f"a bare binding call (reading ta.time), µs: {bare_text}")
    speed = speed_table(problems, best, nominal)
    build_costs = construction_table(problems, construction, orders, fresh)
    loads = ", ".join(f"{x:.1f}" for x in load)
    print(speed)
    print(build_costs)
    print(f"load average (1 min) at the start and after each round: {loads}")
    if args.no_write:
        return
    compiled = ROOT / "target" / "peers-compile-cost" / "result.txt"
    ours_build = ("; ".join(compiled.read_text().splitlines()) if compiled.exists()
                  else "not measured (run `bash benches/peers/compile_cost.sh` first)")
    page = PAGE.format(
        rounds=args.rounds, seed=seed, version=hy.__version__, loads=loads,
        cores=os.cpu_count(), speed=speed, construction=build_costs, ref_gap=ref_gap,
        sympy_gap=sympy_gap, rate_gaps=", ".join(f"{n} {g:.1e}" for n, g in gaps.items()),
        ours_build=ours_build, bare=bare_text, date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        header=" ".join(line[2:] for line in
                        (HERE / "pendulum3_reference.txt").read_text().splitlines()
                        if line.startswith("#")))
    (ROOT / "docs" / "bench" / "heyoka.md").write_text(page)


PAGE = """# heyoka against varmass at equal achieved error

Written by `benches/peers/heyoka.py` ({date}; heyoka {version}; rounds: {rounds}, every
round all points — problem × tolerance × side — in an order shuffled with seed {seed}; the
fastest round per point; load average (1 min) at the start and after each round {loads} on
{cores} cores). Setup and options are in the script's docstring.

## How each side is timed

- **heyoka**: from Python, `time.perf_counter()` around `ta.propagate_until(end)`; the
  integrator is made once before the rounds, its time and state reset before each run; the
  fastest of 3 to 1000 runs over about 0.15 s. Interleaved with those runs, the same
  integrator's **empty call** (`ta.propagate_until(0.0)` at t = 0, which takes no step —
  checked) is timed the same way. **heyoka net** = fastest run − fastest empty call: the
  Python binding's entry and exit, the timer, and heyoka's own set-up of a propagation are
  all taken off, so it is a lower bound on what a C++ caller would measure. For scale, a
  bare binding call (reading `ta.time`, timed the same way, integrators at 1e-12) costs, in
  µs: {bare}; the rest of the empty call (most of it, and it grows with the order) is
  heyoka's own work on a call that takes no step and the building of its Python result.
- **ours**: inside Rust (`benches/common/timing.rs`), `Instant` around one run of a Taylor
  stepper made once and restarted (restart, stop time, the steps); DOP853 made afresh each
  run (it allocates nothing); the fastest of 3 to 1000 runs over about 0.15 s; our binary
  stays running (`peers -- serve`) and answers the points in the shuffled order. Nothing is
  subtracted on our side.
- The **raw** ratio (ours ÷ heyoka) leans our way (heyoka carries the Python call); the
  **equalised** ratio (ours ÷ heyoka net) leans heyoka's (its set-up is taken off, ours is
  not). The ratio a caller of both in one language would see lies between the two.

## References (none from varmass)

- **sled**: the closed form v(x) (eq. 24) at the numerical x, in 40 digits.
- **rocket** (m = m0 − μ t, m0 = 1, μ = 0.05, u_e = 300, g = 9.81, to 15 s): the closed form
  v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t², in 40 digits.
- **kepler**: the exact orbit through the initial state as stored, in 40 digits (mpmath;
  the "nominal orbit" row shows why: the stored p_θ is rounded).
- **pendulum3**: `benches/peers/pendulum3_reference.txt`, made by
  `benches/peers/pendulum3_reference.py`: the equations derived from the Lagrangian by
  sympy in that script and integrated by heyoka's Taylor method in 256-bit arithmetic.
  {header} Its right-hand side agrees with ours at a test state to {sympy_gap:.1e}
  (relative); heyoka's as typed into this script: {rate_gaps}. Our own order-30 Taylor
  reference (the one this page used before issue 38) is {ref_gap:.2e} from it.
  `pendulum3_reference.py --sensitivity` (deterministic, long double at tol 1e-19): that
  run is 1.46e-17 from the stored reference, and moving g by one binary64 ulp moves the
  final state by 4.25e-15 — the problem's conditioning in double: below about 5e-15 an
  error depends on how each side rounds its constants (3 g, say) as much as on its method.

Errors: sled |v − v(x)|/v(x); Kepler position over a and velocity over √(k/a); rocket the
largest relative error of height, speed and mass; pendulum the largest state difference
(angles and momenta).

## Time at equal error

Times in µs per run; "not reached": no run of that side gets down to the target; "looser":
the target is above the error of that side's loosest run (1e-4); "–": no ratio.

{speed}

### Why the sled and the rocket were slower, and what changed (issue 38, item 3)

Both sides take the same steps at the same orders (J&Z's rule on both: p = ⌈−½ ln ε + 1⌉,
the step from the last two coefficients): the sled 12, 13, 14, 14 steps at 1e-6, 1e-9,
1e-12, 1e-14 (orders 8, 12, 15, 18), the rocket 10, 9, 9, 9, Kepler 87, 94, 97, 100, with
errors equal to two digits. The gap was the cost of a step. Profiled before the change
(`perf record -e cpu-clock` on `peers -- only sled taylor 1e-9 300000`; the sled 2.72 µs
for 13 steps, 209 ns a step, against heyoka's net 157 ns): the recurrences 53 %, the two
powers of ρₚ₋₁ and ρₚ 15.5 %, the step's own work 18 % (its Horner sum of the increment
7 %), sin θ and cos θ recomputed at every expansion 6 % (heyoka's sled has the drive
g (sin θ − f_d cos θ) as a number), the finite check 2.5 %; restart and stop time 0.05 %
(no fixed cost to speak of: the runs are all steps). The rocket at 1e-12 (1.92 µs for 9
steps): the recurrences 56 %, the powers 14 %, the step 21 %. The recurrences are a chain
of dependent orders, so their latency counts, not their operations: the chain of an order
ran through additions of rows known to be constant (m0 in m = m0 + c x, μ u_e in ṗ) and
through the three additions that end a sum's four partial sums, and the rocket's p/m
convolved over every coefficient of m, which has two. Changed (the emitter and the
stepper, one copy each): each row's degree in t is derived (`Degrees` in
`symbolic/src/emit/taylor.rs`: t is of degree 1, m = m0 − μ t and a state mass at a
constant rate too) and the terms that read coefficients above it are left out (constant
rows are no addition at k ≥ 1; p/m at order k is one product); a sum adds its two newest
terms last; the step takes exp(min(ln ρ)) for the two powers; the increment is summed as
two Horner chains in h²; constants of the parameters alone are kept in the scratch while
the parameters are the same bits. What is left: heyoka compiles for this CPU (FMA, AVX-512
here), so its multiply–adds are one fused operation, where ours are built for baseline
x86-64 (Rust never fuses a · b + c by itself); and its jet lives in registers, ours in the
scratch, each order's result stored and loaded back by the next.

## Construction

heyoka JIT-compiles each integrator (one per problem and tolerance, as the order follows
the tolerance) and keeps the code in an in-memory and an on-disk cache (heyoka.py ≥ 7.10).
Timed: in a new Python process (after `import heyoka`, not timed) with the on-disk cache off
(cold: LLVM's start and the JIT); in a new process reading the on-disk cache a previous one
wrote; in this session with the on-disk cache off, the first construction of each
integrator (the rounds' integrators, made in shuffled order: a JIT, LLVM already started)
and a second construction of it at once (the in-memory cache).

{construction}

Ours is compiled ahead of time. `bash benches/peers/compile_cost.sh`: a release crate holding
the four systems (emitted with the Taylor recurrences, Kepler with its head) and a function
running each with the Taylor stepper, rebuilt alone, against the same crate without them
(wall seconds of the build, and the macro expansion inside it, fastest of 3): {ours_build}.
"""


if __name__ == "__main__":
    main()
