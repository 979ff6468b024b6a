//! Forward sensitivities on the Taylor stepper (docs/sensitivities.md#taylor): the augmented
//! state's Taylor coefficients by the generated recurrences over tangents
//! (`emit = ["sensitivities", "taylor"]`, `taylor_coefficients_tangents`), against the
//! closed forms of `tests/sensitivities.rs` and the scalar expansion.

mod sensitivity_support;

use sensitivity_support::rocket_by_hand;
use varmass::core::scratch::Scratch;
use varmass::core::sensitivity::{Column, Sensitive};
use varmass::prelude::*;

/// Tsiolkovsky's rocket going up: m = m0 − μ t, exhaust at u_e backwards, weight m g (the
/// model of `tests/sensitivities.rs`, with its Taylor recurrences).
#[variable_mass_system(
    r#"
    coordinates y
    mass m = m0 - mu*t
    body rocket: mass m, position [y]
    force rocket: [-m*g]
    outflow rocket: rate mu, relative_velocity [-u_e]
"#,
    emit = ["sensitivities", "taylor"]
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

/// u_e, μ, m0 and p(0): two passes of two tangents.
const COLUMNS: [Column; 4] = [
    Column::Parameter("u_e"),
    Column::Parameter("mu"),
    Column::Parameter("m0"),
    Column::Initial(1),
];

fn taylor(tolerance: f64) -> TaylorControl {
    TaylorControl::adaptive(Tolerance::for_floor(tolerance, tolerance, Floor::Taylor).unwrap())
}

/// ∂(y, v)/∂(u_e, μ, m0, p0) at t from rest, by hand (derived in
/// `sensitivity_support::rocket_by_hand`).
fn by_hand(r: &Rocket, t: f64) -> [(f64, f64); 4] {
    rocket_by_hand((r.m0, r.mu, r.u_e), t)
}

/// The issue's closed-form case with the Taylor stepper: the rocket's sensitivities to
/// u_e, μ, m0 and p(0) at t = 10 s (m = 50 kg) at tolerance 1e-12 against the closed
/// forms (v = p/m, ∂v/∂w = (∂p/∂w − v ∂m/∂w)/m with ∂m/∂μ = −t, ∂m/∂m0 = 1). Measured:
/// 1.2e-14 relative at most, in 6 steps; bound 1e-10 (the issue's).
#[test]
fn the_rockets_sensitivities_meet_their_closed_forms_on_taylor() {
    let sensitive: Sensitive<Rocket, 2> =
        Sensitive::new::<1, 10>(ROCKET, &COLUMNS).expect("the columns fit");
    let start: SVector<f64, 10> = sensitive.start(&SVector::from([0.0, 0.0]));
    let mut stepper = Taylor::new(&sensitive, 0.0, start, taylor(1e-12)).expect("a stepper");
    let t = 10.0;
    let solution = run(&mut stepper, &RunConfig::until(t), &[]).expect("the burn runs");
    let (end, state) = solution.last().expect("points");
    assert_eq!(end, t);
    let m = ROCKET.m0 - ROCKET.mu * t;
    let v = state[1] / m;
    let mut worst = 0f64;
    for (c, (dy, dv)) in by_hand(&ROCKET, t).into_iter().enumerate() {
        let column = |i| sensitive.sensitivity(state, i, c).expect("in the state");
        let dm = [0.0, -t, 1.0, 0.0][c];
        let ours_v = (column(1) - v * dm) / m;
        eprintln!(
            "column {c}: ∂y {:.15e} ({dy:.15e}), ∂v {ours_v:.15e} ({dv:.15e})",
            column(0)
        );
        worst = worst.max(((column(0) - dy) / dy).abs());
        worst = worst.max(((ours_v - dv) / dv).abs());
    }
    eprintln!(
        "worst relative error {worst:e} in {} steps",
        solution.statistics.accepted_steps
    );
    assert!(worst <= 1e-10, "{worst:e}");
}

