//! Stage 4: Rust code for a derivation (SPEC §3).
//!
//! [`emit_system`] turns a [`Derivation`] into the `VariableMassSystem` impl that the
//! `#[variable_mass_system]` macro adds to the user's struct: straight-line functions with
//! common subexpressions shared, no allocation, no dynamic dispatch and no identically-zero
//! terms, each with its formula in a doc comment; plus the whole derivation as text and
//! LaTeX constants.

mod expression;
mod methods;
mod system;

use proc_macro2::{Literal, TokenStream};
use quote::quote;

pub use system::Target;

use crate::mechanics::Derivation;
use system::Emitter;

/// The inherent constants and the trait impl for `target.name`.
pub fn emit_system(d: &mut Derivation, source: &str, target: &Target) -> TokenStream {
    let text = d.to_text();
    let latex = d.to_latex();
    let velocity_ids = d
        .coordinates
        .iter()
        .map(|c| d.pool.sym(c.velocity))
        .collect();
    let name = &target.name;
    let runtime = &target.runtime;
    let emitter = Emitter {
        d,
        target,
        velocity_ids,
    };
    let n = d.coordinates.len();
    let k = d.state_mass_count();
    let (n_lit, s_lit) = (
        Literal::usize_unsuffixed(n),
        Literal::usize_unsuffixed(2 * n + k),
    );
    let coordinates = d.coordinates.iter().map(|c| c.name.as_str());
    let masses = d.masses.iter().map(|m| m.name.as_str());
    let parameters = d.parameters.iter().map(|(p, _)| p.as_str());
    let methods = [
        emitter.mass(),
        emitter.mass_rate(),
        emitter.mass_matrix(),
        emitter.coordinate_vector_method(
            "momenta",
            "The generalized momenta p = ∂*L/∂q̇ (eq. 8).",
            "p_#",
            &d.momenta,
        ),
        emitter.lagrangian(),
        emitter.coordinate_vector_method(
            "lagrangian_gradient",
            "∂*L/∂q, masses frozen (= −∂*H/∂q, eq. 13).",
            "∂*L/∂#",
            &d.lagrangian_gradient,
        ),
        emitter.coordinate_vector_method(
            "active_force",
            "The generalized active force Q* (eq. 22 for the sled).",
            "Q*_#",
            &d.active_force,
        ),
        emitter.coordinate_vector_method(
            "reactive_thrust",
            "The generalized reactive thrust R1 = Σ Q1 v_r1 · ∂r/∂q.",
            "R1_#",
            &d.reactive_thrust,
        ),
        emitter.coordinate_vector_method(
            "impact_force",
            "The generalized impact force R2 = Σ Q2 v_r2 · ∂r/∂q (eq. 23 for the sled).",
            "R2_#",
            &d.impact_force,
        ),
        emitter.coordinate_vector_method(
            "mass_flux_force",
            "The mass-flux term Σ ṁᵢ ∂*p/∂mᵢ of the true ṗ.",
            "flux_#",
            &d.mass_flux_force,
        ),
        emitter.accelerations(),
        emitter.velocities(),
        emitter.hamiltonian(),
        emitter.canonical_rates(),
        emitter.state_rate(),
        emitter.power(),
        emitter.jacobian(),
    ];
    quote! {
        impl #name {
            /// The system in the DSL, as written.
            pub const SOURCE: &'static str = #source;
            /// The derivation of this system as text, in the order of the paper
            /// (L, p, H, forces, canonical equations, true rates).
            pub const DERIVATION: &'static str = #text;
            /// The derivation of this system as LaTeX (`align*` environments).
            pub const DERIVATION_LATEX: &'static str = #latex;
            /// The parameters (fields) the equations use, in order.
            pub const PARAMETERS: &'static [&'static str] = &[#(#parameters),*];
        }

        #[allow(unused_variables, non_snake_case, clippy::all)]
        impl #runtime::VariableMassSystem<#n_lit, #s_lit> for #name {
            const COORDINATES: [&'static str; #n_lit] = [#(#coordinates),*];
            const MASSES: &'static [&'static str] = &[#(#masses),*];
            #(#methods)*
        }
    }
}
