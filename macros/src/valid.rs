//! Checks on the struct and on the names the derivation brings into generated code, one
//! rule a function (after serde_derive's `check_*`).

use varmass_symbolic::mechanics::Derivation;
use varmass_symbolic::Diagnostic;

use crate::ctxt::Ctxt;

/// The names of the struct's parameter fields (every field but those of the `= runtime`
/// tables `tables`), after checking every rule below.
pub fn parameter_fields(cx: &Ctxt, item: &syn::ItemStruct, tables: &[String]) -> Vec<syn::Ident> {
    check_no_generics(cx, item);
    let fields = check_named_fields(cx, item);
    let is_table = |f: &syn::Field| {
        f.ident
            .as_ref()
            .is_some_and(|i| tables.contains(&i.to_string()))
    };
    check_table_fields(cx, item, &fields, tables);
    let parameters: Vec<&syn::Field> = fields.iter().filter(|f| !is_table(f)).collect();
    for field in &parameters {
        check_f64(cx, field);
    }
    parameters.iter().filter_map(|f| f.ident.clone()).collect()
}

/// Each `table F(..) = runtime` reads its data from the field `F` (docs/tables.md#runtime-tables).
fn check_table_fields(cx: &Ctxt, item: &syn::ItemStruct, fields: &[syn::Field], tables: &[String]) {
    for table in tables {
        let found = fields
            .iter()
            .any(|f| f.ident.as_ref().is_some_and(|i| i == table.as_str()));
        if !found {
            cx.error_spanned_by(
                &item.ident,
                format!(
                    "table `{table}` is `= runtime`: its data are the struct's field \
                     `{table}: varmass::core::table::Tabulated` (made by `Self::tabulate_{table}(&points)`)"
                ),
            );
        }
    }
}

/// Generated code reads each parameter as `self.name: f64`; a type parameter would leave
/// the equations' types open.
fn check_no_generics(cx: &Ctxt, item: &syn::ItemStruct) {
    if !item.generics.params.is_empty() || item.generics.where_clause.is_some() {
        cx.error_spanned_by(
            &item.generics,
            "a variable-mass system cannot be generic: its parameters are plain `f64` fields",
        );
    }
}

/// Parameters are named in the DSL, so the fields must have names.
fn check_named_fields(cx: &Ctxt, item: &syn::ItemStruct) -> Vec<syn::Field> {
    match &item.fields {
        syn::Fields::Named(named) => named.named.iter().cloned().collect(),
        syn::Fields::Unnamed(unnamed) => {
            cx.error_spanned_by(
                unnamed,
                "a variable-mass system needs named fields (its parameters); a tuple struct has none",
            );
            Vec::new()
        }
        syn::Fields::Unit => Vec::new(),
    }
}

/// The equations are `f64` arithmetic.
fn check_f64(cx: &Ctxt, field: &syn::Field) {
    let is_f64 =
        matches!(&field.ty, syn::Type::Path(p) if p.qself.is_none() && p.path.is_ident("f64"));
    if !is_f64 {
        let name = field
            .ident
            .as_ref()
            .map(|i| i.to_string())
            .unwrap_or_default();
        cx.error_spanned_by(
            &field.ty,
            format!("parameter `{name}` must be an `f64`: every field of a variable-mass system is a parameter of its equations"),
        );
    }
}

/// A field the equations never read is most likely a misspelt or forgotten parameter.
/// Fields starting with `_` are exempt.
pub fn check_unused_fields(cx: &Ctxt, fields: &[syn::Ident], d: &Derivation) {
    if !d.inputs.is_empty() {
        // The struct's `…Inputs` methods may read any field (gains, set points).
        return;
    }
    let used = d.used_parameters();
    for field in fields {
        let name = field.to_string();
        let reserved = varmass_symbolic::mechanics::is_reserved(&name);
        if !name.starts_with('_') && !reserved && !used.contains(&name) {
            cx.error_spanned_by(
                field,
                format!("field `{name}` is not used by the system's equations; use it in the DSL, remove it, or name it `_{name}`"),
            );
        }
    }
}

/// Generated code binds `x_dot` for the velocity of coordinate `x`; a field or mass of that
/// name would be shadowed, silently feeding the velocity where the parameter was meant.
pub fn check_generated_names(cx: &Ctxt, fields: &[syn::Ident], d: &Derivation) {
    let generated: Vec<String> = d
        .coordinates
        .iter()
        .flat_map(|c| [format!("{}_dot", c.name), format!("{}_ddot", c.name)])
        .collect();
    for field in fields {
        let name = field.to_string();
        if varmass_symbolic::mechanics::is_reserved(&name) {
            cx.error_spanned_by(
                field,
                format!(
                    "field `{name}` has a reserved name: in the DSL `t` is the time and {} are derived quantities; rename it",
                    varmass_symbolic::quantity::reserved_names()
                ),
            );
        } else if generated.contains(&name) {
            cx.error_spanned_by(
                field,
                format!("field `{name}` clashes with the generated name of a coordinate's velocity; rename it"),
            );
        }
    }
}

/// Coordinates and masses become locals of the generated code (`x`, `x_dot`, `p_x`, `m`), so
/// each must be a Rust identifier: not a keyword, not `_`, and not `__…`, which the generated
/// temporaries use.
pub fn rust_name_diagnostics(d: &Derivation) -> Vec<Diagnostic> {
    let names = d
        .coordinates
        .iter()
        .map(|c| (&c.name, c.span, "coordinate"))
        .chain(d.masses.iter().map(|m| (&m.name, m.span, "mass")));
    let velocities: Vec<String> = d
        .coordinates
        .iter()
        .map(|c| format!("{}_dot", c.name))
        .collect();
    names
        .filter(|(name, _, _)| {
            name.starts_with("__")
                || velocities.contains(name)
                || syn::parse_str::<syn::Ident>(name).is_err()
        })
        .map(|(name, span, what)| {
            Diagnostic::new(
                span,
                format!("`{name}` cannot name a {what}: generated Rust code uses it as a variable, and it is a Rust keyword or reserved"),
            )
            .with_help("rename it (names starting with `__` are reserved for generated temporaries)")
        })
        .collect()
}
