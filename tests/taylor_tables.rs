//! Tables in the Taylor stepper (docs/tables.md#taylor-series): between knots a table is a
//! polynomial of its argument, so the series of F(a(t)) is that polynomial composed with
//! a's series; the knots of a table of t are stop times, so no Taylor step straddles one.
//! Shown on the M1670 rocket (`models/motor_rocket.vms`, its closed form by hand in
//! `tests/table_dsl_rocket.rs`: m = m₀ − I(t)/u_e, v = u_e ln(m₀/m) − g t), on the rocket
//! with quadratic drag against DOP853, and generated code against the run-time tapes, bit
//! for bit, for file and runtime tables.

use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl, Taylor, TaylorControl};
use varmass::core::table::Tabulated;
use varmass::interpret::Program;
use varmass::prelude::*;
use varmass::symbolic::parse::parse_system;
use varmass::symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};
use varmass_table::{Interpolation, Motor};

#[variable_mass_system(file = "models/motor_rocket.vms", emit = ["taylor"])]
struct MotorRocket {
    u_e: f64,
    g: f64,
}

#[variable_mass_system(file = "models/motor_rocket_drag.vms", emit = ["taylor"])]
struct DragRocket {
    u_e: f64,
    g: f64,
    k_d: f64,
}

#[variable_mass_system(file = "models/motor_rocket_runtime.vms", emit = ["taylor"])]
#[allow(non_snake_case)] // the field is named as the model's table
struct RuntimeRocket {
    u_e: f64,
    g: f64,
    F: Tabulated,
}

const G: f64 = 9.80665;
const M0: f64 = 20.0;
/// Past burnout (3.9 s): the knots and the end of the data are crossed.
const END: f64 = 6.0;
/// ½ ρ C_d A for a 0.1 m airframe at sea level, kg/m.
const K_D: f64 = 0.5 * 1.225 * 0.45 * 0.007_85;

fn motor() -> Motor {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/motors/Cesaroni_M1670.eng"
    );
    Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn start() -> SVector<f64, 3> {
    SVector::from([0.0, 0.0, M0])
}

/// The generated coefficients to order 20 against the interpreter's tapes on the same model
/// file: equal to the bit.
fn same_as_the_tapes<Sys: VariableMassSystem<1, 3>>(system: &Sys, file: &str, set: &[(&str, f64)]) {
    const ORDER: usize = 20;
    let models = concat!(env!("CARGO_MANIFEST_DIR"), "/models");
    let source = std::fs::read_to_string(format!("{models}/{file}")).unwrap();
    let ast = parse_system(&source).unwrap();
    let derivation = derive_in(&ast, Parameters::Inferred, Outputs::FULL, models.as_ref());
    let program = Program::new(derivation.unwrap(), set).unwrap();
    // One scratch for every point, filled with NaN first: what it held (the last point's
    // pieces included) must never reach a result.
    let mut scratch = varmass::core::steppers::taylor::series::Scratch::filled(4096, 64, f64::NAN);
    // Inside the pieces, on a knot (0.055 s, the first after ignition), and after burnout.
    for t in [0.01, 0.055, 1.234, 3.5, 4.5] {
        let state = [120.0, 2400.0, 17.5];
        let mut expected = vec![f64::NAN; (ORDER + 1) * 3];
        program.taylor(t, &state, ORDER, &mut expected).unwrap();
        let mut generated = [SVector::<f64, 3>::zeros(); ORDER + 1];
        let y = SVector::from(state);
        system
            .taylor_coefficients(t, &y, &mut generated, &mut scratch)
            .expect("emitted")
            .unwrap();
        for (k, c) in generated.iter().enumerate() {
            for i in 0..3 {
                assert_eq!(
                    c[i].to_bits(),
                    expected[k * 3 + i].to_bits(),
                    "{file} t {t} k {k} i {i}: {} vs {}",
                    c[i],
                    expected[k * 3 + i]
                );
            }
        }
        // Order 1 is the state rate (other generated code): equal to rounding (measured:
        // an ulp of ṗ).
        let rate = system.state_rate(t, &y).unwrap();
        assert!(
            (generated[1] - rate).amax() <= 1e-14 * rate.amax(),
            "{rate}"
        );
    }
}

