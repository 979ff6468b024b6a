//! `emit = [..., "sensitivities"]`: the state rate over forward-mode tangents
//! (`varmass_core::tangent::Tangent<W>`), the `state_rate_tangents` method forward
//! sensitivities integrate with (`core::sensitivity`): f and W directional derivatives
//! J_y s + ∂f/∂θ e in one pass, no Jacobian formed.
//!
//! As for lanes and the head, the body is the scalar `state_rate`'s, printed by the same walk:
//! its text (`f64` literals, `+ - * /`, `.sqrt()`, `.powi(n)`, `.sin()`, the LDLᵀ's
//! `if !(d > floor)` guards) compiles unchanged over `Tangent<W>`, whose operators take an
//! `f64` on either side and whose comparisons read the value. The parameters become a
//! companion struct `__<Name>Tangents<W>` of tangents, seeded with 1 in the directions that
//! move them. A state rate with tables, inputs, `sign`, `abs`, `min` or `max`, or a `powf`
//! or `atan2` of a constant or of t alone (their functions take an `f64`) gets no tangent
//! form: the trait's default `None`, and the sensitivities go through the whole Jacobians
//! instead (or, with a switch, are refused).

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::system::{Emitter, Input};
use crate::expr::{Func, Id, Node};
use crate::mechanics::VelocitySolve;

impl Emitter<'_> {
    /// Whether the state rate has a tangent form: no tables, no inputs, no `sign`, `abs`,
    /// `min` or `max` (switches, which the sensitivities refuse anyway), no `powf` or
    /// `atan2` whose receiver is printed as an `f64` (a constant, a function of t alone, a
    /// law mass of t alone).
    fn has_tangents(&self, roots: &[Id]) -> bool {
        let d = self.d;
        if d.pool.table_count() > 0 || !d.inputs.is_empty() {
            return false;
        }
        let mut scanned = roots.to_vec();
        scanned.extend(d.mass_matrix.iter().flatten());
        scanned.extend(&d.momentum_offset);
        scanned.extend(d.closed_laws.iter().flatten());
        if let Some(rigid) = &d.rigid_velocities {
            scanned.extend(&rigid.velocities);
            scanned.extend(rigid.guards.iter().map(|(value, _)| *value));
        }
        // An argument with no symbol but t and the law masses of t alone (`mass m = 2 + t`,
        // bound to an f64) is printed as an f64, whose own `powf` and `atan2` take no
        // tangent.
        let mut floats = vec![d.time];
        for (mass, law) in d.masses.iter().zip(&d.closed_laws) {
            let of_time = |law: &Id| d.pool.free_symbols(*law).iter().all(|s| *s == d.time);
            if law.as_ref().is_some_and(of_time) {
                floats.push(mass.symbol);
            }
        }
        let plain = |e: &Id| d.pool.free_symbols(*e).iter().all(|s| floats.contains(s));
        let reachable = d.pool.reachable(&scanned, true);
        !reachable.into_iter().any(|id| match d.pool.node(id) {
            Node::Call(Func::Sign | Func::Abs | Func::Min | Func::Max, _) => true,
            Node::Call(Func::Atan2, args) => args.first().is_some_and(plain),
            Node::Pow(base, exponent) => d.pool.as_rational(*exponent).is_none() && plain(base),
            _ => false,
        })
    }
}

/// Whether the Taylor recurrences have a tangent form (`taylor_coefficients_tangents`):
/// the state rate has one and q̇ is in closed form (the numeric solve of M q̇ = p − b is
/// written for `f64` coefficients).
pub(crate) fn has_taylor_tangents(emitter: &Emitter<'_>) -> bool {
    let numeric = matches!(emitter.d.velocities, VelocitySolve::Numeric);
    !numeric && emitter.has_tangents(&emitter.state_rate_roots())
}

