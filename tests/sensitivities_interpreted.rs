//! Forward sensitivities of run-time models (docs/sensitivities.md): the interpreter's
//! symbolic Jacobians (`Program::jacobian`, `Program::parameter_jacobian`) against generated
//! code's and against central differences, and `Sensitive` over a `TapeSystem` against the
//! rocket's closed forms.

use varmass::core::sensitivity::{Column, Sensitive, SensitivityError};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::mechanics::{Derivation, Outputs, Parameters};
use varmass::symbolic::{derive_for, parse::parse_system};

/// Tsiolkovsky's rocket, m = m0 − μ t (the compiled twin of `ROCKET_SOURCE`).
const ROCKET_SOURCE: &str = "
    coordinates y
    mass m = m0 - mu*t
    body rocket: mass m, position [y]
    force rocket: [-m*g]
    outflow rocket: rate mu, relative_velocity [-u_e]
";

#[variable_mass_system(
    r#"
    coordinates y
    mass m = m0 - mu*t
    body rocket: mass m, position [y]
    force rocket: [-m*g]
    outflow rocket: rate mu, relative_velocity [-u_e]
"#,
    emit = ["sensitivities"]
)]
struct Rocket {
    m0: f64,
    mu: f64,
    g: f64,
    u_e: f64,
}

const ROCKET: Rocket = Rocket {
    m0: 100.0,
    mu: 5.0,
    g: 9.81,
    u_e: 300.0,
};

const VALUES: [(&str, f64); 4] = [("m0", 100.0), ("mu", 5.0), ("g", 9.81), ("u_e", 300.0)];

