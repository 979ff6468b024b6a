//! Dormand–Prince in SIMD lanes (`varmass_core::lanes::run_lanes`) against the scalar path,
//! member by member, on the rocket dispersion of `examples/dispersion.rs`: 1 000 vertical
//! rockets with dispersed burn rate, exhaust speed and dry mass, flown to burnout (an event
//! on the mass) and then coasting to the apex (an event on the momentum), at tolerance 1e-9.
//! Every lane must give the scalar run's burnout and apex — times and states — to the bit,
//! with 4 and with 8 lanes (members take different numbers of steps, so lanes are refilled
//! at different times: the test exercises the refill too). The apex is also held against
//! its closed form, an independent reference.

use varmass::core::ensemble::member_rng;
use varmass::core::ensemble::rand::RngExt;
use varmass::core::lanes::{
    run_lanes, run_lanes_with, LaneEnd, LaneJob, LaneKernel, LaneSystem, Lanes,
};
use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", emit = ["lanes"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

const M0: f64 = 1000.0;
const G: f64 = 9.81;

/// (burn rate, exhaust speed, dry mass), as the example samples them.
fn sample(index: u64) -> (f64, f64, f64) {
    let mut rng = member_rng(2015, index);
    (
        rng.random_range(9.5..10.5),
        rng.random_range(2400.0..2600.0),
        rng.random_range(380.0..420.0),
    )
}

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-9,
        absolute_tolerance: 1e-9,
        ..AdaptiveControl::default()
    })
}

fn rocket(mu: f64, u_e: f64) -> Rocket {
    Rocket { mu, u_e, g: G }
}

