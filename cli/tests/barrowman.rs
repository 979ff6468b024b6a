//! Airframe aerodynamics by Barrowman's method (`models/lib/barrowman_*.vms`;
//! docs/components.md#airframe-aerodynamics-barrowman), run through the tool on the probes
//! `tests/data/library/barrowman_airframe.vms` (RocketPy's Calisto: a von Kármán nose, four
//! trapezoidal fins, a conical boat-tail, on a 6-DOF body turned by a quaternion) and
//! `barrowman_noses.vms` (every nose shape and a set of elliptical fins), against:
//!
//! * a published example: the normal-force slopes, centres of pressure and static margin
//!   RocketPy prints for Calisto (no handbook example with numbers was found: see
//!   `calisto_matches_the_published_slopes_centres_of_pressure_and_margin`);
//! * a second formulation of each formula: Barrowman's own closed forms for the fins and the
//!   transition, Diederich's form (OpenRocket eq. 3.37) for the fins at a Mach number, and
//!   the profiles' volumes and the fins' MAC and roll integrals by quadrature here;
//! * two flights whose closed forms are derived here: the weathercock oscillation of the
//!   nudged rocket in a steady airstream, and the spin-up of canted fins to their steady
//!   roll rate.

mod common;

use common::{column, csv, root, written};

use std::f64::consts::PI;

/// Calisto's body: diameter, the inertia and mass used in the flights (RocketPy's
/// printout: 16.241 kg dry with the unloaded motor, I = 7.864 and 0.036 kg m²), its
/// centre of mass at time 0 (body z, m) and the air.
const D: f64 = 0.127;
const MASS: f64 = 16.241;
const I_LATERAL: f64 = 7.864;
const I_AXIAL: f64 = 0.036;
const Z_CG: f64 = -0.221;
const RHO: f64 = 1.225;

/// Calisto's fins (RocketPy's first simulation): root, tip, span, sweep (RocketPy's default,
/// root − tip), the body z of the root's leading edge; the nose's length and tip; the
/// boat-tail's length, aft diameter and fore end.
const ROOT: f64 = 0.12;
const TIP: f64 = 0.06;
const SPAN: f64 = 0.11;
const SWEEP: f64 = 0.06;
const Z_FINS: f64 = -1.049_56;
const L_NOSE: f64 = 0.558_29;
const Z_NOSE: f64 = 1.278;
const L_TAIL: f64 = 0.06;
const D_TAIL: f64 = 0.087;
const Z_TAIL: f64 = -1.194_656;

/// Runs `model` of `tests/data/library/` with DOP853 at 1e-12, `sets` and `inits`,
/// recording `record` every `every` seconds to `until`: the columns, by name.
fn fly(
    model: &str,
    sets: &[(&str, f64)],
    inits: &[(&str, f64)],
    (record, until, every): (&str, f64, f64),
    name: &str,
) -> Vec<Vec<f64>> {
    let file = root(&format!("tests/data/library/{model}"));
    let (until, every) = (until.to_string(), every.to_string());
    let mut args: Vec<String> = ["run", &file, "--until", &until, "--every", &every]
        .map(String::from)
        .to_vec();
    args.extend(["--method", "dop853", "--tol", "1e-12", "--record", record].map(String::from));
    for (flag, pairs) in [("--set", sets), ("--init", inits)] {
        for (n, v) in pairs {
            args.extend([flag.to_string(), format!("{n}={v:e}")]);
        }
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (header, rows) = csv(&written(&args, name));
    record
        .split(',')
        .map(|n| rows.iter().map(|r| r[column(&header, n)]).collect())
        .collect()
}

/// The Calisto probe's parameters: its body and air, the speed of sound `a0` (the fins'
/// Mach number is |V|/a0), the fins' cant `delta` (rad) and 2-D lift slope `cl_alpha`.
fn calisto_sets(a0: f64, delta: f64, cl_alpha: f64) -> Vec<(&'static str, f64)> {
    vec![
        ("m0", MASS),
        ("A", I_LATERAL),
        ("C", I_AXIAL),
        ("z_cg", Z_CG),
        ("rho0", RHO),
        ("d_ref", D),
        ("a0", a0),
        ("delta", delta),
        ("fins_cl_alpha", cl_alpha),
    ]
}

/// The probe's start: at the origin, turned by `pitch` about body y, flying at `speed`
/// along world z (the airspeed, in still air), not turning.
fn calisto_start(pitch: f64, speed: f64) -> Vec<(&'static str, f64)> {
    let (s, c) = (pitch / 2.0).sin_cos();
    vec![
        ("x", 0.0),
        ("y", 0.0),
        ("z", 0.0),
        ("e0", c),
        ("e1", 0.0),
        ("e2", s),
        ("e3", 0.0),
        ("z'", speed),
    ]
}

/// The first row of each column.
fn first(columns: &[Vec<f64>]) -> Vec<f64> {
    columns.iter().map(|c| c[0]).collect()
}

fn relative(ours: f64, theirs: f64) -> f64 {
    ((ours - theirs) / theirs).abs()
}

/// Composite Simpson's rule of `f` over [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|k| f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + inner + f(b)) * h / 3.0
}

