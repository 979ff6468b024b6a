"""What the Python boundary costs, and what Dask's workers give.

1. The paper's sled from rest to x = 50 m (DOP853, tolerance 1e-12, x and x' recorded at
   every accepted step). Python times ``Model.run`` on a model made once: the arguments'
   checks, the program given the parameter values, the tool's plan (kept from the last
   run, what depends on the values made and checked again), the tool's run, the recorded
   table, the NumPy solution and x' at 50 m read from its column (the end state, the
   statistics and the summary's text are made when read: not here). Rust
   (``bench/reference``) times the same integration written directly on the interpreter: the model derived and compiled once,
   untimed, each run giving the program its values and integrating it. Target ≤ 1.2×.
   The bare run does not record x' at every point, which the Python run returns; a second
   Rust figure does (the program's velocities at each point, as the tool records them).
   A third, the tool's run called from Rust (``Compiled::run``, what ``Model.run``
   calls), splits the difference into the tool's own work and the Python boundary.
2. Rocket ensemble members per second on one thread, ``Ensemble.run(n, threads=1)``
   (each member: the tool's run on a compiled model reused from member to member) against
   the Rust interpreter ensemble (the core's serial ``Ensemble``, one compiled program
   given each member's values). Target ≥ 90 %.
3. ``varmass.dask.run`` on 10⁵ members: a LocalCluster of two worker processes against
   one, the fastest of ``--dask-repeats`` interleaved runs of each. Target ≥ 1.6×.

Neither side derives or compiles in the timed loop: a Python ``Model`` derives when made
and compiles at its first run, as the Rust reference does before its loop. Each figure is
the fastest of interleaved repeats (robust on a shared machine). Run from the repository
root, with the package installed (``pip install ./python[dask]``):

    python python/bench/bench.py [--repeats 5] [--members 5000] [--dask-members 100000]
                                 [--dask-repeats 2]
"""

from __future__ import annotations

import argparse
import math
import os
import pathlib
import resource
import subprocess
import time

import varmass
import varmass.dask

ROOT = pathlib.Path(__file__).resolve().parents[2]
PYTHON = ROOT / "python"
# The reference's build directory: CARGO_TARGET_DIR when set (one target/ for everything),
# else python/target.
TARGET = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", PYTHON / "target"))
REFERENCE = TARGET / "release" / "varmass-python-bench-reference"
SLED = {"m0": 10.0, "c": 2.0, "g": 9.81, "theta": math.radians(30.0), "f_d": 0.1}


def build_reference() -> None:
    env = dict(os.environ, CARGO_TARGET_DIR=str(TARGET))
    manifest = PYTHON / "bench" / "reference" / "Cargo.toml"
    subprocess.run(
        ["cargo", "build", "--release", "--quiet", "--manifest-path", str(manifest)],
        check=True,
        env=env,
    )


def reference(what: str, count: int) -> float:
    out = subprocess.run([str(REFERENCE), what, str(count)], check=True, capture_output=True, text=True)
    return float(out.stdout.strip())


def fastest(f, repeats: int) -> float:
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - start)
    return best


def sled_run(sled) -> float:
    """One run; x' at 50 m, read from its column (as the Rust references read theirs)."""
    sol = sled.run(set=SLED, init={"x": 0}, until=100, stop_when="x = 50", method="dop853",
                   tol=1e-12, record=["x", "x'"])
    return sol["x'"][-1]


def rocket_ensemble(rocket):
    return rocket.ensemble(
        2015,
        sample={"mu": varmass.uniform(9.5, 10.5), "u_e": varmass.normal(2500, 50)},
        set={"g": 9.81},
        init={"y": 0, "m": 1000.0},
        until=1e4,
        stop_when="m = 400",
        observables=["y"],
    )


