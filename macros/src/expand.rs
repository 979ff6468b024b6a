//! The expansion: read the input, run the symbolic pipeline, emit the impl — or every error
//! at once plus a stub.

use proc_macro2::TokenStream;
use quote::{quote, ToTokens};
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::mechanics::{derive, Parameters};
use varmass_symbolic::parse::ast::{MassLaw, StatementKind, SystemAst};
use varmass_symbolic::parse::{parse_system, Origin};
use varmass_symbolic::Diagnostic;

use crate::ast::{parse_source, parse_struct};
use crate::ctxt::Ctxt;
use crate::fallback::stub;
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
    let fields = parameter_fields(&cx, &item_struct);
    let source = parse_source(attr).map_err(|e| cx.push(e)).ok();
    let mut dims = (1, 0);
    let mut generated = None;
    if let Some(source) = &source {
        let text = source.value();
        match parse_system(&text) {
            Err(errors) => report(&cx, source, &text, &errors),
            Ok(ast) => {
                dims = dimensions(&ast);
                let names = fields.iter().map(|f| f.to_string()).collect();
                match derive(&ast, Parameters::Declared(names)) {
                    Err(errors) => report(&cx, source, &text, &errors),
                    Ok(mut derivation) => {
                        check_unused_fields(&cx, &fields, &derivation);
                        check_generated_names(&cx, &fields, &derivation);
                        let bad_names = rust_name_diagnostics(&derivation);
                        report(&cx, source, &text, &bad_names);
                        if !bad_names.is_empty() {
                            // No code: it would not compile with these names.
                            return finish(cx, &item_struct, dims, None);
                        }
                        let target = Target {
                            name: item_struct.ident.clone(),
                            runtime: quote!(::varmass::core),
                        };
                        generated = Some(emit_system(&mut derivation, &text, &target));
                    }
                }
            }
        }
    }
    finish(cx, &item_struct, dims, generated)
}

/// The struct, then the generated items, or every error and a stub.
fn finish(
    cx: Ctxt,
    item_struct: &syn::ItemStruct,
    dims: (usize, usize),
    generated: Option<TokenStream>,
) -> TokenStream {
    let item_tokens = item_struct.to_token_stream();
    match (cx.check(), generated) {
        (Ok(()), Some(generated)) => quote!(#item_tokens #generated),
        (Err(e), _) => {
            let errors = e.to_compile_error();
            let stub = stub(item_struct, dims.0, dims.1);
            quote!(#item_tokens #errors #stub)
        }
        (Ok(()), None) => item_tokens,
    }
}

/// Each diagnostic as a compile error on the string literal, with the file's line:column and
/// a caret under the offending DSL text in the message. (A span inside the literal needs the
/// unstable `Literal::subspan`; the message carries the exact position instead.)
fn report(cx: &Ctxt, literal: &syn::LitStr, source: &str, errors: &[Diagnostic]) {
    let origin = origin(literal);
    for d in errors {
        let rendered = d.render_at(source, origin);
        // `render` starts with "error: <message>"; the compiler prints its own "error: ".
        let body: Vec<&str> = rendered.lines().skip(1).collect();
        cx.error_at(
            literal.span(),
            format!("{}\n{}", d.message, body.join("\n")),
        );
    }
}

/// Where the literal's text starts in the file, when its value is its text verbatim (no
/// escapes), so DSL positions map to file positions; otherwise positions stay relative to
/// the DSL text (line 1 is the first line of the string).
fn origin(literal: &syn::LitStr) -> Origin {
    let token = literal.token().to_string();
    let prefix = token.find('"').map_or(0, |i| i + 1);
    let suffix = token.len() - token.rfind('"').unwrap_or(token.len());
    let verbatim = token
        .get(prefix..token.len() - suffix)
        .is_some_and(|inner| inner == literal.value());
    let start = literal.span().start();
    if verbatim && start.line > 0 {
        Origin {
            line: start.line as u32,
            // `start.column` is 0-based and points at the literal's first character.
            column: (start.column + prefix + 1) as u32,
        }
    } else {
        Origin::default()
    }
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