/// The augmented expansion's state part is the scalar expansion's to the bit (the tangents'
/// values are computed by the same operations in the same order), and each column's
/// coefficients are the derivatives of the scalar ones: against central differences of
/// the scalar expansion in u_e (h = 1e-4 of it), to 1e-8 relative of the largest.
/// Measured: 0 and 1.0e-12.
#[test]
fn the_augmented_coefficients_are_the_scalar_ones_and_their_derivatives() {
    let sensitive: Sensitive<Rocket, 2> =
        Sensitive::new::<1, 10>(ROCKET, &COLUMNS).expect("the columns fit");
    let y = SVector::from([12.0, 1500.0]);
    let mut augmented: SVector<f64, 10> = sensitive.start(&y);
    for i in 2..10 {
        augmented[i] = 0.1 * i as f64;
    }
    let t = 2.5;
    let order = 12;
    let mut ours = vec![SVector::<f64, 10>::zeros(); order + 1];
    let mut scratch = Scratch::new();
    (sensitive.taylor_coefficients(t, &augmented, &mut ours, &mut scratch))
        .expect("recurrences")
        .expect("an expansion");
    let scalar = |r: &Rocket, y: &SVector<f64, 2>| {
        let mut c = vec![SVector::<f64, 2>::zeros(); order + 1];
        (r.taylor_coefficients(t, y, &mut c, &mut Scratch::new()))
            .expect("recurrences")
            .expect("an expansion");
        c
    };
    let plain = scalar(&ROCKET, &y);
    for k in 0..=order {
        assert_eq!(
            ours[k].fixed_rows::<2>(0),
            plain[k].fixed_rows::<2>(0),
            "order {k}"
        );
    }
    // Column 0 is u_e with s = (0.2, 0.3): the directional derivative of the expansion
    // along (y moved by s, u_e by 1).
    let h = 1e-4 * ROCKET.u_e;
    let moved = |sign: f64| {
        let r = Rocket {
            u_e: ROCKET.u_e + sign * h,
            ..ROCKET
        };
        scalar(
            &r,
            &(y + SVector::from([augmented[2], augmented[3]]) * (sign * h)),
        )
    };
    let (up, down) = (moved(1.0), moved(-1.0));
    let mut worst = 0f64;
    let largest = (0..=order)
        .map(|k| ours[k][2].abs().max(ours[k][3].abs()))
        .fold(0.0, f64::max);
    for k in 0..=order {
        for i in 0..2 {
            let difference = (up[k][i] - down[k][i]) / (2.0 * h);
            worst = worst.max((ours[k][2 + i] - difference).abs() / largest);
        }
    }
    eprintln!("against central differences of the expansion: {worst:e}");
    assert!(worst <= 1e-8, "{worst:e}");
}

#[variable_mass_system(file = "models/sled.vms", with = ["impact"], emit = ["sensitivities", "taylor"])]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

