//! The unit check never panics: mutated systems with `units` (unit tokens swapped in,
//! spans deleted or duplicated) come out as a derivation or as diagnostics that render.
//! Fixed seed, so CI runs the same cases; `VARMASS_FUZZ_CASES` runs more.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use varmass_symbolic::{derive_source, mechanics::Parameters};

const SYSTEMS: &[&str] = &[
    "coordinates x
units x: m, m0: kg, c: kg/m, g: m/s^2, theta: rad, f_d: 1
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]
check R2_x = -c*x'^2",
    "coordinates y
units y: m, mu: kg/s, u_e: m/s, g: m/s^2
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [-u_e]
check y'' = mu*u_e/m - g",
    "coordinates x, y
units x: m, y: m, mu: kg/s, u_e: m/s, k: N/m, l0: m, g: m/s^2, J0: kg*m^2
mass m: state, rate -mu
inertia J = J0
let r = sqrt(x^2 + y^2)
body bob: mass m, position [x, y]
kinetic 1/2*J*(x'^2 + y'^2)/l0^2
potential 1/2*k*(r - l0)^2 + m*g*y
outflow bob: rate mu, relative_velocity [u_e*y/r, -u_e*x/r]
check p_x = p_x",
];

const TOKENS: &[&str] = &[
    "units ",
    "x: ",
    "kg",
    "m",
    "s",
    "rad",
    "N",
    "J",
    "W",
    "Pa",
    "1",
    "0",
    "2",
    "^(1/2)",
    "^-1",
    "^x",
    "/",
    "*",
    "+",
    "-",
    ",",
    ":",
    "(",
    ")",
    "[",
    "]",
    "\n",
    "sqrt(",
    "sin(",
    "atan2(x, ",
    "min(",
    "x'",
    "x''",
    "t",
    "H",
    "p_x",
    "Q_x",
    "mdot_m",
    "1e308",
    "^1e30",
    "^(1/0)",
    "^(2^200)",
    "kg^(1/3)",
    "sec",
    "let ",
    "check ",
    "mass ",
];

#[derive(Clone, Debug)]
enum Edit {
    Replace(usize, &'static str),
    Delete(usize, usize),
    Duplicate(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), prop::sample::select(TOKENS)).prop_map(|(i, t)| Edit::Replace(i, t)),
        (any::<usize>(), 1usize..6).prop_map(|(i, n)| Edit::Delete(i, n)),
        (any::<usize>(), 1usize..12).prop_map(|(i, n)| Edit::Duplicate(i, n)),
    ]
}

/// The range `i..i + n` of `s` (wrapped and clamped) on character boundaries.
fn range(s: &str, i: usize, n: usize) -> (usize, usize) {
    let mut start = i % (s.len() + 1);
    while !s.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = (start + n).min(s.len());
    while !s.is_char_boundary(end) {
        end += 1;
    }
    (start, end)
}

fn apply(source: &str, edits: &[Edit]) -> String {
    let mut s = source.to_string();
    for e in edits {
        match *e {
            Edit::Replace(i, token) => {
                let (a, b) = range(&s, i, 1);
                s.replace_range(a..b, token);
            }
            Edit::Delete(i, n) => {
                let (a, b) = range(&s, i, n);
                s.replace_range(a..b, "");
            }
            Edit::Duplicate(i, n) => {
                let (a, b) = range(&s, i, n);
                let piece = s[a..b].to_string();
                s.insert_str(b, &piece);
            }
        }
    }
    s
}

fn config() -> Config {
    let cases = std::env::var("VARMASS_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok());
    Config {
        cases: cases.unwrap_or(1500),
        rng_seed: RngSeed::Fixed(20261123),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn the_unit_check_never_panics(system in 0..SYSTEMS.len(), edits in prop::collection::vec(edit(), 1..5)) {
        let source = apply(SYSTEMS[system], &edits);
        if let Err(errors) = derive_source(&source, Parameters::Inferred) {
            prop_assert!(!errors.is_empty());
            for error in errors {
                prop_assert!(!error.render(&source).is_empty());
            }
        }
    }
}

#[test]
fn the_seed_systems_derive() {
    for source in SYSTEMS {
        derive_source(source, Parameters::Inferred)
            .unwrap_or_else(|e| panic!("{}", e[0].render(source)));
    }
}
