//! The signatures of the `VariableMassSystem` methods that generated code implements: one
//! list, read by the emitter and by the macro's stub impl (which must spell the required
//! methods exactly as the trait does).

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

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
    Scalar,
    Coordinates,
    MassMatrix,
    ResultScalar,
    ResultCoordinates,
    ResultPair,
    ResultState,
    ResultJacobian,
}

impl Method {
    /// The method's name.
    pub fn name(self) -> &'static str {
        self.spec().0
    }

    /// (name, takes a mass index, reads a velocity state, output).
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
            Output::Scalar => quote!(f64),
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
        let state = vector(&s);
        quote!(fn #name(&self, #index t: f64, #input: &#state) -> #output)
    }
}
