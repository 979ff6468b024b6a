//! A hovering rocket whose altitude-hold autopilot is written in Rust (docs/inputs.md):
//! `input u(t, y, y')` makes the macro emit the trait `HoverInputs`, which `Hover`
//! implements with a PD law u = g + kp (y_ref − y) − kd ẏ (the commanded acceleration; the
//! thrust is m u, the propellant burns at ṁ = −m u/u_e). Prints the altitude and mass every
//! 3 s of a 15 s flight from the ground to 10 m.
//!
//! Run: `cargo run --example hover_input`

use varmass::core::nalgebra::Vector3;
use varmass::core::steppers::{AdaptiveControl, DormandPrince, StepControl};
use varmass::core::{run, RunConfig};
use varmass::prelude::variable_mass_system;

#[variable_mass_system(
    r#"
    coordinates y
    input u(t, y, y')
    mass m: state, rate -m*u(t, y, y')/u_e
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate m*u(t, y, y')/u_e, relative_velocity [-u_e]
    units y: m, u: m/s^2, u_e: m/s, g: m/s^2
"#
)]
struct Hover {
    u_e: f64,
    g: f64,
    kp: f64,
    kd: f64,
    y_ref: f64,
}

impl HoverInputs for Hover {
    fn u(&self, _t: f64, y: f64, y_dot: f64) -> f64 {
        self.g + self.kp * (self.y_ref - y) - self.kd * y_dot
    }
}

fn main() {
    let hover = Hover {
        u_e: 2000.0,
        g: 9.80665,
        kp: 4.0,
        kd: 2.5,
        y_ref: 10.0,
    };
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..AdaptiveControl::default()
    });
    // [y, p, m]: on the ground, at rest, 50 kg.
    let start = Vector3::new(0.0, 0.0, 50.0);
    let mut stepper = DormandPrince::new(&hover, 0.0, start, control).expect("a valid start");
    let flight = run(&mut stepper, &RunConfig::until(15.0), &[]).expect("the flight runs");
    println!("   t (s)    y (m)    m (kg)");
    let mut next = 0.0;
    for (t, state) in flight.times.iter().zip(&flight.states) {
        if *t >= next {
            println!("{t:8.3} {:8.4} {:9.4}", state[0], state[2]);
            next += 3.0;
        }
    }
}
