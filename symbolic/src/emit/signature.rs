//! The signatures of the `VariableMassSystem` methods that generated code implements: one
//! list, read by the emitter and by the macro's stub impl (which must spell the required
//! methods exactly as the trait does).

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::quantity::Quantity;

/// A method of `VariableMassSystem` that generated code implements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// `mass(index, t, state) -> f64`.
    Mass,
    /// `mass_rate(index, t, velocity_state) -> f64`.
    MassRate,
    /// `mass_matrix(t, state) -> SMatrix<N, N>`.
    MassMatrix,
    /// `momenta(t, velocity_state) -> SVector<N>`.
    Momenta,
    /// `lagrangian(t, velocity_state) -> f64`.
    Lagrangian,
    /// `lagrangian_gradient(t, velocity_state) -> SVector<N>`.
    LagrangianGradient,
    /// `active_force(t, velocity_state) -> SVector<N>`.
    ActiveForce,
    /// `reactive_thrust(t, velocity_state) -> SVector<N>`.
    ReactiveThrust,
    /// `impact_force(t, velocity_state) -> SVector<N>`.
    ImpactForce,
    /// `mass_flux_force(t, velocity_state) -> SVector<N>`.
    MassFluxForce,
    /// `accelerations(t, velocity_state) -> Result<SVector<N>>`.
    Accelerations,
    /// `velocities(t, state) -> Result<SVector<N>>` (provided by the trait).
    Velocities,
    /// `hamiltonian(t, state) -> Result<f64>` (provided by the trait).
    Hamiltonian,
    /// `canonical_rates(t, state) -> Result<(SVector<N>, SVector<N>)>` (provided).
    CanonicalRates,
    /// `state_rate(t, state) -> Result<SVector<S>>` (provided by the trait).
    StateRate,
    /// `power(t, state) -> Result<f64>` (provided by the trait).
    Power,
    /// `jacobian(t, state) -> Result<SMatrix<S, S>>` (provided by the trait).
    Jacobian,
    /// `flow_rate(index, t, velocity_state) -> f64` (provided: no flows).
    FlowRate,
    /// `singular_attitude_distance(t, state) -> Option<f64>` (provided: `None`).
    SingularAttitudeDistance,
    /// `switching_functions(t, velocity_state, values)` (provided: no switches).
    SwitchingFunctions,
    /// `switch_anchors(t, velocity_state, anchors)` (provided: no anchored switches).
    SwitchAnchors,
    /// `anchored_switching_functions(t, velocity_state, anchors, values)` (provided).
    AnchoredSwitchingFunctions,
}

/// The methods the trait does not provide, in the trait's order: every impl has them.
pub const REQUIRED: [Method; 11] = [
    Method::Mass,
    Method::MassRate,
    Method::MassMatrix,
    Method::Momenta,
    Method::Lagrangian,
    Method::LagrangianGradient,
    Method::ActiveForce,
    Method::ReactiveThrust,
    Method::ImpactForce,
    Method::MassFluxForce,
    Method::Accelerations,
];

/// What a method returns, for N coordinates and a state of S.
enum Output {
    /// Nothing: the method writes into the slices it takes.
    Unit,
    Scalar,
    OptionScalar,
    Coordinates,
    MassMatrix,
    ResultScalar,
    ResultCoordinates,
    ResultPair,
    ResultState,
    ResultJacobian,
}

impl Method {
    /// The generated method that carries `quantity`, with its doc comment's title: the
    /// emitter's half of the registry (`crate::quantity`). `None` for a quantity that no
    /// method of its own carries (T, V and the intermediates of the true ṗ and of eq. 6 are
    /// lines in other methods' doc comments). One exhaustive `match`, as
    /// [`Quantity::spec`] is, so a new quantity without its entry does not compile.
    pub fn carrying(quantity: Quantity) -> Option<(Method, &'static str)> {
        let carrier = match quantity {
            Quantity::MassRates => (Method::MassRate, "ṁ of every mass along the motion."),
            Quantity::Momenta => (
                Method::Momenta,
                "The generalized momenta p = ∂*L/∂q̇ (eq. 8).",
            ),
            Quantity::MassMatrix => (
                Method::MassMatrix,
                "The mass matrix M = ∂²L/∂q̇², masses frozen.",
            ),
            Quantity::Lagrangian => (Method::Lagrangian, "The Lagrangian L = T − V."),
            Quantity::LagrangianGradient => (
                Method::LagrangianGradient,
                "∂*L/∂q, masses frozen (= −∂*H/∂q, eq. 13).",
            ),
            Quantity::ActiveForce => (
                Method::ActiveForce,
                "The generalized active force Q* (eq. 22 for the sled).",
            ),
            Quantity::ReactiveThrust => (
                Method::ReactiveThrust,
                "The generalized reactive thrust R1 = Σ Q1 v_r1 · ∂r/∂q.",
            ),
            Quantity::ImpactForce => (
                Method::ImpactForce,
                "The generalized impact force R2 = Σ Q2 v_r2 · ∂r/∂q (eq. 23 for the sled).",
            ),
            Quantity::MassFluxForce => (
                Method::MassFluxForce,
                "The mass-flux term Σ ṁᵢ ∂*p/∂mᵢ of the true ṗ.",
            ),
            Quantity::Accelerations => (
                Method::Accelerations,
                "q̈(q, q̇, t) from M q̈ = d*p/dt − ∂*p/∂q q̇ − ∂*p/∂t (eq. 6).",
            ),
            Quantity::Power => (
                Method::Power,
                "The energy-budget power dH/dt = ∂*H/∂t + q̇·(Q* − R1 + R2 + Σ ṁ ∂*p/∂m) + Σ ṁ ∂H/∂m.",
            ),
            Quantity::Energy => (
                Method::Hamiltonian,
                "The Hamiltonian H(q, p, t) = p·q̇ − L (eqs. 9–10).",
            ),
            Quantity::Kinetic
            | Quantity::Potential
            | Quantity::FrozenMomentumRate
            | Quantity::MomentumRate
            | Quantity::AccelerationRhs => return None,
        };
        Some(carrier)
    }

