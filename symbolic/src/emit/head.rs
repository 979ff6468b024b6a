//! `emit = [..., "taylor", "head"]`: the state rate over double-double dual numbers
//! (`varmass_core::dd::Dual`), the `taylor_head` method the Taylor stepper's head
//! (`Taylor::with_head`) evaluates for c₁ and c₂ in double-double.
//!
//! As for lanes, the body is the scalar `state_rate`'s, printed by the same walk: its text
//! (`f64` literals and parameters, `+ - * /`, `.sqrt()`, `.cbrt()`, `.powi(n)`) compiles
//! unchanged over `Dual`, whose operators take an `f64` or a `Dd` on either side. The
//! parameters become a companion struct `__<Name>Head` of double-double fields, so that
//! `let m1 = self.m1;` binds a `Dd` and what depends on the parameters alone (1/m, k m) is
//! not rounded to double: a rounded 1/m in θ̇ = p_θ/(m r²) but not in m r θ̇² makes the
//! rates of no Hamiltonian: Kepler then ended 3.7e-14 off at tolerance 1e-15, against
//! 5.2e-16 with them in double-double. The literals stay `f64` (the model's constants as
//! the double path has them: 1/3 is fl(1/3) in both). The number type is the one the
//! stepper evaluates, not a type parameter: the literals come first in the printed text
//! (`2f64 * x`), and `f64: Mul<T>` cannot be implied by a trait bound on T.
//! Whatever has no double-double form yet — every function call (sin, exp, ln, abs, sign,
//! min, max, …), powers with other exponents, tables, inputs, a numeric solve of
//! M q̇ = p − b — gets a compile error naming it, never a silent evaluation in double.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use super::system::{Emitter, Input};
use crate::expr::{Id, Node};
use crate::mechanics::VelocitySolve;

impl Emitter<'_> {
    /// Why the state rate has no double-double form, if it has none.
    fn without_head(&self, roots: &[Id]) -> Option<String> {
        let d = self.d;
        if d.pool.table_count() > 0 {
            return Some("tables".to_string());
        }
        if !d.inputs.is_empty() {
            return Some("inputs".to_string());
        }
        let mut scanned = roots.to_vec();
        match &d.velocities {
            VelocitySolve::Symbolic(v) => scanned.extend(v),
            VelocitySolve::Numeric => {
                return Some("a numeric solve of M q' = p - b (coupled velocities)".to_string())
            }
        }
        scanned.extend(d.closed_laws.iter().flatten());
        d.pool
            .reachable(&scanned, true)
            .into_iter()
            .find_map(|id| match d.pool.node(id) {
                Node::Call(func, _) => Some(format!("`{}` in the state rate", func.name())),
                Node::Pow(_, e) => match d.pool.node(*e) {
                    Node::Num(r) if r.denom() == 1 && i32::try_from(r.numer()).is_ok() => None,
                    Node::Num(r) if r.numer().abs() == 1 && matches!(r.denom(), 2 | 3) => None,
                    Node::Num(r) => Some(format!(
                        "a power with exponent {}/{} in the state rate",
                        r.numer(),
                        r.denom()
                    )),
                    _ => Some("a power with a non-constant exponent in the state rate".into()),
                },
                _ => None,
            })
    }
}

