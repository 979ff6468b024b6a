//! Forward sensitivities across a phase change (docs/sensitivities.md#in-a-run-of-phases-a-two-stage-rocket): the two-stage
//! rocket of `models/two_stage_rocket.vms` run by `run_phases` with its columns, against the
//! closed form of the flight.
//!
//! Stage 1 (burn rate μ₁, exhaust speed u₁) burns from M₁ = 1000 kg until its mass m
//! reaches m_b = 500 kg, at T₁ = (M₁ − m_b)/μ₁ = 50 s; the dry stage separates (q, q̇ kept,
//! m set to M₂ = 300 kg, p recomputed) and stage 2 (μ₂, u₂) burns to t_e = 150 s. With
//! Δ = t_e − T₁ and m₂ = M₂ − μ₂ Δ (Tsiolkovsky with gravity loss in each stage, and
//! ∫ ln(M/(M − μs)) ds = s − (m/μ) ln(M/m)):
//!
//! ```text
//! v₁ = v₀ + u₁ ln(M₁/m_b) − g T₁,   y₁ = y₀ + v₀ T₁ + u₁ (T₁ − (m_b/μ₁) ln(M₁/m_b)) − g T₁²/2
//! v  = v₁ + u₂ ln(M₂/m₂) − g Δ,     y  = y₁ + v₁ Δ + u₂ (Δ − (m₂/μ₂) ln(M₂/m₂)) − g Δ²/2
//! ```
//!
//! The separation's time moves with μ₁ and M₁ (∂T₁/∂μ₁ = −T₁/μ₁, ∂T₁/∂M₁ = 1/μ₁), and
//! ∂v/∂T₁ = −g − u₂ μ₂/m₂ + g: a later separation leaves stage 2 less time to burn. Hence
//!
//! ```text
//! ∂v/∂μ₁ = u₂ μ₂ T₁/(μ₁ m₂) = 300,   ∂v/∂u₁ = ln 2,   ∂v/∂μ₂ = u₂ Δ/m₂ = 3000,
//! ∂v/∂u₂ = ln 3,   ∂v/∂v₀ = 1,   ∂v/∂M₁ = u₁/M₁ − u₂ μ₂/(μ₁ m₂) = −3.5,
//! ∂m/∂μ₁ = −μ₂ T₁/μ₁ = −10,   ∂m/∂M₁ = μ₂/μ₁ = 0.2,   ∂m/∂μ₂ = −Δ = −100,
//! ```
//!
//! and y's derivatives from the closed form by a fourth-order central difference (its
//! truncation and rounding below 1e-11 relative at the step used).

#![allow(clippy::result_large_err)] // the stepper closure's StepError<45> carries the state

use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::steppers::{AdaptiveControl, StepControl};
use varmass::core::{run_phases, Carry, EventAction, Phase, PhasedSolution};
use varmass::prelude::*;

