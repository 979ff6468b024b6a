//! The switching functions in generated code (docs/mechanics.md#switches): the arguments of
//! `sign` and `abs` and the gaps of `min` and `max`, then one anchored switch per call of a
//! table of the state (docs/tables.md#knots-are-switches), whose anchor is the knot
//! bracket of the call's argument and whose g is the distance to the bracket's nearer end.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::system::{count_and_names, Emitter, Input};
use super::tables::reference;
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
        let (_, s_lit, _, _) = self.sizes();
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
        let statics: Vec<TokenStream> = tables
            .iter()
            .map(|s| super::expression::tokens(&reference(&self.d.pool, s.table, 0)))
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
                    let __bracket = #runtime::table::knot_bracket(&#statics, __x);
                    values[#table_slots] = #runtime::table::knot_gap(&#statics, __x, __bracket);
                })*
            }
        });
        let anchored = self.anchored(switches, tables, &statics, &table_slots);
        let count_and_names = count_and_names("switch", switches.len() + tables.len(), &names);
        quote! {
            #count_and_names
            #docs
            #[inline]
            fn switching_functions(
                &self,
                t: f64,
                velocity_state: &#runtime::nalgebra::SVector<f64, #s_lit>,
                values: &mut [f64],
            ) {
                #plain
            }
            #anchored
        }
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
        let (_, s_lit, _, _) = self.sizes();
        let m = switches.len();
        let arguments: Vec<Id> = tables.iter().map(|s| s.argument).collect();
        let anchors = self.body(
            Input::VelocityState,
            &arguments,
            |xs| quote!(#(anchors[#slots] = #runtime::table::knot_bracket(&#statics, #xs);)*),
        );
        let mut roots = switches.to_vec();
        roots.extend(&arguments);
        let values = self.body(Input::VelocityState, &roots, |outs| {
            let (gs, xs) = outs.split_at(m);
            let indices = (0..m).map(Literal::usize_unsuffixed);
            quote! {
                #(values[#indices] = #gs;)*
                #(values[#slots] = #runtime::table::knot_gap(&#statics, #xs, anchors[#slots]);)*
            }
        });
        quote! {
            #[inline]
            fn switch_anchors(
                &self,
                t: f64,
                velocity_state: &#runtime::nalgebra::SVector<f64, #s_lit>,
                anchors: &mut [f64],
            ) {
                #anchors
            }
            #[inline]
            fn anchored_switching_functions(
                &self,
                t: f64,
                velocity_state: &#runtime::nalgebra::SVector<f64, #s_lit>,
                anchors: &[f64],
                values: &mut [f64],
            ) {
                #values
            }
        }
    }
}