/// The published example. Barrowman & Barrowman (1966), Centuri's TIR-33, the OpenRocket
/// technical documentation, NASA's Beginner's Guide and Apogee's Peak of Flight state the
/// equations without a worked example with numbers that the searches of this work found, so
/// the example is RocketPy's Calisto, as the issue allows: RocketPy-Team/RocketPy at d41dd11,
/// `docs/notebooks/getting_started.ipynb`, the printed output of `calisto.all_info()` (cell
/// 13), whose geometry is this probe's (the fins with the NACA 0012 airfoil table
/// `data/airfoils/NACA0012-radians.txt`, whose first segment, 0.11 per 0.017453293 rad, is
/// RocketPy's 2-D slope, `differentiate_complex_step` at 1e-3 rad; RocketPy's Barrowman
/// fin equations are Diederich's, OpenRocket eq. 3.37 with that slope):
///
/// | | published | by hand here |
/// |---|---|---|
/// | nose C_Nα | 2.000/rad | 2 |
/// | fins C_Nα | 6.280/rad | 6.27988 (6.27255 with 2π) |
/// | tail C_Nα | −1.061/rad | 2 [(0.087/0.127)² − 1] = −1.06144 |
/// | nose CP | 0.999 m | 1.278 − 0.55829/2 = 0.998855 |
/// | fins CP | −1.100 m | −1.04956 − 0.05 = −1.09956 |
/// | tail CP | −1.223 m | −1.194656 − 0.028131 = −1.222787 |
/// | whole CP | −0.500 m | −0.500036 |
/// | static margin | 2.199 c (centre of mass −0.221 m) | 2.1971 |
///
/// The published figures are rounded to 3 decimals; the margin's centre of mass too
/// (±0.0005 m is ±0.004 calibers, 0.18 %).
#[test]
fn calisto_matches_the_published_slopes_centres_of_pressure_and_margin() {
    let naca0012 = 0.11 / 0.017_453_293;
    let record = "nose_cn_alpha,fins_cn_alpha,tail_cn_alpha,nose_z_cp,fins_z_cp,tail_z_cp,\
                  margin_z_cp,margin_static_margin";
    let ours = first(&fly(
        "barrowman_airframe.vms",
        &calisto_sets(1e12, 0.0, naca0012),
        &calisto_start(0.0, 100.0),
        (record, 0.01, 0.01),
        "barrowman_calisto.csv",
    ));
    #[allow(clippy::approx_constant)] // RocketPy's printed fins' slope, 6.280, is not 2π
    let published = [2.000, 6.280, -1.061, 0.999, -1.100, -1.223, -0.500, 2.199];
    let gaps: Vec<f64> = ours
        .iter()
        .zip(published)
        .map(|(o, p)| relative(*o, p))
        .collect();
    let shown: Vec<String> = gaps.iter().map(|g| format!("{g:.1e}")).collect();
    println!("Calisto, ours {ours:?}\n published {published:?}\n relative gaps {shown:?}");
    // Measured: 0, 1.9e-5 (fins), 4.2e-4 (tail), 1.5e-4, 4.0e-4, 1.7e-4, 7.2e-5 (whole CP),
    // 8.5e-4 (margin): each within the last printed digit. The bound, 0.5 %.
    for (gap, name) in gaps.iter().zip(record.split(',')) {
        assert!(*gap < 5e-3, "{name}: {gap:e} ({ours:?})");
    }
    // Positive = stable: the centre of pressure below the centre of mass.
    assert!(ours[7] > 0.0 && ours[6] < Z_CG, "{ours:?}");
}

