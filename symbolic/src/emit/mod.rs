//! Stage 4: Rust code for a derivation (ARCHITECTURE.md#stage-4-emit).
//!
//! [`emit_system`] turns a [`Derivation`] into the `VariableMassSystem` impl that the
//! `#[variable_mass_system]` macro adds to the user's struct: straight-line functions with
//! common subexpressions shared, no allocation, no dynamic dispatch and no identically-zero
//! terms, each with its formula in a doc comment; plus the whole derivation as text and
//! LaTeX constants.

mod expression;
mod factor;
mod head;
mod inputs;
mod lanes;
mod lex;
mod methods;
mod signature;
mod stops;
mod switches;
mod system;
mod tables;
mod taylor;

use proc_macro2::{Literal, TokenStream};
use quote::quote;

pub use signature::{Method, REQUIRED};
pub use system::Target;

use rustc_hash::{FxHashMap, FxHashSet};

use crate::expr::{ExprPool, Func, Id, Node};
use crate::mechanics::{Derivation, Outputs};
use crate::quantity::{documented_roots, Quantity};
use system::Emitter;

/// The inherent constants and the trait impl for `target.name`, with every optional output.
pub fn emit_system(d: &mut Derivation, source: &str, target: &Target) -> TokenStream {
    emit_system_for(d, source, target, Outputs::FULL)
}