    /// The method's name.
    pub fn name(self) -> &'static str {
        self.spec().0
    }

    /// (name, takes an index (of a mass, of a flow), reads a velocity state, output).
    fn spec(self) -> (&'static str, bool, bool, Output) {
        use Output::*;
        match self {
            Method::Mass => ("mass", true, false, Scalar),
            Method::MassRate => ("mass_rate", true, true, Scalar),
            Method::MassMatrix => ("mass_matrix", false, false, MassMatrix),
            Method::Momenta => ("momenta", false, true, Coordinates),
            Method::Lagrangian => ("lagrangian", false, true, Scalar),
            Method::LagrangianGradient => ("lagrangian_gradient", false, true, Coordinates),
            Method::ActiveForce => ("active_force", false, true, Coordinates),
            Method::ReactiveThrust => ("reactive_thrust", false, true, Coordinates),
            Method::ImpactForce => ("impact_force", false, true, Coordinates),
            Method::MassFluxForce => ("mass_flux_force", false, true, Coordinates),
            Method::Accelerations => ("accelerations", false, true, ResultCoordinates),
            Method::Velocities => ("velocities", false, false, ResultCoordinates),
            Method::Hamiltonian => ("hamiltonian", false, false, ResultScalar),
            Method::CanonicalRates => ("canonical_rates", false, false, ResultPair),
            Method::StateRate => ("state_rate", false, false, ResultState),
            Method::Power => ("power", false, false, ResultScalar),
            Method::Jacobian => ("jacobian", false, false, ResultJacobian),
            Method::FlowRate => ("flow_rate", true, true, Scalar),
            Method::SingularAttitudeDistance => {
                ("singular_attitude_distance", false, false, OptionScalar)
            }
            Method::SwitchingFunctions => ("switching_functions", false, true, Unit),
            Method::SwitchAnchors => ("switch_anchors", false, true, Unit),
            Method::AnchoredSwitchingFunctions => {
                ("anchored_switching_functions", false, true, Unit)
            }
        }
    }

    /// The slices a switching method takes after its state (the run's buffers of the
    /// switches' values and knot brackets), else nothing.
    fn slices(self) -> TokenStream {
        match self {
            Method::SwitchingFunctions => quote!(, values: &mut [f64]),
            Method::SwitchAnchors => quote!(, anchors: &mut [f64]),
            Method::AnchoredSwitchingFunctions => quote!(, anchors: &[f64], values: &mut [f64]),
            _ => TokenStream::new(),
        }
    }

    /// `fn name(&self, …) -> …` for `n` coordinates and a state of `s`, with the runtime at
    /// `runtime` (a path to `varmass_core`).
    pub fn signature(self, runtime: &TokenStream, n: usize, s: usize) -> TokenStream {
        let (name, indexed, velocity, output) = self.spec();
        let name = format_ident!("{}", name);
        let (n, s) = (Literal::usize_unsuffixed(n), Literal::usize_unsuffixed(s));
        let vector = |len: &Literal| quote!(#runtime::nalgebra::SVector<f64, #len>);
        let matrix = |len: &Literal| quote!(#runtime::nalgebra::SMatrix<f64, #len, #len>);
        let input = if velocity {
            quote!(velocity_state)
        } else {
            quote!(state)
        };
        let index = indexed.then(|| quote!(index: usize,));
        // Qualified: a `type Result<T> = …` of the user's in scope must not change the
        // signatures.
        let result = |ok: TokenStream| quote!(::core::result::Result<#ok, #runtime::SystemError>);
        let output = match output {
            Output::Unit => TokenStream::new(),
            Output::Scalar => quote!(f64),
            Output::OptionScalar => quote!(Option<f64>),
            Output::Coordinates => vector(&n),
            Output::MassMatrix => matrix(&n),
            Output::ResultScalar => result(quote!(f64)),
            Output::ResultCoordinates => result(vector(&n)),
            Output::ResultPair => {
                let v = vector(&n);
                result(quote!((#v, #v)))
            }
            Output::ResultState => result(vector(&s)),
            Output::ResultJacobian => result(matrix(&s)),
        };
        let output = (!output.is_empty()).then(|| quote!(-> #output));
        let (state, slices) = (vector(&s), self.slices());
        quote!(fn #name(&self, #index t: f64, #input: &#state #slices) #output)
    }
}