/// Barrowman's fins at Mach 0 (Barrowman & Barrowman 1966; the OpenRocket documentation's
/// eqs. 3.33-3.34 say they are Barrowman's): for N fins,
/// C_Nα = K 4N (s/d)²/(1 + √(1 + (2 l_m/(C_r + C_t))²)), K = 1 + r/(s + r),
/// X_f = m (C_r + 2C_t)/(3(C_r + C_t)) + (C_r + C_t − C_r C_t/(C_r + C_t))/6.
/// Calisto's by hand: l_m = √(0.11² + 0.03²) = 0.114018, 2 l_m/0.18 = 1.266862,
/// √(1 + 1.604938) = 1.613982, 16 (0.11/0.127)² = 12.003224, so 4.591934 before K =
/// 1.365994: 6.27255; X_f = 0.06·0.24/0.54 + (0.18 − 0.04)/6 = 0.026667 + 0.023333 = 0.05.
fn barrowman_fins() -> (f64, f64) {
    let mid = (SPAN.powi(2) + (SWEEP + TIP / 2.0 - ROOT / 2.0).powi(2)).sqrt();
    let bare =
        4.0 * 4.0 * (SPAN / D).powi(2) / (1.0 + (1.0 + (2.0 * mid / (ROOT + TIP)).powi(2)).sqrt());
    let k = 1.0 + (D / 2.0) / (SPAN + D / 2.0);
    let x = SWEEP * (ROOT + 2.0 * TIP) / (3.0 * (ROOT + TIP))
        + (ROOT + TIP - ROOT * TIP / (ROOT + TIP)) / 6.0;
    (k * bare, x)
}

/// Barrowman's conical transition (Barrowman & Barrowman 1966): C_Nα = 2[(d_R/d)² −
/// (d_F/d)²], X_T = L/3 [1 + (1 − d_F/d_R)/(1 − (d_F/d_R)²)] from its fore end.
/// Calisto's by hand: 2 (0.469279 − 1) = −1.061442; d_F/d_R = 1.459770, (1 − 1.459770)/(1 −
/// 2.130928) = 0.406546, X_T = 0.02 · 1.406546 = 0.028131.
fn barrowman_transition() -> (f64, f64) {
    let ratio = D / D_TAIL;
    let cn = 2.0 * ((D_TAIL / D).powi(2) - 1.0);
    (
        cn,
        L_TAIL / 3.0 * (1.0 + (1.0 - ratio) / (1.0 - ratio * ratio)),
    )
}

/// Diederich's form, OpenRocket eq. 3.37, of one fin: C_Nα0 = cl/β (eq. 3.38), F_D = AR/(C_Nα0
/// cos Γ_c/2π) (eq. 3.39), AR = 2s²/A_fin, (C_Nα)_1 = C_Nα0 F_D (A_fin/A_ref) cos Γ_c/(2 +
/// F_D √(1 + 4/F_D²)): a second algebra of the component's eq. 3.40. On A_ref = π d²/4.
fn diederich(d: f64, span: f64, area_fin: f64, cos_gc: f64, (mach, cl): (f64, f64)) -> f64 {
    let a_ref = PI * d * d / 4.0;
    let cn0 = cl / (1.0 - mach * mach).sqrt();
    let aspect = 2.0 * span * span / area_fin;
    let fd = aspect / (cn0 * cos_gc / (2.0 * PI));
    cn0 * fd * (area_fin / a_ref) * cos_gc / (2.0 + fd * (1.0 + 4.0 / (fd * fd)).sqrt())
}

