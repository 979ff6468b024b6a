//! The switching functions in generated code (docs/mechanics.md#switches): the arguments of
//! `sign` and `abs` and the gaps of `min` and `max`, then one anchored switch per call of a
//! table of the state (docs/tables.md#knots-are-switches), whose anchor is the knot
//! bracket of the call's argument and whose g is the distance to the bracket's nearer end.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::signature::Method;
use super::system::{count_and_names, method_item, Emitter, Input};
use super::tables::orders_read;
use crate::expr::Id;
use crate::mechanics::TableSwitch;

impl Emitter<'_> {
    /// `switch_count`, `switch_name` and `switching_functions(t, velocity_state, values)`,
    /// and with tables of the state `switch_anchors` and `anchored_switching_functions`;
    /// with the sensitivities ([`gradients`] non-empty) `switch_gradient`. Nothing when
    /// there are no switches (the trait's defaults).
    pub(crate) fn switching_functions(
        &self,
        switches: &[Id],
        tables: &[TableSwitch],
        gradients: &[Id],
    ) -> TokenStream {
        if switches.is_empty() && tables.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let mut names: Vec<String> = switches.iter().map(|g| self.display(*g)).collect();
        names.extend(tables.iter().map(|s| {
            let table = self.d.pool.table_name(s.table);
            format!("the knots of {table}({})", self.display(s.argument))
        }));
        let docs = self.docs(
            "The switching functions g: the state rate jumps or kinks where one changes sign.",
            names
                .iter()
                .enumerate()
                .map(|(i, name)| format!("g_{i} = {name}")),
        );
        let m = switches.len();
        // Per switch, the orders read, 0 to the highest (`knot_bracket_read`).
        let statics: Vec<TokenStream> = (tables.iter())
            .map(|s| orders_read(&self.d.pool, s.table, s.order))
            .collect();
        let table_slots: Vec<Literal> = (m..m + tables.len())
            .map(Literal::usize_unsuffixed)
            .collect();
        let mut roots = switches.to_vec();
        roots.extend(tables.iter().map(|s| s.argument));
        let plain = self.body(Input::VelocityState, &roots, |outs| {
            let (gs, xs) = outs.split_at(m);
            let indices = (0..m).map(Literal::usize_unsuffixed);
            quote! {
                #(values[#indices] = #gs;)*
                #({
                    let __x = #xs;
                    let __bracket = #runtime::table::knot_bracket_read(#statics, __x);
                    values[#table_slots] = #runtime::table::knot_gap_read(#statics, __x, __bracket);
                })*
            }
        });
        let anchored = self.anchored(switches, tables, &statics, &table_slots);
        let mut code = count_and_names("switch", switches.len() + tables.len(), &names);
        let signature = self.signature(Method::SwitchingFunctions);
        code.extend(method_item(docs, signature, plain));
        code.extend(anchored);
        code.extend(self.switch_gradient(gradients, switches.len() + tables.len()));
        code
    }

    /// `has_switch_gradients` and `switch_gradient(index, t, velocity_state, out)`: the
    /// gradients of the `count` switches, [g_t, g_q, g_q̇, g_m_s, g_θ] each, one after the
    /// other in `gradients`; nothing without them.
    fn switch_gradient(&self, gradients: &[Id], count: usize) -> TokenStream {
        if gradients.is_empty() || count == 0 {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let s = self.sizes().state_literal();
        let width = Literal::usize_unsuffixed(gradients.len() / count);
        let count = Literal::usize_unsuffixed(count);
        let body = self.body(Input::VelocityState, gradients, |outs| {
            quote! {
                if index >= #count {
                    return ::core::result::Result::Ok(false);
                }
                let __all = [#(#outs),*];
                let __own = &__all[index * #width..(index + 1) * #width];
                for (slot, value) in out.iter_mut().zip(__own) {
                    *slot = *value;
                }
                ::core::result::Result::Ok(true)
            }
        });
        let docs = self.docs(
            "The switches' gradients [g_t, g_q, g_q̇, g_m_s, g_θ] (an anchored switch's: its \
             argument's), for the sensitivities' jumps.",
            Vec::<String>::new(),
        );
        let signature = quote! {
            fn switch_gradient(
                &self,
                index: usize,
                t: f64,
                velocity_state: &#runtime::nalgebra::SVector<f64, #s>,
                out: &mut [f64],
            ) -> ::core::result::Result<bool, #runtime::SystemError>
        };
        let mut code = quote! {
            fn has_switch_gradients(&self) -> bool {
                true
            }
        };
        code.extend(method_item(docs, signature, body));
        code
    }

    /// `switch_anchors` and `anchored_switching_functions` for the switches of tables of
    /// the state (nothing without them: the trait's defaults).
    fn anchored(
        &self,
        switches: &[Id],
        tables: &[TableSwitch],
        statics: &[TokenStream],
        slots: &[Literal],
    ) -> TokenStream {
        if tables.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let m = switches.len();
        let arguments: Vec<Id> = tables.iter().map(|s| s.argument).collect();
        let anchors = self.body(
            Input::VelocityState,
            &arguments,
            |xs| quote!(#(anchors[#slots] = #runtime::table::knot_bracket_read(#statics, #xs);)*),
        );
        let mut roots = switches.to_vec();
        roots.extend(&arguments);
        let values = self.body(Input::VelocityState, &roots, |outs| {
            let (gs, xs) = outs.split_at(m);
            let indices = (0..m).map(Literal::usize_unsuffixed);
            quote! {
                #(values[#indices] = #gs;)*
                #(values[#slots] = #runtime::table::knot_gap_read(#statics, #xs, anchors[#slots]);)*
            }
        });
        let methods = [
            (Method::SwitchAnchors, anchors),
            (Method::AnchoredSwitchingFunctions, values),
        ];
        let mut code = TokenStream::new();
        for (method, body) in methods {
            code.extend(method_item(
                TokenStream::new(),
                self.signature(method),
                body,
            ));
        }
        code
    }
}

/// The gradients of the switching functions and of the tables of the state's arguments
/// (`mechanics::gradient`: [g_t, g_q, g_q̇, g_m_s, g_θ] each, total derivatives with the
/// mass laws followed), one after the other: what `switch_gradient` emits.
pub(crate) fn gradients(
    d: &mut crate::mechanics::Derivation,
    switches: &[Id],
    tables: &[TableSwitch],
) -> Vec<Id> {
    let roots: Vec<Id> = (switches.iter().copied())
        .chain(tables.iter().map(|s| s.argument))
        .collect();
    (roots.into_iter())
        .flat_map(|g| crate::mechanics::gradient(d, g))
        .collect()
}