#[variable_mass_system(file = "models/two_stage_rocket.vms", emit = ["sensitivities"])]
#[derive(Clone, Copy)]
struct Stage {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// The flight's inputs: [μ₁, u₁, μ₂, u₂, M₁, v₀].
const INPUTS: [f64; 6] = [10.0, 2500.0, 2.0, 3000.0, 1000.0, 0.0];
const G: f64 = 9.81;
const BURNOUT: f64 = 500.0;
const SECOND_STAGE: f64 = 300.0;
const END: f64 = 150.0;

/// The columns of stage 1 and stage 2: each stage's μ and u_e are its own (the other
/// stage's are `Elsewhere`), the initial mass and velocity entries of the velocity state.
const COLUMNS_1: [Column; 6] = [
    Column::Parameter("mu"),
    Column::Parameter("u_e"),
    Column::Elsewhere,
    Column::Elsewhere,
    Column::Initial(2),
    Column::Initial(1),
];
const COLUMNS_2: [Column; 6] = [
    Column::Elsewhere,
    Column::Elsewhere,
    Column::Parameter("mu"),
    Column::Parameter("u_e"),
    Column::Initial(2),
    Column::Initial(1),
];

/// (y, v, m) at t_e from the closed form (the module's comment), stage 2 entered with mass
/// `m_2` by a separation (v continuous) or a capture (m v continuous).
fn closed_form(w: [f64; 6], (m_2, carry): (f64, Carry)) -> [f64; 3] {
    let [mu1, u1, mu2, u2, m1, v0] = w;
    let t1 = (m1 - BURNOUT) / mu1;
    let v1 = v0 + u1 * (m1 / BURNOUT).ln() - G * t1;
    let y1 = v0 * t1 + u1 * (t1 - BURNOUT / mu1 * (m1 / BURNOUT).ln()) - G * t1 * t1 / 2.0;
    let v1 = match carry {
        Carry::Separation => v1,
        Carry::Capture => v1 * BURNOUT / m_2,
    };
    let d = END - t1;
    let m2 = m_2 - mu2 * d;
    let v = v1 + u2 * (m_2 / m2).ln() - G * d;
    let y = y1 + v1 * d + u2 * (d - m2 / mu2 * (m_2 / m2).ln()) - G * d * d / 2.0;
    [y, v, m2]
}

/// ∂(y, v, m)/∂w_c of the closed form by a fourth-order central difference, a step of
/// 1e-3 of the input (1 m/s for v₀ = 0: y is linear in it, and a smaller step would leave
/// y's rounding, 1e-11 m, over it).
fn closed_form_derivative(c: usize, stage_2: (f64, Carry)) -> [f64; 3] {
    let h = match INPUTS[c] {
        0.0 => 1.0,
        w => 1e-3 * w.abs(),
    };
    let at = |k: f64| {
        let mut w = INPUTS;
        w[c] += k * h;
        closed_form(w, stage_2)
    };
    let (a, b, d, e) = (at(-2.0), at(-1.0), at(1.0), at(2.0));
    core::array::from_fn(|i| (a[i] - 8.0 * b[i] + 8.0 * d[i] - e[i]) / (12.0 * h))
}

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::dop853()
    })
}

/// The flight with its columns, stage 2 entered with mass `m_2` by `carry`.
fn fly(stage_2: (f64, Carry)) -> Result<PhasedSolution<1, 21>, RunError<1, 21>> {
    fly_with(stage_2, Event::mass_reaches(0, BURNOUT), &COLUMNS_2)
}

/// The flight with stage 1 ended by `until` and stage 2's columns `columns_2`.
fn fly_with(
    (m_2, carry): (f64, Carry),
    until: Event<'_, 21>,
    columns_2: &[Column],
) -> Result<PhasedSolution<1, 21>, RunError<1, 21>> {
    let [mu1, u1, mu2, u2, m1, v0] = INPUTS;
    let stage_1 = Stage {
        mu: mu1,
        u_e: u1,
        g: G,
    };
    let stage_2 = Stage {
        mu: mu2,
        u_e: u2,
        g: G,
    };
    let first = Sensitive::new::<1, 21>(stage_1, &COLUMNS_1).expect("stage 1's columns");
    let second = Sensitive::new::<1, 21>(stage_2, columns_2).expect("stage 2's columns");
    let start = first
        .start_at_velocities::<1, 21>(0.0, &SVector::from([0.0, v0, m1]))
        .expect("the start");
    let phases = [
        Phase {
            system: first,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(until),
        },
        Phase {
            system: second,
            carry,
            state_masses: &[(0, m_2)],
            until: None,
        },
    ];
    run_phases(
        &phases,
        (0.0, start),
        |system, t, state| Dop853::new(system, t, state, control()),
        &RunConfig::until(END),
    )
}

