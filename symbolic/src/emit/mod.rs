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
mod tangents;
mod taylor;

use proc_macro2::{Literal, TokenStream};
use quote::quote;

pub use signature::{Method, REQUIRED};
pub use system::Target;

use rustc_hash::{FxHashMap, FxHashSet};

use crate::expr::{ExprPool, Func, Id, Node};
use crate::mechanics::{Derivation, Outputs, TableSwitch, TimeTable, VelocitySolve};
use crate::quantity::Quantity;
use system::{Emitter, Sizes};

/// The inherent constants and the trait impl for `target.name`, with every optional output.
pub fn emit_system(d: &mut Derivation, source: &str, target: &Target) -> TokenStream {
    emit_system_for(d, source, target, Outputs::FULL)
}

/// [`emit_system`] with only the optional outputs `outputs` asks for; the trait's defaults
/// serve for the methods left out. The Jacobian is emitted when it is asked for and was
/// derived (see [`crate::pipeline::derive_for`]).
pub fn emit_system_for(
    d: &mut Derivation,
    source: &str,
    target: &Target,
    outputs: Outputs,
) -> TokenStream {
    // Every step that adds nodes to the pool runs first, in this order (the texts, the
    // velocity symbols, the forms for code, the switches and stop times): the code's
    // names and shared subexpressions follow the pool's order.
    let (texts, shown_texts) = doc_texts(d, outputs);
    let velocity_ids = d
        .coordinates
        .iter()
        .map(|c| d.pool.sym(c.velocity))
        .collect();
    let for_code = code_forms(d, outputs);
    let switches = crate::mechanics::switching_functions(d);
    let table_switches = crate::mechanics::table_switches(d);
    let switch_gradients = match outputs.sensitivities {
        true => switches::gradients(d, &switches, &table_switches),
        false => Vec::new(),
    };
    let time_tables = crate::mechanics::time_tables(d, &d.code_roots(outputs));
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
    let head = match outputs.head {
        true => head::head_items(&emitter, outputs.taylor),
        false => Default::default(),
    };
    let lanes_taylor = outputs.taylor && outputs.lanes && emitter.has_lanes();
    let taylor_tangents = outputs.taylor && tangents::has_taylor_tangents(&emitter);
    let tangents = match outputs.sensitivities {
        true => tangents::tangent_items(&emitter, (taylor_tangents, !lanes_taylor)),
        false => Default::default(),
    };
    let generic_taylor = lanes_taylor || (outputs.sensitivities && taylor_tangents);
    let stops = (
        &switches[..],
        &table_switches[..],
        &time_tables[..],
        &switch_gradients[..],
    );
    let methods = trait_methods(
        &emitter,
        (outputs, generic_taylor),
        stops,
        (head.0, tangents.0),
    );
    let lanes = optional(outputs.lanes, || {
        lanes::lanes_impl(&emitter, outputs.taylor)
    });
    let trait_impl = trait_impl(d, target, methods, statics);
    let inherent = inherent_items(d, source, texts, constructors);
    let name = &target.name;
    let (head_struct, tangents_struct) = (head.1, tangents.1);
    quote! {
        impl #name {
            #inherent
        }

        #trait_impl
        #lanes
        #head_struct
        #tangents_struct
    }
}

/// The `DERIVATION` constants when `outputs` asks for them, and the DSL text of every
/// root the doc comments show: from the derivation text's printing walk when there is
/// one (the quantities do not change after it: what follows adds nodes to the pool only).
fn doc_texts(d: &mut Derivation, outputs: Outputs) -> (Option<TokenStream>, FxHashMap<Id, String>) {
    let shown = documented_roots(d);
    let (texts, shown_texts) = if outputs.derivation {
        let (texts, shown_texts) = derivation_texts(d, &shown);
        (Some(texts), shown_texts)
    } else {
        (None, d.pool.display_all(&shown))
    };
    (texts, shown.iter().copied().zip(shown_texts).collect())
}

