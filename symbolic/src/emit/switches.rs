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
    /// and with tables of the state `switch_anchors` and `anchored_switching_functions`.
    /// Nothing when there are no switches (the trait's defaults).
    pub(crate) fn switching_functions(
        &self,
        switches: &[Id],
        tables: &[TableSwitch],
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
