//! DSL text → derivation (parse, model, derivation, checks), then the emitted code for a
//! system that derives: never a panic; a rejected system has at least one diagnostic, each
//! with a span inside the source that renders.
#![no_main]

use libfuzzer_sys::fuzz_target;
use quote::quote;
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::mechanics::{derive_source, Parameters};

fuzz_target!(|data: &[u8]| {
    let source = String::from_utf8_lossy(data);
    match derive_source(&source, Parameters::Inferred) {
        Ok(mut derivation) => {
            let target = Target {
                name: proc_macro2::Ident::new("Fuzzed", proc_macro2::Span::call_site()),
                runtime: quote!(::varmass::core),
            };
            let code = emit_system(&mut derivation, &source, &target);
            assert!(!code.is_empty());
        }
        Err(diagnostics) => {
            assert!(!diagnostics.is_empty(), "an error without a diagnostic");
            for d in &diagnostics {
                assert!(d.span.start <= d.span.end && d.span.end <= source.len());
                assert!(d.render(&source).contains(&d.message));
            }
        }
    }
});
