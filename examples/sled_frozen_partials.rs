//! The paper's sled through the symbolic engine: the Lagrangian, its frozen partials and,
//! for contrast, the ordinary partial that a constant-mass tool would take.
//!
//! Run with `cargo run --release --example sled_frozen_partials`.

use std::collections::HashMap;
use std::process::ExitCode;

use varmass::symbolic::mechanics::{derive_source, Parameters};

/// The paper's sled, body form (SPEC §2), with the paper's results stated as checks.
const SLED: &str = "
coordinates x
units x: m, m0: kg, c: kg/m, g: m/s^2, theta: rad, f_d: 1
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]
check p_x = m*x'
check H = p_x^2/(2*m) - m*g*x*sin(theta)
check R2_x = -c*x'^2
check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m
";

fn main() -> ExitCode {
    let mut d = match derive_source(SLED, Parameters::Inferred) {
        Ok(d) => d,
        Err(errors) => {
            for e in errors {
                eprintln!("{}", e.render(SLED));
            }
            return ExitCode::FAILURE;
        }
    };
    let x = d.coordinates[0].clone();
    let law = d.closed_laws[0].expect("m follows a law");
    let m = d.masses[0].symbol;
    let lagrangian = d.lagrangian;
    let frozen_dx = d.pool.diff(lagrangian, x.q);
    let frozen_dv = d.pool.diff(lagrangian, x.velocity);
    // The ordinary partial: substitute m = m0 + c x first, then differentiate.
    let law_of_m = HashMap::from([(m, law)]);
    let substituted = d.pool.substitute(lagrangian, &law_of_m);
    let ordinary_dx = d.pool.diff(substituted, x.q);
    // Compare both on the motion, where m = m0 + c x.
    let frozen_on_motion = d.pool.substitute(frozen_dx, &law_of_m);
    let difference = d.pool.sub(ordinary_dx, frozen_on_motion);
    let spurious = d.pool.expand(difference);

    println!(
        "The paper's sled (Zhang 2015, §4), m = {}",
        d.pool.display(law)
    );
    println!("  L          = {}", d.pool.display(lagrangian));
    println!(
        "  ∂*L/∂x     = {}   (frozen: m held constant)",
        d.pool.display(frozen_dx)
    );
    println!("  ∂*L/∂ẋ     = {}", d.pool.display(frozen_dv));
    println!(
        "  ∂L/∂x      = {}   (ordinary, after substituting m)",
        d.pool.display(ordinary_dx)
    );
    println!(
        "  difference = {}   (the spurious term c(½ẋ² + g x sin θ))",
        d.pool.display(spurious)
    );
    println!();
    println!("{}", d.to_text());
    println!("all {} checks hold", d.checks.len());
    ExitCode::SUCCESS
}