/// ∫ c(ξ) ξ² dξ over a fin from r_t to r_t + s (OpenRocket's roll-damping sum, eqs.
/// 3.69-3.71) and the MAC's span position (1/A) ∫ y c(y) dy (eq. 3.31), by quadrature.
fn roll_integrals(chord: impl Fn(f64) -> f64, span: f64, radius: f64) -> (f64, f64) {
    let n = 400_000;
    let area = simpson(&chord, 0.0, span, n);
    let roll = simpson(|y| chord(y) * (radius + y).powi(2), 0.0, span, n);
    (roll, simpson(|y| y * chord(y), 0.0, span, n) / area)
}

#[test]
fn the_trapezoidal_fins_and_the_transition_agree_with_a_second_formulation() {
    let record = "fins_cn_alpha,fins_x_cp,tail_cn_alpha,tail_x_cp,fins_cn_alpha_1,fins_roll_sum,\
                  fins_y_mac";
    let at = |a0: f64, name: &str| {
        first(&fly(
            "barrowman_airframe.vms",
            &calisto_sets(a0, 0.0, 2.0 * PI),
            &calisto_start(0.0, 100.0),
            (record, 0.01, 0.01),
            name,
        ))
    };
    let (still, fast) = (
        at(1e12, "barrowman_m0.csv"),
        at(100.0 / 0.6, "barrowman_m06.csv"),
    );
    let (fins, x_fins) = barrowman_fins();
    let (tail, x_tail) = barrowman_transition();
    // Mach 0.6 by Diederich's form: A_fin = 0.0099 m², cos Γ_c = s/l_m.
    let mid = (SPAN.powi(2) + (SWEEP + TIP / 2.0 - ROOT / 2.0).powi(2)).sqrt();
    let one_fin = diederich(
        D,
        SPAN,
        SPAN * (ROOT + TIP) / 2.0,
        SPAN / mid,
        (0.6, 2.0 * PI),
    );
    let interference = 1.0 + (D / 2.0) / (SPAN + D / 2.0);
    let trapezoid = |y: f64| ROOT - (ROOT - TIP) * y / SPAN;
    let (roll_sum, y_mac) = roll_integrals(trapezoid, SPAN, D / 2.0);
    let pairs = [
        ("fins C_Nα, M = 0", still[0], fins),
        ("fins X_f", still[1], x_fins),
        ("tail C_Nα", still[2], tail),
        ("tail X_T", still[3], x_tail),
        ("one fin C_Nα, M = 0.6", fast[4], one_fin),
        (
            "fins C_Nα, M = 0.6",
            fast[0],
            interference * 4.0 / 2.0 * one_fin,
        ),
        ("roll sum", still[5], roll_sum),
        ("y_MAC", still[6], y_mac),
    ];
    for (name, ours, theirs) in pairs {
        let gap = relative(ours, theirs);
        println!("{name}: {ours} against {theirs} ({gap:.1e})");
        // Measured: the algebra ≤ 3.9e-16, the quadratures of the (polynomial) roll and MAC
        // integrands 6.8e-15 and 1.5e-14. Bound 1e-12.
        assert!(gap < 1e-12, "{name}: {ours} against {theirs}");
    }
    // Compressibility raises the fins' slope (β = 0.8): 2.29597 → 2.47613 per fin (+7.8 %),
    // by hand; not by 1/β (+25 %): the planform's aspect ratio damps it.
    assert!(fast[4] > 1.05 * still[4], "{fast:?} {still:?}");
}

