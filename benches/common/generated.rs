//! The benchmark systems as users write them: DSL in the `#[variable_mass_system]` macro.
//! Each has a twin written by hand in `hand.rs` and a reference solution in `problems.rs`.
//! The sled, the rocket and Kepler also emit the Taylor recurrences, for the Taylor stepper
//! (Kepler its double-double head too).

use varmass::prelude::*;

/// The paper's sled (§4, eqs. 20–24), body form: it scoops up snow at rest, m = m0 + c x.
#[variable_mass_system(
    "
    coordinates x
    mass m = m0 + c*x
    body sled: mass m, position [x]
    potential -m*g*x*sin(theta)
    force sled: [-f_d*m*g*cos(theta)]
    inflow sled: velocity [0]
",
    emit = ["hamiltonian", "power", "jacobian", "derivation", "taylor"]
)]
#[derive(Clone, Copy, Debug)]
pub struct Sled {
    pub m0: f64,
    pub c: f64,
    pub g: f64,
    pub theta: f64,
    pub f_d: f64,
}

/// A vertical rocket burning at the constant rate μ, exhaust at −u_e relative (docs/mechanics.md#vertical-rocket).
#[variable_mass_system(
    "
    coordinates y
    mass m: state, rate -mu
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate mu, relative_velocity [-u_e]
",
    emit = ["hamiltonian", "power", "jacobian", "derivation", "taylor"]
)]
#[derive(Clone, Copy, Debug)]
pub struct Rocket {
    pub mu: f64,
    pub u_e: f64,
    pub g: f64,
}

/// The Kepler problem in polar coordinates, constant mass: the constant-mass reference.
#[variable_mass_system(
    "
    coordinates r, th
    mass m = m1
    body planet: mass m, position [r*cos(th), r*sin(th)]
    potential -k*m/r
",
    emit = ["hamiltonian", "power", "jacobian", "derivation", "taylor", "head"]
)]
#[derive(Clone, Copy, Debug)]
pub struct Kepler {
    pub m1: f64,
    pub k: f64,
}

/// The same Kepler problem with T written in polar form, so no sin²θ + cos²θ is left for the
/// simplifier: separates the cost of that gap from the cost of generated code as such.
#[variable_mass_system(
    "
    coordinates r, th
    mass m = m1
    kinetic 1/2*m*(r'^2 + r^2*th'^2)
    potential -k*m/r
"
)]
#[derive(Clone, Copy, Debug)]
pub struct KeplerPolar {
    pub m1: f64,
    pub k: f64,
}

/// The six-degree-of-freedom rocket of `models/rocket_6dof.vms`, emitted as users get it
/// (default outputs); its twin by hand is `rocket_6dof.rs`.
#[variable_mass_system(file = "../models/rocket_6dof.vms")]
#[allow(non_snake_case)] // the model's names: A_d, C_d
#[derive(Clone, Copy, Debug)]
pub struct Rocket6 {
    pub mu: f64,
    pub m_d: f64,
    pub A_d: f64,
    pub C_d: f64,
    pub k_a: f64,
    pub k_c: f64,
    pub g_c: f64,
    pub l: f64,
    pub u_e: f64,
    pub delta: f64,
    pub g: f64,
}

impl Rocket6 {
    /// The rocket with the parameters of `hand`.
    pub fn like(hand: &super::rocket_6dof::HandRocket6) -> Self {
        Self {
            mu: hand.mu,
            m_d: hand.m_d,
            A_d: hand.A_d,
            C_d: hand.C_d,
            k_a: hand.k_a,
            k_c: hand.k_c,
            g_c: hand.g_c,
            l: hand.l,
            u_e: hand.u_e,
            delta: hand.delta,
            g: hand.g,
        }
    }
}