def cpu_seconds() -> float:
    """This process's CPU time (user and system), run on each worker."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def dask_seconds(ensemble, members: int, workers: int):
    """The wall time of ``varmass.dask.run`` on ``members`` members with ``workers`` worker
    processes, and the CPU time each worker spent in it (largest first)."""
    from dask.distributed import Client, LocalCluster

    with LocalCluster(
        n_workers=workers, threads_per_worker=1, dashboard_address=None, silence_logs=40
    ) as cluster, Client(cluster) as client:
        varmass.dask.run(client, ensemble, 200)  # warm the workers (imports, first derive)
        before = client.run(cpu_seconds)
        start = time.perf_counter()
        result = varmass.dask.run(client, ensemble, members)
        seconds = time.perf_counter() - start
        after = client.run(cpu_seconds)
    assert result.member_count == members and not result.failures
    return seconds, sorted((after[w] - before[w] for w in after), reverse=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--members", type=int, default=5000)
    parser.add_argument("--dask-members", type=int, default=100_000, help="0: skip Dask")
    parser.add_argument("--dask-repeats", type=int, default=2)
    args = parser.parse_args()
    build_reference()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")

    sled = varmass.Model.from_file(ROOT / "models" / "sled.vms", with_=["impact"])
    python_sled, tool_sled = math.inf, math.inf
    rust_sled, rust_recorded = math.inf, math.inf
    for _ in range(args.repeats):
        python_sled = min(python_sled, fastest(lambda: sled_run(sled), 40))
        tool_sled = min(tool_sled, reference("tool-sled", 40))
        rust_sled = min(rust_sled, reference("sled", 40))
        rust_recorded = min(rust_recorded, reference("sled-recorded", 40))
    print(
        f"sled to 50 m, DOP853 tol 1e-12 (compiled once, run): Python {python_sled * 1e6:.1f} µs, "
        f"Rust {rust_sled * 1e6:.1f} µs: {python_sled / rust_sled:.2f}×; Rust recording x' "
        f"at every point as Python does {rust_recorded * 1e6:.1f} µs: "
        f"{python_sled / rust_recorded:.2f}× (target ≤ 1.2×); "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    print(
        f"  the tool's run called from Rust {tool_sled * 1e6:.1f} µs: its own work beyond the "
        f"bare run {(tool_sled - rust_sled) * 1e6:.1f} µs (x' at every point "
        f"{(rust_recorded - rust_sled) * 1e6:.1f} µs of it), the Python boundary "
        f"{(python_sled - tool_sled) * 1e6:.1f} µs"
    )

    ensemble = rocket_ensemble(varmass.Model.from_file(ROOT / "models" / "rocket.vms"))
    python_rate, rust_rate = 0.0, 0.0
    for _ in range(max(1, args.repeats // 2)):
        seconds = fastest(lambda: ensemble.run(args.members, threads=1), 1)
        python_rate = max(python_rate, args.members / seconds)
        rust_rate = max(rust_rate, reference("ensemble", args.members))
    print(
        f"rocket ensemble, 1 thread: Python {python_rate:.0f} members/s, Rust {rust_rate:.0f} "
        f"members/s: {100 * python_rate / rust_rate:.0f} % (target ≥ 90 %); "
        f"load average {os.getloadavg()[0]:.1f}"
    )

    if args.dask_members == 0:
        return
    one, two = (math.inf, []), (math.inf, [])
    for _ in range(max(1, args.dask_repeats)):
        one = min(one, dask_seconds(ensemble, args.dask_members, 1))
        two = min(two, dask_seconds(ensemble, args.dask_members, 2))
    print(
        f"Dask, {args.dask_members} members: 1 worker {one[0]:.1f} s, 2 workers {two[0]:.1f} s: "
        f"{one[0] / two[0]:.2f}× (target ≥ 1.6×); load average {os.getloadavg()[0]:.1f}"
    )
    # What two free cores would give: the work divided between the workers. Linux shares
    # the CPU between sessions (autogroups) first, so on a machine loaded by other sessions
    # the benchmark's workers share one session's part and the wall ratio tends to 1.
    cpu = ", ".join(f"{c:.1f}" for c in two[1])
    print(
        f"  CPU time in the workers: 1 worker {one[1][0]:.1f} s, 2 workers {cpu} s: "
        f"{one[1][0] / two[1][0]:.2f}× on two free cores"
    )


if __name__ == "__main__":
    main()
