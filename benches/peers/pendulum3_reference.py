#!/usr/bin/env python3
"""The 3-link pendulum's reference final state, independent of varmass (issue 38, item 1).

The equations are derived here from the Lagrangian by sympy (nothing is read from
varmass's derivation): three equal bobs m on massless links l, angles a_k from the
downward vertical, bob k at Σ_{j≤k} l (sin a_j, −cos a_j); T = ½ m Σ |ṙ_k|², V = m g Σ y_k,
L = T − V. The state is (a, p) with p = ∂L/∂ȧ = M(a) ȧ, so ȧ = M⁻¹ p (sympy's adjugate and
determinant) and ṗ = ∂L/∂a at ȧ = M⁻¹ p. m = l = 1 and g = 9.81 are the doubles the bench
integrates (9.81 rounded to binary64, held exactly in the wider types), start a = (0.6,
−0.4, 0.3), p = 0, end t = 10.

These equations are integrated by heyoka's Taylor method in quadruple precision (real128,
113-bit significand) at its default tolerance (machine epsilon, 1.9e-34) and at 1e-28, and
in 256-bit MPFR arithmetic (hy.real, 77 digits) at 1e-60; the 256-bit run is stored
and the runs' gaps are printed and written into the file's header.

    target/venv-heyoka/bin/python benches/peers/pendulum3_reference.py  # writes the file
    target/venv-heyoka/bin/python benches/peers/pendulum3_reference.py --sensitivity

Writes benches/peers/pendulum3_reference.txt: comment lines, then the six final state
components (a1 a2 a3 p1 p2 p3), one a line, to 40 significant digits.
"""

import sys
import time
from pathlib import Path

# This directory holds heyoka.py: keep it off the path, or `import heyoka` imports that.
sys.path = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import heyoka as hy  # noqa: E402
import mpmath as mp  # noqa: E402
import sympy as sp  # noqa: E402

HERE = Path(__file__).resolve().parent
OUT = HERE / "pendulum3_reference.txt"
START = [0.6, -0.4, 0.3, 0.0, 0.0, 0.0]
END = 10.0
G = 9.81  # the double; sp.Rational(G) is its exact binary value


def derive():
    """(a symbols, p symbols, ȧ as sympy expressions of (a, p), ∂L/∂a as expressions of
    (a, ȧ symbols), ȧ symbols)."""
    a = sp.symbols("a1 a2 a3")
    ad = sp.symbols("ad1 ad2 ad3")
    p = sp.symbols("p1 p2 p3")
    # g stays a symbol: heyoka gets it as a runtime parameter in the working precision, so
    # that no product like 3 g is folded in binary64 on the way.
    m, l, g = sp.Integer(1), sp.Integer(1), sp.Symbol("g")
    x, y, bobs = 0, 0, []
    for k in range(3):
        x += l * sp.sin(a[k])
        y += -l * sp.cos(a[k])
        bobs.append((x, y))
    T, V = 0, 0
    for bx, by in bobs:
        vx = sum(sp.diff(bx, a[j]) * ad[j] for j in range(3))
        vy = sum(sp.diff(by, a[j]) * ad[j] for j in range(3))
        T += m * (vx**2 + vy**2) / 2
        V += m * g * by
    L = sp.expand(T - V)
    M = sp.Matrix(3, 3, lambda i, j: sp.simplify(sp.diff(L, ad[i], ad[j])))
    # ȧ = M⁻¹ p by the adjugate over the determinant.
    adj, det = M.adjugate(), sp.simplify(M.det())
    velocity = [sp.simplify(sum(adj[i, j] * p[j] for j in range(3))) / det for i in range(3)]
    force = [sp.simplify(sp.diff(L, a[k])) for k in range(3)]
    return a, p, ad, velocity, force, L, M, g


def heyoka_system():
    a, p, ad, velocity, force, _, _, g = derive()
    ha = hy.make_vars("a1", "a2", "a3")
    hp = hy.make_vars("p1", "p2", "p3")
    names = {s: h for s, h in zip(a, ha)} | {s: h for s, h in zip(p, hp)} | {g: hy.par[0]}
    hv = [hy.from_sympy(v, names) for v in velocity]
    # ṗ = ∂L/∂a with ȧ the heyoka expressions of M⁻¹ p.
    hf = [hy.from_sympy(f, names | {s: v for s, v in zip(ad, hv)}) for f in force]
    return list(zip([*ha, *hp], hv + hf))