/// The sled's ∂v/∂c at x = 50 m on the Taylor stepper, against the derivative of eq. 24
/// (derived in `tests/sensitivities.rs`): ∂v/∂c = a x² φ'(ε)/(3 v m0), φ'(ε) =
/// −(3 + ε)/(1 + ε)³, ε = c x/m0, a = g (sin θ − f_d cos θ); ours from the run stopped at
/// x = 50 m on the Taylor series and `at_crossing`. Measured: 5.0e-13 relative; bound 1e-9
/// (the issue's).
#[test]
fn the_sleds_speed_sensitivity_to_c_meets_eq_24_on_taylor() {
    let sled = Sled {
        m0: 10.0,
        c: 2.0,
        g: 9.81,
        theta: 30f64.to_radians(),
        f_d: 0.1,
    };
    let (m0, c, x) = (sled.m0, sled.c, 50.0);
    let a = sled.g * (sled.theta.sin() - sled.f_d * sled.theta.cos());
    let eps = c * x / m0;
    let phi = (3.0 + 3.0 * eps + eps * eps) / (1.0 + eps).powi(2);
    let v = (2.0 / 3.0 * a * x * phi).sqrt();
    let by_hand = a * x * x * (-(3.0 + eps) / (1.0 + eps).powi(3)) / (3.0 * v * m0);
    let sensitive: Sensitive<Sled, 2> =
        Sensitive::new::<1, 4>(sled, &[Column::Parameter("c")]).expect("the column fits");
    let start: SVector<f64, 4> = sensitive.start(&SVector::zeros());
    let mut stepper = Taylor::new(&sensitive, 0.0, start, taylor(1e-12)).expect("a stepper");
    let at_50_m = Event::state_reaches(0, x, Direction::Rising);
    let solution = run(&mut stepper, &RunConfig::until(1e3), &[at_50_m]).expect("the sled runs");
    let (t, state) = solution.last().expect("points");
    let at = (sensitive.at_crossing(t, state, 0))
        .expect("a state")
        .expect("a crossing");
    let m = m0 + c * state[0];
    let speed = state[1] / m;
    let ours = (at[0].state[1] - speed * state[0]) / m;
    let error = ((ours - by_hand) / by_hand).abs();
    eprintln!("∂v/∂c at 50 m: {ours:.15e} (eq. 24: {by_hand:.15e}), {error:e}");
    assert!(error <= 1e-9, "{error:e}");
}

/// The passes' widths (1 for one column, 2 for two, 4 for more) give each column the same
/// bits: a lane's arithmetic does not depend on its neighbours. The columns of one, two and
/// four at once, and of five (passes of 4 + 4 with three lanes unseeded) meet to the bit.
#[test]
fn every_pass_width_gives_the_same_columns() {
    let y = SVector::from([12.0, 1500.0]);
    let (t, order) = (2.5, 10);
    let expand = |columns: &[Column]| -> Vec<Vec<f64>> {
        let k = columns.len();
        let mut out = vec![vec![0.0; 2 * (1 + k)]; order + 1];
        macro_rules! with {
            ($sa:literal) => {{
                let sensitive = Sensitive::<Rocket, 2>::new::<1, $sa>(ROCKET, columns).unwrap();
                let mut augmented: SVector<f64, $sa> = sensitive.start(&y);
                for i in 2..$sa {
                    augmented[i] += 0.1 * (i % 4) as f64;
                }
                let mut c = vec![SVector::<f64, $sa>::zeros(); order + 1];
                (sensitive.taylor_coefficients(t, &augmented, &mut c, &mut Scratch::new()))
                    .expect("recurrences")
                    .expect("an expansion");
                for (row, series) in out.iter_mut().zip(&c) {
                    row.copy_from_slice(series.as_slice());
                }
            }};
        }
        match k {
            1 => with!(4),
            2 => with!(6),
            4 => with!(10),
            _ => with!(12),
        }
        out
    };
    let four = expand(&COLUMNS);
    let five = expand(&[
        COLUMNS[0],
        COLUMNS[1],
        COLUMNS[2],
        COLUMNS[3],
        Column::Initial(0),
    ]);
    let two = expand(&COLUMNS[..2]);
    let one = expand(&COLUMNS[..1]);
    // The fifth column, in a pass of 4 with three lanes unseeded, alone in a pass of 1.
    let alone = expand(&[Column::Initial(0)]);
    for k in 0..=order {
        assert_eq!(two[k][..], four[k][..6], "order {k}");
        assert_eq!(one[k][..], four[k][..4], "order {k}");
        assert_eq!(five[k][..10], four[k][..], "order {k}");
        if k > 0 {
            // Coefficients 1 on of a column do not read its own start: the same bits.
            assert_eq!(five[k][10..], alone[k][2..], "order {k}");
        }
    }
}

/// Every function of the DSL on parameters alone (sin θ of a parameter θ: the tape writes a
/// constant's call as one op whose order-0 derivative is the function's own) and on the
/// state.
#[variable_mass_system(
    r#"
    coordinates x
    mass m = m0
    body b: mass m, position [x]
    potential m*g*x*(sin(al) + cos(be)*tan(ga) + asin(de) + acos(de)*atan(al) + sinh(be) + cosh(ga) + tanh(al) + ln(m0) + exp(de)) + 1/2*k*sin(x)^2*cosh(x)
