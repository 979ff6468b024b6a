//! The expansion: read the input, run the symbolic pipeline, emit the impl — or every error
//! at once plus a stub.

use proc_macro2::TokenStream;
use quote::{quote, ToTokens};
use varmass_symbolic::compose::{compose, Composition};
use varmass_symbolic::emit::{emit_system_for, Target};
use varmass_symbolic::parse::ast::{MassLaw, StatementKind, SystemAst};
use varmass_symbolic::parse::{parse_system, select_tags};
use varmass_symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};

use crate::ast::{parse_attribute, parse_struct, Attribute};
use crate::ctxt::Ctxt;
use crate::fallback::stub;
use crate::model::ModelText;
use crate::valid::{
    check_generated_names, check_unused_fields, parameter_fields, rust_name_diagnostics,
};

pub fn expand(attr: TokenStream, item: TokenStream) -> TokenStream {
    let item_struct = match parse_struct(item.clone()) {
        Ok(s) => s,
        // Not a struct: nothing to attach an impl to; report and keep the item.
        Err(e) => {
            let error = e.to_compile_error();
            return quote!(#item #error);
        }
    };
    let cx = Ctxt::new();
    let attribute = parse_attribute(attr).map_err(|e| cx.push(e)).ok();
    let model = attribute
        .as_ref()
        .and_then(|a| ModelText::load(&a.source).map_err(|e| cx.push(e)).ok());
    let mut dims = (1, 0);
    let mut generated = None;
    let composed = match (&attribute, &model) {
        (Some(attribute), Some(model)) => selected_system(&cx, attribute, model),
        _ => None,
    };
    // The fields of `= runtime` tables hold their data; every other field is a parameter.
    let tables = composed
        .as_ref()
        .map(|(ast, _)| runtime_tables(ast))
        .unwrap_or_default();
    let fields = parameter_fields(&cx, &item_struct, &tables);
    if let (Some(attribute), Some(model), Some((ast, composition))) =
        (&attribute, &model, &composed)
    {
        dims = dimensions(ast);
        let outputs = outputs(&cx, attribute);
        generated = generate(
            &cx,
            &item_struct,
            &fields,
            (model, composition),
            ast,
            outputs,
        );
    }
    let composition = composed.as_ref().map(|(_, composition)| composition);
    let tracking = model.as_ref().map(|m| m.tracking(composition));
    finish(cx, &item_struct, dims, generated, tracking)
}

/// The parsed system, its components expanded (docs/components.md), with the statements the
/// attribute's `with` selects, and the composition that locates diagnostics in components;
/// or `None` after reporting why not.
fn selected_system(
    cx: &Ctxt,
    attribute: &Attribute,
    model: &ModelText,
) -> Option<(SystemAst, Composition)> {
    let ast = parse_system(&model.text)
        .map_err(|errors| model.report(cx, &errors))
        .ok()?;
    let composition = compose(&model.text, ast, &model.path())
        .map_err(|errors| model.report(cx, &errors))
        .ok()?;
    let with: Vec<String> = attribute.with.iter().map(|t| t.value()).collect();
    select_tags(&composition.ast, &with)
        .map(|ast| (ast, composition))
        .map_err(|unknown| {
            for u in unknown {
                cx.error_at(attribute.with[u.index].span(), &u);
            }
        })
        .ok()
}

/// The optional outputs `emit = [...]` names (all without it); an unknown name is reported
/// on its string.
fn outputs(cx: &Ctxt, attribute: &Attribute) -> Outputs {
    let Some(names) = &attribute.emit else {
        return Outputs::FULL;
    };
    let values: Vec<String> = names.iter().map(|n| n.value()).collect();
    Outputs::from_names(&values).unwrap_or_else(|unknown| {
        for u in unknown {
            cx.error_at(names[u.index].span(), &u);
        }
        Outputs::FULL
    })
}

/// Derives the system and emits its code, or `None` after reporting every problem.
fn generate(
    cx: &Ctxt,
    item_struct: &syn::ItemStruct,
    fields: &[syn::Ident],
    (model, composition): (&ModelText, &Composition),
    ast: &SystemAst,
    outputs: Outputs,
) -> Option<TokenStream> {
    let names = fields.iter().map(|f| f.to_string()).collect();
    let mut derivation = derive_in(ast, Parameters::Declared(names), outputs, &model.base())
        .map_err(|errors| model.report(cx, &composition.locate(errors)))
        .ok()?;
    check_unused_fields(cx, fields, &derivation);
    check_generated_names(cx, fields, &derivation);
    let bad_names = rust_name_diagnostics(&derivation);
    model.report(cx, &bad_names);
    if !bad_names.is_empty() {
        // No code: it would not compile with these names.
        return None;
    }
    let target = Target {
        name: item_struct.ident.clone(),
        runtime: quote!(::varmass::core),
    };
    let tables = model.table_tracking(&derivation);
    let code = emit_system_for(&mut derivation, &model.text, &target, outputs);
    Some(quote!(#tables #code))
}

/// The struct, then the generated items (and the model file's tracking), or every error
/// and a stub.
fn finish(
    cx: Ctxt,
    item_struct: &syn::ItemStruct,
    dims: (usize, usize),
    generated: Option<TokenStream>,
    tracking: Option<TokenStream>,
) -> TokenStream {
    let item_tokens = item_struct.to_token_stream();
    match (cx.check(), generated) {
        (Ok(()), Some(generated)) => quote!(#item_tokens #tracking #generated),
        (Err(e), _) => {
            let errors = e.to_compile_error();
            let stub = stub(item_struct, dims.0, dims.1);
            quote!(#item_tokens #tracking #errors #stub)
        }
        (Ok(()), None) => quote!(#item_tokens #tracking),
    }
}

/// The names of the `table F(..) = runtime` statements: fields of the struct.
fn runtime_tables(ast: &SystemAst) -> Vec<String> {
    let names = ast.statements.iter().filter_map(|s| match &s.kind {
        StatementKind::Table(t) if t.runtime => Some(t.name.node.clone()),
        _ => None,
    });
    names.collect()
}

/// The number of coordinates and of state masses, for the stub.
fn dimensions(ast: &SystemAst) -> (usize, usize) {
    let mut coordinates = 0;
    let mut state_masses = 0;
    for s in &ast.statements {
        match &s.kind {
            StatementKind::Coordinates(names) => coordinates += names.len(),
            StatementKind::Mass(m) | StatementKind::Inertia(m) => {
                if matches!(m.law, MassLaw::State { .. }) {
                    state_masses += 1;
                }
            }
            _ => {}
        }
    }
    (coordinates.max(1), state_masses)
}
