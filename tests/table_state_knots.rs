//! Knots of a table of the state are switches (docs/tables.md#knots-are-switches): a body
//! thrown up by a lift L(y) read from a linear table of its altitude (knots at 10, 20, 25,
//! 30 and 40 m, kinks of both signs; tests/data/lift_ramp.csv) under gravity. The state
//! rate kinks wherever y crosses a knot; one anchored switch per call watches the knot
//! bracket y is in, so the runs land on every crossing, in both directions.
//!
//! Reference (by hand): m ÿ = L(y) − m g is conservative, so
//! E = ½ m ẏ² + m g y − A(y), A(y) = ∫₀ʸ L the exact antiderivative of the linear table
//! (trapezoids, `Piecewise::antiderivative`), is constant. From rest at y = 0 with
//! L = 30 N > m g the body rises; past 30 m L < m g (L = 2 N falling to 0 at 40 m,
//! m g = 9.81 N) and it falls back: it oscillates between y = 0 and the apex where ½ m ẏ² = 0, i.e.
//! A(y_apex) = m g y_apex, crossing four knots each way twice a period.

use std::path::Path;

use varmass::core::nalgebra::{SVector, Vector2};
use varmass::core::steppers::{AdaptiveControl, Dop853, DormandPrince, StepControl};
use varmass::core::{run, RunConfig, Stepper, VariableMassSystem};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::variable_mass_system;
use varmass::symbolic::parse::parse_system;
use varmass::symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};
use varmass_table::{CsvTable, Interpolation, Piecewise};

#[variable_mass_system(
    r#"
    coordinates y
    units y: m, m_c: kg, g: m/s^2, lift: N
    table lift(y) = "tests/data/lift_ramp.csv", outside hold
    mass m = m_c
    body b: mass m, position [y]
    potential m*g*y
    force b: [lift(y)]
"#
)]
struct Lifted {
    m_c: f64,
    g: f64,
}

const BODY: Lifted = Lifted { m_c: 1.0, g: 9.81 };
/// The end of the runs, s (about four periods).
const END: f64 = 20.0;

/// A(y) = ∫₀ʸ L, exact on the linear table.
fn impulse_of_altitude() -> Piecewise {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lift_ramp.csv");
    let points = CsvTable::parse(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .points;
    Interpolation::Linear.interpolate(&points).antiderivative()
}

fn control(tolerance: f64, base: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..base
    })
}

fn start() -> SVector<f64, 2> {
    Vector2::new(0.0, 0.0)
}

/// The largest |E(t) − E(0)| over the accepted points of a run to END, relative to the
/// work the lift does up to the apex (≈ 400 J), and the highest altitude reached.
fn energy_drift<St: Stepper<1, 2>>(mut stepper: St, config: &RunConfig) -> (f64, f64) {
    let a = impulse_of_altitude();
    let solution = run(&mut stepper, config, &[]).unwrap();
    let energy = |state: &SVector<f64, 2>| {
        let (y, p) = (state[0], state[1]);
        let m = BODY.m_c;
        p * p / (2.0 * m) + m * BODY.g * y - a.value(y)
    };
    let e0 = energy(&solution.states[0]);
    let drift = solution
        .states
        .iter()
        .map(|s| (energy(s) - e0).abs() / 400.0)
        .fold(0.0, f64::max);
    let apex = solution.states.iter().map(|s| s[0]).fold(0.0, f64::max);
    (drift, apex)
}