#[test]
fn generated_table_series_equal_the_tapes_to_the_bit() {
    let u_e = motor().exhaust_speed();
    let file = MotorRocket { u_e, g: G };
    same_as_the_tapes(&file, "motor_rocket.vms", &[("u_e", u_e), ("g", G)]);
    let drag = DragRocket {
        u_e,
        g: G,
        k_d: K_D,
    };
    let set = [("u_e", u_e), ("g", G), ("k_d", K_D)];
    same_as_the_tapes(&drag, "motor_rocket_drag.vms", &set);
    // The runtime table's code reads the field; the tapes the same data from the file.
    let runtime = RuntimeRocket {
        u_e,
        g: G,
        F: RuntimeRocket::tabulate_F(&motor().thrust),
    };
    same_as_the_tapes(&runtime, "motor_rocket.vms", &[("u_e", u_e), ("g", G)]);
}

#[test]
fn the_taylor_rocket_lands_on_the_knots_and_meets_the_closed_form() {
    let u_e = motor().exhaust_speed();
    let system = MotorRocket { u_e, g: G };
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-12, 1e-12, Floor::Taylor).unwrap());
    let mut stepper = Taylor::new(&system, 0.0, start(), control).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(END), &[]).unwrap();
    let impulse = Interpolation::Linear
        .interpolate(&motor().thrust)
        .antiderivative();
    let mut worst = [0.0_f64; 2];
    for (&t, state) in solution.times.iter().zip(&solution.states) {
        let m = M0 - impulse.value(t.min(impulse.domain().1)) / u_e;
        let v = u_e * (M0 / m).ln() - G * t;
        worst[0] = worst[0].max((state[2] - m).abs() / M0);
        worst[1] = worst[1].max((state[1] / state[2] - v).abs() / 290.0);
    }
    for knot in &motor().thrust.arguments()[1..] {
        assert!(solution.times.contains(knot), "no step ends at {knot}");
    }
    // Measured (m, v): 1.8e-16, 7.8e-16 in 17 steps (16 of them ending on a knot or the
    // end); bound 1e-12, the for the other steppers at tolerance 1e-12.
    assert!(worst[0] <= 1e-12 && worst[1] <= 1e-12, "{worst:?}");
}

/// With quadratic drag (no closed form), Taylor against DOP853, both at tolerance 1e-12.
/// The rocket leaves its rail at 1 m/s: from rest it would first sink (the thrust starts
/// from 0 N) and turn at 0.078 s, and a Taylor step starting at ẏ = 0 expands |ẏ| on the
/// positive branch (a tie at order 0) while ẏ goes negative: a limitation of `abs` at a
/// zero start, not of tables (measured 2.4e-9 in p at 6 s from rest).
#[test]
fn the_taylor_drag_rocket_agrees_with_dop853() {
    let u_e = motor().exhaust_speed();
    let system = DragRocket {
        u_e,
        g: G,
        k_d: K_D,
    };
    let start = SVector::from([0.0, M0 * 1.0, M0]);
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-12, 1e-12, Floor::Taylor).unwrap());
    let mut taylor = Taylor::new(&system, 0.0, start, control).unwrap();
    let by_taylor = run(&mut taylor, &RunConfig::until(END), &[]).unwrap();
    let dop = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::dop853()
    });
    let mut dop853 = Dop853::new(&system, 0.0, start, dop).unwrap();
    let by_dop853 = run(&mut dop853, &RunConfig::until(END), &[]).unwrap();
    let (a, b) = (by_taylor.last().unwrap().1, by_dop853.last().unwrap().1);
    let gap = [
        (a[0] - b[0]).abs() / b[0].abs(),
        (a[1] - b[1]).abs() / b[1].abs(),
        (a[2] - b[2]).abs() / b[2].abs(),
    ];
    // Measured (y, p, m): 9.7e-15, 3.1e-14, 0 at 6 s (y = 1171.6 m); bound 1e-12.
    assert!(gap.iter().all(|g| *g <= 1e-12), "{gap:?}");
}
