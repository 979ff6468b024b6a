//! A switch within a few roundings of the run's end (docs/mechanics.md#switches): the run
//! ends on its end time, on the crossing's sliver, and is not crossed past it. Before, the
//! crossing carried t a few roundings past `--until`, and the next stop time (the end, now
//! behind t) was refused: "the stop time must be finite and not before the current time".

use varmass::core::steppers::{AdaptiveControl, StepControl, Taylor, TaylorControl};
use varmass::prelude::*;

/// A unit mass pushed by |t − c|: a kink of the rate at t = c.
#[variable_mass_system(
    "coordinates y
mass m = 1
body b: mass m, position [y]
force b: [abs(t - c)]",
    emit = ["taylor"]
)]
struct Kinked {
    c: f64,
}

/// Every stepper kind that locates switches: adaptive explicit (Dormand–Prince, DOP853),
/// fixed-step (RK4) and Taylor.
const METHODS: [&str; 4] = ["Dormand–Prince", "DOP853", "RK4", "Taylor"];

/// Runs `method` on `system` from rest at t = 0 to `end`.
fn fly(method: &str, system: &Kinked, end: f64) -> Result<Solution<1, 2>, RunError<1, 2>> {
    let start = SVector::zeros();
    let config = RunConfig::until(end);
    let tight = |defaults| {
        StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: 1e-12,
            absolute_tolerance: 1e-12,
            ..defaults
        })
    };
    match method {
        "Dormand–Prince" => run(
            &mut DormandPrince::new(system, 0.0, start, tight(AdaptiveControl::default()))
                .expect("a valid start"),
            &config,
            &[],
        ),
        "DOP853" => run(
            &mut Dop853::new(system, 0.0, start, tight(AdaptiveControl::dop853()))
                .expect("a valid start"),
            &config,
            &[],
        ),
        "RK4" => run(
            &mut ClassicalRk4::new(system, 0.0, start, FixedStep { step: 0.01 })
                .expect("a valid start"),
            &config,
            &[],
        ),
        _ => run(
            &mut Taylor::new(
                system,
                0.0,
                start,
                TaylorControl::adaptive(Tolerance::for_floor(1e-14, 1e-14, Floor::Taylor).unwrap()),
            )
            .expect("a valid start"),
            &config,
            &[],
        ),
    }
}

/// `x` moved by `ulps` representable numbers (negative: down).
fn ulps_from(x: f64, ulps: i32) -> f64 {
    (0..ulps.unsigned_abs()).fold(x, |v, _| if ulps > 0 { v.next_up() } else { v.next_down() })
}

/// From rest, y'' = |t − c| gives, for t ≤ c, y' = c t − t²/2 and y = c t²/2 − t³/6: at
/// t = c, y = c³/3 and y' = c²/2 (c = 1: 1/3 and 1/2). The end and the switch lie within 8
/// roundings of each other around c (17 × 17 pairs), so every run ends within 2·10⁻¹⁵ of
/// t = c, where y and y' move by less than 10⁻¹⁵: the state is the closed form at c to the
/// method's own error (RK4 is exact for the cubic below the kink). Measured: largest
/// |y − 1/3|, |y' − 1/2| over the four methods 2.4·10⁻¹⁵; bound 1e-14. Every run must reach
/// its end exactly (the last recorded time is the end time, not past it). Before the fix
/// Dormand–Prince failed at the first pair (switch −8, end −7 ulps: "the step size 0e0
/// underflowed"), and 147 of 378 such runs through the tool failed.
#[test]
fn a_switch_a_few_roundings_from_the_end_ends_the_run_at_its_end() {
    let mut worst: f64 = 0.0;
    for method in METHODS {
        for switch in -8..=8 {
            for end in -8..=8 {
                let system = Kinked {
                    c: ulps_from(1.0, switch),
                };
                let end_time = ulps_from(1.0, end);
                let case = format!("{method}, switch {switch:+} ulps, end {end:+} ulps");
                let solution =
                    fly(method, &system, end_time).unwrap_or_else(|e| panic!("{case}: {e}"));
                assert_eq!(solution.stop, StopReason::ReachedEnd, "{case}");
                assert_eq!(*solution.times.last().unwrap(), end_time, "{case}");
                let state = solution.states.last().unwrap();
                let error = (state[0] - 1.0 / 3.0).abs().max((state[1] - 0.5).abs());
                assert!(error <= 1e-14, "{case}: off by {error:e}");
                worst = worst.max(error);
            }
        }
    }
    eprintln!("largest error of the end state: {worst:e}");
}
