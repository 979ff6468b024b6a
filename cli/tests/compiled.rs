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
    let rows = done.table.rows.iter();
    let values = rows.flat_map(|(t, row)| std::iter::once(t).chain(row));
    values.chain(&done.end.1).map(|v| v.to_bits()).collect()
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
