//! DSL text → `parse_system` and `parse_expression`: never a panic, and every result well
//! formed — spans inside the source on character boundaries, an error result with at least
//! one diagnostic, and every diagnostic renders with its message.
#![no_main]

use libfuzzer_sys::fuzz_target;
use varmass_symbolic::parse::{parse_expression, parse_system, Diagnostic, Span};

fn assert_span_valid(source: &str, span: Span) {
    assert!(
        span.start <= span.end && span.end <= source.len(),
        "{span:?} out of the source"
    );
    assert!(source.is_char_boundary(span.start) && source.is_char_boundary(span.end));
    assert!(
        span.line >= 1 && span.column >= 1,
        "{span:?} has a zero line or column"
    );
}

fn assert_diagnostic_valid(source: &str, diagnostic: &Diagnostic) {
    assert_span_valid(source, diagnostic.span);
    assert!(diagnostic.render(source).contains(&diagnostic.message));
}

fuzz_target!(|data: &[u8]| {
    let source = String::from_utf8_lossy(data);
    match parse_system(&source) {
        Ok(system) => {
            for statement in &system.statements {
                assert_span_valid(&source, statement.span);
            }
        }
        Err(diagnostics) => {
            assert!(!diagnostics.is_empty(), "an error without a diagnostic");
            for diagnostic in &diagnostics {
                assert_diagnostic_valid(&source, diagnostic);
            }
        }
    }
    if let Err(diagnostic) = parse_expression(&source) {
        assert_diagnostic_valid(&source, &diagnostic);
    }
});
