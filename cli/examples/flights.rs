//! The public flights against their measured apogees, beside RocketPy's published ones
//! (issue 36, item 6; docs/validation.md#the-public-flights):
//!
//! ```text
//! cargo run --release -p varmass-cli --example flights
//! ```
//!
//! Flies each scene `flights/<name>/<name>.toml` (rail, ascent, parachutes, landing) through
//! the cli crate's scene API (`varmass_cli::scene::run_file`, what `varmass run` does) and
//! prints, for each flight: our apogee (the flight summary's, located between rows, m above
//! the pad), RocketPy's published simulated apogee and the measured one
//! (flight.toml's `[apogee]`: RocketPy's docs/examples/index.rst), both relative errors
//! against the measured, and the mean absolute errors of both over the same flights. Run it
//! from anywhere: the paths are the crate's.

use std::path::{Path, PathBuf};

use varmass_cli::scene;

const FLIGHTS: [&str; 8] = [
    "bella_lui",
    "ndrt_2020",
    "andromeda",
    "astra",
    "erebus",
    "cavour",
    "genesis",
    "lince",
];

/// flight.toml's `[apogee]` numbers: RocketPy's published simulated apogee, the measured.
fn published(folder: &Path) -> Result<(f64, f64), String> {
    let path = folder.join("flight.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let doc: toml::Table = text
        .parse()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let apogee = doc
        .get("apogee")
        .and_then(|a| a.as_table())
        .ok_or_else(|| format!("{}: no [apogee]", path.display()))?;
    let number = |key: &str| -> Result<f64, String> {
        apogee
            .get(key)
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .ok_or_else(|| format!("{}: no [apogee] {key}", path.display()))
    };
    Ok((number("published_sim")?, number("measured")?))
}

/// Our apogee: the flight summary's located apogee of the scene's full flight.
fn ours(folder: &Path, name: &str) -> Result<f64, String> {
    let path = folder.join(format!("{name}.toml"));
    let run = scene::run_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    if let Some(failure) = run.failure {
        return Err(format!("{}: the run failed: {failure}", path.display()));
    }
    run.flight
        .and_then(|f| f.summary.apogee)
        .map(|a| a.altitude)
        .ok_or_else(|| format!("{}: no apogee", path.display()))
}

fn main() -> Result<(), String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    println!(
        "{:<10} {:>9} {:>10} {:>9} {:>8} {:>9}",
        "flight", "varmass", "RocketPy", "measured", "varmass", "RocketPy"
    );
    println!(
        "{:<10} {:>9} {:>10} {:>9} {:>8} {:>9}",
        "", "(m)", "pub. (m)", "(m)", "error", "error"
    );
    let (mut ours_sum, mut theirs_sum) = (0.0, 0.0);
    for name in FLIGHTS {
        let folder = root.join("flights").join(name);
        let (rocketpy, measured) = published(&folder)?;
        let apogee = ours(&folder, name)?;
        let ours_err = (apogee - measured) / measured;
        let theirs_err = (rocketpy - measured) / measured;
        ours_sum += ours_err.abs();
        theirs_sum += theirs_err.abs();
        println!(
            "{name:<10} {apogee:>9.2} {rocketpy:>10.2} {measured:>9.2} {:>+7.2}% {:>+8.2}%",
            100.0 * ours_err,
            100.0 * theirs_err
        );
    }
    let n = FLIGHTS.len() as f64;
    println!(
        "mean absolute error over the {} flights: varmass {:.2} %, RocketPy (published) {:.2} %",
        FLIGHTS.len(),
        100.0 * ours_sum / n,
        100.0 * theirs_sum / n
    );
    Ok(())
}
