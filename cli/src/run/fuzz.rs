//! A fuzz of the command line: random argument vectors drawn from the grammar of the
//! options (good and bad names, numbers, expressions and conditions, options repeated,
//! missing or unknown) go through clap and everything a run checks before its first step;
//! none may panic, and every failure must be an exit-2 error with a message.
//!
//! In process, without integrating: clap's parse, then for `run` the parameters, the
//! program and the plan ([`Compiled::check`], the tool's own path); for `check` and
//! `derive` the command itself. Loading a model derives it, so the compiled model is cached per
//! (file, tags) and given each case's `--set` values, as a run is.
//!
//! Cases: `VARMASS_FUZZ_CASES` (default 3000, about two seconds in the test profile);
//! the seed is fixed, `VARMASS_FUZZ_SEED` moves it. The 10⁵ run:
//! `VARMASS_FUZZ_CASES=100000 cargo test -p varmass-cli --lib fuzz -- --nocapture`
//! (measured: no panic, 12586 cases planned, 87414 refused with exit 2, 11 s).

use std::cell::RefCell;
use std::collections::HashMap;

use clap::error::ErrorKind;
use clap::Parser;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

use super::{plan, Compiled};
use crate::args::{Cli, Command, Method};
use crate::error::CliError;
use crate::model::load;

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

fn path(relative: &str) -> String {
    format!("{}/{relative}", env!("CARGO_MANIFEST_DIR"))
}

/// The model files with a good `--set` list and `--init` list each: the rocket (a state
/// mass, an outflow, a tag), the sled (a law, a tagged inflow), the falling chain (a
/// `let`), the sand cart (an inflow), and no file.
fn scenarios() -> Vec<(String, &'static str, &'static str)> {
    vec![
        (path("../models/rocket.vms"), "mu=1 u_e=10 g=1", "y=0 m=1"),
        (
            path("../models/sled.vms"),
            "m0=10 c=2 g=9.81 theta=0.5 f_d=0.1",
            "x=0",
        ),
        (
            path("tests/data/falling_chain.vms"),
            "lam=1 g=9.81",
            "x=1 x'=2",
        ),
        (path("tests/data/sand_cart.vms"), "mu=1 F=1", "x=0 m=1"),
        (path("no/such/model.vms"), "", ""),
    ]
}

/// Values a user means: most options get one of these.
const GOOD_NUMBERS: &[&str] = &["0.5", "1", "2", "1e-6", "0.01", "0.25"];

const NUMBERS: &[&str] = &[
    "0", "1", "0.5", "-1", "2", "100", "1e-12", "1e-30", "10", "0.1", "1e300", "-1e-9", "nan",
    "NaN", "inf", "-inf", "abc", "", "1e", "--", "-", "0x10", "1_000", "1e-7", "3e7", "-0",
    "5e-324",
];

const NAMES: &[&str] = &[
    "x", "y", "m", "x'", "y'", "m0", "mu", "u_e", "g", "c", "theta", "f_d", "lam", "F", "k_d", "w",
    "xx", "", "p_x", "H", "x''", "mdot_m", "depth", "t", " y ", "ü", "m=",
];

const SETS: &[&str] = &[
    "mu=1 u_e=10 g=1",
    "mu=1 u_e=10 g=1 k_d=0.1",
    "m0=10 c=2 g=9.81 theta=0.5 f_d=0.1",
    "lam=1 g=9.81",
    "mu=-5 F=1",
    "mu=1 F=1 mu=2",
    "g=9.81",
    "g=ten lam=1",
    "lam=1 g=nan",
    "lam g=1",
    "=1",
    "w=3 lam=1 g=9.81",
    "",
];

/// Every `--method` name (the tool's own list) and two that are none.
fn methods() -> impl Strategy<Value = String> {
    let mut names = Method::names();
    names.extend(["rk5", ""].map(String::from));
    proptest::sample::select(names)
}

const RECORDS: &[&str] = &[
    "x",
    "y,m",
    "E=1/2*m*y'^2",
    "mdot_m",
    "depth",
    "atan2(y, 1)",
    "(",
    "E=",
    "=",
    "a=b=c",
    "x,,y",
    "sin(",
    "1/0",
    "x'''",
    "foo(1)",
    ",",
    "H, power",
    "E=1/2*mm*x'^2",
    "t*g",
    "2mu",
    "min(x)",
    "Q_x",
    "pdot_y",
];

