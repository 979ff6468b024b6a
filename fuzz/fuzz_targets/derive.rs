//! DSL text → derivation (parse, tag selection, model, derivation, checks), then the
//! emitted code for a system that derives: never a panic; a rejected system has at least
//! one diagnostic, each with a span inside the source that renders.
//!
//! The last byte of the input chooses the tags: odd selects every tag the text uses (all
//! optional effects in), even selects none, as `with = [...]` would.
#![no_main]

use libfuzzer_sys::fuzz_target;
use quote::quote;
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::{derive, mechanics::Parameters};
use varmass_symbolic::parse::{known_tags, parse_system, select_tags};
use varmass_symbolic::Diagnostic;

fn check_diagnostics(source: &str, diagnostics: &[Diagnostic]) {
    assert!(!diagnostics.is_empty(), "an error without a diagnostic");
    for d in diagnostics {
        assert!(d.span.start <= d.span.end && d.span.end <= source.len());
        assert!(d.render(source).contains(&d.message));
    }
}

fuzz_target!(|data: &[u8]| {
    let all_tags = data.last().is_some_and(|b| b & 1 == 1);
    let source = String::from_utf8_lossy(data);
    let ast = match parse_system(&source) {
        Ok(ast) => ast,
        Err(diagnostics) => return check_diagnostics(&source, &diagnostics),
    };
    let with = if all_tags {
        known_tags(&ast)
    } else {
        Vec::new()
    };
    let selected = select_tags(&ast, &with).expect("the text's own tags are known");
    match derive(&selected, Parameters::Inferred) {
        Ok(mut derivation) => {
            let target = Target {
                name: proc_macro2::Ident::new("Fuzzed", proc_macro2::Span::call_site()),
                runtime: quote!(::varmass::core),
            };
            let code = emit_system(&mut derivation, &source, &target);
            assert!(!code.is_empty());
        }
        Err(diagnostics) => check_diagnostics(&source, &diagnostics),
    }
});