def rates_at(state):
    """The sympy right-hand side at `state` (a1, a2, a3, p1, p2, p3) in 40 digits."""
    a, p, ad, velocity, force, _, _, g = derive()
    mp.mp.dps = 40
    at = {s: sp.Float(mp.mpf(v), 40) for s, v in zip([*a, *p], state)} | {g: sp.Rational(G)}
    v = [sp.N(e.subs(at), 40) for e in velocity]
    f = [sp.N(e.subs(at | dict(zip(ad, v))), 40) for e in force]
    return [float(x) for x in v + f]


def integrate(fp_type, tol, make):
    sys_ = heyoka_system()
    began = time.perf_counter()
    ta = hy.taylor_adaptive(sys_, [make(x) for x in START], fp_type=fp_type, tol=make(tol),
                            pars=[make(G)])
    built = time.perf_counter() - began
    began = time.perf_counter()
    outcome = ta.propagate_until(make(END))
    ran = time.perf_counter() - began
    steps = outcome[3]
    print(f"{fp_type.__name__} tol {tol:.0e}: order {ta.order}, {steps} steps, "
          f"JIT {built:.1f} s, run {ran:.1f} s", file=sys.stderr)
    return [mp.mpf(str(x)) for x in ta.state], ta.order, steps


def sensitivity():
    """`--sensitivity`: the problem's conditioning, in long double (64-bit significand, tol
    1e-19): how far the final state moves when g moves by one binary64 ulp (relative
    2⁻⁵²), and this run's distance to the stored reference (a third check of it)."""
    import numpy as np

    ld = np.longdouble
    ta = hy.taylor_adaptive(heyoka_system(), [ld(x) for x in START], fp_type=ld,
                            tol=ld(1e-19), pars=[ld(G)])
    ta.propagate_until(ld(END))
    base = ta.state.copy()
    ta.time, ta.state[:] = ld(0), [ld(x) for x in START]
    ta.pars[0] = ld(G) * (1 + ld(2.0**-52))
    ta.propagate_until(ld(END))
    lines = OUT.read_text().splitlines()
    stored = np.array([ld(x) for x in lines if x.strip() and not x.startswith("#")])
    print(f"g one ulp up moves the final state by {float(np.max(np.abs(ta.state - base))):.2e};"
          f" long double at 1e-19 against the stored reference: "
          f"{float(np.max(np.abs(base - stored))):.2e}")


def main():
    if "--sensitivity" in sys.argv:
        sensitivity()
        return
    mp.mp.dps = 80
    quad = integrate(hy.real128, 2.0**-112, hy.real128)
    quad_loose = integrate(hy.real128, 1e-28, hy.real128)
    wide = integrate(hy.real, 1e-60, lambda x: hy.real(x, 256))
    gap = lambda u, v: max(abs(x - y) for x, y in zip(u[0], v[0]))
    g_quad = gap(quad, wide)
    g_loose = gap(quad_loose, wide)
    print(f"real128 at eps against 256-bit: {mp.nstr(g_quad, 3)}; real128 at 1e-28 against "
          f"256-bit: {mp.nstr(g_loose, 3)}")
    lines = [
        "# The planar 3-link pendulum (m = l = 1, g = 9.81 as a double) at t = 10 from",
        "# a = (0.6, -0.4, 0.3), p = 0: state a1 a2 a3 p1 p2 p3. Made by",
        "# benches/peers/pendulum3_reference.py (sympy from the Lagrangian, heyoka "
        f"{hy.__version__}),",
        f"# 256-bit MPFR Taylor, order {wide[1]}, {wide[2]} steps, tol 1e-60. Gaps (largest",
        f"# component): real128 at eps ({quad[2]} steps) {mp.nstr(g_quad, 3)}, real128 at 1e-28 "
        f"{mp.nstr(g_loose, 3)}.",
    ]
    lines += [mp.nstr(x, 40, strip_zeros=False) for x in wide[0]]
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
