//! Taylor's method in lanes (`run_lanes` with a `TaylorControl`, `emit = ["taylor",
//! "lanes"]`) against the scalar Taylor run member by member, on vertical rockets with
//! dispersed burn rate μ and exhaust speed u_e: issue 38's rocket (m0 = 1 kg, μ = 0.05 kg/s,
//! u_e = 300 m/s, to 15 s, where a quarter of the mass is left), μ and u_e each spread by
//! ±10 %.
//!
//! The closed form (m = m0 − μt; Meshchersky, thrust μ u_e, gravity g): m v̇ = μ u_e − m g,
//! so v̇ = μ u_e/(m0 − μt) − g and, from rest,
//!   v(t) = u_e ln(m0/m) − g t,
//!   y(t) = ∫₀ᵗ v = u_e [t − (m/μ) ln(m0/m)] − ½ g t²
//! (∫ ln(m0/(m0 − μs)) ds = t − ((m0 − μt)/μ) ln(m0/(m0 − μt)), by parts). The state is
//! [y, p, m] with p = m v.

use varmass::core::ensemble::member_rng;
use varmass::core::ensemble::rand::RngExt;
use varmass::core::lanes::{run_lanes, run_lanes_with, LaneEnd, LaneJob, LaneKernel};
use varmass::core::{EventAction, Statistics};
use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", emit = ["taylor", "lanes"])]
#[derive(Clone, Copy)]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

const M0: f64 = 1.0;
const G: f64 = 9.81;
const END: f64 = 15.0;

/// (burn rate, exhaust speed) of member `index`.
fn sample(index: u64) -> (f64, f64) {
    let mut rng = member_rng(38, index);
    (
        rng.random_range(0.045..0.055),
        rng.random_range(270.0..330.0),
    )
}

fn control(tolerance: f64) -> TaylorControl {
    TaylorControl::adaptive(Tolerance::new(tolerance, tolerance).expect("a usable tolerance"))
}

fn start() -> SVector<f64, 3> {
    SVector::<f64, 3>::new(0.0, 0.0, M0)
}

