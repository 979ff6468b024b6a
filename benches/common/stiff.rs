//! The stiff scene: the leaking spring pendulum of `examples/leaking_spring_pendulum.rs`
//! with a spring of stiffness k from 1e2 to 1e8 N/m, started at rest on the slow manifold
//! (the spring balancing the weight), run for 10 s. The radial mode oscillates at √(k/m),
//! the swing at about 0.5 Hz: from k ≈ 1e4 on, explicit steps are set by stability.
//!
//! The reference is a tight explicit run (DOP853 at 1e-12, stability-limited steps); the
//! error is the relative error of the angle θ at 10 s. The sweep (`stiff_sweep` in
//! `work_precision.rs`) runs Dormand–Prince, DOP853, SDIRK4, ESDIRK4(3) and the stiff peer,
//! diffsol's BDF and ESDIRK34 (`diffsol_peer.rs`), on this scene's generated state rate
//! and Jacobian.

use varmass::core::steppers::Dop853;
use varmass::prelude::*;

/// Polar form, as in the example: the bob at r (sin θ, −cos θ), leaking along −ê_θ.
#[variable_mass_system(
    "
    coordinates r, th
    mass m: state, rate -mu
    body bob: mass m, position [r*sin(th), -r*cos(th)]
    potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
    outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
"
)]
#[derive(Clone, Copy, Debug)]
pub struct StiffPendulum {
    pub mu: f64,
    pub u_e: f64,
    pub k: f64,
    pub l0: f64,
    pub g: f64,
}

/// The stiffnesses of the scene and their names in tables and plots.
pub const SCENES: [(f64, &str); 4] = [
    (1e2, "pendulum k = 1e2"),
    (1e4, "pendulum k = 1e4"),
    (1e6, "pendulum k = 1e6"),
    (1e8, "pendulum k = 1e8"),
];

const M0: f64 = 2.0;
const THETA0: f64 = 0.5;
/// The end of every run (s).
pub const END: f64 = 10.0;

/// One stiffness: the system, its start and the reference angle at [`END`].
pub struct StiffScene {
    /// The generated system.
    pub system: StiffPendulum,
    /// The name in tables and plots.
    pub name: &'static str,
    /// θ(10) of the reference run.
    pub reference_angle: f64,
}

impl StiffScene {
    /// The scene with spring stiffness `k`, with its reference computed.
    pub fn new(k: f64, name: &'static str) -> Result<Self, StepError<5>> {
        let system = StiffPendulum {
            mu: 0.05,
            u_e: 2.0,
            k,
            l0: 1.0,
            g: 9.81,
        };
        let control = StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: 1e-12,
            absolute_tolerance: 1e-12,
            ..AdaptiveControl::dop853()
        });
        let mut stepper =
            Dop853::new(&system, 0.0, start(&system), control)?.without_dense_output();
        let solution = run(&mut stepper, &RunConfig::until(END), &[])?;
        let reference_angle = solution.last().map_or(f64::NAN, |(_, state)| state[1]);
        Ok(Self {
            system,
            name,
            reference_angle,
        })
    }

    /// The state at t = 0.
    pub fn start(&self) -> SVector<f64, 5> {
        start(&self.system)
    }

    /// The relative error of the angle of `state` against the reference.
    pub fn error(&self, state: &SVector<f64, 5>) -> f64 {
        ((state[1] - self.reference_angle) / self.reference_angle).abs()
    }
}

/// At rest, the spring stretched to balance the weight along the string:
/// k (r₀ − l₀) = m₀ g cos θ₀.
fn start(system: &StiffPendulum) -> SVector<f64, 5> {
    let r0 = system.l0 + M0 * system.g * THETA0.cos() / system.k;
    SVector::<f64, 5>::from([r0, THETA0, 0.0, 0.0, M0])
}