/// The scalar path: one run to the event (or the end), its last point.
fn scalar_run(
    system: &Rocket,
    (time, state): (f64, SVector<f64, 3>),
    events: &[Event<'_, 3>],
) -> Result<(f64, SVector<f64, 3>), StepError<3>> {
    let mut stepper = DormandPrince::new(system, time, state, control())?;
    let solution = run(&mut stepper, &RunConfig::until(1e4), events).map_err(|e| e.error)?;
    let (t, y) = solution.last().expect("a run records its start");
    Ok((t, *y))
}

fn same_bits(a: &SVector<f64, 3>, b: &SVector<f64, 3>) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// The apex height in closed form (examples/dispersion.rs): burning from rest,
/// v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t², then y_b + v_b²/(2g).
fn exact_apex_height((mu, u_e, dry): (f64, f64, f64)) -> f64 {
    let t_b = (M0 - dry) / mu;
    let log_ratio = (M0 / dry).ln();
    let v_b = u_e * log_ratio - G * t_b;
    let y_b = u_e * (t_b - dry / mu * log_ratio) - 0.5 * G * t_b * t_b;
    y_b + v_b * v_b / (2.0 * G)
}

/// `run_lanes` with the lanes' arithmetic compiled as `kernel` says: `Detected` is AVX
/// where the CPU has it (`run_lanes`), `Portable` the build's target only (SSE2 in a
/// default x86-64 build), the path of a CPU without AVX.
fn run_in<const W: usize>(
    kernel: LaneKernel,
    jobs: &[LaneJob<'_, Rocket, 3>],
    config: &RunConfig,
) -> Vec<Result<LaneEnd<3>, StepError<3>>> {
    run_lanes_with::<_, 1, 3, W>(jobs, control(), config, kernel)
}

/// Both phases of `members` rockets in W lanes: the burnout and apex ends.
fn lanes_flight<const W: usize>(
    members: &[(f64, f64, f64)],
    kernel: LaneKernel,
) -> Vec<(LaneEnd<3>, LaneEnd<3>)> {
    let burnout: Vec<[Event<'_, 3>; 1]> = members
        .iter()
        .map(|&(_, _, dry)| [Event::mass_reaches(0, dry)])
        .collect();
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let powered: Vec<_> = members
        .iter()
        .zip(&burnout)
        .map(|(&(mu, u_e, _), events)| LaneJob {
            system: rocket(mu, u_e),
            time: 0.0,
            state: start,
            events,
        })
        .collect();
    let config = RunConfig::until(1e4);
    let burnouts = run_in::<W>(kernel, &powered, &config);
    let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let coasting: Vec<_> = members
        .iter()
        .zip(&burnouts)
        .map(|(&(_, u_e, _), end)| {
            let end = end.as_ref().expect("every burn ends at burnout");
            LaneJob {
                system: rocket(0.0, u_e),
                time: end.time,
                state: end.state,
                events: &apex,
            }
        })
        .collect();
    let apexes = run_in::<W>(kernel, &coasting, &config);
    burnouts
        .into_iter()
        .zip(apexes)
        .map(|(b, a)| (b.expect("burnout"), a.expect("apex")))
        .collect()
}

fn check_against_scalar<const W: usize>(count: u64, kernel: LaneKernel) {
    let members: Vec<_> = (0..count).map(sample).collect();
    let flights = lanes_flight::<W>(&members, kernel);
    let mut worst = 0.0_f64;
    for (index, (&(mu, u_e, dry), (burnout, apex))) in members.iter().zip(&flights).enumerate() {
        let start = (0.0, SVector::<f64, 3>::new(0.0, 0.0, M0));
        let (t_b, y_b) = scalar_run(&rocket(mu, u_e), start, &[Event::mass_reaches(0, dry)])
            .expect("scalar burn");
        let apex_event = [Event::state_reaches(1, 0.0, Direction::Falling)];
        let (t_a, y_a) =
            scalar_run(&rocket(0.0, u_e), (t_b, y_b), &apex_event).expect("scalar coast");
        assert!(
            burnout.time.to_bits() == t_b.to_bits() && same_bits(&burnout.state, &y_b),
            "member {index}, {W} lanes: burnout {:?} vs scalar ({t_b}, {y_b:?})",
            (burnout.time, burnout.state)
        );
        assert!(
            apex.time.to_bits() == t_a.to_bits() && same_bits(&apex.state, &y_a),
            "member {index}, {W} lanes: apex {:?} vs scalar ({t_a}, {y_a:?})",
            (apex.time, apex.state)
        );
        assert_eq!((burnout.event, apex.event), (Some(0), Some(0)));
        let exact = exact_apex_height((mu, u_e, dry));
        worst = worst.max((apex.state[0] - exact).abs() / exact);
    }
    // Measured worst relative error 2.8e-10 over the 1 000 members; the example's own bound.
    assert!(worst < 1e-7, "worst apex error {worst:e}");
}

#[test]
fn four_lanes_give_the_scalar_runs_bit_for_bit() {
    check_against_scalar::<4>(1000, LaneKernel::Detected);
}

#[test]
fn eight_lanes_give_the_scalar_runs_bit_for_bit() {
    check_against_scalar::<8>(1000, LaneKernel::Detected);
}

/// The same without AVX, on any CPU: the arithmetic compiled for the build's target.
#[test]
fn lanes_without_avx_give_the_scalar_runs_bit_for_bit() {
    check_against_scalar::<4>(500, LaneKernel::Portable);
    check_against_scalar::<8>(500, LaneKernel::Portable);
}

/// The generated lane state rate is the scalar one in every lane, bit for bit, at states
/// far apart (a heavy slow rocket, a light fast one, a falling one).
#[test]
fn the_lane_state_rate_is_the_scalar_state_rate_in_every_lane() {
    let systems = [
        rocket(9.7, 2450.0),
        rocket(10.3, 2590.0),
        rocket(0.0, 2500.0),
    ];
    let states = [
        SVector::<f64, 3>::new(0.0, 0.0, 1000.0),
        SVector::<f64, 3>::new(3.1e4, 4.2e5, 401.7),
        SVector::<f64, 3>::new(1.7e5, -1.3e4, 390.2),
    ];
    let times = [0.0, 57.3, 412.9];
    let mut parameters = <Rocket as LaneSystem<1, 3, 3>>::splat(&systems[0]);
    for (lane, system) in systems.iter().enumerate() {
        <Rocket as LaneSystem<1, 3, 3>>::set_lane(&mut parameters, lane, system);
    }
    let t = Lanes(times);
    let state: [Lanes<3>; 3] = core::array::from_fn(|j| Lanes::from_fn(|i| states[i][j]));
    let rates = <Rocket as LaneSystem<1, 3, 3>>::state_rate_lanes(&parameters, t, &state);
    for lane in 0..3 {
        let scalar = systems[lane]
            .state_rate(times[lane], &states[lane])
            .unwrap();
        for j in 0..3 {
            assert_eq!(
                rates[j].0[lane].to_bits(),
                scalar[j].to_bits(),
                "lane {lane}, {j}"
            );
        }
    }
}

/// Members that end otherwise than at their event keep the scalar path's outcome in their
/// lane while their neighbours fly on: a rocket that never reaches its dry mass (μ = 0)
/// reaches the end time; one with a negative burn rate fails at its start with the scalar
/// run's typed error (a negative flow rate), its time and state; both between ordinary
/// members so that their lanes are refilled.
#[test]
fn members_that_end_otherwise_keep_the_scalar_outcome() {
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let members = [
        (10.0, 2500.0),
        (0.0, 2500.0),
        (-5.0, 2500.0),
        (9.6, 2410.0),
        (10.4, 2600.0),
    ];
    let burnout = [Event::mass_reaches(0, 400.0)];
    let jobs: Vec<_> = members
        .iter()
        .map(|&(mu, u_e)| LaneJob {
            system: rocket(mu, u_e),
            time: 0.0,
            state: start,
            events: &burnout,
        })
        .collect();
    let config = RunConfig::until(1e4);
    let ends = run_lanes::<_, 1, 3, 4>(&jobs, control(), &config);
    for (&(mu, u_e), end) in members.iter().zip(&ends) {
        let scalar = scalar_run(&rocket(mu, u_e), (0.0, start), &burnout);
        match (end, scalar) {
            (Ok(end), Ok((t, y))) => {
                assert!(end.time.to_bits() == t.to_bits() && same_bits(&end.state, &y));
                let expected_event = if mu > 0.0 { Some(0) } else { None };
                assert_eq!(end.event, expected_event, "μ = {mu}");
            }
            (Err(lanes), Err(scalar)) => {
                assert_eq!(lanes, &scalar, "μ = {mu}");
                assert!(matches!(lanes.kind, StepErrorKind::NegativeFlowRate { .. }));
                assert_eq!(lanes.time, 0.0);
            }
            (lanes, scalar) => panic!("μ = {mu}: lanes {lanes:?}, scalar {scalar:?}"),
        }
    }
    // μ = 0: no burnout, so the end time.
    assert_eq!(ends[1].as_ref().map(|e| e.time), Ok(1e4));
}

/// `LaneEnsemble` flying the members in lanes gives the `Partial` — values, failures,
/// statistics — that `Ensemble` gives on the scalar path, in parallel and serially, for a
/// chunk size that does not divide the batches.
#[test]
fn a_lane_ensemble_equals_the_scalar_ensemble() {
    use varmass::core::ensemble::{Ensemble, LaneEnsemble, MemberRng};
    let sample = |rng: &mut MemberRng| {
        (
            rng.random_range(9.5..10.5),
            rng.random_range(2400.0..2600.0),
            rng.random_range(380.0..420.0),
        )
    };
    let fly = |&(mu, u_e, dry): &(f64, f64, f64)| -> Result<[f64; 2], StepError<3>> {
        let start = (0.0, SVector::<f64, 3>::new(0.0, 0.0, M0));
        let burnout = scalar_run(&rocket(mu, u_e), start, &[Event::mass_reaches(0, dry)])?;
        let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
        let (t, y) = scalar_run(&rocket(0.0, u_e), burnout, &apex)?;
        Ok([y[0], t])
    };
    let fly_chunk = |members: &[(f64, f64, f64)]| -> Vec<Result<[f64; 2], StepError<3>>> {
        lanes_flight::<4>(members, LaneKernel::Detected)
            .into_iter()
            .map(|(_, apex)| Ok([apex.state[0], apex.time]))
            .collect()
    };
    let names = ["apex_height", "apex_time"];
    let scalar = Ensemble::new(11, names, sample, fly)
        .batch_size(100)
        .run(0..300);
    let lanes = LaneEnsemble::new(11, names, sample, fly_chunk)
        .batch_size(100)
        .chunk_size(37);
    assert_eq!(lanes.run(0..300), scalar);
    assert_eq!(lanes.serial().run(0..300), scalar);
    assert_eq!(scalar.member_count(), 300);
}

/// Rejections, and trial states outside the domain, go as on the scalar path: first steps
/// from 5 s to 150 s make the controller reject (error above 1) and shrink, and the longest
/// ones carry the mass below zero (1000 kg − 10 kg/s · 150 s), a step too long that is
/// shrunk by `min_factor` and retried. Every member ends at burnout with the scalar run's
/// time, state and counts of accepted and rejected steps, with and without AVX.
#[test]
fn rejected_and_failed_attempts_go_as_on_the_scalar_path() {
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let burnout = [Event::mass_reaches(0, 400.0)];
    let first_steps = [150.0, 5.0, 60.0, 20.0, 110.0, 35.0];
    let control_for = |h: f64| {
        StepControl::Adaptive(AdaptiveControl {
            initial_step: Some(h),
            relative_tolerance: 1e-9,
            absolute_tolerance: 1e-9,
            ..AdaptiveControl::default()
        })
    };
    let config = RunConfig::until(1e4);
    let mut rejected = 0;
    for (index, &h) in first_steps.iter().enumerate() {
        let system = rocket(10.0 + 0.1 * index as f64, 2500.0);
        let mut stepper = DormandPrince::new(&system, 0.0, start, control_for(h)).expect("valid");
        let solution = run(&mut stepper, &config, &burnout).expect("scalar burn");
        let (t, y) = solution.last().expect("a point");
        let job = || LaneJob {
            system: rocket(10.0 + 0.1 * index as f64, 2500.0),
            time: 0.0,
            state: start,
            events: &burnout[..],
        };
        let jobs = [job(), job(), job()];
        for ends in [
            run_lanes::<_, 1, 3, 4>(&jobs, control_for(h), &config),
            run_lanes_with::<_, 1, 3, 4>(&jobs, control_for(h), &config, LaneKernel::Portable),
        ] {
            for end in ends {
                let end = end.expect("burnout in lanes");
                assert!(end.time.to_bits() == t.to_bits() && same_bits(&end.state, y));
                let (lanes, scalar) = (end.statistics, stepper.statistics());
                assert_eq!(
                    (lanes.accepted_steps, lanes.rejected_steps),
                    (scalar.accepted_steps, scalar.rejected_steps),
                    "first step {h}"
                );
            }
        }
        rejected += stepper.statistics().rejected_steps;
    }
    // Measured: 27 rejections over the six members; the test needs some to mean anything.
    assert!(rejected >= 6, "{rejected} rejections");
}

/// Events of every kind, several per member, end each lane where they end its scalar run:
/// a user function recording the 5 km mark (located, then the run goes on), a stop at
/// 15 km (a state component) and the burnout (a state mass). With burn rates of 25 to
/// 48 kg/s the burnout comes first for the fast burners (burnout height from the closed
/// form: 13.5 km at 40 kg/s, 17.5 km at 30 kg/s) and the 15 km stop for the slow ones, so
/// both stops and the recorded crossing are exercised, on the AVX and the portable path.
#[test]
fn several_events_of_every_kind_end_as_on_the_scalar_path() {
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let mark = |_: f64, y: &SVector<f64, 3>| y[0] - 5_000.0;
    let events = [
        Event::function(&mark, Direction::Rising, varmass::core::EventAction::Record),
        Event::state_reaches(0, 15_000.0, Direction::Rising),
        Event::mass_reaches(0, 400.0),
    ];
    let rates: Vec<f64> = (0..24).map(|i| 25.0 + f64::from(i)).collect();
    let jobs: Vec<_> = rates
        .iter()
        .map(|&mu| LaneJob {
            system: rocket(mu, 2500.0),
            time: 0.0,
            state: start,
            events: &events,
        })
        .collect();
    let config = RunConfig::until(1e4);
    let mut stopped_by = [0; 3];
    for kernel in [LaneKernel::Detected, LaneKernel::Portable] {
        let ends = run_lanes_with::<_, 1, 3, 4>(&jobs, control(), &config, kernel);
        for (&mu, end) in rates.iter().zip(ends) {
            let end = end.expect("the lanes' run");
            let (t, y) = scalar_run(&rocket(mu, 2500.0), (0.0, start), &events).expect("scalar");
            assert!(
                end.time.to_bits() == t.to_bits() && same_bits(&end.state, &y),
                "μ = {mu}"
            );
            let event = end.event.expect("a stop");
            stopped_by[event] += 1;
        }
    }
    assert_eq!(stopped_by[0], 0, "the recording event never stops a run");
    assert!(stopped_by[1] > 0 && stopped_by[2] > 0, "{stopped_by:?}");
}
