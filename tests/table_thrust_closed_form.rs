//! A rocket flying vertically on the M1670's measured thrust curve (a linear table, `outside
//! zero`), its mass following the curve at a constant exhaust speed, written by hand over
//! `varmass-table`: the reference the DSL's `table` will be held to (issue 21), and the proof
//! that knots as stop times integrate a piecewise-linear curve to the tolerance.
//!
//! Closed form (by hand). With μ = F(t)/u_e, ṁ = −μ gives m(t) = m₀ − I(t)/u_e, I the exact
//! trapezoid integral of the curve (`Piecewise::antiderivative`). Meshchersky:
//! m v̇ = μ u_e − m g = −u_e ṁ − m g, so v̇ = −u_e ṁ/m − g and v(t) = u_e ln(m₀/m(t)) − g t.
//!
//! Flown straight through the 15 kinks instead (one run to the end, no stop times), the
//! same steppers measured relative errors in v of 6.0e-11 (Dormand–Prince) and 3.4e-12
//! (DOP853) at tolerance 1e-12, and 7.6e-7 and 1.4e-7 at 1e-8: the kinks, not the
//! tolerance, set the error. Landing on the knots is what the tables of t will do.

use varmass::core::nalgebra::{SMatrix, SVector, Vector1, Vector3};
use varmass::core::steppers::{AdaptiveControl, Dop853, DormandPrince, StepControl};
use varmass::core::{run, RunConfig, Stepper, SystemError, VariableMassSystem};
use varmass_table::{Interpolation, Motor, Outside, Piecewise, Table};

/// Gravity, m/s².
const G: f64 = 9.80665;
/// Lift-off mass, kg: the loaded motor (5.231 kg) in a 14.769 kg airframe.
const M0: f64 = 20.0;
/// The end of the run, s: 2.1 s of coasting after burnout at 3.9 s.
const END: f64 = 6.0;

struct MotorRocket {
    thrust: Table,
    impulse: Piecewise,
    exhaust_speed: f64,
}

impl MotorRocket {
    fn m1670() -> Self {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/models/motors/Cesaroni_M1670.eng"
        );
        let motor = Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
        let curve = Interpolation::Linear.interpolate(&motor.thrust);
        Self {
            impulse: curve.antiderivative(),
            thrust: Table::from_piecewise(curve, Outside::Zero),
            exhaust_speed: motor.exhaust_speed(),
        }
    }

    /// F(t), N; under `outside zero` every finite t has a value.
    fn thrust(&self, t: f64) -> f64 {
        self.thrust.value(t).expect("a finite time")
    }

    /// The closed form (m, v) at t.
    fn exact(&self, t: f64) -> (f64, f64) {
        let burnt = self.impulse.value(t.min(self.impulse.domain().1));
        let m = M0 - burnt / self.exhaust_speed;
        (m, self.exhaust_speed * (M0 / m).ln() - G * t)
    }
}

impl VariableMassSystem<1, 3> for MotorRocket {
    const COORDINATES: [&'static str; 1] = ["y"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 3>) -> f64 {
        s[2]
    }
    fn mass_rate(&self, _: usize, t: f64, _: &SVector<f64, 3>) -> f64 {
        -self.thrust(t) / self.exhaust_speed
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 3>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(s[2])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(vs[2] * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 3>) -> f64 {
        0.5 * vs[2] * vs[1] * vs[1] - vs[2] * G * vs[0]
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-vs[2] * G)
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn reactive_thrust(&self, t: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.thrust(t))
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, t: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(self.mass_rate(0, t, vs) * vs[1])
    }
    fn accelerations(&self, t: f64, vs: &SVector<f64, 3>) -> Result<SVector<f64, 1>, SystemError> {
        Ok(Vector1::new(self.thrust(t) / vs[2] - G))
    }
    fn state_rate(&self, t: f64, s: &SVector<f64, 3>) -> Result<SVector<f64, 3>, SystemError> {
        let (p, m) = (s[1], s[2]);
        let (force, v) = (self.thrust(t), p / m);
        let rate = force / self.exhaust_speed;
        Ok(Vector3::new(v, -m * G + force - rate * v, -rate))
    }
}

fn control(tolerance: f64, base: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..base
    })
}

/// The largest relative error of m and of v against the closed form over every accepted
/// step, flying to each of `stops` in turn (each run lands on its end time exactly).
fn worst<St: Stepper<1, 3, System = MotorRocket>>(mut stepper: St, stops: &[f64]) -> [f64; 2] {
    let system = MotorRocket::m1670();
    let mut worst = [0.0_f64; 2];
    for &stop in stops {
        let solution = run(&mut stepper, &RunConfig::until(stop), &[]).unwrap();
        for (&t, state) in solution.times.iter().zip(&solution.states) {
            let (m, v) = system.exact(t);
            worst[0] = worst[0].max((state[2] - m).abs() / M0);
            // v reaches ≈ 290 m/s: relative to the largest speed, since v passes through 0.
            worst[1] = worst[1].max((state[1] / state[2] - v).abs() / 290.0);
        }
    }
    worst
}

/// The knots after the start, then the end: the stop times the DSL's tables of t will give.
fn knot_stops(system: &MotorRocket) -> Vec<f64> {
    let mut stops: Vec<f64> = system.thrust.knots()[1..].to_vec();
    stops.push(END);
    stops
}

fn start() -> SVector<f64, 3> {
    Vector3::new(0.0, 0.0, M0)
}

#[test]
fn dormand_prince_lands_on_the_knots_and_meets_the_closed_form() {
    let system = MotorRocket::m1670();
    let stops = knot_stops(&system);
    // Measured (m, v): 7.1e-16, 6.7e-15 at 1e-12; 3.6e-16, 4.6e-11 at 1e-8 (the issue asks
    // ≤ 1e-12 and ≤ 1e-8). Between knots ṁ is linear in t, so m is integrated exactly and
    // only v = u_e ln(m₀/m) − g t carries truncation error. Bounds ~10× the measured.
    for (tolerance, bounds) in [(1e-12, [1e-14, 1e-13]), (1e-8, [1e-14, 5e-10])] {
        let base = AdaptiveControl::default();
        let stepper = DormandPrince::new(&system, 0.0, start(), control(tolerance, base)).unwrap();
        let [mass, speed] = worst(stepper, &stops);
        assert!(
            mass <= bounds[0] && speed <= bounds[1],
            "{tolerance:e}: {mass:e} {speed:e}"
        );
    }
}

#[test]
fn dop853_lands_on_the_knots_and_meets_the_closed_form() {
    let system = MotorRocket::m1670();
    let stops = knot_stops(&system);
    // Measured (m, v): 1.8e-16, 6.5e-15 at 1e-12; 1.8e-16, 6.3e-15 at 1e-8. Bounds ~10×.
    for (tolerance, bounds) in [(1e-12, [1e-14, 1e-13]), (1e-8, [1e-14, 1e-13])] {
        let base = AdaptiveControl::dop853();
        let stepper = Dop853::new(&system, 0.0, start(), control(tolerance, base)).unwrap();
        let [mass, speed] = worst(stepper, &stops);
        assert!(
            mass <= bounds[0] && speed <= bounds[1],
            "{tolerance:e}: {mass:e} {speed:e}"
        );
    }
}
