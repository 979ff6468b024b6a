//! Minimal against full emission: what the macro does for a system (parse, select the
//! tags, derive, emit), with every optional output or with none (`emit = []`), and the size
//! of the code it generates, in bytes of prettyplease-formatted Rust.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use varmass_symbolic::emit::{emit_system_for, Target};
use varmass_symbolic::parse::{parse_system, select_tags};
use varmass_symbolic::{
    derive_for,
    mechanics::{Outputs, Parameters},
};

/// A system to expand: a name, its DSL text and the tags it is built with.
pub struct Subject {
    /// What the row is called.
    pub name: String,
    /// The DSL text.
    pub source: String,
    /// The tags asked for.
    pub with: Vec<String>,
}

impl Subject {
    /// The model file `models/<file>` of the repository with the tags `with`.
    pub fn model(file: &str, with: &[&str]) -> Subject {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../models")
            .join(file);
        let source = std::fs::read_to_string(&path).unwrap_or_default();
        let tags = if with.is_empty() {
            String::new()
        } else {
            format!(" [{}]", with.join(", "))
        };
        Subject {
            name: format!("{}{tags}", file.trim_end_matches(".vms")),
            source,
            with: with.iter().map(|s| s.to_string()).collect(),
        }
    }
}

/// The macro's work for `subject` with `outputs`: the generated tokens (empty if the
/// system does not derive).
pub fn expand_for(subject: &Subject, parameters: &Parameters, outputs: Outputs) -> TokenStream {
    let target = Target {
        name: Ident::new("System", Span::call_site()),
        runtime: quote!(::varmass::core),
    };
    let Ok(ast) = parse_system(&subject.source) else {
        return TokenStream::new();
    };
    let Ok(selected) = select_tags(&ast, &subject.with) else {
        return TokenStream::new();
    };
    match derive_for(&selected, parameters.clone(), outputs) {
        Ok(mut d) => emit_system_for(&mut d, &subject.source, &target, outputs),
        Err(_) => TokenStream::new(),
    }
}

/// Bytes of the generated code once formatted by prettyplease (0 if it does not parse).
pub fn formatted_size(tokens: TokenStream) -> usize {
    syn::parse2::<syn::File>(tokens).map_or(0, |file| prettyplease::unparse(&file).len())
}
