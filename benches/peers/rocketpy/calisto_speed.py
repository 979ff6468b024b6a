#!/usr/bin/env python3
"""Calisto's full flight: RocketPy 1.13's `Flight(...)` at its defaults against varmass's compiled flight, interleaved (issue 36).

Not in CI. Alternates `-n` times between RocketPy's getting-started Calisto flown as it is
at its defaults (calisto.py's `rocketpy` row: LSODA at rtol 1e-6, pad to landing, both
parachutes with their noisy triggers; timed in-process around `Flight(...)` alone, as
calisto.py times it) and one run of our bench binary (`benches/calisto.rs`: the same flight,
rail, ascent, drogue, main, landing, compiled from flights/calisto/calisto.vms, DOP853 at
rtol = atol = 1e-8), which prints its own in-process time per flight, the fastest of `-k`;
RocketPy's `Flight(...)` is timed the fastest of `-k` in each round too, so both sides are
sampled alike, and each round's ratio is printed.
Prints both minima and medians and their ratios. `--once` flies RocketPy's flight once and
exits (a whole-process run to time from outside).

    cargo bench -p varmass-benches --bench calisto --no-run   # prints the binary's path
    target/venv-rocketpy/bin/python benches/peers/rocketpy/calisto_speed.py --ours target/release/deps/calisto-HASH
"""

import argparse
import statistics
import subprocess
import sys
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import calisto  # noqa: E402  (benches/peers/rocketpy/calisto.py)


def ours(binary, k):
    out = subprocess.run([binary, "time", str(k)], capture_output=True, text=True, check=True)
    return float(out.stdout.split()[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ours", help="the calisto bench binary")
    ap.add_argument("-n", type=int, default=9, help="interleaved rounds")
    ap.add_argument("-k", type=int, default=5,
                    help="flights per round on each side, the fastest kept (both sides alike)")
    ap.add_argument("--once", action="store_true")
    args = ap.parse_args()
    warnings.simplefilter("ignore")
    if args.once:
        calisto.fly("rocketpy")
        return
    calisto.fly("rocketpy")  # warm-up: imports, caches
    ours(args.ours, 1)
    rp, us = [], []
    for i in range(args.n):
        rp.append(min(calisto.fly("rocketpy")[3] for _ in range(args.k)))
        us.append(ours(args.ours, args.k))
        print(f"round {i + 1}: RocketPy {rp[-1]:.4f} s, ours {us[-1] * 1e3:.3f} ms, "
              f"ratio {rp[-1] / us[-1]:.1f}", flush=True)
    for name, f in (("min", min), ("median", statistics.median)):
        a, b = f(rp), f(us)
        print(f"{name:6s}: RocketPy Flight(...) {a:.4f} s, ours {b * 1e3:.3f} ms, ratio {a / b:.1f}")
    paired = sorted(a / b for a, b in zip(rp, us))
    below = sum(r < 50 for r in paired)
    print(f"paired ratios (each round, the fastest of {args.k} on each side): median "
          f"{statistics.median(paired):.1f}, range {paired[0]:.1f}-{paired[-1]:.1f}, "
          f"{below} of {len(paired)} rounds below 50")


if __name__ == "__main__":
    main()
