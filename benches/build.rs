//! Generates the n-link chains (n = 1…6) with the same pipeline the macro runs
//! (parse → derive → `emit_system`), plus two variants that the macro never emits, to
//! measure the symbolic-inverse threshold (`SYMBOLIC_INVERSE_MAX_DOF`) in compiled code:
//! `Chain2Numeric` (2 links, q̇ from M q̇ = p − b by Cholesky) and `Chain3Closed` (3 links,
//! q̇ = adj(M)(p − b)/det M in closed form).

#[path = "common/adjugate.rs"]
mod adjugate;
#[path = "common/chain.rs"]
mod chain;

use std::fmt::Write as _;
use std::path::PathBuf;

use proc_macro2::{Ident, Span};
use quote::quote;
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::{
    derive_source,
    mechanics::{Parameters, VelocitySolve},
};

const PARAMETERS: [&str; 4] = ["m0", "c", "l", "g"];

/// How q̇ is recovered from p in the emitted code.
#[derive(Clone, Copy, PartialEq)]
enum Variant {
    /// Whatever the derivation chose (what the macro emits).
    AsDerived,
    /// Always the numeric Cholesky solve.
    Numeric,
    /// Always the closed form (3 × 3 adjugate).
    Closed,
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=common/chain.rs");
    println!("cargo:rerun-if-changed=common/adjugate.rs");
    let mut code = String::new();
    for links in 1..=6 {
        code += &emit(links, &format!("Chain{links}"), Variant::AsDerived);
    }
    code += &emit(2, "Chain2Numeric", Variant::Numeric);
    code += &emit(3, "Chain3Closed", Variant::Closed);
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("chains.rs"), code).expect("OUT_DIR is writable");
}

fn emit(links: usize, name: &str, variant: Variant) -> String {
    let source = chain::chain_source(links);
    let parameters = Parameters::Declared(PARAMETERS.iter().map(|p| p.to_string()).collect());
    let mut d = derive_source(&source, parameters)
        .unwrap_or_else(|e| panic!("the {links}-link chain derives: {e:?}"));
    match variant {
        Variant::AsDerived => {}
        Variant::Numeric => d.velocities = VelocitySolve::Numeric,
        Variant::Closed => {
            d.velocities = VelocitySolve::Symbolic(adjugate::closed_velocities(&mut d))
        }
    }
    let ident = Ident::new(name, Span::call_site());
    let target = Target {
        name: ident.clone(),
        runtime: quote!(::varmass::core),
    };
    let implementation = emit_system(&mut d, &source, &target);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "/// The {links}-link chain ({}).\n#[derive(Clone, Copy, Debug)]\npub struct {name} {{ {} }}\n{implementation}\n",
        match variant {
            Variant::AsDerived => "as the macro emits it",
            Variant::Numeric => "q̇ by Cholesky",
            Variant::Closed => "q̇ in closed form",
        },
        PARAMETERS.map(|p| format!("pub {p}: f64")).join(", ")
    );
    out
}
