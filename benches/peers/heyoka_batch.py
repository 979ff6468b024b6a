"""heyoka's batch Taylor (`taylor_adaptive_batch`) on issue 38's 512 rockets, per member, to set
beside `cargo bench -p varmass-benches --bench taylor_lanes` (Taylor's method in our lanes).

The rocket of models/rocket.vms in its state (y, p, m): y' = p/m, p' = μ u_e − m g − μ p/m,
m' = −μ (Meshchersky's m ÿ = μ u_e − m g with p = m ẏ); μ in 0.045–0.055 kg/s and u_e in
270–330 m/s (the bench's ranges, other draws), m0 = 1 kg, from rest to 15 s. Each batch
is timed as the fastest of 15 passes over the 512 members from Python, and the same loop
with an empty propagation (already at the end) is subtracted: "net" is heyoka's integration
alone, "raw" what a Python caller pays. The error is the worst member's against the closed
form.

    python3 -m venv /tmp/hy && /tmp/hy/bin/pip install heyoka numpy
    /tmp/hy/bin/python benches/peers/heyoka_batch.py

Session 39 (heyoka 7.13.2, 2 shared cores): batch 8 net 0.46 / 0.49 / 0.54 µs per member
at 1e-6 / 1e-9 / 1e-12 (raw 0.88 / 0.92 / 0.97), errors 2.6e-8 / 9.2e-12 / 2.6e-14; ours,
Taylor lanes of 8, 1.41 / 1.48 / 1.60 µs at 2.6e-8 / 9.3e-12 / 2.5e-14 (session 46: 1.13 / 1.19 / 1.30).
"""
import time, numpy as np, heyoka as hy
rng = np.random.default_rng(38)
N = 512
# Same ranges as benches/taylor_lanes.rs (not the same draws: the error is the worst member's).
mu = rng.uniform(0.045, 0.055, N); ue = rng.uniform(270.0, 330.0, N)
M0, G, END = 1.0, 9.81, 15.0
y, p, m = hy.make_vars("y", "p", "m")
sys = [(y, p / m), (p, hy.par[0] * hy.par[1] - m * G - hy.par[0] * p / m), (m, -hy.par[0])]
def exact(mu, ue, t):
    mm = M0 - mu * t; L = np.log(M0 / mm)
    return ue * (t - mm / mu * L) - 0.5 * G * t * t, ue * L - G * t, mm
for tol in (1e-6, 1e-9, 1e-12):
    for B in (4, 8):
        st = np.zeros((3, B)); st[2] = M0
        ta = hy.taylor_adaptive_batch(sys, st, tol=tol, pars=np.zeros((2, B)))
        best, best_empty, worst = 1e9, 1e9, 0.0
        for rep in range(15):
            t0 = time.perf_counter()
            ends = []
            for k in range(0, N, B):
                ta.set_time(0.0); ta.state[:] = 0.0; ta.state[2] = M0
                ta.pars[0] = mu[k:k+B]; ta.pars[1] = ue[k:k+B]
                ta.propagate_until(END)
                ends.append(ta.state.copy())
            dt = time.perf_counter() - t0
            best = min(best, dt)
            # The same loop with an empty propagation (already at END): the call's cost.
            t0 = time.perf_counter()
            for k in range(0, N, B):
                ta.set_time(END); ta.state[:] = 0.0; ta.state[2] = M0
                ta.pars[0] = mu[k:k+B]; ta.pars[1] = ue[k:k+B]
                ta.propagate_until(END)
            best_empty = min(best_empty, time.perf_counter() - t0)
        E = np.concatenate(ends, axis=1)
        yy, vv, mm = exact(mu, ue, END)
        err = max(np.max(np.abs(E[0] - yy) / np.abs(yy)), np.max(np.abs(E[1] / E[2] - vv) / np.abs(vv)), np.max(np.abs(E[2] - mm) / mm))
        print(f"{tol:g} batch {B}: raw {best / N * 1e6:.3f} µs/member, empty loop {best_empty / N * 1e6:.3f}, net {(best - best_empty) / N * 1e6:.3f}, worst error {err:.1e}")