/// What `emit = [..., "head"]` adds for `emitter`'s system (see the module docs): the
/// `taylor_head` method (`.0`, inside the trait impl) and the companion struct of the
/// parameters in double-double it evaluates on (`.1`, beside the impl); or a compile error
/// naming what has no double-double form. `taylor` says whether the Taylor recurrences are
/// emitted too: the head is their complement and is refused without them.
pub(crate) fn head_items(emitter: &Emitter<'_>, taylor: bool) -> (TokenStream, TokenStream) {
    let refused = |message: &str| {
        (
            quote!(::core::compile_error!(#message);),
            TokenStream::new(),
        )
    };
    if !taylor {
        return refused("varmass: emit \"head\" serves the Taylor stepper: emit \"taylor\" too");
    }
    let roots = emitter.state_rate_roots();
    if let Some(reason) = emitter.without_head(&roots) {
        return refused(&format!(
            "varmass: emit \"head\" (the Taylor stepper's double-double head) is not \
             available for a model with {reason}; leave \"head\" out (the stepper then \
             computes every coefficient in double)"
        ));
    }
    let runtime = &emitter.target.runtime;
    let name = &emitter.target.name;
    let head_name = format_ident!("__{}Head", name);
    let s_lit = emitter.sizes().state_literal();
    let (dual, dd) = (quote!(#runtime::dd::Dual), quote!(#runtime::dd::Dd));
    let fields: Vec<Ident> = emitter
        .d
        .parameters
        .iter()
        .map(|(p, _)| Ident::new(p, Span::call_site()))
        .collect();
    let body = |number: &TokenStream| {
        emitter.body(Input::State, &roots, |outs| {
            let outs = outs.into_iter().map(|o| quote!(#number::from(#o)));
            quote!([#(#outs),*])
        })
    };
    let (dual_body, dd_body) = (body(&dual), body(&dd));
    let doc = format!("The parameters of a `{name}` in double-double (`emit = [..., \"head\"]`).");
    let method = head_methods(&head_name, &fields, (&dual, &dd), &s_lit);
    let items = quote! {
        #[doc = #doc]
        #[doc(hidden)]
        #[derive(Clone, Copy, Debug)]
        pub struct #head_name {
            #(#fields: #dd,)*
        }

        #[allow(unused_variables, non_snake_case, clippy::all)]
        impl #head_name {
            /// `state_rate` over dual numbers, the parameters in double-double (so that
            /// what depends on them alone, such as 1/m, is not rounded to double).
            #[inline]
            fn state_rate(&self, t: #dual, state: &[#dual; #s_lit]) -> [#dual; #s_lit] {
                #dual_body
            }

            /// The same in double-double: the rate alone, for c₁.
            #[inline]
            fn rate(&self, t: #dd, state: &[#dd; #s_lit]) -> [#dd; #s_lit] {
                #dd_body
            }
        }
    };
    (method, items)
}

/// `taylor_head` and `taylor_head_rate`, inside the trait impl: each fills the companion
/// struct `head_name` (its `fields`, the parameters, in double-double) and evaluates on it.
fn head_methods(
    head_name: &Ident,
    fields: &[Ident],
    (dual, dd): (&TokenStream, &TokenStream),
    s_lit: &Literal,
) -> TokenStream {
    quote! {
        /// The state rate over double-double dual numbers (`emit = [..., "head"]`).
        #[inline]
        fn taylor_head(
            &self,
            t: #dual,
            state: &[#dual; #s_lit],
        ) -> ::core::option::Option<[#dual; #s_lit]> {
            let parameters = #head_name {
                #(#fields: #dd::from(self.#fields),)*
            };
            ::core::option::Option::Some(parameters.state_rate(t, state))
        }

        /// The state rate in double-double (`emit = [..., "head"]`).
        #[inline]
        fn taylor_head_rate(
            &self,
            t: f64,
            state: &[#dd; #s_lit],
        ) -> ::core::option::Option<[#dd; #s_lit]> {
            let parameters = #head_name {
                #(#fields: #dd::from(self.#fields),)*
            };
            ::core::option::Option::Some(parameters.rate(#dd::from(t), state))
        }
    }
}

#[cfg(test)]
mod tests {
    use proc_macro2::{Ident, Span};
    use quote::quote;

    use crate::emit::{emit_system_for, Target};
    use crate::mechanics::{Outputs, Parameters};
    use crate::pipeline::derive_source;

    fn emitted(source: &str, taylor: bool) -> String {
        let mut d = derive_source(source, Parameters::Inferred).expect("the model derives");
        let target = Target {
            name: Ident::new("Model", Span::call_site()),
            runtime: quote!(::rt),
        };
        let outputs = Outputs {
            taylor,
            head: true,
            ..Outputs::MINIMAL
        };
        emit_system_for(&mut d, source, &target, outputs).to_string()
    }

    /// Kepler gets the head with its parameters in double-double; a rate calling `cos`
    /// gets a compile error naming it and no head; "head" without "taylor" is refused.
    #[test]
    fn a_rate_with_cos_is_refused_and_kepler_emitted() {
        let kepler = "coordinates r, th\nmass m = m1\n\
                      body planet: mass m, position [r*cos(th), r*sin(th)]\npotential -k*m/r\n";
        let text = emitted(kepler, true);
        assert!(text.contains("fn taylor_head") && text.contains("__ModelHead"));
        assert!(text.contains("m1 : :: rt :: dd :: Dd"), "{text}");
        assert!(!text.contains("compile_error"));
        let pendulum =
            "coordinates th\nmass m = m1\nbody b: mass m, position [l*sin(th), -l*cos(th)]\n\
                        potential -m*g*l*cos(th)\n";
        let refused = emitted(pendulum, true);
        assert!(refused.contains("`sin` in the state rate"), "{refused}");
        assert!(!refused.contains("fn taylor_head"));
        let alone = emitted(kepler, false);
        assert!(alone.contains("emit \\\"taylor\\\" too"), "{alone}");
    }
}
