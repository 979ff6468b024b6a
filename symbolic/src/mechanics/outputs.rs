//! What a system's generated code provides beyond what every system needs.
//!
//! Every system gets the masses, M, p, L, ∂*L/∂q, the forces, q̈, q̇(q, p), the canonical
//! equations and the state rate: the steppers need them. The rest is optional: a quantity
//! that is not asked for is neither derived (where it costs derivation time) nor emitted,
//! and the runtime trait's default serves in its place (H = p·q̇ − L from q̇(q, p); the
//! power by central differences of H; the Jacobian by central differences of the state
//! rate; no `DERIVATION` text).

/// The optional outputs of a system. [`Outputs::FULL`] (the default) has all of them but the
/// opt-in `taylor`, `head`, `lanes` and `sensitivities`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outputs {
    /// The closed-form `hamiltonian` method.
    pub hamiltonian: bool,
    /// The closed-form energy-budget `power` method.
    pub power: bool,
    /// The symbolic Jacobian (derived and emitted), for the implicit steppers.
    pub jacobian: bool,
    /// The `DERIVATION` and `DERIVATION_LATEX` texts.
    pub derivation: bool,
    /// The Taylor recurrences (`taylor_coefficients`, for the Taylor stepper). Opt-in: not
    /// in [`Outputs::FULL`], since they add to expansion time and code size.
    pub taylor: bool,
    /// The state rate over SIMD lanes (`LaneSystem`, for ensembles run in lanes). Opt-in
    /// as the Taylor recurrences are: it repeats the state rate's code.
    pub lanes: bool,
    /// The state rate over double-double dual numbers (`taylor_head`, for the Taylor
    /// stepper's head, `Taylor::with_head`). Opt-in, with `taylor`.
    pub head: bool,
    /// The Jacobian of the state rate with respect to the parameters
    /// (`parameter_jacobian`, for forward sensitivities, docs/sensitivities.md); it brings
    /// the state Jacobian with it. Opt-in.
    pub sensitivities: bool,
}

/// The name of an output that does not exist.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown output `{name}`; expected one of {}", Outputs::NAMES.map(|n| format!("`{n}`")).join(", "))]
pub struct UnknownOutput {
    /// The name as given.
    pub name: String,
    /// Its position in the list given.
    pub index: usize,
}

impl Outputs {
    /// Every output but the opt-in Taylor recurrences, head, lanes and sensitivities.
    pub const FULL: Outputs = Outputs {
        hamiltonian: true,
        power: true,
        jacobian: true,
        derivation: true,
        taylor: false,
        lanes: false,
        head: false,
        sensitivities: false,
    };

    /// Only what the steppers need.
    pub const MINIMAL: Outputs = Outputs {
        hamiltonian: false,
        power: false,
        jacobian: false,
        derivation: false,
        taylor: false,
        lanes: false,
        head: false,
        sensitivities: false,
    };

    /// The names of the optional outputs, as [`Outputs::from_names`] reads them.
    pub const NAMES: [&'static str; 8] = [
        "hamiltonian",
        "power",
        "jacobian",
        "derivation",
        "taylor",
        "lanes",
        "head",
        "sensitivities",
    ];

    /// The outputs named (the others left out): `[]` is [`Outputs::MINIMAL`].
    ///
    /// ```
    /// use varmass_symbolic::mechanics::Outputs;
    /// let outputs = Outputs::from_names(&["power"]).unwrap();
    /// assert!(outputs.power && !outputs.jacobian);
    /// assert_eq!(Outputs::from_names(&["jacobain"]).unwrap_err()[0].index, 0);
    /// ```
    pub fn from_names<S: AsRef<str>>(names: &[S]) -> Result<Outputs, Vec<UnknownOutput>> {
        let mut outputs = Outputs::MINIMAL;
        let mut unknown = Vec::new();
        for (index, name) in names.iter().enumerate() {
            match name.as_ref() {
                "hamiltonian" => outputs.hamiltonian = true,
                "power" => outputs.power = true,
                "jacobian" => outputs.jacobian = true,
                "derivation" => outputs.derivation = true,
                "taylor" => outputs.taylor = true,
                "lanes" => outputs.lanes = true,
                "head" => outputs.head = true,
                "sensitivities" => outputs.sensitivities = true,
                other => unknown.push(UnknownOutput {
                    name: other.to_string(),
                    index,
                }),
            }
        }
        if unknown.is_empty() {
            Ok(outputs)
        } else {
            Err(unknown)
        }
    }
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs::FULL
    }
}
