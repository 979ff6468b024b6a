#!/usr/bin/env python3
"""Calisto's `all` flight (calisto.py) with pieces switched, to locate varmass's gap (issue 36).

Not in CI. Each row is RocketPy 1.13's `all` flight of calisto.py (its known differences
corrected, LSODA at rtol 1e-9, the rail phase's step bounded) with:

- `cm_sign`: the sign of RocketPy's centre-of-mass and nozzle offsets corrected. Rocket's
  `com_to_cdm_function` is -(propellant centre - dry centre) csys m_p/m and `nozzle_to_cdm`
  -(nozzle - dry centre) csys: the vectors FROM the centre of mass (the nozzle) TO the centre
  of dry mass, where Flight.u_dot_generalized uses them as r_CM and r_NOZ, the positions OF
  the centre of mass and the nozzle relative to the centre of dry mass, in the body frame in
  which it places the aerodynamic surfaces (surfaces_cp_to_cdm, +(position - cdm) csys).
  For Calisto the propellant (grains at body z -0.753 m) is put 0.753 m FORWARD of the dry
  centre in the equations of motion: the aerodynamic forces' moments are taken about a
  centre of mass 2 |r_CM| (0.232 m, 1.83 calibers at ignition, 0.213 m at rail exit) too far
  forward. Corrected:
  both replaced by their negatives (set after the rocket is built; they are used nowhere
  else in the 6-DOF flight).
- `vdot`: with `cm_sign`, the translation equation's -(r_CM x w') written for the same
  convention: u_dot_generalized's v_dot = K (T20/m - (r_CM ^ w_dot)) holds for r_CM the vector
  from the centre of mass (rigid kinematics: a_O = a_CM - w' x c - w x (w x c) for c the centre
  of mass from O; RocketPy's own I_CM = I - m [c]^T [c] assumes it); with the offsets' sign
  corrected it must read (w_dot ^ r_CM). Patched in the method's source (review of session 36:
  the two sign errors cancel in this one term as RocketPy ships it).
- `axial`: T04's -m r_CM'' - 2 m' r_CM' dropped: with the propellant at a fixed point of the
  body its centre of mass moves only because mass vanishes there, and the first moment
  m r_CM = m_p z_g gives m r_CM'' + 2 m' r_CM' = m'' (z_g - r_CM), the same kind of spurious
  axial force as the m'' (r_NOZ - r_CM) that `all` removes.
- `thomson`: T03 = m'(r_NOZ - r_CM) - m r_CM' in place of 2 m'(r_NOZ - r_CM) - 2 m r_CM': the
  factor 2 is the Coriolis force of the steady internal gas flow, which varmass (Thomson's
  model, docs/mechanics.md: internal flow of negligible momentum) leaves out. A difference of
  model, not an error of RocketPy's.
- `nowind`: the wind set to zero (flight.toml's [weather] wind).
- `no_rcm_dot`: r_CM's derivatives set to zero everywhere u_dot_generalized takes them: T04's
  axial terms (as `axial`) and T03's -2 m r_CM' too (kept for the record: it removes more
  than the spurious term).
- `sin_alpha`: every surface's lift coefficient C_N_alpha sin(alpha) in place of
  C_N_alpha alpha (varmass's barrowman_lift.vms is linear in the lateral airspeed).

Rows: apogee (m above the pad, of the centre of dry mass), its time, rail-exit speed, max
speed, static margin at 0 and at rail exit. docs/validation.md#calisto-in-six-degrees-of-freedom.

    target/venv-rocketpy/bin/python benches/peers/rocketpy/calisto_6dof.py
"""

import csv
import sys
import warnings
from pathlib import Path

import numpy as np
from rocketpy import Function

sys.path.insert(0, str(Path(__file__).resolve().parent))
import calisto  # noqa: E402  (benches/peers/rocketpy/calisto.py)