"#,
    emit = ["sensitivities", "taylor"]
)]
struct Functions {
    m0: f64,
    g: f64,
    al: f64,
    be: f64,
    ga: f64,
    de: f64,
    k: f64,
}

/// Coefficient 1 of the expansion is the state rate (y\[1\] = f(y)), so each column's
/// coefficient 1 is J_y s + ∂f/∂w: the Taylor recurrences over tangents against the state
/// rate over tangents (another generated function, the printed state rate), for every
/// parameter of the sled (its sin θ and cos θ of a parameter) and of a model with every
/// function. Measured: 3.3e-16 and 1.3e-16 relative; bound 1e-13. Before the constant calls took
/// their own slope (session 41's review) the sled's θ column was 87 % off.
#[test]
fn the_first_coefficients_are_the_state_rates_for_every_parameter() {
    fn worst<Sys: VariableMassSystem<1, 2>, const SA: usize>(
        sensitive: &Sensitive<Sys, 2>,
        y: SVector<f64, 2>,
    ) -> f64 {
        let mut augmented: SVector<f64, SA> = sensitive.start(&y);
        for i in 2..SA {
            augmented[i] = 0.01 * i as f64;
        }
        let mut c = vec![SVector::<f64, SA>::zeros(); 3];
        (sensitive.taylor_coefficients(0.7, &augmented, &mut c, &mut Scratch::new()))
            .expect("recurrences")
            .expect("an expansion");
        let rate = sensitive.state_rate(0.7, &augmented).expect("a rate");
        (2..SA)
            .map(|i| (c[1][i] - rate[i]).abs() / rate[i].abs().max(1.0))
            .fold(0.0, f64::max)
    }
    let sled = Sled {
        m0: 10.0,
        c: 2.0,
        g: 9.81,
        theta: 0.5,
        f_d: 0.1,
    };
    let names = ["m0", "c", "g", "theta", "f_d"].map(Column::Parameter);
    let sled = Sensitive::<Sled, 2>::new::<1, 12>(sled, &names).unwrap();
    let functions = Functions {
        m0: 2.0,
        g: 9.81,
        al: 0.3,
        be: 0.7,
        ga: 0.4,
        de: 0.2,
        k: 5.0,
    };
    let names = ["m0", "g", "al", "be", "ga", "de", "k"].map(Column::Parameter);
    let functions = Sensitive::<Functions, 2>::new::<1, 16>(functions, &names).unwrap();
    let (a, b) = (
        worst::<_, 12>(&sled, SVector::from([3.0, 40.0])),
        worst::<_, 16>(&functions, SVector::from([0.8, 1.5])),
    );
    eprintln!("sled {a:e}, every function {b:e}");
    assert!(a <= 1e-13 && b <= 1e-13, "{a:e} {b:e}");
}

/// An oscillator x and a particle z pushed by a parameter w = 0: ∂z/∂w = t²/2 grows to 2e6
/// while x stays of size 1.
#[variable_mass_system(
    r#"
    coordinates x, z
    mass m = m0
    body b: mass m, position [x, z]
    potential 1/2*k*x^2 - m*w*z
"#,
    emit = ["sensitivities", "taylor"]
)]
#[derive(Clone, Copy)]
struct Pushed {
    m0: f64,
    k: f64,
    w: f64,
}