/// A cart on a spring, burning from a state mass and damped, with a bob of growing mass
/// swinging from it: coupled velocities, a state mass, a law mass.
const COUPLED_SOURCE: &str = "
    coordinates x, th
    mass m: state, rate -mu
    mass b = b0 + c*t
    body cart: mass m, position [x, 0]
    body bob: mass b, position [x + l*sin(th), -l*cos(th)]
    potential b*g*(-l*cos(th)) + 1/2*k*x^2
    force cart: [-d*x', 0]
    outflow cart: rate mu, relative_velocity [-u_e, 0]
";

const COUPLED_VALUES: [(&str, f64); 9] = [
    ("mu", 0.3),
    ("b0", 0.7),
    ("c", 0.05),
    ("l", 1.3),
    ("g", 9.81),
    ("k", 4.0),
    ("d", 0.2),
    ("u_e", 12.0),
    ("m_unused", 1.0),
];

/// `source` derived with the parameter Jacobian.
fn derived(source: &str) -> Derivation {
    let ast = parse_system(source).expect("parses");
    let outputs = Outputs {
        sensitivities: true,
        ..Outputs::FULL
    };
    derive_for(&ast, Parameters::Inferred, outputs).expect("derives")
}

/// The program of `source` with those of `values` it has.
fn program(source: &str, values: &[(&str, f64)]) -> Program {
    let d = derived(source);
    let known: Vec<(&str, f64)> = (values.iter().copied())
        .filter(|(name, _)| d.parameters.iter().any(|(n, _)| n == name))
        .collect();
    Program::new(d, &known).expect("the parameters fit")
}

/// The interpreter's Jacobians equal generated code's at 50 states along the burn (the same
/// derivation evaluated by a tape and assembled at run time, against the emitted blocks
/// and nalgebra's assembly). Measured: 3.7e-16 relative; bound 1e-14 (the two assemblies
/// round differently; a wrong block gives order one).
#[test]
fn the_interpreters_jacobians_equal_generated_codes() {
    let tape = TapeSystem::<1, 2>::new(program(ROCKET_SOURCE, &VALUES)).expect("sizes");
    let names = tape.parameter_names();
    let compiled = ROCKET.parameter_names();
    let mut worst = 0f64;
    for i in 0..50 {
        let t = 0.3 * f64::from(i);
        let state = SVector::from([10.0 * f64::from(i), 40.0 - 1.7 * f64::from(i)]);
        let (ours, theirs) = (tape.jacobian(t, &state), ROCKET.jacobian(t, &state));
        let (ours, theirs) = (ours.expect("regular"), theirs.expect("regular"));
        worst = worst.max((ours - theirs).abs().max() / theirs.abs().max());
        let (mut ours, mut theirs) = (vec![0.0; 2 * names.len()], vec![0.0; 2 * compiled.len()]);
        assert!(tape
            .parameter_jacobian(t, &state, &mut ours)
            .expect("regular"));
        assert!(ROCKET
            .parameter_jacobian(t, &state, &mut theirs)
            .expect("regular"));
        for (j, name) in names.iter().enumerate() {
            let k = compiled
                .iter()
                .position(|c| c == name)
                .expect("the same parameters");
            for row in 0..2 {
                let (a, b) = (
                    ours[row * names.len() + j],
                    theirs[row * compiled.len() + k],
                );
                worst = worst.max((a - b).abs() / b.abs().max(1e-300));
            }
        }
    }
    eprintln!("interpreter against generated code: {worst:e}");
    assert!(worst <= 1e-14, "{worst:e}");
}

/// The coupled model's Jacobians (closed-form velocities of two coupled coordinates, a
/// state mass, a law mass) against central differences of its state rate, at 20 states.
/// Measured: 1.3e-10 relative to the largest entry at most, the differences' own error
/// (step 1e-5 relative: truncation ~h² = 1e-10); bound 1e-8 (a wrong block, a dropped
/// law-mass term or a sign gives order one).
#[test]
fn the_coupled_models_jacobians_meet_central_differences() {
    let base = program(COUPLED_SOURCE, &COUPLED_VALUES);
    let names = base.parameter_names();
    let tape = TapeSystem::<2, 5>::new(base).expect("sizes");
    let mut shifted =
        TapeSystem::<2, 5>::new(program(COUPLED_SOURCE, &COUPLED_VALUES)).expect("sizes");
    let mut worst = 0f64;
    for i in 0..20 {
        let f = f64::from(i);
        let t = 0.17 * f;
        let state = SVector::from([
            0.3 - 0.05 * f,
            0.9 - 0.1 * f,
            0.4 + 0.1 * f,
            -0.7 + 0.2 * f,
            3.0,
        ]);
        let exact = tape.jacobian(t, &state).expect("regular");
        let rate = |y: &SVector<f64, 5>| tape.state_rate(t, y).expect("regular");
        for j in 0..5 {
            let h = 1e-5 * state[j].abs().max(1.0);
            let (mut up, mut down) = (state, state);
            up[j] += h;
            down[j] -= h;
            let column = (rate(&up) - rate(&down)) / (2.0 * h);
            let gap = (exact.column(j) - column).abs().max();
            worst = worst.max(gap / exact.abs().max());
        }
        let mut exact = vec![0.0; 5 * names.len()];
        assert!(tape
            .parameter_jacobian(t, &state, &mut exact)
            .expect("regular"));
        for (j, name) in names.iter().enumerate() {
            let mut moved = |sign: f64| {
                let values: Vec<(&str, f64)> = (COUPLED_VALUES.iter())
                    .filter(|(n, _)| names.contains(n))
                    .map(|&(n, v)| {
                        (
                            n,
                            if n == *name {
                                v * (1.0 + sign * 1e-5)
                            } else {
                                v
                            },
                        )
                    })
                    .collect();
                let value = COUPLED_VALUES
                    .iter()
                    .find(|(n, _)| n == name)
                    .expect("given")
                    .1;
                shifted.program_mut().set_parameters(&values).expect("fits");
                (
                    shifted.state_rate(t, &state).expect("regular"),
                    value * 1e-5,
                )
            };
            let ((up, h), (down, _)) = (moved(1.0), moved(-1.0));
            let column = (up - down) / (2.0 * h);
            let scale = exact.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for row in 0..5 {
                let gap = (exact[row * names.len() + j] - column[row]).abs();
                worst = worst.max(gap / scale);
            }
        }
    }
    eprintln!("against central differences: {worst:e}");
    assert!(worst <= 1e-8, "{worst:e}");
}

/// `jacobians` with some parameters' columns (a tape compiled for them alone, what
/// `Sensitive` evaluates at each stage) gives J and those columns to the bit of `jacobian`
/// and `parameter_jacobian` (each node of the tapes is the same operation on the same
/// values), the other columns NaN; columns out of order or past the parameters are refused.
#[test]
fn some_parameters_columns_are_the_whole_jacobians_bits() {
    let tape = TapeSystem::<2, 5>::new(program(COUPLED_SOURCE, &COUPLED_VALUES)).expect("sizes");
    let count = tape.parameter_names().len();
    let subsets: [&[usize]; 4] = [&[], &[1], &[0, 3, 5], &[0, 1, 2, 3, 4, 5, 6, 7]];
    for i in 0..10 {
        let f = f64::from(i);
        let (t, state) = (
            0.21 * f,
            SVector::from([0.1 * f, 0.5 - 0.1 * f, 0.3, 0.2 * f, 2.5]),
        );
        let whole = tape.jacobian(t, &state).expect("regular");
        let mut every = vec![0.0; 5 * count];
        assert!(tape
            .parameter_jacobian(t, &state, &mut every)
            .expect("regular"));
        for wanted in subsets.iter().copied().filter(|w| w.len() <= count) {
            let mut out = vec![0.0; 5 * count];
            let (jacobian, given) = tape
                .jacobians(t, &state, wanted, &mut out)
                .expect("regular");
            assert!(given);
            assert_eq!(jacobian.as_slice(), whole.as_slice(), "J with {wanted:?}");
            for (k, (ours, theirs)) in out.iter().zip(&every).enumerate() {
                match wanted.contains(&(k % count)) {
                    true => assert_eq!(ours.to_bits(), theirs.to_bits(), "entry {k} of {wanted:?}"),
                    false => assert!(ours.is_nan(), "entry {k} of {wanted:?} is {ours}"),
                }
            }
        }
        let mut out = vec![0.0; 5 * count];
        assert!(tape.jacobians(t, &state, &[2, 1], &mut out).is_err());
        assert!(tape.jacobians(t, &state, &[count], &mut out).is_err());
    }
}

/// ∂(y, v)/∂(u_e, μ, m0) of the run-time rocket at t = 10 s by DOP853 at 1e-12 against the
/// closed forms of tests/sensitivities.rs (derived there by hand):
/// ∂v/∂u_e = L, ∂v/∂μ = u_e t/m, ∂v/∂m0 = u_e (1/m0 − 1/m), ∂y/∂u_e = t − (m/μ) L,
/// ∂y/∂μ = u_e ((m0/μ²) L − t/μ), ∂y/∂m0 = −(u_e/μ)(L + m/m0 − 1), L = ln(m0/m).
/// Measured: 2.1e-13 relative at most; bound 1e-10 (the issue's).
#[test]
fn the_run_time_rockets_sensitivities_meet_their_closed_forms() {
    let tape = TapeSystem::<1, 2>::new(program(ROCKET_SOURCE, &VALUES)).expect("sizes");
    let columns = [
        Column::Parameter("u_e"),
        Column::Parameter("mu"),
        Column::Parameter("m0"),
    ];
    let sensitive: Sensitive<_, 2> = Sensitive::new::<1, 8>(tape, &columns).expect("fits");
    let start: SVector<f64, 8> = sensitive.start(&SVector::from([0.0, 0.0]));
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::dop853()
    });
    let mut stepper = Dop853::new(&sensitive, 0.0, start, control).expect("a stepper");
    let t = 10.0;
    let solution = run(&mut stepper, &RunConfig::until(t), &[]).expect("the burn runs");
    let (_, state) = solution.last().expect("points");
    let speeds = sensitive.velocity_sensitivities(t, state).expect("regular");
    let (m0, mu, u_e) = (100.0, 5.0, 300.0);
    let m = m0 - mu * t;
    let l = f64::ln(m0 / m);
    let by_hand = [
        (t - m / mu * l, l),
        (u_e * (m0 / (mu * mu) * l - t / mu), u_e * t / m),
        (-(u_e / mu) * (l + m / m0 - 1.0), u_e * (1.0 / m0 - 1.0 / m)),
    ];
    let mut worst = 0f64;
    for (c, (dy, dv)) in by_hand.into_iter().enumerate() {
        let ours_y = sensitive.sensitivity(state, 0, c).expect("in the state");
        worst = worst.max(((ours_y - dy) / dy).abs());
        worst = worst.max(((speeds[c][0] - dv) / dv).abs());
    }
    eprintln!("worst relative error {worst:e}");
    assert!(worst <= 1e-10, "{worst:e}");
}