/// Each column of (y, v, m) at t_e against the closed form: v's and m's against the
/// derivatives written out above, y's against the closed form's central difference.
/// Measured: at most 5.3e-12 relative (of the derivative, or absolute below 1); bound
/// 1e-10. Without the change's time moving (dτ/dw = 0 in the departure) ∂y/∂μ₁ comes out
/// 29829 m instead of 21308 m.
#[test]
fn the_columns_cross_a_separation_whose_time_moves() {
    let stage_2 = (SECOND_STAGE, Carry::Separation);
    let phased = fly(stage_2).expect("the flight");
    let (time, state) = phased.solution.last().expect("points");
    assert_eq!(time, END);
    let motion = closed_form(INPUTS, stage_2);
    let v = state[1] / state[2];
    for (ours, exact) in [state[0], v, state[2]].iter().zip(motion) {
        assert!(
            (ours - exact).abs() <= 1e-11 * exact.abs(),
            "{ours} against {exact}"
        );
    }
    let [mu1, u1, mu2, u2, m1, _] = INPUTS;
    let t1 = (m1 - BURNOUT) / mu1;
    let m2 = SECOND_STAGE - mu2 * (END - t1);
    let written = [
        (u2 * mu2 * t1 / (mu1 * m2), -mu2 * t1 / mu1),
        (2f64.ln(), 0.0),
        (u2 * (END - t1) / m2, -(END - t1)),
        (3f64.ln(), 0.0),
        (u1 / m1 - u2 * mu2 / (mu1 * m2), mu2 / mu1),
        (1.0, 0.0),
    ];
    assert_eq!(written[0].0, 300.0);
    let mut worst = 0f64;
    for (c, (dv, dm)) in written.iter().enumerate() {
        let s = |i: usize| state[3 * (1 + c) + i];
        // v = p/m: dv = (s_p − v s_m)/m.
        let ours = [s(0), (s(1) - v * s(2)) / state[2], s(2)];
        let difference = closed_form_derivative(c, stage_2);
        let expected = [difference[0], *dv, *dm];
        for i in 0..3 {
            let scale = expected[i].abs().max(1.0);
            let error = (ours[i] - expected[i]).abs() / scale;
            eprintln!(
                "column {c}, quantity {i}: {} against {} ({error:.1e})",
                ours[i], expected[i]
            );
            assert!(error <= 1e-10, "column {c}, quantity {i}: {error:e}");
            // The written-out derivatives of v and m and the difference agree too.
            if i > 0 {
                assert!((difference[i] - expected[i]).abs() <= 1e-7 * scale);
            }
            worst = worst.max(error);
        }
    }
    eprintln!("worst: {worst:.1e}");
}

/// A capture instead: stage 2 entered with 700 kg at the same momentum (v⁺ = v₁ m_b/M₂),
/// every column against the closed form's central difference. Measured: at most 4.1e-12
/// relative; bound 1e-10. Carried by the separation's rule instead (q̇'s columns kept),
/// ∂y/∂μ₁ comes out 8101 m instead of 6700 m.
#[test]
fn the_columns_cross_a_capture() {
    let stage_2 = (700.0, Carry::Capture);
    let phased = fly(stage_2).expect("the flight");
    let (time, state) = phased.solution.last().expect("points");
    assert_eq!(time, END);
    let motion = closed_form(INPUTS, stage_2);
    let v = state[1] / state[2];
    for (ours, exact) in [state[0], v, state[2]].iter().zip(motion) {
        assert!(
            (ours - exact).abs() <= 1e-11 * exact.abs(),
            "{ours} against {exact}"
        );
    }
    let mut worst = 0f64;
    for c in 0..6 {
        let s = |i: usize| state[3 * (1 + c) + i];
        let ours = [s(0), (s(1) - v * s(2)) / state[2], s(2)];
        let expected = closed_form_derivative(c, stage_2);
        for i in 0..3 {
            let error = (ours[i] - expected[i]).abs() / expected[i].abs().max(1.0);
            assert!(
                error <= 1e-10,
                "column {c}, quantity {i}: {} against {}",
                ours[i],
                expected[i]
            );
            worst = worst.max(error);
        }
    }
    eprintln!("worst: {worst:.1e}");
}

/// A phase that ends at an event of a function (its gradient unknown) cannot carry the
/// columns: the run stops at the change with the reason, the first stage's points kept.
#[test]
fn a_change_at_an_event_without_a_gradient_is_refused() {
    let burnout = |_: f64, state: &SVector<f64, 21>| state[2] - BURNOUT;
    let until = Event::function(&burnout, Direction::Falling, EventAction::Stop);
    let failure =
        fly_with((SECOND_STAGE, Carry::Separation), until, &COLUMNS_2).expect_err("refused");
    let message = failure.error.to_string();
    assert!(message.contains("event on a state entry"), "{message}");
    let (time, _) = failure.partial.last().expect("stage 1's points");
    assert!((time - 50.0).abs() < 1e-9, "{time}");
}

