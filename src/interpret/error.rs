//! Why a [`super::Program`] or a [`super::TapeSystem`] could not be made.

/// A parameter list that does not fit the model, or sizes that do not fit it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProgramError {
    /// A value was given for a name that is not a parameter of the model.
    #[error("`{name}` is not a parameter of the model{}; its parameters are: {}",
        suggestion.as_ref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default(),
        list(parameters))]
    UnknownParameter {
        /// The name given.
        name: String,
        /// The nearest parameter name, if one is a likely typo of it.
        suggestion: Option<String>,
        /// Every parameter of the model.
        parameters: Vec<String>,
    },
    /// Parameters the equations read were given no value.
    #[error(
        "missing value for {}; the model's parameters are: {}",
        list(missing),
        list(parameters)
    )]
    MissingParameters {
        /// The parameters without a value.
        missing: Vec<String>,
        /// Every parameter of the model.
        parameters: Vec<String>,
    },
    /// A parameter value is NaN or infinite.
    #[error("the value of parameter `{name}` is not finite ({value})")]
    NonFiniteParameter {
        /// The parameter.
        name: String,
        /// Its value.
        value: f64,
    },
    /// A sampled input (`input u(…) every T`) has no law to sample: the interpreter
    /// evaluates the law given for it (`varmass run --input`), not Rust code.
    #[error("sampled input `{name}` has no law to sample (give one with --input {name}=EXPR)")]
    MissingInputLaw {
        /// The input's name.
        name: String,
    },
    /// A continuous input (a function written in Rust under the macro) has no law: its
    /// calls would evaluate to NaN.
    #[error(
        "input `{name}` is a function written in Rust; the interpreter needs a law for it \
         (varmass run --input {name}=EXPRESSION)"
    )]
    InputWithoutLaw {
        /// The input's name.
        name: String,
    },
    /// The sizes of a [`super::TapeSystem`] do not match the model's.
    #[error(
        "the model has {coordinates} coordinates and {state_masses} state masses, \
         not the N = {n}, S = {s} asked for"
    )]
    WrongSize {
        /// The model's number of coordinates.
        coordinates: usize,
        /// The model's number of state masses.
        state_masses: usize,
        /// The N asked for.
        n: usize,
        /// The S asked for.
        s: usize,
    },
    /// A `table F(t) = runtime` was given no data (docs/tables.md#runtime-tables): the
    /// derivation holds a placeholder for it, which a run must not use.
    #[error(
        "table `{name}` is `= runtime` and was given no data; give it as a table file \
         (command line: --table {name}=FILE.eng or FILE.csv)"
    )]
    RuntimeTableWithoutData {
        /// The table.
        name: String,
    },
}

fn list(names: &[String]) -> String {
    if names.is_empty() {
        return "(none)".to_string();
    }
    names.join(", ")
}
