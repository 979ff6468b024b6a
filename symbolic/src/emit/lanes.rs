//! `emit = [..., "lanes"]`: the state rate over SIMD lanes (`varmass_core::lanes`), for
//! ensembles that integrate W members at once (`run_lanes`).
//!
//! The body is the scalar `state_rate`'s, printed by the same walk: its text — `f64`
//! literals, `+ - * /`, `.sqrt()`, `.powi(n)`, `.ln()` — compiles unchanged over
//! `Lanes<W>`, whose operators and methods apply the scalar operation lane by lane, so each
//! lane is bit-identical to the scalar state rate. The parameters become a companion
//! struct `__<Name>Lanes<W>` whose fields are lanes, so that the prologue's
//! `let mu = self.mu;` binds a lane value. Models with what has no lane form yet — tables,
//! inputs, `sign` (its own runtime function), a numeric solve of M q̇ = p − b — get a
//! compile error naming the reason instead.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::system::{Emitter, Input};
use crate::expr::{Func, Id, Node};
use crate::mechanics::VelocitySolve;

impl Emitter<'_> {
    /// The roots of `state_rate`: q̇, the true ṗ, the state masses' rates.
    pub(super) fn state_rate_roots(&self) -> Vec<Id> {
        let k = self.sizes().state_masses;
        let mut roots = self.velocity_ids.clone();
        roots.extend(&self.d.momentum_rate);
        roots.extend(self.d.mass_rates.iter().take(k));
        roots
    }

    /// Whether the state rate (and so its Taylor recurrences) has a lane form.
    pub(super) fn has_lanes(&self) -> bool {
        self.without_lanes(&self.state_rate_roots()).is_none()
    }

    /// Why the state rate has no lane form, if it has none. The Taylor recurrences have one
    /// exactly when the state rate has: their arithmetic is generic over the coefficient,
    /// a function's value and the selection rules (abs, min, max) go lane by lane, and what
    /// the state rate refuses (tables, inputs, `sign`, a numeric solve) they refuse too.
    fn without_lanes(&self, roots: &[Id]) -> Option<&'static str> {
        let d = self.d;
        if d.pool.table_count() > 0 {
            return Some("tables");
        }
        if !d.inputs.is_empty() {
            return Some("inputs");
        }
        if matches!(d.velocities, VelocitySolve::Numeric) {
            return Some("a numeric solve of M q' = p - b (coupled velocities)");
        }
        let uses_sign = d
            .pool
            .reachable(roots, true)
            .into_iter()
            .any(|id| matches!(d.pool.node(id), Node::Call(Func::Sign, _)));
        uses_sign.then_some("`sign` in the state rate")
    }
}

/// The compile error of a model whose state rate has no lane form, for `reason`.
fn refused(reason: &str, taylor: bool) -> TokenStream {
    let what = match taylor {
        true => "emit \"lanes\" (with \"taylor\": Taylor's method in lanes)",
        false => "emit \"lanes\"",
    };
    let message = format!(
        "varmass: {what} is not available for a model with {reason}; \
         run its ensemble on the scalar path"
    );
    quote!(::core::compile_error!(#message);)
}

/// The companion struct of lane parameters and the `LaneSystem` impl for `emitter`'s
/// system (see the module docs); with `taylor`, the Taylor recurrences over lanes too
/// (`taylor_coefficients_lanes`, for `run_lanes` with a `TaylorControl`).
pub(crate) fn lanes_impl(emitter: &Emitter<'_>, taylor: bool) -> TokenStream {
    let roots = emitter.state_rate_roots();
    if let Some(reason) = emitter.without_lanes(&roots) {
        return refused(reason, taylor);
    }
    let (taylor_helper, taylor_method) = match taylor {
        true => {
            super::taylor::taylor_lanes(emitter.d, &emitter.target.runtime, &emitter.target.name)
        }
        false => Default::default(),
    };
    let runtime = &emitter.target.runtime;
    let name = &emitter.target.name;
    let lanes_name = format_ident!("__{}Lanes", name);
    let sizes = emitter.sizes();
    let (n_lit, s_lit) = (sizes.coordinates_literal(), sizes.state_literal());
    let fields: Vec<Ident> = emitter
        .d
        .parameters
        .iter()
        .map(|(p, _)| Ident::new(p, Span::call_site()))
        .collect();
    let lane = quote!(#runtime::lanes::Lanes<W>);
    let body = emitter.body(Input::State, &roots, |outs| {
        let outs = outs
            .into_iter()
            .map(|o| quote!(#runtime::lanes::Lanes::<W>::from(#o)));
        quote!([#(#outs),*])
    });
    let doc = format!("The parameters of W `{name}`s in lanes (`emit = [..., \"lanes\"]`).");
    quote! {
        #[doc = #doc]
        #[doc(hidden)]
        #[derive(Clone, Copy, Debug)]
        pub struct #lanes_name<const W: usize> {
            #(#fields: #lane,)*
        }

        #[allow(unused_variables, non_snake_case, clippy::all)]
        impl<const W: usize> #lanes_name<W> {
            /// `state_rate` over lanes: its operations, lane by lane.
            #[inline]
            fn state_rate(&self, t: #lane, state: &[#lane; #s_lit]) -> [#lane; #s_lit] {
                #body
            }
        }

        #[allow(unused_variables, clippy::all)]
        impl<const W: usize> #runtime::lanes::LaneSystem<#n_lit, #s_lit, W> for #name {
            type Parameters = #lanes_name<W>;

            fn splat(system: &Self) -> Self::Parameters {
                #lanes_name {
                    #(#fields: #runtime::lanes::Lanes::splat(system.#fields),)*
                }
            }

            fn set_lane(parameters: &mut Self::Parameters, lane: usize, system: &Self) {
                #(parameters.#fields.0[lane] = system.#fields;)*
            }

            #[inline]
            fn state_rate_lanes(
                parameters: &Self::Parameters,
                t: #lane,
                state: &[#lane; #s_lit],
            ) -> [#lane; #s_lit] {
                parameters.state_rate(t, state)
            }

            #taylor_method
        }

        #taylor_helper
    }
}

#[cfg(test)]
mod tests {
    use proc_macro2::{Ident, Span};
    use quote::quote;

    use crate::emit::{emit_system_for, Target};
    use crate::mechanics::{Outputs, Parameters};
    use crate::pipeline::derive_source;

    fn emitted(source: &str) -> String {
        let mut d = derive_source(source, Parameters::Inferred).expect("the model derives");
        let target = Target {
            name: Ident::new("Oscillator", Span::call_site()),
            runtime: quote!(::rt),
        };
        let outputs = Outputs {
            lanes: true,
            ..Outputs::MINIMAL
        };
        emit_system_for(&mut d, source, &target, outputs).to_string()
    }

    /// A smooth rate gets the lane impl; a rate calling `sign` (its runtime function has no
    /// lane form) gets a compile error saying so, and no impl.
    #[test]
    fn a_rate_with_sign_is_refused_and_a_smooth_one_emitted() {
        let model = "coordinates x\nmass m = m0\nbody b: mass m, position [x]\npotential k*x^2/2\n";
        let smooth = emitted(model);
        assert!(smooth.contains("LaneSystem") && smooth.contains("__OscillatorLanes"));
        assert!(!smooth.contains("compile_error"));
        let with_sign = emitted(&format!("{model}force b: [-f*sign(x')]\n"));
        assert!(
            with_sign.contains("`sign` in the state rate"),
            "{with_sign}"
        );
        assert!(!with_sign.contains("LaneSystem"));
    }
}