/// The apex: where ½ m ẏ² = A(y) − m g y returns to 0 above the 30 m knot (past it
/// L ≤ 2 N < m g), by bisection on the exact A to rounding.
fn apex() -> f64 {
    let a = impulse_of_altitude();
    let kinetic = |y: f64| a.value(y) - BODY.m_c * BODY.g * y;
    let (mut low, mut high) = (30.0, 100.0);
    assert!(kinetic(low) > 0.0 && kinetic(high) < 0.0);
    while high - low > 1e-13 * high {
        let mid = 0.5 * (low + high);
        if kinetic(mid) > 0.0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    low
}

#[test]
fn the_table_call_is_one_anchored_switch() {
    assert_eq!(BODY.switch_count(), 1);
    assert_eq!(BODY.switch_name(0), Some("the knots of lift(y)"));
    // Anchored at y = 22 (between 20 and 25): g is the distance to the nearer end, and
    // negative anywhere outside, however far (so a step across two knots is a crossing).
    let at = |y: f64| SVector::<f64, 2>::new(y, 0.0);
    let mut anchors = [0.0];
    BODY.switch_anchors(0.0, &at(22.0), &mut anchors);
    assert_eq!(anchors, [2.0]);
    let mut g = [0.0];
    for (y, expected) in [
        (22.0, 2.0),
        (24.0, 1.0),
        (19.0, -1.0),
        (26.0, -1.0),
        (35.0, -10.0),
    ] {
        BODY.anchored_switching_functions(0.0, &at(y), &anchors, &mut g);
        assert_eq!(g[0], expected, "y = {y}");
    }
    // Below the first knot and past the last, the brackets are half-lines.
    BODY.switch_anchors(0.0, &at(-1.0), &mut anchors);
    assert_eq!(anchors, [-1.0]);
    BODY.switch_anchors(0.0, &at(140.0), &mut anchors);
    assert_eq!(anchors, [6.0]);
    BODY.anchored_switching_functions(0.0, &at(130.0), &anchors, &mut g);
    assert_eq!(g[0], 30.0);
}

#[test]
fn landing_on_the_knots_conserves_the_energy() {
    // Measured drift (switching on / off), END = 20 s: Dormand–Prince 8.5e-9 / 3.1e-6 at
    // 1e-8, 1.3e-10 / 6.8e-8 at 1e-10; DOP853 9.6e-14 / 2.1e-7 at 1e-8, 2.2e-14 / 1.4e-10
    // at 1e-12. Bounds 3–10× the located drift; stepping straight through must be ≥ 100×
    // worse (measured 360–2 000 000×: the kinks cost the steppers their order).
    let cases: [(&str, f64, f64); 4] = [
        ("dopri5", 1e-8, 3e-8),
        ("dopri5", 1e-10, 5e-10),
        ("dop853", 1e-8, 1e-12),
        ("dop853", 1e-12, 2e-13),
    ];
    for (name, tolerance, bound) in cases {
        let mut drifts = [0.0; 2];
        let mut apexes = [0.0; 2];
        for (i, config) in [
            RunConfig::until(END),
            RunConfig::until(END).without_switching(),
        ]
        .iter()
        .enumerate()
        {
            (drifts[i], apexes[i]) = if name == "dopri5" {
                let c = control(tolerance, AdaptiveControl::default());
                energy_drift(DormandPrince::new(&BODY, 0.0, start(), c).unwrap(), config)
            } else {
                let c = control(tolerance, AdaptiveControl::dop853());
                energy_drift(Dop853::new(&BODY, 0.0, start(), c).unwrap(), config)
            };
        }
        assert!(drifts[0] <= bound, "{name} {tolerance:e}: {:e}", drifts[0]);
        assert!(
            drifts[1] >= 100.0 * drifts[0],
            "{name}: {:e} vs {:e}",
            drifts[1],
            drifts[0]
        );
        // Every knot is crossed (the apex is past the last, 40 m), and no point is above
        // the apex (the recorded points sample it only to the steps).
        assert!(
            apexes[0] <= apex() + 1e-6 && apexes[0] > 40.0,
            "{}",
            apexes[0]
        );
    }
}

#[test]
fn the_interpreter_lands_on_the_knots_too() {
    let ast = parse_system(Lifted::SOURCE).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = derive_in(&ast, Parameters::Inferred, Outputs::FULL, base).unwrap();
    let program = Program::new(d, &[("m_c", BODY.m_c), ("g", BODY.g)]).unwrap();
    let tape: TapeSystem<1, 2> = TapeSystem::new(program).unwrap();
    assert_eq!(tape.switch_count(), 1);
    assert_eq!(tape.switch_name(0), Some("the knots of lift(y)"));
    let c = control(1e-10, AdaptiveControl::default());
    let (located, _) = energy_drift(
        DormandPrince::new(&tape, 0.0, start(), c).unwrap(),
        &RunConfig::until(END),
    );
    let (through, _) = energy_drift(
        DormandPrince::new(&tape, 0.0, start(), c).unwrap(),
        &RunConfig::until(END).without_switching(),
    );
    // Measured 1.3e-10 / 6.8e-8, as the generated code's.
    assert!(located <= 5e-10, "{located:e}");
    assert!(through >= 100.0 * located, "{through:e} vs {located:e}");
}
