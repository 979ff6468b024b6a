//! The elementary functions of the DSL (docs/dsl.md#functions). `sqrt` is not among them: it is the
//! power `u^(1/2)`, so that one set of power rules covers it.

/// A function the DSL knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Func {
    /// sin
    Sin,
    /// cos
    Cos,
    /// tan
    Tan,
    /// exp
    Exp,
    /// natural logarithm
    Ln,
    /// absolute value
    Abs,
    /// sign: −1, 0 or 1
    Sign,
    /// tanh
    Tanh,
    /// sinh
    Sinh,
    /// cosh
    Cosh,
    /// arcsine
    Asin,
    /// arccosine
    Acos,
    /// arctangent
    Atan,
    /// two-argument arctangent `atan2(y, x)`
    Atan2,
    /// minimum of two
    Min,
    /// maximum of two
    Max,
    /// A table of the model (docs/tables.md), or one of its derivatives: `table` indexes
    /// the pool's tables ([`ExprPool::add_table`](super::ExprPool::add_table)), `order` is
    /// the derivative order (0 for the table itself). Opaque: never folded, neither odd
    /// nor even; its values live in the pool, not here.
    Table {
        /// Index into the pool's tables.
        table: u16,
        /// Derivative order.
        order: u8,
    },
    /// An `input` of the model (docs/inputs.md), a function the user writes in Rust, or one
    /// of its first partials: `input` indexes the model's inputs, `partial` is 0 for the
    /// value and `j` for ∂/∂(argument j), 1-based. Any number of arguments; opaque: never
    /// folded, and its value is not known to the expression engine (NaN in [`Func::apply`]).
    Input {
        /// Index into the model's inputs.
        input: u16,
        /// 0: the value; j ≥ 1: the partial with respect to argument j.
        partial: u8,
    },
}

impl Func {
    /// Every function, in the order of declaration.
    pub const ALL: [Func; 16] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Exp,
        Func::Ln,
        Func::Abs,
        Func::Sign,
        Func::Tanh,
        Func::Sinh,
        Func::Cosh,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Atan2,
        Func::Min,
        Func::Max,
    ];

    /// The function called `name` in the DSL (the elementary ones; a table's name is the
    /// model's).
    pub fn from_name(name: &str) -> Option<Func> {
        Func::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The DSL name.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Sign => "sign",
            Func::Tanh => "tanh",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Atan2 => "atan2",
            Func::Min => "min",
            Func::Max => "max",
            Func::Table { .. } => "table",
            Func::Input { .. } => "input",
        }
    }

    /// Number of arguments (an input's is its declaration's, not known here: 1 is returned,
    /// and its calls are never folded).
    pub fn arity(self) -> usize {
        match self {
            Func::Atan2 | Func::Min | Func::Max => 2,
            _ => 1,
        }
    }

    /// The function's value; NaN if `args` has the wrong length, and for a table (its data
    /// are in the pool: [`ExprPool::table`](super::ExprPool::table)).
    pub fn apply(self, args: &[f64]) -> f64 {
        match (self, args) {
            (Func::Sin, [u]) => u.sin(),
            (Func::Cos, [u]) => u.cos(),
            (Func::Tan, [u]) => u.tan(),
            (Func::Exp, [u]) => u.exp(),
            (Func::Ln, [u]) => u.ln(),
            (Func::Abs, [u]) => u.abs(),
            (Func::Sign, [u]) => sign(*u),
            (Func::Tanh, [u]) => u.tanh(),
            (Func::Sinh, [u]) => u.sinh(),
            (Func::Cosh, [u]) => u.cosh(),
            (Func::Asin, [u]) => u.asin(),
            (Func::Acos, [u]) => u.acos(),
            (Func::Atan, [u]) => u.atan(),
            (Func::Atan2, [y, x]) => y.atan2(*x),
            (Func::Min, [a, b]) => min(*a, *b),
            (Func::Max, [a, b]) => max(*a, *b),
            _ => f64::NAN,
        }
    }

    /// f′(u) of a one-argument function, with w = f(u) given (tan′ = 1 + w²): the chain rule
    /// of a value with derivatives (`varmass_table::recurrence::Value`). abs′ is +1 at 0
    /// (the branch a kink's switch takes is located elsewhere), sign′ is 0; NaN for the rest.
    pub(crate) fn slope(self, u: f64, w: f64) -> f64 {
        match self {
            Func::Sin => u.cos(),
            Func::Cos => -u.sin(),
            Func::Tan => 1.0 + w * w,
            Func::Exp => w,
            Func::Ln => 1.0 / u,
            Func::Abs => match u < 0.0 {
                true => -1.0,
                false => 1.0,
            },
            Func::Sign => 0.0,
            Func::Tanh => 1.0 - w * w,
            Func::Sinh => u.cosh(),
            Func::Cosh => u.sinh(),
            Func::Asin => 1.0 / (1.0 - u * u).sqrt(),
            Func::Acos => -1.0 / (1.0 - u * u).sqrt(),
            Func::Atan => 1.0 / (1.0 + u * u),
            _ => f64::NAN,
        }
    }

    /// Odd functions: f(−u) = −f(u). Used to pull a negative coefficient out of the argument.
    pub(crate) fn is_odd(self) -> bool {
        matches!(
            self,
            Func::Sin | Func::Tan | Func::Sinh | Func::Tanh | Func::Asin | Func::Atan | Func::Sign
        )
    }

    /// Even functions: f(−u) = f(u).
    pub(crate) fn is_even(self) -> bool {
        matches!(self, Func::Cos | Func::Cosh | Func::Abs)
    }
}

/// sign(u) with sign(0) = 0 (unlike `f64::signum`), NaN for NaN.
pub(crate) fn sign(u: f64) -> f64 {
    if u > 0.0 {
        1.0
    } else if u < 0.0 {
        -1.0
    } else {
        u * 0.0
    }
}

/// min that propagates NaN (a missing value must not be hidden).
pub(crate) fn min(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.min(b)
    }
}

/// max that propagates NaN.
pub(crate) fn max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
