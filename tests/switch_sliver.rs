//! Events in the sliver a run crosses a switch by (docs/mechanics.md#switches): the Euler
//! step from just before a switch to just past it is recorded as any step is, so a stopping
//! condition met there stops the run there, not on the far side.

use varmass::core::steppers::{AdaptiveControl, StepControl};
use varmass::prelude::*;

/// A unit mass pushed by |x − 1|: a kink of the rate where x crosses 1.
#[variable_mass_system(
    "coordinates x
mass m = 1
body b: mass m, position [x]
force b: [abs(x - 1)]"
)]
struct Pushed {}

/// A run by one stepper, named.
type Flight<'a> = (&'static str, Box<dyn FnMut() -> Solution<1, 2> + 'a>);

/// Both tolerances at `tolerance`, with `defaults` (the method's own factors).
fn control(tolerance: f64, defaults: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..defaults
    })
}

/// Below the switch, u = x − 1 obeys u'' = −u with u(0) = −1, u'(0) = 1, so
/// u = sin t − cos t = √2 sin(t − π/4): x reaches 1 at π/4 with speed √2, and a threshold δ
/// below 1 a time δ/√2 earlier. With δ = 10⁻¹¹ the threshold lies inside the bracket the
/// run crosses the switch by (a few roundings of t wide), so the hit is found only if that
/// sliver is checked: its state must be the threshold to the event's time tolerance
/// (10⁻¹² s at speed √2: 1.4·10⁻¹²). Before the sliver was recorded the run stopped past
/// the switch, 1.06·10⁻¹¹ past the threshold. Measured now: 0 to 2.2·10⁻¹⁶ for both
/// steppers at tolerances 10⁻¹, 10⁻³, 10⁻⁶; bound 2·10⁻¹² (the time tolerance's share).
#[test]
fn a_condition_just_before_a_switch_stops_before_it() {
    let threshold = 1.0 - 1e-11;
    let start = SVector::from([0.0, 1.0]);
    for tolerance in [1e-1, 1e-3, 1e-6] {
        let steppers: [Flight; 2] = [
            (
                "Dormand–Prince",
                Box::new(|| {
                    let c = control(tolerance, AdaptiveControl::default());
                    let mut dp = DormandPrince::new(&Pushed {}, 0.0, start, c).unwrap();
                    run_to(&mut dp, threshold)
                }),
            ),
            (
                "DOP853",
                Box::new(|| {
                    let c = control(tolerance, AdaptiveControl::dop853());
                    let mut dop = Dop853::new(&Pushed {}, 0.0, start, c).unwrap();
                    run_to(&mut dop, threshold)
                }),
            ),
        ];
        for (name, mut fly) in steppers {
            let solution = fly();
            assert_eq!(solution.stop, StopReason::EventFound { index: 0 }, "{name}");
            let x = solution.states.last().unwrap()[0];
            eprintln!(
                "{name} at {tolerance:e}: x − threshold = {:e}",
                x - threshold
            );
            assert!(
                (x - threshold).abs() <= 2e-12,
                "{name} at {tolerance:e}: {x}"
            );
        }
    }
}

/// Runs `stepper` to t = 2 (past the switch at π/4), stopping where x rises through
/// `threshold`.
fn run_to<St: Stepper<1, 2>>(stepper: &mut St, threshold: f64) -> Solution<1, 2> {
    let events = [Event::state_reaches(0, threshold, Direction::Rising)];
    run(stepper, &RunConfig::until(2.0), &events).expect("the push runs")
}