/// A model derived without the parameter Jacobian is refused by name, not integrated with
/// differences; so is a model with a sampled input.
#[test]
fn a_model_without_its_jacobians_is_refused() {
    let ast = parse_system(ROCKET_SOURCE).expect("parses");
    let plain = derive_for(&ast, Parameters::Inferred, Outputs::FULL).expect("derives");
    let program = Program::new(plain, &VALUES).expect("fits");
    assert!(!program.has_jacobians());
    let tape = TapeSystem::<1, 2>::new(program).expect("sizes");
    let refused = Sensitive::<_, 2>::new::<1, 4>(tape, &[Column::Initial(1)]);
    assert!(
        matches!(refused, Err(SensitivityError::Unsupported(reason)) if reason.contains("parameter Jacobian")),
        "{:?}",
        refused.err()
    );
}

/// Every function the tapes expand, of the state and of parameters: each one-argument
/// function, atan2, a power with a parameter as exponent, √, abs, min, max and a spline of
/// the coordinate (`tests/data/lift_ramp.csv`), in the potential and in a force of x′.
const EVERY_FUNCTION: &str = r#"
    coordinates x
    table lift(x) = "tests/data/lift_ramp.csv", spline
    mass m = m0*(1 + de*x^2)
    body b: mass m, position [x]
    potential m*g*x*(sin(al) + cos(be)*tan(ga) + asin(de) + acos(de)*atan(al) + sinh(be) + cosh(ga) + tanh(al) + ln(m0) + exp(de)) + 1/2*k*sin(x)^2*cosh(x) + al*atan2(x, be) + ga*(1 + x^2)^n + de*sqrt(2 + x) - lift(12*x + 15)*x
    force b: [-k*tanh(x')*abs(x') - de*min(x', al)*ln(2 + x) - al*max(x, be)*acos(x/3) + be*asin(x/3)*exp(-x') - ga*tan(x/4)*sinh(x') - de*cosh(x)*atan(x') - al*atan2(x', be)]
"#;

const EVERY_VALUE: [(&str, f64); 8] = [
    ("m0", 2.0),
    ("g", 9.81),
    ("al", 0.3),
    ("be", 0.7),
    ("ga", 0.4),
    ("de", 0.2),
    ("k", 5.0),
    ("n", 1.5),
];

/// The run-time tapes' Taylor recurrences over tangents (`Program::taylor_tangents`, through
/// `Sensitive` on a `TapeSystem`): coefficient k ≤ 8 of every column — each parameter's and
/// each initial entry's — against the central difference (Richardson-extrapolated) of the
/// plain expansion (`Program::taylor`) with that parameter or entry moved, each order's two
/// entries against the larger of them. Each function's order-0 slope and every recurrence
/// over tangents is in some column. Measured: 4.2e-10; bound 1e-8, 24× (the differences'
/// own error at relative step 1e-4: O(h⁴) truncation and ε/h rounding of coefficients
/// larger than the column's). One slope off by 1e-3 gives 7.7e-8 (√, the weakest) to 8.3e-3
/// (the review's sabotage of every function's); abs's branch reversed, 17.
#[test]
fn the_tapes_recurrences_over_tangents_meet_central_differences() {
    const ORDER: usize = 8;
    let base = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = || {
        let ast = parse_system(EVERY_FUNCTION).expect("parses");
        let outputs = Outputs {
            sensitivities: true,
            ..Outputs::FULL
        };
        varmass::symbolic::derive_in(&ast, Parameters::Inferred, outputs, base).expect("derives")
    };
    let (t, y) = (0.4, [0.9, 1.3]);
    let plain = |values: &[(&str, f64)], y: [f64; 2]| -> Vec<f64> {
        let program = Program::new(d(), values).expect("the parameters fit");
        let mut out = vec![0.0; 2 * (ORDER + 1)];
        program
            .taylor(t, &y, ORDER, &mut out)
            .expect("an expansion");
        out
    };
    let program = Program::new(d(), &EVERY_VALUE).expect("the parameters fit");
    let names: Vec<&'static str> = program.parameter_names().to_vec();
    assert_eq!(names.len(), 8, "{names:?}");
    let mut columns: Vec<Column> = names.iter().map(|n| Column::Parameter(n)).collect();
    columns.extend([Column::Initial(0), Column::Initial(1)]);
    let tape = TapeSystem::<1, 2>::new(program).expect("sizes");
    let sensitive = Sensitive::<_, 2>::new::<1, 22>(tape, &columns).expect("the columns fit");
    let augmented: SVector<f64, 22> = sensitive.start(&SVector::from(y));
    let mut c = vec![SVector::<f64, 22>::zeros(); ORDER + 1];
    (sensitive.taylor_coefficients(
        t,
        &augmented,
        &mut c,
        &mut varmass::core::scratch::Scratch::new(),
    ))
    .expect("recurrences over tangents")
    .expect("an expansion");
    let mut worst = 0f64;
    for (column, kind) in columns.iter().enumerate() {
        let moved = |h: f64| -> Vec<f64> {
            match kind {
                Column::Initial(i) => {
                    let mut z = y;
                    z[*i] += h;
                    plain(&EVERY_VALUE, z)
                }
                _ => {
                    let values =
                        EVERY_VALUE.map(|(n, v)| (n, v + h * f64::from(n == names[column])));
                    plain(&values, y)
                }
            }
        };
        let size = match kind {
            Column::Initial(i) => y[*i].abs(),
            _ => EVERY_VALUE
                .iter()
                .find(|(n, _)| *n == names[column])
                .unwrap()
                .1
                .abs(),
        };
        let h = 1e-4 * size;
        let central = |h: f64| -> Vec<f64> {
            let (up, down) = (moved(h), moved(-h));
            up.iter()
                .zip(&down)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        };
        let (d1, d2) = (central(h), central(2.0 * h));
        let difference: Vec<f64> = d1
            .iter()
            .zip(&d2)
            .map(|(a, b)| (4.0 * a - b) / 3.0)
            .collect();
        let ours: Vec<f64> = (0..=ORDER)
            .flat_map(|k| [c[k][2 * (1 + column)], c[k][2 * (1 + column) + 1]])
            .collect();
        // Order by order: each order's two entries against the larger of them.
        let mut gap = 0f64;
        for (a, b) in ours.chunks(2).zip(difference.chunks(2)) {
            let scale = b[0].abs().max(b[1].abs()).max(1e-300);
            gap = gap.max((a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / scale);
        }
        eprintln!("{kind:?}: {gap:e}");
        worst = worst.max(gap);
    }
    eprintln!("worst {worst:e}");
    assert!(worst <= 1e-8, "{worst:e}");
}
