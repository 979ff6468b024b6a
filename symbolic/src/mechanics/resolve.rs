//! Name resolution: what each identifier of the DSL means, and where it may be used.

use rustc_hash::FxHashMap;

use crate::expr::{lower, ExprPool, Id, Resolver, Symbol, SymbolKind, Written};
use crate::parse::ast::ExprNode;
use crate::parse::keywords;
use crate::parse::Diagnostic;
pub use crate::quantity::is_reserved;

/// What a name is bound to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Binding {
    /// The time symbol `t`.
    Time(Symbol),
    /// Coordinate number `index`, with its symbols.
    Coordinate {
        q: Symbol,
        velocity: Symbol,
        acceleration: Symbol,
    },
    /// A frozen mass or inertia (index into the model's masses).
    Mass(Symbol),
    /// A `let` definition, inlined.
    Let(Id),
    /// A parameter (a field of the struct).
    Parameter(Symbol),
    /// A `table` (index into the pool's tables): a function, called `F(t)`.
    Table(u16),
    /// An `input` (index into the pool's inputs, number of arguments): a function the user
    /// writes in Rust, called `u(t, y, y')`.
    Input(u16, usize),
}

/// Where an expression stands, which decides what it may refer to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Context {
    /// Anything but accelerations and derived quantities.
    Ordinary,
    /// A `check`: accelerations and derived quantities (H, p_x, …) are allowed too.
    Check,
}

/// How parameters are known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Parameters {
    /// Exactly these names are parameters (the struct's `f64` fields); any other unknown
    /// name is an error.
    Declared(Vec<String>),
    /// Every name that is nothing else is a parameter (for `.vms` files and tests).
    Inferred,
}

/// The resolver handed to expression lowering.
pub(crate) struct NameResolver<'a> {
    pub names: &'a mut FxHashMap<String, Binding>,
    pub parameters: &'a Parameters,
    pub inferred: &'a mut Vec<(String, Symbol)>,
    pub context: Context,
    /// Derived quantities a `check` may name (velocity form).
    pub quantities: Option<&'a FxHashMap<String, Id>>,
}

impl Resolver for NameResolver<'_> {
    fn resolve(&mut self, pool: &mut ExprPool, written: Written<'_>) -> Result<Id, Diagnostic> {
        let Written { name, primes, span } = written;
        if primes == 0 {
            if let Some(value) = self.quantities.and_then(|q| q.get(name)) {
                return Ok(*value);
            }
        }
        match self.names.get(name).copied() {
            Some(Binding::Coordinate {
                q,
                velocity,
                acceleration,
            }) => match primes {
                0 => Ok(pool.sym(q)),
                1 => Ok(pool.sym(velocity)),
                _ if self.context == Context::Check => {
                    match self.quantities.and_then(|q| q.get(&format!("{name}''"))) {
                        Some(value) => Ok(*value),
                        None => Ok(pool.sym(acceleration)),
                    }
                }
                _ => Err(Diagnostic::new(
                    span,
                    format!("the acceleration `{name}''` may appear only in a `check`"),
                )
                .with_help("equations of motion are derived, not written; state them as `check`s")),
            },
            Some(binding) if primes > 0 => Err(Diagnostic::new(
                span,
                format!(
                    "`{}`: only coordinates have velocities, and `{name}` is {}",
                    written.text(),
                    describe(binding)
                ),
            )),
            Some(Binding::Time(s) | Binding::Mass(s) | Binding::Parameter(s)) => Ok(pool.sym(s)),
            Some(Binding::Let(value)) => Ok(value),
            Some(Binding::Table(_)) => Err(Diagnostic::new(
                span,
                format!("`{name}` is a table, a function of one argument"),
            )
            .with_help(format!("call it: `{name}(t)`, `{name}(x)`"))),
            Some(Binding::Input(_, arity)) => Err(Diagnostic::new(
                span,
                format!(
                    "`{name}` is an input, a function of {arity} argument{}",
                    if arity == 1 { "" } else { "s" }
                ),
            )
            .with_help(format!(
                "call it with its arguments, as declared: `{name}(…)`"
            ))),
            None => self.unknown(pool, written),
        }
    }

    fn table(&self, name: &str) -> Option<u16> {
        match self.names.get(name) {
            Some(Binding::Table(index)) => Some(*index),
            _ => None,
        }
    }

    fn input(&self, name: &str) -> Option<(u16, usize)> {
        match self.names.get(name) {
            Some(Binding::Input(index, arity)) => Some((*index, *arity)),
            _ => None,
        }
    }
}

impl NameResolver<'_> {
    /// A name nothing binds: a new parameter when parameters are inferred, else an error
    /// with the nearest bound name.
    fn unknown(&mut self, pool: &mut ExprPool, written: Written<'_>) -> Result<Id, Diagnostic> {
        let Written { name, primes, span } = written;
        if primes == 0 {
            if let Parameters::Inferred = self.parameters {
                if !is_reserved(name) {
                    let symbol = pool.symbols_mut().add(name, SymbolKind::Parameter);
                    self.names
                        .insert(name.to_string(), Binding::Parameter(symbol));
                    self.inferred.push((name.to_string(), symbol));
                    return Ok(pool.sym(symbol));
                }
            }
        }
        let what = if primes > 0 {
            format!("`{}`: `{name}` is not a coordinate", written.text())
        } else if self.context == Context::Check && is_reserved(name) {
            format!("`{name}` is not a quantity this system derives")
        } else {
            format!("unknown symbol `{name}`")
        };
        let candidates = self.names.keys().map(String::as_str).chain(
            self.quantities
                .into_iter()
                .flat_map(|q| q.keys().map(String::as_str)),
        );
        let suggestion =
            keywords::nearest(name, candidates).map(|close| format!("did you mean `{close}`?"));
        let declared = primes == 0 && matches!(self.parameters, Parameters::Declared(_));
        let field = declared.then(|| {
            format!("if `{name}` is a parameter, add the field `{name}: f64` to the struct")
        });
        let help = match (suggestion, field) {
            (Some(s), Some(f)) => Some(format!("{s} {}{}", &f[..1].to_uppercase(), &f[1..])),
            (s, f) => s.or(f),
        };
        let mut diagnostic = Diagnostic::new(span, what);
        if let Some(help) = help {
            diagnostic = diagnostic.with_help(help);
        }
        Err(diagnostic)
    }
}

fn describe(binding: Binding) -> &'static str {
    match binding {
        Binding::Time(_) => "the time",
        Binding::Coordinate { .. } => "a coordinate",
        Binding::Mass(_) => "a mass (its rate is derived)",
        Binding::Let(_) => "a definition",
        Binding::Parameter(_) => "a parameter",
        Binding::Table(_) => "a table",
        Binding::Input(..) => "an input",
    }
}

/// Lowers `node` with the given scope.
pub(crate) fn lower_with(
    pool: &mut ExprPool,
    names: &mut FxHashMap<String, Binding>,
    parameter_mode: &Parameters,
    parameters: &mut Vec<(String, Symbol)>,
    node: &ExprNode,
    context: Context,
    quantities: Option<&FxHashMap<String, Id>>,
) -> Result<Id, Vec<Diagnostic>> {
    let mut resolver = NameResolver {
        names,
        parameters: parameter_mode,
        inferred: parameters,
        context,
        quantities,
    };
    lower(pool, node, &mut resolver)
}
