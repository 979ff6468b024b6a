# %% [markdown]
# # A launch dispersion study from Python
#
# Derive the vertical rocket of `models/rocket.vms`, look at its derivation, fly one rocket,
# then fly 10⁵ rockets with dispersed burn rate and exhaust speed on a Dask `LocalCluster`
# and plot where their apexes fall. Run it as a script (`python python/examples/dispersion.py`)
# or open it as a notebook (Jupyter with jupytext, or VS Code's `# %%` cells).
#
# Knobs (environment): `VARMASS_MEMBERS` (default 100 000), `VARMASS_WORKERS` (default 2),
# `VARMASS_FIGURE` (save the histogram there instead of showing it).

# %%
import math
import os
import pathlib

import numpy as np

import varmass
import varmass.dask

MEMBERS = int(os.environ.get("VARMASS_MEMBERS", "100000"))
WORKERS = int(os.environ.get("VARMASS_WORKERS", "2"))
HERE = pathlib.Path(globals().get("__file__", "python/examples/dispersion.py")).resolve()
MODELS = HERE.parents[2] / "models"

M0, DRY, G = 1000.0, 400.0, 9.81  # lift-off mass (kg), dry mass (kg), gravity (m/s²)

# %% [markdown]
# ## The model and its derivation
# In Jupyter, `rocket` on its own line shows the derivation as LaTeX.

# %%
rocket = varmass.Model.from_file(MODELS / "rocket.vms")
print(rocket)
for check in rocket.check():
    print(f"  {check.statement} ... {check.verdict}")
print(rocket.derivation)

# %% [markdown]
# ## One rocket
# μ = 10 kg/s, u_e = 2500 m/s, burning from rest to the dry mass (`stop_when`). After
# burnout it coasts: a second run from the burnout state with μ = 0 (the same model, no
# flow) until y' falls through 0 integrates the coast to the apex, which for this
# ballistic coast (uniform gravity, no drag) is y_b + v_b²/(2g).

# %%
one = rocket.run(
    set={"mu": 10.0, "u_e": 2500.0, "g": G},
    init={"y": 0, "m": M0},
    until=1e4,
    stop_when=f"m = {DRY}",
    record=["y", "y'", "m"],
)
y_b, v_b = one["y"][-1], one["y'"][-1]
# Closed form at burnout: t_b = (m0 − m_dry)/μ, v_b = u_e ln(m0/m_dry) − g t_b.
t_b = (M0 - DRY) / 10.0
exact_v = 2500.0 * math.log(M0 / DRY) - G * t_b
print(one)
print(f"burnout at t = {one.t[-1]:.6f} s (exact {t_b}), v = {v_b:.9f} m/s (exact {exact_v:.9f})")
assert abs(v_b - exact_v) < 1e-6 * exact_v
coast = rocket.run(
    set={"mu": 0.0, "u_e": 2500.0, "g": G},
    from_=one.t[-1],
    init={"y": y_b, "y'": v_b, "m": one["m"][-1]},
    until=1e4,
    stop_when="y' < 0",
    record=["y", "y'"],
)
apex = coast["y"][-1]
print(f"apex {apex:.3f} m at t = {coast.t[-1]:.3f} s (closed form {y_b + v_b**2 / (2 * G):.3f} m)")
assert abs(apex - (y_b + v_b**2 / (2 * G))) < 1e-6 * apex

# %% [markdown]
# ## 10⁵ dispersed rockets on Dask
# Each member draws μ ~ U(9.5, 10.5) kg/s and u_e ~ N(2500, 50) m/s from its own random
# stream (seed and index), so the result is the same bits on any number of workers.

# %%
ensemble = rocket.ensemble(
    2015,
    sample={"mu": varmass.uniform(9.5, 10.5), "u_e": varmass.normal(2500, 50)},
    set={"g": G},
    init={"y": 0, "m": M0},
    until=1e4,
    stop_when=f"m = {DRY}",
    observables=["y", "y'", "t"],
)

if __name__ == "__main__":  # Dask's worker processes import this file again: run once.
    from dask.distributed import Client, LocalCluster

    with LocalCluster(
        n_workers=WORKERS, threads_per_worker=1, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        result = varmass.dask.run(client, ensemble, MEMBERS)
    print(result)
    assert result.member_count == MEMBERS and not result.failures

    # %% [markdown]
    # ## Apex heights

    # %%
    # An ensemble member is one run (to burnout): its apex is the coast's closed form,
    # which the integrated coast of the single rocket above confirms.
    apex = result["y"] + result["y'"] ** 2 / (2 * G)
    print(
        f"apex: mean {apex.mean() / 1e3:.3f} km, sd {apex.std() / 1e3:.3f} km, "
        f"5 % {np.quantile(apex, 0.05) / 1e3:.3f} km, 95 % {np.quantile(apex, 0.95) / 1e3:.3f} km"
    )
    burnout = result.summary("y")
    print(f"burnout height: mean {burnout['mean']:.1f} m, 95 % CI {burnout['confidence_interval']}")

    import matplotlib.pyplot as plt

    figure, ax = plt.subplots(figsize=(7, 4))
    ax.hist(apex / 1e3, bins=60)
    ax.set_xlabel("apex height (km)")
    ax.set_ylabel("rockets")
    ax.set_title(f"{MEMBERS} rockets: μ ~ U(9.5, 10.5) kg/s, u_e ~ N(2500, 50) m/s")
    if "VARMASS_FIGURE" in os.environ:
        figure.savefig(os.environ["VARMASS_FIGURE"], dpi=100)
        print(f"wrote {os.environ['VARMASS_FIGURE']}")
    else:
        plt.show()