/// The nose shapes' centres of pressure, X = L − V/A(L) (OpenRocket eq. 3.28 with A(0) = 0),
/// with V = ∫ π r(x)² dx of each profile by quadrature (the components use the volumes
/// integrated by hand), and the elliptical fins' X_f = x_MAC,LE + c̄/4 from the MAC
/// integrals (eqs. 3.30-3.32) by quadrature, their roll sum and y_MAC, and Diederich's slope
/// at Mach 0.5.
#[test]
fn the_nose_shapes_and_elliptical_fins_agree_with_their_profiles_integrated() {
    let (length, radius, d_ref) = (0.3, 0.04, 0.1);
    let (haack, power, parabola) = (1.0 / 3.0, 0.75, 0.5);
    let (root_chord, span, mach) = (0.12, 0.09, 0.5);
    let sets = [
        ("m0", 1.0),
        ("A", 1.0),
        ("C", 0.1),
        ("rho0", 1.2),
        ("d_ref", d_ref),
        ("l_nose", length),
        ("d_nose", 2.0 * radius),
        ("fin_root", root_chord),
        ("fin_span", span),
        ("z_fins", -1.0),
        ("haack", haack),
        ("exponent", power),
        ("parabola", parabola),
        ("mach0", mach),
    ];
    let record = "cone_x_cp,ogive_x_cp,haack_x_cp,series_x_cp,parabolic_x_cp,cone_cn_alpha,\
                  fins_x_cp,fins_roll_sum,fins_y_mac,fins_cn_alpha_1";
    let ours = first(&fly(
        "barrowman_noses.vms",
        &sets,
        &calisto_start(0.0, 50.0),
        (record, 0.01, 0.01),
        "barrowman_noses.csv",
    ));
    let arc = (radius * radius + length * length) / (2.0 * radius);
    let profiles: [&dyn Fn(f64) -> f64; 5] = [
        &|x| radius * x / length,
        &|x| (arc * arc - (length - x).powi(2)).sqrt() + radius - arc,
        &|x| {
            let theta = (1.0 - 2.0 * x / length).clamp(-1.0, 1.0).acos();
            let s = theta - (2.0 * theta).sin() / 2.0 + haack * theta.sin().powi(3);
            radius * (s.max(0.0) / PI).sqrt()
        },
        &|x| radius * (x / length).powf(power),
        &|x| {
            let xi = x / length;
            radius * (2.0 * xi - parabola * xi * xi) / (2.0 - parabola)
        },
    ];
    let mut expected: Vec<f64> = profiles
        .iter()
        .map(|r| {
            let volume = simpson(|x| PI * r(x).powi(2), 0.0, length, 400_000);
            length - volume / (PI * radius * radius)
        })
        .collect();
    expected.push(2.0 * (2.0 * radius / d_ref).powi(2));
    let chord = |y: f64| root_chord * (1.0 - (y / span).powi(2)).max(0.0).sqrt();
    let n = 400_000;
    let area = simpson(chord, 0.0, span, n);
    let mac = simpson(|y| chord(y).powi(2), 0.0, span, n) / area;
    let x_le = simpson(|y| (root_chord - chord(y)) / 2.0 * chord(y), 0.0, span, n) / area;
    let (roll_sum, y_mac) = roll_integrals(chord, span, d_ref / 2.0);
    expected.extend([x_le + mac / 4.0, roll_sum, y_mac]);
    expected.push(diederich(
        d_ref,
        span,
        PI * root_chord * span / 4.0,
        1.0,
        (mach, 2.0 * PI),
    ));
    let names: Vec<&str> = record.split(',').collect();
    for ((name, ours), theirs) in names.iter().zip(&ours).zip(&expected) {
        let gap = relative(*ours, *theirs);
        println!("{name}: {ours} against {theirs} ({gap:.1e})");
        // Measured: the noses ≤ 6.0e-14 (the tangent ogive's), the elliptical fins' X_f,
        // roll sum and y_MAC 4.3e-10, 1.4e-9, 7.8e-10 — the quadrature's error at the
        // ellipse's square-root tip (20 times fewer intervals: 1.2e-7) — and their slope 0.
        // Bound 1e-7.
        assert!(gap < 1e-7, "{name}: {ours} against {theirs}");
    }
}

