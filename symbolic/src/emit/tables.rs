//! Tables in generated code (docs/tables.md#the-macro-data-embedded-at-compile-time): one
//! `static` per table and derivative order the pool holds, over the interpolant's
//! coefficients computed at compile time and printed with `{:?}` (which round-trips every
//! `f64`), so the generated code parses nothing and allocates nothing. A `= runtime`
//! table is the struct's field instead, with a constructor over the user's data.

use proc_macro2::TokenStream;
use quote::quote;

use super::expression::tokens;
use crate::expr::ExprPool;
use crate::mechanics::Derivation;
use varmass_table::Outside;

/// The static holding order `order` of table `table`.
pub(crate) fn static_name(table: u16, order: u8) -> String {
    format!("__VARMASS_TABLE_{table}_{order}")
}

/// How generated code names order `order` of table `table` (a `&Table` place): its static,
/// or for a `= runtime` table the struct's field, a `Tabulated` holding every order
/// (docs/tables.md#runtime-tables).
pub(crate) fn reference(pool: &ExprPool, table: u16, order: u8) -> String {
    if pool.is_runtime_table(table) {
        format!("(*self.{}.order({order}))", pool.table_name(table))
    } else {
        static_name(table, order)
    }
}

/// `&[&order 0, …, &order highest]` of `table`: the orders a knot reader
/// (`knot_bracket_read`, `next_knot_time_read`) looks at for the edges where one of them
/// jumps (docs/tables.md#knots-are-switches).
pub(crate) fn orders_read(pool: &ExprPool, table: u16, highest: u8) -> TokenStream {
    let orders = (0..=highest).map(|order| tokens(&reference(pool, table, order)));
    quote!(&[#(&#orders),*])
}

/// For each `= runtime` table, `pub fn tabulate_F(points) -> Tabulated`: the field's value
/// over the user's data, with the statement's interpolation and rule.
pub(crate) fn constructors(d: &Derivation, runtime: &TokenStream) -> TokenStream {
    let runtime = runtime.to_string();
    let mut text = String::new();
    for t in d.tables.iter().filter(|t| t.runtime) {
        let interpolation = format!("{:?}", t.interpolation);
        let outside = format!("{:?}", t.outside);
        text.push_str(&format!(
            "/// The value of the field `{name}` (`table {name}(..) = runtime`): the table \
             interpolating `points` as the model says ({interpolation}, outside \
             {outside}), with its derivative tables.\n\
             #[allow(non_snake_case)]\n\
             pub fn tabulate_{name}(points: &{runtime}::table::Points) -> {runtime}::table::Tabulated {{\n\
             {runtime}::table::Tabulated::new(points, {runtime}::table::Interpolation::{interpolation}, \
             {runtime}::table::Outside::{outside})\n}}\n",
            name = t.name,
        ));
    }
    tokens(&text)
}

/// Every table's statics (nothing for a system without tables).
pub(crate) fn statics(pool: &ExprPool, runtime: &TokenStream) -> TokenStream {
    let runtime = runtime.to_string();
    let mut text = String::new();
    for table in 0..pool.table_count() {
        let Ok(table) = u16::try_from(table) else {
            break;
        };
        if pool.is_runtime_table(table) {
            continue;
        }
        for order in 0..=u8::MAX {
            let Some(t) = pool.table(table, order) else {
                break;
            };
            let curve = t.curve();
            let outside = match t.outside() {
                Outside::Error => "Error",
                Outside::Zero => "Zero",
                Outside::Hold => "Hold",
            };
            text.push_str(&format!(
                "#[allow(dead_code)]\nstatic {}: {runtime}::table::Table = {runtime}::table::Table::from_piecewise(\
                 {runtime}::table::Piecewise::from_static(&[{}], &[{}], {}), {runtime}::table::Outside::{outside});\n",
                static_name(table, order),
                literals(curve.knots()),
                literals(curve.coefficients()),
                curve.degree(),
            ));
        }
    }
    tokens(&text)
}

/// `1.5f64, -2f64, …`: `{:?}` round-trips every finite `f64` (the data are checked finite).
fn literals(values: &[f64]) -> String {
    let all: Vec<String> = values.iter().map(|v| format!("{v:?}f64")).collect();
    all.join(", ")
}