/// [`emit_system`] with only the optional outputs `outputs` asks for; the trait's defaults
/// serve for the methods left out. The Jacobian is emitted when it is asked for and was
/// derived (see [`crate::mechanics::derive_for`]).
pub fn emit_system_for(
    d: &mut Derivation,
    source: &str,
    target: &Target,
    outputs: Outputs,
) -> TokenStream {
    // The doc comments' texts come from the derivation text's printing walk when there is
    // one (the quantities do not change below: what follows adds nodes to the pool only).
    let shown = documented_roots(d);
    let (texts, shown_texts) = if outputs.derivation {
        let (texts, shown_texts) = derivation_texts(d, &shown);
        (Some(texts), shown_texts)
    } else {
        (None, d.pool.display_all(&shown))
    };
    let shown_texts = shown.iter().copied().zip(shown_texts).collect();
    let velocity_ids = d
        .coordinates
        .iter()
        .map(|c| d.pool.sym(c.velocity))
        .collect();
    // The code evaluates sin/cos of sums of two coordinates through the sines and cosines
    // of the coordinates themselves (shared by CSE); the text above keeps cos(a - b).
    let mut for_code = FxHashMap::default();
    for e in with_angle_sums(&d.pool, &d.code_roots(outputs)) {
        let expanded = d.pool.expand_trig_arguments(e);
        if expanded != e {
            for_code.insert(e, expanded);
        }
    }
    let switches = crate::mechanics::switching_functions(d);
    let table_switches = crate::mechanics::table_switches(d);
    let time_tables = crate::mechanics::time_tables(d, &d.code_roots(outputs));
    let name = &target.name;
    let runtime = &target.runtime;
    let statics = (d.pool.table_count() > 0).then(|| tables::statics(&d.pool, runtime));
    let constructors = tables::constructors(d, runtime);
    let emitter = Emitter {
        d,
        target,
        velocity_ids,
        for_code,
        texts: shown_texts,
    };
    let n = d.coordinates.len();
    let k = d.state_mass_count();
    let (n_lit, s_lit) = (
        Literal::usize_unsuffixed(n),
        Literal::usize_unsuffixed(d.state_len()),
    );
    let _ = k;
    let coordinates = d.coordinates.iter().map(|c| c.name.as_str());
    let masses = d.masses.iter().map(|m| m.name.as_str());
    let parameters = d.parameters.iter().map(|(p, _)| p.as_str());
    let head = match outputs.head {
        true => head::head_items(&emitter, outputs.taylor),
        false => Default::default(),
    };
    let methods = [
        emitter.mass(),
        emitter.mass_rate(),
        emitter.mass_matrix(),
        emitter.vector_method(Quantity::Momenta),
        emitter.lagrangian(),
        emitter.vector_method(Quantity::LagrangianGradient),
        emitter.vector_method(Quantity::ActiveForce),
        emitter.vector_method(Quantity::ReactiveThrust),
        emitter.vector_method(Quantity::ImpactForce),
        emitter.vector_method(Quantity::MassFluxForce),
        emitter.accelerations(),
        emitter.velocities(),
        optional(outputs.hamiltonian, || emitter.hamiltonian()),
        emitter.canonical_rates(),
        emitter.state_rate(),
        optional(outputs.power, || emitter.power()),
        optional(outputs.jacobian, || emitter.jacobian()),
        emitter.switching_functions(&switches, &table_switches),
        optional(outputs.taylor, || taylor::taylor_method(d, runtime, name)),
        head.0,
        emitter.flow_rates(),
        emitter.stop_times(&time_tables),
        emitter.sample(),
    ];
    let lanes = optional(outputs.lanes, || lanes::lanes_impl(&emitter));
    let head_struct = head.1;
    let units_doc = d.units_line().map(|line| {
        let line = format!("Units: {line}.");
        quote!(#[doc = ""] #[doc = #line])
    });
    // The held values of the sampled inputs: the state's last entries.
    let held = match d.held().len() {
        0 => TokenStream::new(),
        h => {
            let h = Literal::usize_unsuffixed(h);
            quote!(const HELD: usize = #h;)
        }
    };
    let trait_impl = quote! {
        #[allow(unused_variables, non_snake_case, clippy::all)]
        impl #runtime::VariableMassSystem<#n_lit, #s_lit> for #name {
            const COORDINATES: [&'static str; #n_lit] = [#(#coordinates),*];
            const MASSES: &'static [&'static str] = &[#(#masses),*];
            #held
            #(#methods)*
        }
    };
    // Tables: their statics beside the impl that calls them, in a block of their own;
    // inputs: the alias of their trait there too.
    let alias = (!d.inputs.is_empty()).then(|| inputs::alias(name));
    let trait_impl = match (statics, alias) {
        (None, None) => trait_impl,
        (statics, alias) => quote!(const _: () = { #alias #statics #trait_impl };),
    };
    let inputs_trait = inputs::inputs_trait(name, &d.inputs, runtime);
    quote! {
        impl #name {
            /// The system in the DSL, as written.
            pub const SOURCE: &'static str = #source;
            #texts
            /// The parameters (fields) the equations use, in order.
            #units_doc
            pub const PARAMETERS: &'static [&'static str] = &[#(#parameters),*];
            #constructors
        }

        #inputs_trait
        #trait_impl
        #lanes
        #head_struct
    }
}

/// The `DERIVATION` and `DERIVATION_LATEX` constants, and the DSL text of each of `shown`.
fn derivation_texts(d: &mut Derivation, shown: &[Id]) -> (TokenStream, Vec<String>) {
    let (text, latex, shown_texts) = d.to_text_and_latex_showing(shown);
    let constants = quote! {
        /// The derivation of this system as text, in the order of the paper
        /// (L, p, H, forces, canonical equations, true rates).
        pub const DERIVATION: &'static str = #text;
        /// The derivation of this system as LaTeX (`align*` environments).
        pub const DERIVATION_LATEX: &'static str = #latex;
    };
    (constants, shown_texts)
}

/// A method's code when it is asked for, nothing otherwise.
fn optional(asked: bool, method: impl FnOnce() -> TokenStream) -> TokenStream {
    if asked {
        method()
    } else {
        TokenStream::new()
    }
}

/// The roots, each once and in order, under which some sine or cosine takes a sum of two
/// terms: the only ones `expand_trig_arguments` can change. One walk over all roots
/// replaces a walk of each root's whole tree (the roots share most of their nodes).
fn with_angle_sums(pool: &ExprPool, roots: &[Id]) -> Vec<Id> {
    let mut below: FxHashSet<Id> = FxHashSet::default();
    for id in pool.reachable(roots, false) {
        let found = match pool.node(id) {
            Node::Call(Func::Sin | Func::Cos, args) => args
                .iter()
                .any(|a| matches!(pool.node(*a), Node::Add(terms) if terms.len() == 2)),
            node => node.children().any(|c| below.contains(&c)),
        };
        if found {
            below.insert(id);
        }
    }
    let mut seen = FxHashSet::default();
    let unique = roots.iter().copied().filter(|r| seen.insert(*r));
    unique.filter(|r| below.contains(r)).collect()
}