const CONDITIONS: &[&str] = &[
    "y = 1",
    "y > 1",
    "m < 0.5",
    "x ~ 2",
    "= 3",
    "y =",
    "H > -1e300",
    "powr = 1",
    "x >= 1",
    "x' < -1",
    "m<=0.9",
    "",
];

const JUNK: &[&str] = &[
    "--bogus",
    "-x",
    "--tol=1e-9",
    "--until=-1",
    "--",
    "--help",
    "-h",
    "--version",
    "--step=",
    "extra.vms",
    "--with=impact",
];

fn pick(list: &'static [&'static str]) -> impl Strategy<Value = String> {
    proptest::sample::select(list).prop_map(str::to_string)
}

/// One option with its value (or a stray token), as argv words.
fn option() -> impl Strategy<Value = Vec<String>> {
    let with = pick(&["impact", "drag", "dragg", "", "impact,drag"]);
    let number = || prop_oneof![2 => pick(GOOD_NUMBERS), 1 => pick(NUMBERS)];
    let assignment = (pick(NAMES), pick(NUMBERS)).prop_map(|(n, v)| format!("{n}={v}"));
    let flagged = |flag: &'static str, value: BoxedStrategy<String>| {
        value.prop_map(move |v| vec![flag.to_string(), v])
    };
    prop_oneof![
        flagged("--with", with.boxed()),
        flagged("--init", assignment.boxed()),
        flagged("--from", number().boxed()),
        flagged("--until", number().boxed()),
        flagged("--until", number().boxed()),
        flagged("--tol", number().boxed()),
        flagged("--step", number().boxed()),
        flagged("--every", number().boxed()),
        flagged("--max-seconds", number().boxed()),
        flagged(
            "--max-steps",
            pick(&[
                "0",
                "1",
                "10",
                "-1",
                "18446744073709551616",
                "abc",
                "10000000"
            ])
            .boxed()
        ),
        flagged("--method", methods().boxed()),
        flagged("--record", pick(RECORDS).boxed()),
        flagged("--stop-when", pick(CONDITIONS).boxed()),
        flagged(
            "--sensitivity",
            pick(&[
                "c", "u_e", "mu", "g", "m0", "k_d", "init:x", "init:x'", "init:y", "init:y'",
                "init:m", "init:q", "init:", "x", "", "u_e "
            ])
            .boxed()
        ),
        flagged("--csv", pick(&["/dev/null"]).boxed()),
        pick(JUNK).prop_map(|j| vec![j]),
        Just(vec!["--latex".to_string()]),
    ]
}

/// A whole argument vector: a scenario's good values (most of the time) or a pool's, then
/// a few options.
fn argv() -> impl Strategy<Value = Vec<String>> {
    let command = prop_oneof![
        8 => Just("run".to_string()),
        1 => Just("check".to_string()),
        1 => Just("derive".to_string()),
        1 => pick(&["runn", "", "Run"]),
    ];
    let scenario = proptest::sample::select(scenarios());
    let own = proptest::bool::weighted(0.8);
    let other_sets = pick(SETS);
    let other_inits =
        proptest::collection::vec(pick(&["x=1", "y=0", "m=1", "x'=2", "x=0", "m=0"]), 0..4);
    let options = proptest::collection::vec(option(), 0..6);
    let until_first = proptest::bool::weighted(0.9);
    (
        command,
        scenario,
        own,
        other_sets,
        other_inits,
        options,
        until_first,
    )
        .prop_map(
            |(command, (file, sets, inits), own, other_sets, other_inits, options, until_first)| {
                let mut argv = vec!["varmass".to_string(), command, file];
                if until_first {
                    argv.extend(["--until".to_string(), "1".to_string()]);
                }
                let (sets, inits) = match own {
                    true => (
                        sets.to_string(),
                        inits.split_whitespace().map(str::to_string).collect(),
                    ),
                    false => (other_sets, other_inits),
                };
                for s in sets.split_whitespace() {
                    argv.extend(["--set".to_string(), s.to_string()]);
                }
                for i in inits {
                    argv.extend(["--init".to_string(), i]);
                }
                argv.extend(options.into_iter().flatten());
                argv
            },
        )
}

