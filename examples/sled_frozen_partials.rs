//! The paper's sled through the symbolic engine: the Lagrangian, its frozen partials and,
//! for contrast, the ordinary partial that a constant-mass tool would take.
//!
//! Run with `cargo run --release --example sled_frozen_partials`.

use std::collections::HashMap;
use std::process::ExitCode;

use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::{
    derive,
    mechanics::{Derivation, Parameters},
};

/// The paper's sled, body form, with the paper's results stated as checks.
const SLED: &str = include_str!("../models/sled.vms");

/// The sled's model with its impact force (the paper's sled), derived.
fn derive_sled() -> Result<Derivation, String> {
    let ast = parse_system(SLED).map_err(|errors| render(&errors))?;
    let paper = select_tags(&ast, &["impact".to_string()])
        .map_err(|unknown| unknown.iter().map(|u| u.to_string()).collect::<String>())?;
    derive(&paper, Parameters::Inferred).map_err(|errors| render(&errors))
}

fn render(errors: &[varmass::symbolic::Diagnostic]) -> String {
    let rendered: Vec<String> = errors
        .iter()
        .map(|e| e.render_in_file(SLED, "models/sled.vms"))
        .collect();
    rendered.join("\n")
}

fn main() -> ExitCode {
    let mut d = match derive_sled() {
        Ok(d) => d,
        Err(errors) => {
            eprintln!("{errors}");
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