/// The Calisto components' slopes and centres of pressure (body z) at Mach 0, by the
/// formulas of this file: nose, fins, tail.
fn calisto_components(z_fins: f64) -> [(f64, f64); 3] {
    let (fins, x_fins) = barrowman_fins();
    let (tail, x_tail) = barrowman_transition();
    [
        (2.0, Z_NOSE - L_NOSE / 2.0),
        (fins, z_fins - x_fins),
        (tail, Z_TAIL - x_tail),
    ]
}

/// The small-angle pitch matrix A of (α, q)' = A (α, q) derived below, for the fins' root
/// leading edge at `z_fins`, at `speed`.
fn pitch_matrix(z_fins: f64, speed: f64) -> [[f64; 2]; 2] {
    let a_ref = PI * D * D / 4.0;
    let (mut k, mut s1, mut s2) = (0.0, 0.0, 0.0);
    for (c, z) in calisto_components(z_fins) {
        let ki = 0.5 * RHO * a_ref * c;
        k += ki;
        s1 += ki * (z - Z_CG);
        s2 += ki * (z - Z_CG).powi(2);
    }
    [
        [-k * speed / MASS, 1.0 + s1 / MASS],
        [speed * speed * s1 / I_LATERAL, -speed * s2 / I_LATERAL],
    ]
}

/// The weathercock (and `pitch_matrix`). In still air, no gravity, constant ρ, the rocket flies at V along its
/// axis, nudged by α₀ in pitch (about body y). Small angles, in the pitch plane: α the angle
/// from the velocity of the centre of mass to the body axis, γ the velocity's turn, q = θ̇,
/// α = θ − γ; component i (slope C_i, centre of pressure z_i from the centre of mass) feels
/// the local lateral airspeed u + q z_i with u = −V α, and pushes F_i = −k_i V (u + q z_i),
/// k_i = ½ ρ A_ref C_i. With K = Σ k_i, S₁ = Σ k_i z_i, S₂ = Σ k_i z_i²:
///
///   m V γ̇ = Σ F_i = K V² α − V S₁ q,      I q̇ = Σ z_i F_i = V² S₁ α − V S₂ q,
///
/// so (α, q)' = A (α, q) with A = [[−KV/m, 1 + S₁/m], [V² S₁/I, −V S₂/I]], and
/// e^{At} = e^{σt} [cos ω_d t + sin(ω_d t)/ω_d (A − σ)], σ = tr A/2, ω_d² = det A − σ².
/// det A = ω₀² (1 + S₁/m) + (KV/m)(V S₂/I), where ω₀² = −V² S₁/I = q̄ A_ref C_Nα (z_cg −
/// z_cp)/I is the weathercock frequency of the rocket held at its centre of mass (S₁ =
/// K (z_cp − z_cg)); the pitch damping of the local airspeed is the V S₂/I, the lift's
/// turning of the path the KV/m. Calisto at 100 m/s (by hand): ω₀ = 4.4508 rad/s (a period
/// of 1.41 s), σ = −0.5054/s, ω_d = 4.4457 rad/s, ζ = −σ/√det = 0.113.
#[test]
fn a_nudged_rocket_weathercocks_at_the_closed_form_frequency_and_damping() {
    let (speed, alpha0) = (100.0, 1e-3);
    let columns = fly(
        "barrowman_airframe.vms",
        &calisto_sets(1e12, 0.0, 2.0 * PI),
        &calisto_start(alpha0, speed),
        ("axes_u,axes_w,axes_q", 4.0, 0.01),
        "barrowman_weathercock.csv",
    );
    let a = pitch_matrix(Z_FINS, speed);
    let sigma = (a[0][0] + a[1][1]) / 2.0;
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let omega_d = (det - sigma * sigma).sqrt();
    let omega_0 = (-a[1][0]).sqrt();
    let mut worst = 0.0_f64;
    for (i, (u, w)) in columns[0].iter().zip(&columns[1]).enumerate() {
        let t = i as f64 * 0.01;
        let (c, s) = ((omega_d * t).cos(), (omega_d * t).sin() / omega_d);
        let decay = (sigma * t).exp();
        let alpha = decay * (c + s * (a[0][0] - sigma)) * alpha0;
        let q = decay * s * a[1][0] * alpha0;
        // The probe's airspeed is its reference point's (RocketPy's origin, z_cg below it):
        // u_ref = u_cg − q z_cg, so its angle is α + q z_cg/V.
        let alpha_ref = alpha + q * Z_CG / speed;
        worst = worst.max(((-u).atan2(*w) - alpha_ref).abs() / alpha0);
        worst = worst.max((columns[2][i] - q).abs() / (omega_0 * alpha0));
    }
    println!(
        "weathercock: ω₀ = {omega_0:.6} rad/s, ω_d = {omega_d:.6}, σ = {sigma:.6}/s, ζ = {:.5}; \
         |Δα|/α₀, |Δq|/(ω₀α₀) ≤ {worst:.2e} over 4 s",
        -sigma / det.sqrt()
    );
    // Measured: 4.3e-7 — the small-angle closed form's error, O(α₀²) of the α₀ = 1e-3 nudge
    // (at α₀ = 1e-2 it is 4.3e-5: a hundredfold, the square); the integration's is ~1e-11.
    // Bound 2e-6. A pitch damping of the wrong sign or size, or a force at the wrong point,
    // misses by the whole oscillation.
    assert!(worst < 2e-6, "{worst:e}");
    // The free flight's frequency is the held rocket's to the lift terms (KV/m ~ 0.34/s).
    assert!(relative(omega_d, omega_0) < 0.02, "{omega_d} {omega_0}");
}

