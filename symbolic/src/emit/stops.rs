//! Knots of tables of t as stop times (docs/tables.md#knots-are-switches): every table
//! call whose argument is affine in t, a·t + b with a and b made of parameters only, gives
//! `next_stop_time`, so the runs land on each knot and restart there instead of stepping
//! across the kink.

use proc_macro2::TokenStream;
use quote::quote;

use super::system::{Emitter, Input};
use super::tables::reference;
use crate::expr::Id;
use crate::mechanics::TimeTable;

impl Emitter<'_> {
    /// `next_stop_time`: the earliest next knot time of every table of t (nothing without
    /// one: the trait's default, no stop times).
    pub(crate) fn stop_times(&self, tables: &[TimeTable]) -> TokenStream {
        if tables.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let roots: Vec<Id> = tables.iter().flat_map(|t| [t.slope, t.offset]).collect();
        let statics: Vec<TokenStream> = tables
            .iter()
            .map(|t| super::expression::tokens(&reference(&self.d.pool, t.table, 0)))
            .collect();
        let body = self.body(Input::Configuration, &roots, |outs| {
            let slopes = outs.iter().step_by(2);
            let offsets = outs.iter().skip(1).step_by(2);
            quote! {
                let mut next = f64::INFINITY;
                #(next = next.min(#runtime::table::next_knot_time(&#statics, #slopes, #offsets, after));)*
                if next < f64::INFINITY {
                    ::core::option::Option::Some(next)
                } else {
                    ::core::option::Option::None
                }
            }
        });
        quote! {
            /// The next knot of a table of t after `after` (docs/tables.md#knots-are-switches).
            fn next_stop_time(&self, after: f64) -> ::core::option::Option<f64> {
                #body
            }
        }
    }
}