fn jobs<'e>(members: &[(f64, f64)], events: &'e [Event<'e, 3>]) -> Vec<LaneJob<'e, Rocket, 3>> {
    members
        .iter()
        .map(|&(mu, u_e)| LaneJob {
            system: Rocket { mu, u_e, g: G },
            time: 0.0,
            state: start(),
            events,
        })
        .collect()
}

/// The scalar Taylor run of one member: its last point and statistics, or its error.
fn scalar(
    system: &Rocket,
    tolerance: f64,
    config: &RunConfig,
    events: &[Event<'_, 3>],
) -> Result<(f64, SVector<f64, 3>, Statistics), StepError<3>> {
    let mut stepper = Taylor::new(system, 0.0, start(), control(tolerance))?;
    let solution = run(&mut stepper, config, events).map_err(|e| e.error)?;
    let (t, y) = solution.last().expect("a run records its start");
    Ok((t, *y, solution.statistics))
}

fn same_bits(a: &SVector<f64, 3>, b: &SVector<f64, 3>) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

fn assert_same(
    index: usize,
    lanes: &LaneEnd<3>,
    (t, y, statistics): &(f64, SVector<f64, 3>, Statistics),
) {
    assert!(
        lanes.time.to_bits() == t.to_bits() && same_bits(&lanes.state, y),
        "member {index}: lanes ({}, {:?}) vs scalar ({t}, {y:?})",
        lanes.time,
        lanes.state
    );
    assert_eq!(
        lanes.statistics.accepted_steps, statistics.accepted_steps,
        "member {index}"
    );
    assert_eq!(
        lanes.statistics.rate_evaluations, statistics.rate_evaluations,
        "member {index}"
    );
}

/// Every member in 4 and 8 lanes, through both kernels, at three tolerances (orders 8, 12
/// and 15; 9 or 10 steps each), once to the end time and once to an event on the mass: the scalar run's end
/// time, state and counts, bit for bit.
#[test]
fn taylor_lanes_equal_the_scalar_taylor_per_member() {
    let members: Vec<_> = (0..64).map(sample).collect();
    let burnout = [Event::mass_reaches(0, 0.4)];
    let none: [Event<'_, 3>; 0] = [];
    let config = RunConfig::until(END);
    for tolerance in [1e-6, 1e-9, 1e-12] {
        for events in [&none[..], &burnout[..]] {
            let jobs = jobs(&members, events);
            let runs = [
                run_lanes::<_, 1, 3, 4>(&jobs, control(tolerance), &config),
                run_lanes::<_, 1, 3, 8>(&jobs, control(tolerance), &config),
                run_lanes_with::<_, 1, 3, 4>(
                    &jobs,
                    control(tolerance),
                    &config,
                    LaneKernel::Portable,
                ),
            ];
            for ends in runs {
                for (index, (end, job)) in ends.iter().zip(&jobs).enumerate() {
                    let expected = scalar(&job.system, tolerance, &config, events).expect("scalar");
                    assert_same(index, end.as_ref().expect("lanes"), &expected);
                    let stopped = if events.is_empty() { None } else { Some(0) };
                    assert_eq!(end.as_ref().map(|e| e.event), Ok(stopped));
                }
            }
        }
    }
}

/// Lanes whose members ask different orders: at rtol 1e-12 and atol 1e-9 the step rule
/// turns relative where ‖y‖∞ passes atol/rtol = 1000 m, which the faster members of the
/// sample reach before 15 s (y(15) ≈ 755 to 1317 m), so one expansion serves lanes of
/// different orders and each must keep its own (the shared order would change them).
/// Measured: every member the scalar run's bits, in 4 and 8 lanes.
#[test]
fn lanes_of_different_orders_keep_each_members_own() {
    let members: Vec<_> = (0..64).map(sample).collect();
    let none: [Event<'_, 3>; 0] = [];
    let config = RunConfig::until(END);
    let mixed =
        || TaylorControl::adaptive(Tolerance::new(1e-12, 1e-9).expect("a usable tolerance"));
    let jobs = jobs(&members, &none);
    let high = |index: usize| {
        let system = &jobs[index].system;
        let mut stepper = Taylor::new(system, 0.0, start(), mixed()).expect("a stepper");
        let solution = run(&mut stepper, &config, &none).expect("the burn");
        let (t, y) = solution.last().expect("points");
        (t, *y, solution.statistics)
    };
    let expected: Vec<_> = (0..jobs.len()).map(high).collect();
    let heights: Vec<f64> = expected.iter().map(|(_, y, _)| y[0]).collect();
    assert!(
        heights.iter().any(|y| *y > 1000.0) && heights.iter().any(|y| *y < 1000.0),
        "the sample straddles the switch of modes: {heights:?}"
    );
    for ends in [
        run_lanes::<_, 1, 3, 4>(&jobs, mixed(), &config),
        run_lanes::<_, 1, 3, 8>(&jobs, mixed(), &config),
    ] {
        for (index, end) in ends.iter().enumerate() {
            assert_same(index, end.as_ref().expect("lanes"), &expected[index]);
        }
    }
}

/// An event whose function is not a number is the scalar run's error in lanes too (it was
/// a member that ended `Ok` at the end time, the event never firing).
#[test]
fn an_event_that_is_not_a_number_is_an_error_in_lanes() {
    let members: Vec<_> = (0..4).map(sample).collect();
    let nan = |_: f64, _: &SVector<f64, 3>| f64::NAN;
    let events = [Event::function(&nan, Direction::Either, EventAction::Stop)];
    let jobs = jobs(&members, &events);
    for end in run_lanes::<_, 1, 3, 4>(&jobs, control(1e-9), &RunConfig::until(END)) {
        let error = end.expect_err("not a number");
        assert!(
            matches!(error.kind, StepErrorKind::InvalidConfiguration { .. }),
            "{error:?}"
        );
    }
}

/// The closed form's v and y at the end of the burn (see the module docs).
fn exact((mu, u_e): (f64, f64), t: f64) -> (f64, f64) {
    let m = M0 - mu * t;
    let log_ratio = (M0 / m).ln();
    let v = u_e * log_ratio - G * t;
    let y = u_e * (t - m / mu * log_ratio) - 0.5 * G * t * t;
    (v, y)
}

/// 10⁴ rockets to 15 s at tolerance 1e-9 in lanes of 1, 4 and 8: the same bits whatever
/// the width (each lane is its member's scalar run), and the closed form's v and y.
#[test]
fn ten_thousand_rockets_are_bit_identical_across_widths_and_match_the_closed_form() {
    let members: Vec<_> = (0..10_000).map(sample).collect();
    let jobs = jobs(&members, &[]);
    let config = RunConfig::until(END);
    let one = run_lanes::<_, 1, 3, 1>(&jobs, control(1e-9), &config);
    let four = run_lanes::<_, 1, 3, 4>(&jobs, control(1e-9), &config);
    let eight = run_lanes::<_, 1, 3, 8>(&jobs, control(1e-9), &config);
    let (mut worst_v, mut worst_y) = (0.0_f64, 0.0_f64);
    for (index, member) in members.iter().enumerate() {
        let a = one[index].as_ref().expect("width 1");
        for other in [&four[index], &eight[index]] {
            let b = other.as_ref().expect("width 4, 8");
            assert!(
                a.time.to_bits() == b.time.to_bits() && same_bits(&a.state, &b.state),
                "member {index}"
            );
        }
        assert_eq!(a.time, END);
        let (v, y) = exact(*member, END);
        let m = a.state[2];
        worst_v = worst_v.max((a.state[1] / m - v).abs() / v.abs());
        worst_y = worst_y.max((a.state[0] - y).abs() / y.abs());
        // The mass is linear in t, which the series carries exactly but for rounding.
        assert!(
            (m - (M0 - member.0 * END)).abs() <= 1e-12 * M0,
            "member {index}: m {m}"
        );
    }
    // Measured: v 9.4e-12, y 6.9e-12 relative; asserted with a margin of ~10.
    assert!(
        worst_v < 1e-10 && worst_y < 1e-10,
        "worst v {worst_v:e}, y {worst_y:e}"
    );
    eprintln!("worst relative error: v {worst_v:e}, y {worst_y:e}");
}

/// Members that fail keep the scalar run's typed error, its time and state, while their
/// neighbours fly on: a NaN exhaust speed (a non-finite expansion at the start) and a burn
/// rate that empties the rocket before the end time (the mass refused, then the step
/// underflowing at burn-out: the scalar run's bisection), between ordinary members.
#[test]
fn failing_members_report_the_scalar_error() {
    let members = [
        (0.05, 300.0),
        (0.05, f64::NAN),
        (0.048, 290.0),
        (0.1, 300.0),
        (0.052, 310.0),
    ];
    let jobs = jobs(&members, &[]);
    let config = RunConfig::until(END);
    let ends = run_lanes::<_, 1, 3, 4>(&jobs, control(1e-9), &config);
    let mut failures = 0;
    for (index, (end, job)) in ends.iter().zip(&jobs).enumerate() {
        match (end, scalar(&job.system, 1e-9, &config, &[])) {
            (Ok(end), Ok(expected)) => assert_same(index, end, &expected),
            (Err(lanes), Err(scalar)) => {
                assert_eq!(lanes, &scalar, "member {index}");
                assert!(lanes.time.is_finite(), "member {index}: {lanes:?}");
                failures += 1;
            }
            (lanes, scalar) => panic!("member {index}: lanes {lanes:?}, scalar {scalar:?}"),
        }
    }
    assert!(
        matches!(
            ends[1],
            Err(StepError {
                kind: StepErrorKind::NonFiniteState,
                ..
            })
        ),
        "{:?}",
        ends[1]
    );
    assert!(
        ends[3].is_err(),
        "a 10 s burn-out before 15 s fails: {:?}",
        ends[3]
    );
    assert_eq!(failures, 2);
}

/// A system without Taylor recurrences over lanes is refused member by member.
#[test]
fn a_system_without_taylor_lanes_is_refused() {
    #[variable_mass_system(file = "models/rocket.vms", emit = ["lanes"])]
    #[derive(Clone, Copy)]
    struct OnlyRates {
        mu: f64,
        u_e: f64,
        g: f64,
    }
    let job = LaneJob {
        system: OnlyRates {
            mu: 0.05,
            u_e: 300.0,
            g: G,
        },
        time: 0.0,
        state: start(),
        events: &[],
    };
    let ends = run_lanes::<_, 1, 3, 4>(&[job], control(1e-9), &RunConfig::until(END));
    match &ends[0] {
        Err(error) => assert!(
            matches!(error.kind, StepErrorKind::InvalidConfiguration { .. }),
            "{error:?}"
        ),
        Ok(end) => panic!("{end:?}"),
    }
}