/// A model where the separation's every term counts (a review's check, kept): a law mass
/// b = b0 + c x + k t of the state and of t, a body at [x + a y sin(w t), y] (a momentum map
/// with t explicit, off-diagonal M), parameters in the momentum map, other values in each
/// phase, columns shared, held elsewhere and an initial entry's.
#[variable_mass_system(
    r#"
    coordinates x, y
    mass m: state, rate -mu
    mass b = b0 + c*x + k*t
    body rocket: mass m, position [x, y]
    body cart: mass b, position [x + a*y*sin(w*t), y]
    potential (m + b)*g*y + 1/2*kk*(x^2 + y^2)
    outflow rocket: rate mu, relative_velocity [-u_e, -u_e]
"#,
    emit = ["sensitivities"]
)]
#[derive(Clone, Copy, Debug)]
struct Cart {
    mu: f64,
    u_e: f64,
    b0: f64,
    c: f64,
    k: f64,
    w: f64,
    g: f64,
    kk: f64,
    a: f64,
}

const CART: Cart = Cart {
    mu: 2.0,
    u_e: 20.0,
    b0: 5.0,
    c: 0.05,
    k: 0.2,
    w: 1.5,
    g: 9.81,
    kk: 30.0,
    a: 0.3,
};

/// Each phase's μ and b0 its own; k, w, c shared (one perturbation of both phases); ẏ(0).
const CART_COLUMNS: [[Column; 8]; 2] = [
    [
        Column::Parameter("mu"),
        Column::Elsewhere,
        Column::Parameter("b0"),
        Column::Elsewhere,
        Column::Parameter("k"),
        Column::Parameter("w"),
        Column::Parameter("c"),
        Column::Initial(3),
    ],
    [
        Column::Elsewhere,
        Column::Parameter("mu"),
        Column::Elsewhere,
        Column::Parameter("b0"),
        Column::Parameter("k"),
        Column::Parameter("w"),
        Column::Parameter("c"),
        Column::Initial(3),
    ],
];

/// The start [x, y, ẋ, ẏ, m] and the end.
const CART_START: [f64; 5] = [0.5, 0.0, 1.0, 2.0, 20.0];
const CART_END: f64 = 9.0;

/// The two phases' systems with column `c` moved by h (an initial speed's move returned).
fn moved(second: Cart, c: usize, h: f64) -> (Cart, Cart, f64) {
    let (mut a, mut b, mut speed) = (CART, second, 0.0);
    match c {
        0 => a.mu += h,
        1 => b.mu += h,
        2 => a.b0 += h,
        3 => b.b0 += h,
        4 => (a.k, b.k) = (a.k + h, b.k + h),
        5 => (a.w, b.w) = (a.w + h, b.w + h),
        6 => (a.c, b.c) = (a.c + h, b.c + h),
        _ => speed = h,
    }
    (a, b, speed)
}

/// Where the first phase ends: its propellant down to 10 kg, or y rising through 1 m.
#[derive(Clone, Copy, Debug)]
enum Until {
    Burnout,
    Rising,
}

impl Until {
    fn event<const S: usize>(self) -> Event<'static, S> {
        match self {
            Until::Burnout => Event::mass_reaches(0, 10.0),
            Until::Rising => Event::state_reaches(1, 1.0, Direction::Rising),
        }
    }
}

/// The phases of `systems`, the second entered by `carry` at `until` with m = 6 kg (a
/// separation) or 15 kg (a capture: mass arrives).
fn cart_phases<Sys, const S: usize>(
    [first, second]: [Sys; 2],
    carry: Carry,
    until: Until,
) -> [Phase<'static, Sys, S>; 2] {
    [
        Phase {
            system: first,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(until.event()),
        },
        Phase {
            system: second,
            carry,
            state_masses: match carry {
                Carry::Separation => &[(0, 6.0)],
                Carry::Capture => &[(0, 15.0)],
            },
            until: None,
        },
    ]
}

