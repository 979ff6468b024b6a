//! A knot of a table of the state reached exactly at the end of a step (issue 34, item 2:
//! the Calisto flight at tolerance 1e-10 whose y + 1400 landed on the density table's knot
//! 4500 m and made no progress for 10⁷ steps).
//!
//! The cause: the step ending on the knot leaves the knot's switch g = 0 there, and the run
//! keeps the side g came from (a zero is no crossing yet). The next step crosses it, located
//! at that step's start; the Euler step across a rounding-wide bracket did not move the
//! argument off the knot, so the run looked for the crossing along the tangent, and the
//! secant's root of a switch standing on zero is −0, dropped as "not ahead". The nearest
//! root left was another switch's (here the next knot of a second table, 3 ahead): the run
//! redid the step to 0.9 of the way there, met the same crossing at the same start, and
//! went round for ever (until `max_steps`; `TooManySteps` at t = 1 here, before the fix).
//! Now a switch on zero that leaves its side has its root 0, and the crossing is made by the
//! shortest Euler step that changes its sign (`run::switching`).
//!
//! The model by hand: a unit mass pushed by G(x) + K(x), both tables zero everywhere, from
//! x(0) = 999, ẋ(0) = 1: x(t) = 999 + t, ẋ = 1. With a fixed step of 0.25, x is exact in
//! binary (sums of quarters) under Euler, RK4 and Dormand–Prince's weights, so the step to
//! t = 1 ends on the knot x = 1000 exactly; at t = 2, x = 1001, ẋ = 1.

use varmass::prelude::*;

#[variable_mass_system(
    r#"
    coordinates x
    table G(s) = "tests/data/zero_knot_1000.csv"
    table K(s) = "tests/data/zero_knot_1003.csv"
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*(G(x) + K(x))]
"#
)]
struct TwoKnots {
    m0: f64,
}

const MASS: TwoKnots = TwoKnots { m0: 1.0 };

/// The run from x = 999 to t = 2, at most 1 000 steps (the flight takes 8).
fn fly<St: Stepper<1, 2>>(stepper: &mut St) -> Solution<1, 2> {
    let config = RunConfig {
        max_steps: 1_000,
        ..RunConfig::until(2.0)
    };
    run(stepper, &config, &[]).expect("the run crosses the knot")
}

#[test]
fn a_knot_of_a_state_table_reached_exactly_is_crossed() {
    assert_eq!(MASS.switch_count(), 2);
    let start = SVector::from([999.0, 1.0]);
    let fixed = FixedStep { step: 0.25 };
    let solutions = [
        (
            "Euler",
            fly(&mut ExplicitEuler::new(&MASS, 0.0, start, fixed).unwrap()),
        ),
        (
            "RK4",
            fly(&mut ClassicalRk4::new(&MASS, 0.0, start, fixed).unwrap()),
        ),
        (
            "Dormand–Prince",
            fly(&mut DormandPrince::new(&MASS, 0.0, start, StepControl::Fixed(fixed)).unwrap()),
        ),
    ];
    for (name, solution) in solutions {
        // The step to t = 1 lands on the knot exactly (the case of the issue).
        let on_knot = solution.times.iter().zip(&solution.states);
        let knot = on_knot.filter(|(&t, _)| t == 1.0).map(|(_, s)| s[0]);
        assert!(
            knot.clone().any(|x| x == 1000.0),
            "{name}: {:?}",
            solution.times
        );
        let (time, state) = solution.last().expect("points");
        assert_eq!(time, 2.0, "{name}");
        // x carries the crossing's Euler sliver (a few roundings of t, at ẋ = 1): measured
        // 0 off; bound 1e-12 (ten thousand roundings of 1000).
        assert!((state[0] - 1001.0).abs() <= 1e-12, "{name}: {state}");
        assert_eq!(state[1], 1.0, "{name}");
        assert!(
            solution.statistics.accepted_steps < 20,
            "{name}: {:?}",
            solution.statistics
        );
    }
}
