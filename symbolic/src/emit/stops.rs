//! Stop times: the sample grids of the sampled inputs (and the `sample` method that
//! replaces their held values there, docs/inputs.md#sampled-inputs) and the knots of tables
//! of t as stop times (docs/tables.md#knots-are-switches): every table
//! call whose argument is affine in t, a·t + b with a and b made of parameters only, gives
//! `next_stop_time`, so the runs land on each knot and restart there instead of stepping
//! across the kink (twice, just before and on it, where a derivative order the code reads
//! jumps there).

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use super::system::{Emitter, Input};
use super::tables::orders_read;
use crate::expr::Id;
use crate::mechanics::{ModelInput, TimeTable};

impl Emitter<'_> {
    /// `next_stop_time`: the earliest next knot time of every table of t and the next
    /// sample time k·T of every sampled input (nothing without either: the trait's
    /// default, no stop times).
    pub(crate) fn stop_times(&self, tables: &[TimeTable]) -> TokenStream {
        let periods: Vec<f64> = self.d.inputs.iter().filter_map(|i| i.every).collect();
        if tables.is_empty() && periods.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let roots: Vec<Id> = tables.iter().flat_map(|t| [t.slope, t.offset]).collect();
        // Per table of t, the orders the code reads, 0 to the highest: where one of them
        // jumps at a knot, the knot has two stop times (`next_knot_time_read`).
        let statics: Vec<TokenStream> = (tables.iter())
            .map(|t| orders_read(&self.d.pool, t.table, t.order))
            .collect();
        let body = self.body(Input::Configuration, &roots, |outs| {
            let slopes = outs.iter().step_by(2);
            let offsets = outs.iter().skip(1).step_by(2);
            quote! {
                let mut next = f64::INFINITY;
                #(next = next.min(#runtime::table::next_knot_time_read(#statics, #slopes, #offsets, after));)*
                #(next = next.min(#runtime::input::next_sample_time(#periods, after));)*
                if next < f64::INFINITY {
                    ::core::option::Option::Some(next)
                } else {
                    ::core::option::Option::None
                }
            }
        });
        quote! {
            /// The next knot of a table of t or sample of a held input after `after`
            /// (docs/tables.md#knots-are-switches, docs/inputs.md#sampled-inputs).
            fn next_stop_time(&self, after: f64) -> ::core::option::Option<f64> {
                #body
            }
        }
    }

    /// `sample`: each sampled input that the `which` asked for takes (all at a run's start,
    /// else those whose grid holds t), its value at `(t, state)`, the user's method called
    /// at its declared arguments, written into its held entry
    /// (docs/inputs.md#sampled-inputs). Nothing without sampled inputs (the trait's
    /// default).
    pub(crate) fn sample(&self) -> TokenStream {
        let sampled: Vec<&ModelInput> = self.d.inputs.iter().filter(|i| i.held.is_some()).collect();
        if sampled.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let sizes = self.sizes();
        let (s, first, n) = (sizes.state_literal(), sizes.first_held(), sizes.coordinates);
        let alias = Ident::new(super::inputs::ALIAS, Span::call_site());
        let coordinate = |name: &str| self.d.coordinates.iter().position(|c| c.name == name);
        let writes = sampled.iter().enumerate().map(|(j, input)| {
            let method = Ident::new(&input.name, Span::call_site());
            let arguments = input.arguments.iter().map(|a| match a.strip_suffix('\'') {
                Some(name) => {
                    let slot = Literal::usize_unsuffixed(n + coordinate(name).unwrap_or(0));
                    quote!(__velocity_state[#slot])
                }
                None => match coordinate(a) {
                    Some(i) => {
                        let slot = Literal::usize_unsuffixed(i);
                        quote!(__velocity_state[#slot])
                    }
                    None => quote!(t),
                },
            });
            let slot = Literal::usize_unsuffixed(first + j);
            let index = Literal::usize_unsuffixed(j);
            let name = &input.name;
            let value = quote!(#alias::#method(self, #(#arguments),*));
            quote!(if __due[#index] {
                state[#slot] = #runtime::input::checked_sample(#name, #value)?;
            })
        });
        let periods = sampled.iter().map(|i| i.every.unwrap_or(f64::NAN));
        let needs_velocities = sampled
            .iter()
            .any(|i| i.arguments.iter().any(|a| a.ends_with('\'')));
        let velocity_state = if needs_velocities {
            quote!(let __velocity_state = #runtime::VariableMassSystem::velocity_state(self, t, state)?;)
        } else {
            quote!(let __velocity_state = *state;)
        };
        quote! {
            /// Samples the held inputs `which` takes at `(t, state)` (each on its own grid):
            /// each calls its method of the inputs' trait at its declared arguments
            /// (docs/inputs.md#sampled-inputs).
            fn sample(
                &self,
                t: f64,
                state: &mut #runtime::nalgebra::SVector<f64, #s>,
                which: #runtime::input::Sampling,
            ) -> ::core::result::Result<(), #runtime::SystemError> {
                let __due = [#(which.takes(#periods, t)),*];
                if !__due.contains(&true) {
                    return Ok(());
                }
                #velocity_state
                #(#writes)*
                Ok(())
            }
        }
    }
}