/// Canted fins in a steady airstream. Flying at V along its axis, the rocket feels only the
/// fins' roll moment q̄ A_ref N (y_MAC + r_t)(C_Nα)_1 δ − ½ ρ V N (cl/β) S_c r (OpenRocket
/// eqs. 3.66, 3.69-3.70), so I_z ṙ = c (r_ss − r) with c = ½ ρ V N (cl/β) S_c and
/// r_ss = V A_ref (y_MAC + r_t)(C_Nα)_1 β δ/(cl S_c): r = r_ss (1 − e^{−ct/I_z}). Calisto's
/// by hand at M = 0.5, δ = 0.5°: β = 0.866025, (C_Nα)_1 = 2.415634, y_MAC = 0.048889 m,
/// S_c = 1.346623e-4 m⁴, c = 0.23936 N m s; r_ss = 3.0719 rad/s, I_z/c = 0.1504 s.
#[test]
fn canted_fins_spin_the_rocket_up_to_the_steady_roll_rate() {
    let (speed, mach, delta) = (100.0, 0.5, 0.5_f64.to_radians());
    let columns = fly(
        "barrowman_airframe.vms",
        &calisto_sets(speed / mach, delta, 2.0 * PI),
        &calisto_start(0.0, speed),
        ("axes_r,axes_p,axes_q", 1.5, 0.01),
        "barrowman_roll.csv",
    );
    let beta = (1.0 - mach * mach).sqrt();
    let (radius, a_ref) = (D / 2.0, PI * D * D / 4.0);
    let mid = (SPAN.powi(2) + (SWEEP + TIP / 2.0 - ROOT / 2.0).powi(2)).sqrt();
    let one_fin = diederich(
        D,
        SPAN,
        SPAN * (ROOT + TIP) / 2.0,
        SPAN / mid,
        (mach, 2.0 * PI),
    );
    let y_mac = SPAN / 3.0 * (ROOT + 2.0 * TIP) / (ROOT + TIP);
    let roll_sum = (ROOT + TIP) / 2.0 * radius * radius * SPAN
        + (ROOT + 2.0 * TIP) / 3.0 * radius * SPAN * SPAN
        + (ROOT + 3.0 * TIP) / 12.0 * SPAN.powi(3);
    let c = 0.5 * RHO * speed * 4.0 * (2.0 * PI / beta) * roll_sum;
    let steady = speed * a_ref * (y_mac + radius) * one_fin * beta * delta / (2.0 * PI * roll_sum);
    let tau = I_AXIAL / c;
    let mut worst = 0.0_f64;
    for (i, r) in columns[0].iter().enumerate() {
        let t = i as f64 * 0.01;
        worst = worst.max((r - steady * (1.0 - (-t / tau).exp())).abs() / steady);
        // No pitch or yaw: the roll moment is about the axis.
        assert!(columns[1][i].abs() + columns[2][i].abs() < 1e-12, "{i}");
    }
    let end = *columns[0].last().expect("rows");
    println!("roll: r_ss = {steady:.6} rad/s, τ = {tau:.5} s, r(1.5 s) = {end:.6}; |Δr|/r_ss ≤ {worst:.2e}");
    // Measured: 1.0e-12 (the integration at 1e-12). Bound 1e-10.
    assert!(worst < 1e-10, "{worst:e}");
    assert!(relative(end, steady) < 1e-3, "{end} {steady}");
}

