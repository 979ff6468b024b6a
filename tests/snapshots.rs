//! Snapshots (insta) of the full expansion of every example system, formatted with
//! prettyplease, and of its derivation text: any change to generated code or to the
//! derivation shows up for review.

use quote::format_ident;
use varmass::symbolic::emit::{emit_system, Target};
use varmass::symbolic::mechanics::{derive_source, Parameters};

fn fields(names: &[&str]) -> Parameters {
    Parameters::Declared(names.iter().map(|s| s.to_string()).collect())
}

/// The formatted expansion and the derivation text of a system.
fn expand(name: &str, source: &str, parameters: &[&str]) -> (String, String) {
    let mut d = derive_source(source, fields(parameters)).unwrap_or_else(|e| panic!("{e:?}"));
    let target = Target {
        name: format_ident!("{}", name),
        runtime: quote::quote!(::varmass::core),
    };
    let tokens = emit_system(&mut d, source, &target);
    let file: syn::File = syn::parse2(tokens).expect("generated code parses as Rust");
    (prettyplease::unparse(&file), d.to_text())
}

macro_rules! snapshot_system {
    ($test:ident, $name:literal, $source:expr, $parameters:expr) => {
        #[test]
        fn $test() {
            let (code, text) = expand($name, $source, $parameters);
            insta::assert_snapshot!(concat!(stringify!($test), "_expansion"), code);
            insta::assert_snapshot!(concat!(stringify!($test), "_derivation"), text);
        }
    };
}

snapshot_system!(
    sled_paper_form,
    "Sled",
    "coordinates x
mass m = m0 + c*x
lagrangian 1/2*m*x'^2 + m*g*x*sin(theta)
force x: -f_d*m*g*cos(theta)
impact x: -c*x'^2",
    &["m0", "c", "g", "theta", "f_d"]
);

snapshot_system!(
    sled_body_form,
    "Sled",
    "coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]",
    &["m0", "c", "g", "theta", "f_d"]
);

snapshot_system!(
    vertical_rocket,
    "Rocket",
    "coordinates y
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [-u_e]",
    &["mu", "u_e", "g"]
);

snapshot_system!(
    double_pendulum,
    "DoublePendulum",
    "coordinates a, b
mass m1 = M1
mass m2 = M2
body bob1: mass m1, position [l1*sin(a), -l1*cos(a)]
body bob2: mass m2, position [l1*sin(a) + l2*sin(b), -l1*cos(a) - l2*cos(b)]
potential m1*g*(-l1*cos(a)) + m2*g*(-l1*cos(a) - l2*cos(b))",
    &["M1", "M2", "l1", "l2", "g"]
);

snapshot_system!(
    swinging_tank,
    "SwingingTank",
    "coordinates x, y, th
mass m: state, rate -mu
mass M = M0
inertia J = J0
body hull: mass M, position [x, y]
body tank: mass m, position [x + l*cos(th), y + l*sin(th)]
kinetic 1/2*J*th'^2
potential M*g*y + m*g*(y + l*sin(th)) + 1/2*K*(x^2 + y^2)
outflow tank: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]",
    &["mu", "M0", "J0", "l", "g", "K", "u_e"]
);
