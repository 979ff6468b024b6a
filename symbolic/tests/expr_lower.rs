//! Lowering from the parser's AST: names through a resolver, numbers exact, every error
//! collected with its span.

mod expr_support;

use expr_support::{build, read, sled_pool, try_build};
use varmass_symbolic::expr::{lower, ExprPool, Func, Id, Rational, Resolver, Written};
use varmass_symbolic::parse::keywords::FUNCTIONS;
use varmass_symbolic::Diagnostic;

#[test]
fn the_function_table_agrees_with_the_parser_keywords() {
    for (name, arity) in FUNCTIONS {
        if *name == "sqrt" {
            continue;
        }
        let f = Func::from_name(name).unwrap_or_else(|| panic!("{name} unknown"));
        assert_eq!(f.arity(), *arity, "{name}");
        assert_eq!(f.name(), *name);
    }
    assert_eq!(FUNCTIONS.len(), Func::ALL.len() + 1, "sqrt plus every Func");
}

#[test]
fn names_and_primes_resolve_through_the_table() {
    let mut p = sled_pool();
    let e = build(&mut p, "x + x' + x''");
    let t = p.symbols();
    let x = t.lookup("x").unwrap();
    let want = [Some(x), t.velocity_of(x), t.acceleration_of(x)];
    let got: Vec<_> = p.terms(e).into_iter().map(|id| p.as_symbol(id)).collect();
    assert_eq!(got, want);
    let sqrt = build(&mut p, "sqrt(m)");
    let half = build(&mut p, "m^(1/2)");
    assert_eq!(sqrt, half);
    let n = build(&mut p, "-9.81");
    assert_eq!(p.as_rational(n), Rational::new(-981, 100));
}

#[test]
fn every_error_is_collected_with_its_span() {
    let mut p = sled_pool();
    let errors = try_build(&mut p, "foo*x + bar(m) + atan2(x) + m' + sin(baz)").unwrap_err();
    let messages: Vec<&str> = errors.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        messages,
        [
            "unknown symbol `foo`",
            "unknown function `bar`",
            "`atan2` takes 2 arguments, found 1",
            "`m` is not a coordinate, so `m'` has no meaning",
            "unknown symbol `baz`",
        ]
    );
    let help = errors[1].help.as_deref().unwrap();
    assert!(help.contains("sin, cos") && help.contains("sqrt") && help.contains("atan2"));
    // Spans point at the offending text.
    assert_eq!((errors[0].span.start, errors[0].span.end), (0, 3));
    assert_eq!((errors[1].span.start, errors[1].span.end), (8, 11));
}

#[test]
fn an_unusable_literal_is_a_diagnostic() {
    let mut p = sled_pool();
    let errors = try_build(&mut p, "1e400*x").unwrap_err();
    assert_eq!(errors.len(), 1);
    assert!(errors[0].message.contains("1e400"));
}

/// A resolver with its own vocabulary, as the mechanics stage will have.
struct Fixed(Id);

impl Resolver for Fixed {
    fn resolve(&mut self, pool: &mut ExprPool, written: Written<'_>) -> Result<Id, Diagnostic> {
        match (written.name, written.primes) {
            ("H", 0) => Ok(self.0),
            _ => {
                let _ = pool;
                let message = format!("no `{}` here", written.name);
                Err(Diagnostic::new(written.span, message))
            }
        }
    }
}

#[test]
fn a_custom_resolver_supplies_derived_quantities() {
    let mut p = sled_pool();
    let h = build(&mut p, "m*g*x");
    let ast = read("2*H - H").unwrap();
    let e = lower(&mut p, &ast, &mut Fixed(h)).unwrap();
    assert_eq!(e, h);
}