/// `state_rate_tangents` inside the trait impl, and the companion struct with the state
/// rate over tangents beside it; both empty without a tangent form. With `taylor` (the
/// Taylor recurrences have a tangent form, [`has_taylor_tangents`]) the trait gets
/// `taylor_coefficients_tangents` too, and with `helper` the generic per-order function
/// it calls (when the lanes do not emit it).
pub(crate) fn tangent_items(
    emitter: &Emitter<'_>,
    (taylor, helper): (bool, bool),
) -> (TokenStream, TokenStream) {
    let roots = emitter.state_rate_roots();
    if !emitter.has_tangents(&roots) {
        return Default::default();
    }
    let runtime = &emitter.target.runtime;
    let name = &emitter.target.name;
    let tangents_name = format_ident!("__{}Tangents", name);
    let s_lit = emitter.sizes().state_literal();
    let tangent = quote!(#runtime::tangent::Tangent<W>);
    let body = emitter.body(Input::State, &roots, |outs| {
        let outs = outs
            .into_iter()
            .map(|o| quote!(#runtime::tangent::Tangent::<W>::from(#o)));
        quote!(::core::result::Result::Ok([#(#outs),*]))
    });
    let method = quote! {
        /// The state rate over tangents (`emit = [..., "sensitivities"]`).
        #[inline]
        fn state_rate_tangents<const W: usize>(
            &self,
            t: f64,
            state: &[#tangent; #s_lit],
            seeds: &[::core::option::Option<usize>; W],
        ) -> ::core::option::Option<::core::result::Result<[#tangent; #s_lit], #runtime::SystemError>> {
            let parameters = #tangents_name::<W>::seeded(self, seeds);
            ::core::option::Option::Some(parameters.state_rate(t, state))
        }
    };
    let d = emitter.d;
    let taylor_method =
        taylor.then(|| super::taylor::taylor_tangents(d, runtime, (name, &tangents_name)));
    let taylor_helper = (taylor && helper).then(|| super::taylor::order_helper(d, runtime, name));
    let method = quote!(#method #taylor_method);
    let items = companion(emitter, &tangents_name, body);
    (method, quote!(#items #taylor_helper))
}

/// The companion struct `tangents` of the parameters as tangents: `seeded` from the system
/// and `state_rate` (whose `body` is the state rate printed over tangents).
fn companion(emitter: &Emitter<'_>, tangents: &Ident, body: TokenStream) -> TokenStream {
    let runtime = &emitter.target.runtime;
    let name = &emitter.target.name;
    let s_lit = emitter.sizes().state_literal();
    let fields: Vec<Ident> = (emitter.d.parameters.iter())
        .map(|(p, _)| Ident::new(p, Span::call_site()))
        .collect();
    let indices = 0..fields.len();
    let tangent = quote!(#runtime::tangent::Tangent<W>);
    let doc =
        format!("The parameters of a `{name}` as tangents (`emit = [..., \"sensitivities\"]`).");
    quote! {
        #[doc = #doc]
        #[doc(hidden)]
        #[derive(Clone, Copy, Debug)]
        pub struct #tangents<const W: usize> {
            #(#fields: #tangent,)*
        }

        #[allow(unused_variables, non_snake_case, clippy::all)]
        impl<const W: usize> #tangents<W> {
            /// The system's parameters as tangents, 1 in the directions `seeds` names.
            #[inline]
            fn seeded(system: &#name, seeds: &[::core::option::Option<usize>; W]) -> Self {
                let seeded = |j: usize, value: f64| {
                    let mut d = [0.0; W];
                    for (slot, seed) in d.iter_mut().zip(seeds) {
                        if *seed == ::core::option::Option::Some(j) {
                            *slot = 1.0;
                        }
                    }
                    #runtime::tangent::Tangent { v: value, d }
                };
                Self {
                    #(#fields: seeded(#indices, system.#fields),)*
                }
            }

            /// `state_rate` over tangents.
            #[inline]
            fn state_rate(
                &self,
                t: f64,
                state: &[#tangent; #s_lit],
            ) -> ::core::result::Result<[#tangent; #s_lit], #runtime::SystemError> {
                #body
            }
        }
    }
}