/// The end state of the plain flight of `systems` from the start with ẏ moved by `speed`.
fn plain_end(systems: [Cart; 2], speed: f64, carry: Carry, until: Until) -> [f64; 5] {
    let mut start = SVector::from(CART_START);
    start[3] += speed;
    let start = VariableMassSystem::<2, 5>::momentum_state(&systems[0], 0.0, &start);
    let phases = cart_phases(systems, carry, until);
    let stepper = |system, t, state| Dop853::new(system, t, state, control());
    let phased = run_phases(&phases, (0.0, start), stepper, &RunConfig::until(CART_END))
        .expect("the plain flight");
    assert_eq!(phased.changes.len(), 1);
    (*phased.solution.last().expect("points").1).into()
}

/// Every column at the end against a fourth-order central difference of whole plain runs
/// (h = 1e-4); the largest error relative to the entry (absolute below 1).
fn cart_error(second: Cart, carry: Carry, until: Until) -> f64 {
    let [first_columns, second_columns] = &CART_COLUMNS;
    let first = Sensitive::new::<2, 45>(CART, first_columns).expect("phase 1's columns");
    let second_system = Sensitive::new::<2, 45>(second, second_columns).expect("phase 2's");
    let start =
        (first.start_at_velocities::<2, 45>(0.0, &SVector::from(CART_START))).expect("the start");
    let phases = cart_phases([first, second_system], carry, until);
    let stepper = |system, t, state| Dop853::new(system, t, state, control());
    let phased = run_phases(&phases, (0.0, start), stepper, &RunConfig::until(CART_END))
        .expect("the flight with its columns");
    let end = *phased.solution.last().expect("points").1;
    let h = 1e-4;
    let mut worst = 0f64;
    for c in 0..8 {
        let at = |k: f64| {
            let (a, b, speed) = moved(second, c, k * h);
            plain_end([a, b], speed, carry, until)
        };
        let (down2, down, up, up2) = (at(-2.0), at(-1.0), at(1.0), at(2.0));
        for i in 0..5 {
            let difference = (down2[i] - 8.0 * down[i] + 8.0 * up[i] - up2[i]) / (12.0 * h);
            let ours = end[5 * (1 + c) + i];
            worst = worst.max((ours - difference).abs() / difference.abs().max(1.0));
        }
    }
    worst
}

/// Separation at a mass event, separation at a coordinate's event, capture at a
/// coordinate's event, each against central differences of whole runs. Measured: at most
/// 3.2e-9 (the differences' own accuracy); bound 1e-7.
#[test]
fn the_columns_cross_changes_of_a_model_with_every_term() {
    let separated = Cart {
        mu: 1.0,
        u_e: 30.0,
        b0: 3.0,
        k: 0.1,
        ..CART
    };
    let captured = Cart {
        b0: 7.0,
        k: 0.3,
        ..separated
    };
    for (second, carry, until) in [
        (separated, Carry::Separation, Until::Burnout),
        (separated, Carry::Separation, Until::Rising),
        (captured, Carry::Capture, Until::Rising),
    ] {
        let error = cart_error(second, carry, until);
        eprintln!("{carry:?} at {until:?}: {error:.1e}");
        assert!(error <= 1e-7, "{carry:?} at {until:?}: {error:e}");
    }
}

/// A column that is one initial entry's before the change and another's after it would
/// change its meaning there: refused at the change with the column.
#[test]
fn a_column_that_changes_its_initial_entry_is_refused() {
    let mut after = COLUMNS_2;
    after[4] = Column::Initial(0);
    let until = Event::mass_reaches(0, BURNOUT);
    let failure = fly_with((SECOND_STAGE, Carry::Separation), until, &after).expect_err("refused");
    let expected = SystemError::PhaseColumnDiffers { column: 4 };
    assert_eq!(failure.error.kind, StepErrorKind::System(expected));
}