/// The sign of the static margin. With the fins moved to body z = 0.5 m, above the centre
/// of mass, the centre of pressure is above it too: the margin is negative, ω₀² = −V² S₁/I
/// < 0, det A < σ², and the same closed form grows: e^{At} = e^{σt} [cosh μt + sinh(μt)/μ
/// (A − σ)], μ = √(σ² − det A) (by hand: z_cp = 0.848 m, margin −8.42 calibers, σ + μ = 8.33/s).
#[test]
fn with_the_centre_of_pressure_above_the_centre_of_mass_the_margin_is_negative_and_the_nudge_grows()
{
    let (speed, alpha0, z_fins) = (100.0, 1e-6, 0.5);
    let mut sets = calisto_sets(1e12, 0.0, 2.0 * PI);
    sets.push(("z_fins", z_fins));
    let columns = fly(
        "barrowman_airframe.vms",
        &sets,
        &calisto_start(alpha0, speed),
        ("axes_u,axes_w,margin_static_margin", 1.0, 0.01),
        "barrowman_unstable.csv",
    );
    let a = pitch_matrix(z_fins, speed);
    let sigma = (a[0][0] + a[1][1]) / 2.0;
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let mu = (sigma * sigma - det).sqrt();
    let mut worst = 0.0_f64;
    for (i, (u, w)) in columns[0].iter().zip(&columns[1]).enumerate() {
        let t = i as f64 * 0.01;
        let (c, s) = ((mu * t).cosh(), (mu * t).sinh() / mu);
        let alpha = (sigma * t).exp() * (c + s * (a[0][0] - sigma)) * alpha0;
        let q = (sigma * t).exp() * s * a[1][0] * alpha0;
        let alpha_ref = alpha + q * Z_CG / speed;
        worst = worst.max(((-u).atan2(*w) - alpha_ref).abs() / alpha_ref.abs());
    }
    let (margin, end) = (columns[2][0], columns[0].last().expect("rows"));
    println!(
        "unstable: margin {margin:.4} calibers, growth σ + μ = {:.4}/s, α(1 s) = {:.3e} rad; \
         |Δα|/α ≤ {worst:.2e}",
        sigma + mu,
        (-end).atan2(*columns[1].last().expect("rows"))
    );
    assert!(margin < -1.0, "{margin}");
    // Measured: 4.1e-8 — the closed form's O(α²) as α grows to 2.1e-3. Bound 1e-6.
    assert!(worst < 1e-6, "{worst:e}");
    assert!((-end).atan2(*columns[1].last().expect("rows")).abs() > 1000.0 * alpha0);
}