/// What one case ended in: Ok, or a failure's exit code and message.
type Verdict = Result<(), (u8, String)>;

fn failed(error: &CliError) -> (u8, String) {
    (error.exit_code(), error.to_string())
}

/// The verdict of the command `key` names: `command`'s the first time, remembered after.
fn once(
    commands: &RefCell<HashMap<String, Verdict>>,
    key: String,
    command: impl FnOnce() -> Result<(), CliError>,
) -> Verdict {
    let mut commands = commands.borrow_mut();
    let verdict = commands
        .entry(key)
        .or_insert_with(|| command().map_err(|e| failed(&e)));
    verdict.clone()
}

/// The models already derived (and compiled by their first run), by (file, tags).
type Programs = HashMap<(String, Vec<String>), Result<Compiled, (u8, String)>>;

/// Runs one argument vector as far as the tool goes before integrating.
fn one(
    argv: &[String],
    programs: &RefCell<Programs>,
    commands: &RefCell<HashMap<String, Verdict>>,
) -> Verdict {
    let cli = match Cli::try_parse_from(argv) {
        Ok(cli) => cli,
        Err(e) => {
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => Ok(()),
                _ => Err((e.exit_code() as u8, e.to_string())),
            }
        }
    };
    match cli.command {
        Command::Check(a) => {
            let key = format!("check {:?} {:?}", a.file, a.with);
            once(commands, key, || {
                crate::commands::check::check(&a).map(|_| ())
            })
        }
        Command::Derive(a) => {
            let key = format!("derive {:?} {:?} {}", a.model.file, a.model.with, a.latex);
            once(commands, key, || {
                crate::commands::derive::derive(&a.model, a.latex).map(|_| ())
            })
        }
        Command::Run(a) => {
            let key = (a.model.file.display().to_string(), a.model.with.clone());
            let mut programs = programs.borrow_mut();
            let compiled = programs
                .entry(key)
                .or_insert_with(|| load(&a.model).map(Compiled::new).map_err(|e| failed(&e)));
            match compiled {
                Ok(c) => plan::parameters(&a)
                    .and_then(|values| c.check(&a, values))
                    .map_err(|e| failed(&e)),
                Err(e) => Err(e.clone()),
            }
        }
        Command::Fit(a) => {
            let key = format!("fit {a:?}");
            once(commands, key, || crate::fit::run(&a).map(|_| ()))
        }
    }
}

#[test]
fn fuzz_the_command_line_no_panic_and_every_failure_exits_2_with_a_message() {
    let cases: u32 = env_or("VARMASS_FUZZ_CASES", 3000);
    let config = Config {
        cases,
        rng_seed: RngSeed::Fixed(env_or("VARMASS_FUZZ_SEED", 20261126)),
        failure_persistence: None,
        ..Config::default()
    };
    let programs = RefCell::new(Programs::new());
    let commands = RefCell::new(HashMap::new());
    let counts = RefCell::new([0_u32; 2]);
    let mut runner = TestRunner::new(config);
    let result = runner.run(&argv(), |argv| {
        let verdict = one(&argv, &programs, &commands);
        if let Err((code, message)) = &verdict {
            prop_assert_eq!(*code, 2, "{:?}: {}", argv, message);
            prop_assert!(!message.trim().is_empty(), "{:?}: no message", argv);
        }
        counts.borrow_mut()[usize::from(verdict.is_err())] += 1;
        Ok(())
    });
    let [passed, refused] = *counts.borrow();
    eprintln!("{cases} cases: {passed} planned, {refused} refused with exit 2");
    if let Err(e) = result {
        panic!("{e}");
    }
    // The grammar reaches both outcomes, each often (measured at 3000 cases: 364 planned,
    // 2636 refused; at 10⁵: 12586 and 87414, in 11 s).
    assert!(
        passed > cases / 10 && refused > cases / 4,
        "{passed} {refused}"
    );
}