/// The code evaluates sin/cos of sums of two coordinates through the sines and cosines of
/// the coordinates themselves (shared by CSE); the text keeps cos(a - b). The rewritten
/// form of each root of the code that changes.
fn code_forms(d: &mut Derivation, outputs: Outputs) -> FxHashMap<Id, Id> {
    let mut for_code = FxHashMap::default();
    for e in with_angle_sums(&d.pool, &d.code_roots(outputs)) {
        let expanded = d.pool.expand_trig_arguments(e);
        if expanded != e {
            for_code.insert(e, expanded);
        }
    }
    for_code
}

/// The switching functions, the tables' anchored switches and the stop times of tables
/// of time, as the mechanics found them, and the switches' gradients (with the
/// sensitivities).
type Stops<'a> = (&'a [Id], &'a [TableSwitch], &'a [TimeTable], &'a [Id]);

/// Every method of the trait impl, in the trait's order; `head` the head's methods,
/// `tangents` the state rate over tangents.
fn trait_methods(
    emitter: &Emitter<'_>,
    (outputs, generic_taylor): (Outputs, bool),
    (switches, table_switches, time_tables, gradients): Stops<'_>,
    (head, tangents): (TokenStream, TokenStream),
) -> [TokenStream; 26] {
    let (d, target) = (emitter.d, emitter.target);
    [
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
        optional(outputs.jacobian || outputs.sensitivities, || {
            emitter.jacobian()
        }),
        optional(outputs.sensitivities, || {
            emitter.parameter_jacobian(time_tables)
        }),
        tangents,
        emitter.switching_functions(switches, table_switches, gradients),
        optional(outputs.taylor, || {
            // With lanes or tangents, the per-order function is shared with their methods.
            taylor::taylor_method(d, &target.runtime, &target.name, generic_taylor)
        }),
        head,
        emitter.flow_rates(),
        emitter.singular_attitude_distance(),
        emitter.stop_times(time_tables),
        emitter.sample(),
    ]
}

/// `impl VariableMassSystem for Name` with `methods`; with the tables' statics and the
/// inputs' trait alias beside it, in a block of their own, when the model has any.
fn trait_impl(
    d: &Derivation,
    target: &Target,
    methods: [TokenStream; 26],
    statics: Option<TokenStream>,
) -> TokenStream {
    let (name, runtime) = (&target.name, &target.runtime);
    let sizes = Sizes::of(d);
    let (n_lit, s_lit) = (sizes.coordinates_literal(), sizes.state_literal());
    let coordinates = d.coordinates.iter().map(|c| c.name.as_str());
    let masses = d.masses.iter().map(|m| m.name.as_str());
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
    quote!(#inputs_trait #trait_impl)
}

/// The inherent items: `SOURCE`, the derivation's texts, `PARAMETERS` (with the units
/// line in its doc) and the tables' constructors.
fn inherent_items(
    d: &Derivation,
    source: &str,
    texts: Option<TokenStream>,
    constructors: TokenStream,
) -> TokenStream {
    let parameters = d.parameters.iter().map(|(p, _)| p.as_str());
    let units_doc = d.units_line().map(|line| {
        let line = format!("Units: {line}.");
        quote!(#[doc = ""] #[doc = #line])
    });
    quote! {
        /// The system in the DSL, as written.
        pub const SOURCE: &'static str = #source;
        #texts
        /// The parameters (fields) the equations use, in order.
        #units_doc
        pub const PARAMETERS: &'static [&'static str] = &[#(#parameters),*];
        #constructors
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

/// The velocity-form roots of every quantity of the registry that `d` holds, in
/// [`Quantity::ALL`] order, plus q̇ in closed form: what the doc comments show.
fn documented_roots(d: &Derivation) -> Vec<Id> {
    let mut roots: Vec<Id> = Quantity::ALL.iter().flat_map(|q| d.quantity(*q)).collect();
    roots.extend(d.hamiltonian);
    roots.extend(d.closed_laws.iter().flatten());
    if let VelocitySolve::Symbolic(v) = &d.velocities {
        roots.extend(v);
    }
    roots
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