/// The Taylor step rule measures the state and each column apart (`measured_block`): a
/// column that grows large does not loosen the state's tolerance. x(2000) = cos 2000 (k =
/// m): with the column ∂/∂w (∂z/∂w = t²/2 = 2e6 at the end, a polynomial: its block bounds
/// no step) the state's error stays the plain run's size, and the column meets t²/2; with
/// the columns out of the error control the run is the plain run, bit for bit. Measured: 4.1e-11 with the column and without,
/// 2935 steps either way (with one norm over everything it was 2.5e-4), ∂z/∂w exact; bound
/// 10× the plain run's error and 1e-10.
#[test]
fn a_large_column_does_not_loosen_the_states_tolerance_on_taylor() {
    let pushed = Pushed {
        m0: 1.0,
        k: 1.0,
        w: 0.0,
    };
    let (end, start) = (2000.0, SVector::from([1.0, 0.0, 0.0, 0.0]));
    let control = taylor(1e-10);
    let mut plain = Taylor::new(&pushed, 0.0, start, control).unwrap();
    let plain = run(&mut plain, &RunConfig::until(end), &[]).expect("the plain run");
    let plain_state = *plain.last().expect("points").1;
    let plain_error = (plain_state[0] - end.cos()).abs();
    let columns = [Column::Parameter("w")];
    for controlled in [true, false] {
        let sensitive = Sensitive::<Pushed, 4>::new::<2, 8>(pushed, &columns)
            .unwrap()
            .with_error_control(controlled);
        let augmented: SVector<f64, 8> = sensitive.start(&start);
        let mut stepper = Taylor::new(&sensitive, 0.0, augmented, control).unwrap();
        let solution = run(&mut stepper, &RunConfig::until(end), &[]).expect("the run");
        let state = *solution.last().expect("points").1;
        let error = (state[0] - end.cos()).abs();
        let column = (state[5] - end * end / 2.0).abs() / (end * end / 2.0);
        eprintln!(
            "controlled {controlled}: x {error:.1e} (plain {plain_error:.1e}), ∂z/∂w {column:.1e}, {} steps (plain {})",
            solution.statistics.accepted_steps, plain.statistics.accepted_steps
        );
        assert!(
            error <= 10.0 * plain_error,
            "{error:e} against {plain_error:e}"
        );
        assert!(column <= 1e-10, "{column:e}");
        if !controlled {
            assert_eq!(state.fixed_rows::<4>(0), plain_state.fixed_rows::<4>(0));
        }
    }
}

/// A column that is no polynomial bounds the steps by its own tolerance: ∂x/∂k of the
/// oscillator (k = m = 1, x = cos √(k/m) t) is −t sin t / 2, of size 1000 at t = 2000, held
/// to rtol of itself; and with a purely relative tolerance (atol = 0) a column that starts
/// at 0 does not stop the run (its tolerance 0 bounds nothing until it moves). Measured:
/// 1.3e-10 of the column's size either way, in 2965 and 2966 steps (the plain run's 2935:
/// the column bounds some); bound 1e-9.
#[test]
fn a_column_is_held_to_its_own_tolerance_on_taylor() {
    let pushed = Pushed {
        m0: 1.0,
        k: 1.0,
        w: 0.0,
    };
    let (end, start): (f64, _) = (2000.0, SVector::from([1.0, 0.0, 0.0, 0.0]));
    let columns = [Column::Parameter("k")];
    let sensitive = Sensitive::<Pushed, 4>::new::<2, 8>(pushed, &columns).unwrap();
    let augmented: SVector<f64, 8> = sensitive.start(&start);
    let exact = -end * end.sin() / 2.0;
    for atol in [1e-10, 0.0] {
        let tolerance = Tolerance::for_floor(1e-10, atol, Floor::Taylor).unwrap();
        let mut stepper = Taylor::new(
            &sensitive,
            0.0,
            augmented,
            TaylorControl::adaptive(tolerance),
        )
        .unwrap();
        let solution = run(&mut stepper, &RunConfig::until(end), &[]).expect("the run");
        let state = *solution.last().expect("points").1;
        let error = (state[4] - exact).abs() / (end / 2.0);
        let steps = solution.statistics.accepted_steps;
        eprintln!(
            "atol {atol:e}: ∂x/∂k {} against {exact} ({error:.1e}), {steps} steps",
            state[4]
        );
        assert!(error <= 1e-9, "{error:e}");
    }
}
