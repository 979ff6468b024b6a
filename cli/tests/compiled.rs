//! `varmass_cli::run::Compiled`, the library entry point the Python package runs through: a
//! model derived and compiled once and run again with other parameter values gives the
//! bits of a run made from scratch, refuses bad values with the tool's messages, and keeps
//! working after a refusal.

use std::path::Path;

use clap::Parser;
use varmass_cli::args::{Cli, Command, RunArgs};
use varmass_cli::error::CliError;
use varmass_cli::model::load_source;
use varmass_cli::run::{Compiled, Completed};

const SLED: &str = include_str!("../../models/sled.vms");

fn compiled() -> Compiled {
    let file = Path::new("models/sled.vms");
    Compiled::new(load_source(SLED, file, &["impact".to_string()]).expect("derives"))
}

fn args() -> RunArgs {
    let argv = [
        "varmass",
        "run",
        "models/sled.vms",
        "--with=impact",
        "--until=100",
        "--init=x=0",
        "--stop-when=x = 50",
        "--method=dop853",
        "--tol=1e-12",
    ];
    match Cli::try_parse_from(argv).expect("parses").command {
        Command::Run(args) => *args,
        _ => unreachable!("a run"),
    }
}

fn sled(theta_degrees: f64) -> [(&'static str, f64); 5] {
    [
        ("m0", 10.0),
        ("c", 2.0),
        ("g", 9.81),
        ("theta", theta_degrees.to_radians()),
        ("f_d", 0.1),
    ]
}

/// Every recorded value and the end state, bit for bit.
fn bits(done: &Completed) -> Vec<u64> {
    let values = done
        .table
        .rows()
        .flat_map(|(t, row)| std::iter::once(t).chain(row));
    values
        .chain(done.end.1.iter().copied())
        .map(f64::to_bits)
        .collect()
}

fn run(compiled: &mut Compiled, parameters: &[(&str, f64)]) -> Result<Completed, CliError> {
    compiled
        .run(parameters, &args())
        .map_err(|failed| failed.error)
}

#[test]
fn a_reused_model_runs_as_one_made_anew() {
    let mut reused = compiled();
    let steep = run(&mut reused, &sled(30.0)).unwrap();
    let gentle = run(&mut reused, &sled(20.0)).unwrap();
    let again = run(&mut reused, &sled(30.0)).unwrap();
    assert_eq!(
        bits(&gentle),
        bits(&run(&mut compiled(), &sled(20.0)).unwrap())
    );
    assert_eq!(bits(&again), bits(&steep));
    // A gentler slope takes longer to 50 m: the values were used.
    assert!(
        gentle.end.0 > steep.end.0,
        "{} vs {}",
        gentle.end.0,
        steep.end.0
    );
    assert_eq!(steep.stopped_by, Some(0));
}

#[test]
fn the_summary_made_when_shown_is_the_tools_text() {
    let done = run(&mut compiled(), &sled(30.0)).expect("runs");
    // The table (x and x', recorded by default) gives the end's values; the text is the
    // tool's summary as it has always been written.
    assert_eq!(done.table.names, ["x", "x'"]);
    let (t, row) = done.table.last().expect("a row");
    let s = &done.statistics;
    let expected = format!(
        "stopped at t = {t} (--stop-when 'x = 50')\nstate:\n  x = {}\n  x' = {}\n  p_x = {}\n\
         steps: {} accepted, {} rejected; {} rate evaluations, {} Jacobians, {} Newton \
         iterations\n",
        row[0],
        row[1],
        done.end.1[1],
        s.accepted_steps,
        s.rejected_steps,
        s.rate_evaluations,
        s.jacobian_evaluations,
        s.newton_iterations
    );
    assert_eq!(done.summary.to_string(), expected);
    assert_eq!((t, row[0]), (done.end.0, done.end.1[0]));
}

#[test]
fn bad_values_are_the_tools_messages_and_the_model_still_runs() {
    let mut model = compiled();
    let steep = run(&mut model, &sled(30.0)).unwrap();
    let missing = run(&mut model, &sled(30.0)[..4]).map(|_| ()).unwrap_err();
    assert!(
        matches!(&missing, CliError::Input(m) if m.contains("missing value for f_d")
            && m.ends_with("give --set f_d=VALUE")),
        "{missing}"
    );
    let mut twice = sled(30.0).to_vec();
    twice.push(("g", 1.62));
    let twice = run(&mut model, &twice).map(|_| ()).unwrap_err();
    assert!(
        matches!(&twice, CliError::Input(m) if m.contains("`g` is set twice")),
        "{twice}"
    );
    let mut typo = sled(30.0).to_vec();
    typo.push(("f_e", 0.2));
    let unknown = run(&mut model, &typo).map(|_| ()).unwrap_err();
    assert!(
        matches!(&unknown, CliError::Input(m) if m.contains("did you mean `f_d`?")),
        "{unknown}"
    );
    assert_eq!(bits(&run(&mut model, &sled(30.0)).unwrap()), bits(&steep));
}

/// A run of the tool's exact size (the sled: 1 coordinate, no state mass, an arm of its own
/// in `run::dispatch`) is the bare interpreter's run, bit for bit: the program with the same
/// values in a `TapeSystem<1, 2>`, DOP853 at the same tolerance, the same event, every
/// accepted step (the second formulation of `python/bench/reference`). Padded to 3 state
/// masses the steps differed in their last bits (the error norm's tolerance is scaled by
/// √(2/5), not equal).
#[test]
fn an_exact_size_runs_as_the_bare_interpreter() {
    use varmass::core::nalgebra::SVector;
    use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl};
    use varmass::core::{run as core_run, Direction, Event, RunConfig};
    use varmass::interpret::{Program, TapeSystem};

    let mut tool = compiled();
    let done = run(&mut tool, &sled(30.0)).unwrap();
    let derivation = (*tool.model().derivation).clone();
    let program = Program::new(derivation, &sled(30.0)).expect("parameters fit");
    let system = TapeSystem::<1, 2>::new(program).expect("sizes");
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::dop853()
    });
    let mut stepper = Dop853::new(&system, 0.0, SVector::zeros(), control).expect("starts");
    let at_50 = Event::state_reaches(0, 50.0, Direction::Either);
    let bare = core_run(&mut stepper, &RunConfig::until(100.0), &[at_50]).expect("runs");
    let times: Vec<u64> = done.table.times().iter().map(|t| t.to_bits()).collect();
    let bare_times: Vec<u64> = bare.times.iter().map(|t| t.to_bits()).collect();
    assert_eq!(times, bare_times);
    let (_, end) = bare.last().expect("a point");
    let end: Vec<u64> = end.iter().map(|v| v.to_bits()).collect();
    let tool_end: Vec<u64> = done.end.1.iter().map(|v| v.to_bits()).collect();
    assert_eq!(tool_end, end);
    assert_eq!(
        done.end.0.to_bits(),
        bare.times.last().expect("a time").to_bits()
    );
}

