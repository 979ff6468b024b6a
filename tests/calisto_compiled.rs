//! Calisto's full flight (flights/calisto/calisto_flight.toml: rail, ascent, drogue, main,
//! landing at tol 1e-8) compiled by the macro from `flights/calisto/calisto.vms` and
//! interpreted from the same file (`TapeSystem`), both flown by one driver through the
//! core's Rust API (tests/calisto_support): the two formulations of the same equations —
//! generated Rust against the interpreter's tapes, which round differently — agree on the
//! apogee, the 800 m crossing, the landing time and point. Measured (test profile, with the
//! quaternion's closed-form q̈ and p forwards): apogee +5.5e-12 m, the crossing +2.1e-12 s,
//! the landing +1.4e-10 s, +4.1e-10 m East, −5.3e-10 m North (the steps differ from the
//! rounding; they move between builds by a few e-12 m and e-10 s); bounds 1e-9 m,
//! 1e-9 s, 1e-8 s, 1e-7 s, 1e-6 m, the tolerance's order over the descent (1e-8 of 295 s is
//! 3e-6 s). The tool's run of the scene (`varmass run flights/calisto/calisto_flight.toml`)
//! lands at 295.0393395410205 s, 4e-10 s from both. The benches' `calisto` bench times the
//! compiled flight against RocketPy (docs/bench/calisto.md).

#![allow(clippy::result_large_err)] // the stepper closure's StepError<15> carries the state

mod calisto_support;

use std::path::Path;

use calisto_support::{fly, Canopies, Flown, S};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::variable_mass_system;
use varmass::symbolic::compose::compose;
use varmass::symbolic::derive_in;
use varmass::symbolic::mechanics::{Outputs, Parameters};
use varmass::symbolic::parse::parse_system;

/// The compiled Calisto: the canopies' times are its fields, every other parameter its
/// default in the model file.
#[variable_mass_system(file = "flights/calisto/calisto.vms")]
#[derive(Clone, Copy, Debug)]
struct Calisto {
    drogue_t_open: f64,
    drogue_t_cut: f64,
    main_t_open: f64,
}

fn compiled(c: Canopies) -> Calisto {
    Calisto {
        drogue_t_open: c.drogue_t_open,
        drogue_t_cut: c.drogue_t_cut,
        main_t_open: c.main_t_open,
    }
}

/// The interpreter's Calisto, derived once; each call sets the canopies' times.
fn interpreted() -> impl Fn(Canopies) -> TapeSystem<7, S> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("flights/calisto/calisto.vms");
    let source = std::fs::read_to_string(&path).expect("the model");
    let composition = compose(&source, parse_system(&source).expect("parses"), &path).unwrap();
    let base = path.parent().unwrap();
    let derivation =
        derive_in(&composition.ast, Parameters::Inferred, Outputs::FULL, base).expect("derives");
    let defaults: Vec<(String, f64)> = composition
        .defaults()
        .into_iter()
        .filter(|(n, _)| derivation.parameters.iter().any(|(p, _)| p == n))
        .collect();
    move |c: Canopies| {
        let mut values = defaults.clone();
        for (name, value) in [
            ("drogue_t_open", c.drogue_t_open),
            ("drogue_t_cut", c.drogue_t_cut),
            ("main_t_open", c.main_t_open),
        ] {
            values.iter_mut().find(|(n, _)| n == name).unwrap().1 = value;
        }
        let values: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        TapeSystem::new(Program::new(derivation.clone(), &values).expect("fits")).expect("sizes")
    }
}

/// Apogee (m, s), the 800 m crossing (s), landing (s, x, y).
fn figures(f: &Flown) -> [f64; 6] {
    let (t_a, apogee) = f.end_of(0);
    let (t_c, _) = f.end_of(1);
    let (t_l, landing) = f.end_of(2);
    [apogee[2], t_a, t_c, t_l, landing[0], landing[1]]
}

#[test]
fn the_compiled_and_the_interpreted_calisto_fly_the_same_flight() {
    let ours = fly(compiled, 1e-8).expect("the compiled flight");
    let tape = fly(interpreted(), 1e-8).expect("the interpreted flight");
    let (a, b) = (figures(&ours), figures(&tape));
    let names = [
        "apogee",
        "apogee time",
        "800 m crossing",
        "landing time",
        "landing x",
        "landing y",
    ];
    for ((name, a), b) in names.iter().zip(a).zip(b) {
        println!(
            "{name}: compiled {a:.12} interpreted {b:.12} ({:+.2e})",
            a - b
        );
    }
    let bounds = [1e-9, 1e-9, 1e-8, 1e-7, 1e-6, 1e-6];
    for ((name, (a, b)), bound) in names.iter().zip(a.iter().zip(b)).zip(bounds) {
        assert!(
            (a - b).abs() < bound,
            "{name}: compiled {a} interpreted {b}"
        );
    }
    for k in 0..3 {
        println!(
            "stage {k}: compiled {:?}\n         interpreted {:?}",
            ours.stages[k], tape.stages[k]
        );
    }
}

/// The flight the driver flies (and the benches' `calisto` times) is
/// `flights/calisto/calisto_flight.toml`'s: its rail, start, lags, main height and
/// tolerance are written in `tests/calisto_support` as numbers, so the scene's lines that
/// hold them are checked here, and a scene changed without the driver fails (review of
/// session 37: nothing tied them before).
#[test]
fn the_driver_flies_the_scene_file_s_flight() {
    let scene = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("flights/calisto/calisto_flight.toml"),
    )
    .expect("the scene");
    let lines: Vec<&str> = scene.lines().map(str::trim).collect();
    let start = calisto_support::start();
    let mut wanted = vec![
        "tol = 1e-8".to_string(),
        format!("inclination = {:?}", calisto_support::INCLINATION),
        "heading = 0.0".to_string(),
        format!("exit_travel = {:?}", calisto_support::EXIT_TRAVEL),
        format!("m_s = {}", start[14]),
    ];
    for (k, name) in ["e0", "e1", "e2", "e3"].iter().enumerate() {
        wanted.push(format!("{name} = {}", start[3 + k]));
    }
    for line in &wanted {
        assert!(lines.contains(&line.as_str()), "the scene has no `{line}`");
    }
    let lag = format!("\"t + {}\"", calisto_support::LAG);
    let main = format!("when = \"z < {}\"", calisto_support::MAIN_HEIGHT);
    assert_eq!(scene.matches(&lag).count(), 3, "each change's lag {lag}");
    assert!(lines.iter().any(|l| l.starts_with(&main)), "no `{main}`");
}
