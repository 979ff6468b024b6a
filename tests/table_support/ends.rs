//! The end states of a one-coordinate model run by several methods, and their check against
//! a closed form: shared by the table-end tests (`tests/table_ends.rs`,
//! `tests/table_state_ends.rs`).

use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{
    AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, FixedStep, StepControl, Taylor,
    TaylorControl,
};
use varmass::core::tolerance::{Floor, Tolerance};
use varmass::core::{run, RunConfig, Solution, VariableMassSystem};

/// The adaptive methods' tolerance, relative and absolute.
pub const TOLERANCE: f64 = 1e-12;

/// A method's name and its end state (x, v).
pub type End = (&'static str, [f64; 2]);

/// (x, v) at `end` from `start` by Taylor, DOP853 and Dormand–Prince at [`TOLERANCE`].
pub fn adaptive_ends<Sys: VariableMassSystem<1, 2>>(
    system: &Sys,
    start: [f64; 2],
    end: f64,
) -> [End; 3] {
    let start = SVector::from(start);
    let config = RunConfig::until(end);
    let adaptive = |base: AdaptiveControl| {
        StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: TOLERANCE,
            absolute_tolerance: TOLERANCE,
            ..base
        })
    };
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(TOLERANCE, TOLERANCE, Floor::Taylor).unwrap());
    let mut taylor = Taylor::new(system, 0.0, start, control).unwrap();
    let mut dop853 = Dop853::new(system, 0.0, start, adaptive(AdaptiveControl::dop853())).unwrap();
    let mut dp =
        DormandPrince::new(system, 0.0, start, adaptive(AdaptiveControl::default())).unwrap();
    [
        ("taylor", last(run(&mut taylor, &config, &[]).unwrap())),
        ("dop853", last(run(&mut dop853, &config, &[]).unwrap())),
        ("dormand-prince", last(run(&mut dp, &config, &[]).unwrap())),
    ]
}

/// (x, v) at `end` from `start` by RK4 and Dormand–Prince at the fixed step `step`.
pub fn fixed_ends<Sys: VariableMassSystem<1, 2>>(
    system: &Sys,
    start: [f64; 2],
    end: f64,
    step: f64,
) -> [End; 2] {
    let start = SVector::from(start);
    let config = RunConfig::until(end);
    let mut rk4 = ClassicalRk4::new(system, 0.0, start, FixedStep { step }).unwrap();
    let control = StepControl::Fixed(FixedStep { step });
    let mut dp = DormandPrince::new(system, 0.0, start, control).unwrap();
    [
        ("rk4 fixed", last(run(&mut rk4, &config, &[]).unwrap())),
        (
            "dormand-prince fixed",
            last(run(&mut dp, &config, &[]).unwrap()),
        ),
    ]
}

/// The last state of `solution`.
fn last(solution: Solution<1, 2>) -> [f64; 2] {
    let (_, state) = solution.last().unwrap();
    [state[0], state[1]]
}

/// Asserts each method's (x, v) within its bound, relative to `expected`.
pub fn assert_near(found: &[End], expected: [f64; 2], bound: impl Fn(&str) -> f64) {
    for (method, state) in found {
        for (value, exact) in state.iter().zip(expected) {
            let error = (value - exact).abs() / exact.abs();
            assert!(
                error <= bound(method),
                "{method}: {value} vs {exact} ({error:e})"
            );
        }
    }
}
