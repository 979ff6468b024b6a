//! RocketPy's Calisto flown straight up with the standard library (`models/calisto.vms`:
//! the M1670 motor, the 1976 atmosphere's density and speed of sound, standard gravity,
//! RocketPy's drag curve cd(Mach)) against the same physics written by hand
//! (`tests/data/library/calisto_hand.vms`: the lowest layer's formulas and their eight
//! constants set here), both by `varmass run` (docs/components.md#the-library).
//!
//! The rocket: RocketPy's Calisto example, 14.426 kg without its motor, radius 127/2000 m
//! (area π 0.0635² = 0.012667686977437444 m²), the Cesaroni M1670 loaded (5.231 kg, 3.101 kg
//! of propellant, the .eng's header) burning at F/u_e with u_e = total impulse / propellant
//! mass. Vertical, from y = 0 without a launch pad (it sinks 1.9 cm before the thrust
//! exceeds its weight at ~0.07 s), no wind: not RocketPy's inclined flight off a rail, so
//! its apogee is not RocketPy's.

mod common;

use common::{csv, model, motor, root, written};

/// Non-blank lines that are not comments: the statements of a model file.
fn statements(path: &str) -> usize {
    let text = std::fs::read_to_string(path).expect("a model file");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .count()
}

/// Flies `file` for 30 s (past the apogee), recording `record` every 0.01 s.
fn fly(file: &str, extra: &[&str], record: &str, name: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let u_e = format!("u_e={:?}", motor().exhaust_speed());
    let mut args = vec!["run", file, "--set", u_e.as_str()];
    args.extend(["--set", "area=0.012667686977437444", "--init", "y=0"]);
    args.extend(["--init", "m=19.657", "--until", "30", "--every", "0.01"]);
    args.extend(["--tol", "1e-12", "--record", record]);
    args.extend(extra);
    csv(&written(&args, name))
}

/// Measured: every column (y, y', m, the speed of sound) within 1.2e-15 of its largest
/// value (the same equations, in another order); apogee 3106.44 m at 25.0 s, Mach 0.82 at
/// most (the drag table's rows 0.01 to 2). Bound 1e-13 (~100×). The
/// library's file has 10 statements and no constant to set; the hand's 13 and eight
/// constants.
#[test]
fn calisto_with_the_library_flies_as_by_hand() {
    let library = model("calisto.vms");
    let hand = root("tests/data/library/calisto_hand.vms");
    let constants = [
        "g0=9.80665",
        "r0=6356766",
        "R_star=8.31432",
        "M0=0.0289644",
        "T0=288.15",
        "p0=101325",
        "L0=-0.0065",
        "gamma=1.4",
    ];
    let sets: Vec<&str> = constants.iter().flat_map(|c| ["--set", c]).collect();
    let (_, ours) = fly(&library, &[], "y,y',m,air_a", "calisto_library.csv");
    let (_, theirs) = fly(&hand, &sets, "y,y',m,a", "calisto_hand.csv");
    assert_eq!(ours.len(), 3001);
    assert_eq!(ours.len(), theirs.len());
    let mut worst = 0.0_f64;
    for column in 1..5 {
        let scale = theirs.iter().fold(0.0_f64, |s, r| s.max(r[column].abs()));
        for (a, b) in ours.iter().zip(&theirs) {
            worst = worst.max((a[column] - b[column]).abs() / scale);
        }
    }
    let apogee = ours.iter().map(|r| r[1]).fold(f64::MIN, f64::max);
    let mach = ours.iter().map(|r| r[2].abs() / r[4]).fold(0.0, f64::max);
    eprintln!("apogee {apogee} m, Mach {mach:.3} at most; worst difference {worst:e}");
    assert!(worst <= 1e-13, "{worst:e}");
    assert!(
        apogee > 3000.0 && apogee < 11_000.0,
        "{apogee} (the hand's layer)"
    );
    assert!(mach > 0.5 && mach < 2.0, "{mach} (within the drag table)");
    let (short, long) = (statements(&library), statements(&hand));
    eprintln!(
        "statements: library {short}, by hand {long} and {} constants",
        constants.len()
    );
    assert!(short < long, "{short} against {long}");
}