/// A model run again with the same arguments keeps its plan and makes again only what
/// depends on the values: what those values make wrong is refused as a plan made anew
/// refuses it (a mass not positive at the start, a `--stop-when` already true there), and
/// the plan still runs as one made anew afterwards.
#[test]
fn a_kept_plan_refuses_values_as_a_new_plan_does() {
    let argv = [
        "varmass",
        "run",
        "models/sled.vms",
        "--with=impact",
        "--until=100",
        "--init=x=0",
        // m = m0 + c x: rising through 12 kg at x = 1 m when m0 = 10 kg.
        "--stop-when=m > 12",
        "--method=dop853",
        "--tol=1e-12",
    ];
    let Command::Run(args) = Cli::try_parse_from(argv).expect("parses").command else {
        unreachable!("a run")
    };
    let with_m0 = |m0: f64| {
        let mut values = sled(30.0);
        values[0].1 = m0;
        values
    };
    let message = |compiled: &mut Compiled, m0: f64| match compiled.run(&with_m0(m0), &args) {
        Err(failed) => failed.error.to_string(),
        Ok(_) => panic!("m0 = {m0} runs"),
    };
    let mut kept = compiled();
    let first = kept
        .run(&with_m0(10.0), &args)
        .map_err(|f| f.error)
        .unwrap();
    assert_eq!(first.stopped_by, Some(0));
    for m0 in [-1.0, 0.0, 13.0, 15.0] {
        let fresh = message(&mut compiled(), m0);
        assert_eq!(message(&mut kept, m0), fresh);
        let expected = match m0 > 0.0 {
            true => "already holds at the start",
            false => "a mass must be positive",
        };
        assert!(fresh.contains(expected), "{fresh}");
    }
    let again = kept
        .run(&with_m0(10.0), &args)
        .map_err(|f| f.error)
        .unwrap();
    assert_eq!(bits(&again), bits(&first));
}

/// A library caller (the Python package's `RunError`) gets the rows before a point that
/// cannot be recorded with the error: `tests/data/tables/recorded_only.vms` records V,
/// whose table h has no data past t = 1 while the run goes on to t = 2 (before the fix
/// `Failed::table` was `None`).
#[test]
fn a_failed_recording_hands_back_the_rows_before_it() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tables/recorded_only.vms");
    let source = std::fs::read_to_string(&file).expect("readable");
    let mut model = Compiled::new(load_source(&source, &file, &[]).expect("derives"));
    let argv = [
        "varmass",
        "run",
        "recorded_only.vms",
        "--until=2",
        "--init=y=0",
        "--every=0.25",
        "--record=V",
    ];
    let Command::Run(args) = Cli::try_parse_from(argv).expect("parses").command else {
        unreachable!("a run")
    };
    let Err(failed) = model.run(&[("m0", 2.0), ("g", 10.0)], &args) else {
        panic!("V is recorded past the table's data");
    };
    assert!(
        matches!(&failed.error, CliError::Run(m) if m.contains("cannot record `V` at t = 1.25")),
        "{}",
        failed.error
    );
    let table = failed.table.expect("the rows before the failure");
    let times = table.times();
    assert_eq!(times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    // V(1) = m0 g y(1) + h(1) = 2·10·(−5) + 3, y exact to rounding (quadratic in t).
    let v_1 = table.column(0)[4];
    assert!((v_1 + 97.0).abs() <= 1e-12, "{v_1}");
}

/// A recorded expression that is not a finite number is refused, with the rows before it:
/// on the sled (θ = 30°, docs/examples) x starts at 0 and grows, so `sqrt(x - 1)` is NaN
/// until x passes 1 — at t = 0 already, so no row precedes it — and `1/(x - x)` is
/// infinite from the first row. Before, both were written as NaN and inf with exit 0.
#[test]
fn a_recorded_value_that_is_not_a_number_is_refused() {
    let mut model = compiled();
    for (expression, shown) in [("sqrt(x - 1)", "NaN"), ("1/(x - x)", "inf")] {
        let mut args = args();
        args.record = vec![format!("s={expression}")];
        let Err(failed) = model.run(&sled(30.0), &args) else {
            panic!("`{expression}` is recorded");
        };
        let expected = format!("cannot record `s` at t = 0: its value is {shown}");
        assert!(
            matches!(&failed.error, CliError::Run(m) if m.contains(&expected)),
            "{}",
            failed.error
        );
        assert_eq!(failed.table.expect("an empty table").len(), 0);
    }
}