ROWS = [
    ("all", ()),
    ("cm_sign_vdot_axial_thomson", ("sign", "vdot", "axial", "thomson")),
    ("cm_sign_vdot_axial_thomson_nowind", ("sign", "vdot", "axial", "thomson", "nowind")),
    ("cm_sign_vdot_axial", ("sign", "vdot", "axial")),
    ("cm_sign_vdot", ("sign", "vdot")),
    ("all_nowind", ("nowind",)),
    ("cm_sign", ("sign",)),
    ("cm_sign_nowind", ("sign", "nowind")),
    ("cm_sign_sin_alpha", ("sign", "sin")),
    ("cm_sign_no_rcm_dot", ("sign", "rdot")),
    ("cm_sign_no_rcm_dot_nowind", ("sign", "rdot", "nowind")),
]
WIND = list(calisto.SPEC["weather"]["wind"])
ORIGINAL = __import__("rocketpy").simulation.flight.Flight.u_dot_generalized
_BUILD = calisto.build


def sine_lift(surface):
    slope = surface.clalpha
    surface.cl = Function(lambda alpha, mach: slope(mach) * np.sin(alpha),
                          ["Alpha (rad)", "Mach"], "Cl")


def patched(switches):
    """Flight.u_dot_generalized with the `vdot`, `axial` and `thomson` edits of its source."""
    import inspect
    import re
    import textwrap

    import rocketpy.simulation.flight as module

    source = textwrap.dedent(inspect.getsource(ORIGINAL)).replace("self.__", "self._Flight__")
    edits = []
    if "vdot" in switches:
        edits.append(("(r_CM ^ w_dot)", "(w_dot ^ r_CM)"))
    if "thomson" in switches:
        edits.append(("T03 = 2 * total_mass_dot * (r_NOZ - r_CM) - 2 * total_mass * r_CM_dot",
                      "T03 = total_mass_dot * (r_NOZ - r_CM) - total_mass * r_CM_dot"))
    for old, new in edits:
        assert old in source, old
        source = source.replace(old, new)
    if "axial" in switches:
        shorter = re.sub(r"\n\s*- total_mass \* r_CM_ddot\n\s*- 2 \* total_mass_dot \* r_CM_dot",
                         "", source)
        assert len(shorter) < len(source), "T04's r_CM terms not found"
        source = shorter
    namespace = dict(vars(module))
    exec(source, namespace)  # noqa: S102  (RocketPy's own method, edited as listed)
    return namespace["u_dot_generalized"]


def fly(switches):
    def build(propellant_exact):
        env, rk = _BUILD(propellant_exact)
        if "sign" in switches:
            rk.com_to_cdm_function = -1 * rk.com_to_cdm_function
            rk.nozzle_to_cdm = -rk.nozzle_to_cdm
        if "rdot" in switches:
            rk.com_to_cdm_function.differentiate_complex_step = lambda *a, **k: 0.0
            rk.com_to_cdm_function.differentiate = lambda *a, **k: 0.0
        if "sin" in switches:
            for surface, _ in rk.aerodynamic_surfaces:
                sine_lift(surface)
        return env, rk

    from rocketpy.simulation.flight import Flight

    calisto.build = build
    calisto.SPEC["weather"]["wind"] = [0.0, 0.0] if "nowind" in switches else WIND
    Flight.u_dot_generalized = patched(switches)
    try:
        f, rk, env, _ = calisto.fly("all", rtol=calisto.TIGHT, terminate_on_apogee=True)
    finally:
        calisto.build = _BUILD
        calisto.SPEC["weather"]["wind"] = WIND
        Flight.u_dot_generalized = ORIGINAL
    return calisto.summary("", f, rk, env)


def main():
    warnings.simplefilter("ignore")
    cols = ["apogee", "apogee_time", "rail_exit_speed", "max_speed", "rail_exit_time",
            "static_margin_0", "static_margin_rail_exit"]
    out = Path(__file__).with_name("calisto_6dof.csv")
    with open(out, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["config"] + cols)
        for name, switches in ROWS:
            row = fly(switches)
            print(f"{name:20s} " + "  ".join(f"{c} {row[c]:.7f}" for c in cols), flush=True)
            w.writerow([name] + [f"{row[c]:.10g}" for c in cols])
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
