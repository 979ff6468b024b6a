//! A rocket on a real motor: vertical flight on the Cesaroni M1670's measured thrust curve
//! (`models/motors/Cesaroni_M1670.eng`, a linear table, zero after burnout), its mass
//! following the curve at the rocketry tools' constant exhaust speed (ṁ = −F/u_e,
//! u_e = total impulse / propellant mass from the file's header) and quadratic drag
//! −k_d ẏ|ẏ| (`models/motor_rocket_drag.vms`). The rocket starts on its pad, held there
//! until the thrust exceeds the weight (`varmass::core::support`,
//! docs/mechanics.md#a-support-that-holds-until-lifted: the held phase, then the free one).
//! The run lands on every knot of the curve (stop times) and stops at the apex (an event on
//! the momentum); it prints the flight summary with the lift-off time and plots altitude
//! and speed against time into `target/motor_rocket.svg`.
//!
//! Check: without drag the speed at burnout has a closed form,
//! v = u_e ln(m_L/m_b) − g (t_b − t_L) from rest at the lift-off t_L, with m_L = m₀ − I(t_L)/u_e
//! (I the exact trapezoid integral of the curve) and m_b = m₀ − propellant (Meshchersky,
//! m v̇ = F − m g with ṁ = −F/u_e); the example flies that case too and exits non-zero if it
//! misses by more than 1e-9 relative.
//!
//! Run with `cargo run --release --example motor_rocket`.

use std::process::ExitCode;

use plotters::prelude::*;
use varmass::core::support::phases;
use varmass::core::{lift_off_time, run_phases};
use varmass::prelude::*;
use varmass_table::{Interpolation, Motor};

#[derive(Clone, Copy)]
#[variable_mass_system(file = "models/motor_rocket_drag.vms")]
struct DragRocket {
    u_e: f64,
    g: f64,
    k_d: f64,
}

/// Gravity, m/s².
const G: f64 = 9.80665;
/// Lift-off mass, kg: the loaded M1670 (5.231 kg) in a 14.769 kg airframe.
const M0: f64 = 20.0;
/// Tolerance of the runs (relative and absolute).
const TOLERANCE: f64 = 1e-10;
/// The closed form's acceptance threshold (relative).
const THRESHOLD: f64 = 1e-9;
/// Where the plot goes.
const PLOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/motor_rocket.svg");

/// A recorded point: t (s), altitude (m), speed (m/s).
type Sample = (f64, f64, f64);

/// A panel's label and what it plots of a sample.
type Series = (&'static str, fn(&Sample) -> f64);

/// The flight's figures.
struct Summary {
    lift_off: f64,
    burnout: (f64, f64, f64),
    max_speed: (f64, f64),
    apex: (f64, f64),
    points: Vec<Sample>,
}

fn motor() -> Result<Motor, String> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/motors/Cesaroni_M1670.eng"
    );
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    Motor::parse(&text).map_err(|e| format!("{path}:{}:{}: {}", e.line, e.column, e.kind))
}

/// Flies `rocket` from its pad (held until lifted) to burnout (the curve's last knot), then
/// on to the apex (ẏ = 0 falling: the momentum, state 1, crosses zero), recording every
/// accepted step.
fn fly(rocket: &DragRocket, burn_time: f64) -> Result<Summary, StepError<3>> {
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: TOLERANCE,
        absolute_tolerance: TOLERANCE,
        ..AdaptiveControl::dop853()
    });
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let on_pad = phases(*rocket, 0, (0.0, &start))?;
    let stepper = |system, t, state| Dop853::new(system, t, state, control);
    let burning = run_phases(&on_pad, (0.0, start), stepper, &RunConfig::until(burn_time))
        .map_err(|e| e.error)?;
    let (t_b, s_b) = match burning.solution.last() {
        Some((t, s)) => (t, *s),
        None => (0.0, start),
    };
    let no_lift_off = "the rocket did not lift off before burnout";
    let lift_off = lift_off_time(&on_pad, &burning).ok_or(StepError::invalid_configuration(
        t_b,
        s_b,
        no_lift_off,
    ))?;
    let mut stepper = Dop853::new(rocket, t_b, s_b, control)?;
    let apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let coasting = run(&mut stepper, &RunConfig::until(120.0), &[apex]).map_err(|e| e.error)?;
    let speed = |s: &SVector<f64, 3>| s[1] / s[2];
    let burning = &burning.solution;
    let points: Vec<Sample> = (burning.times.iter().zip(&burning.states))
        .chain(coasting.times.iter().zip(&coasting.states).skip(1))
        .map(|(&t, s)| (t, s[0], speed(s)))
        .collect();
    let Some(hit) = coasting.events.first() else {
        return Err(StepError::invalid_configuration(
            stepper.time(),
            *stepper.state(),
            "no apex within 120 s",
        ));
    };
    let max_speed =
        points
            .iter()
            .map(|&(t, _, v)| (t, v))
            .fold(
                (0.0, f64::NEG_INFINITY),
                |a, b| if b.1 > a.1 { b } else { a },
            );
    Ok(Summary {
        lift_off,
        burnout: (t_b, speed(&s_b), s_b[0]),
        max_speed,
        apex: (hit.time, hit.state[0]),
        points,
    })
}

fn plot(points: &[Sample]) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(PLOT, (900, 700)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((2, 1));
    let end = points.last().map_or(1.0, |p| p.0);
    let series: [Series; 2] = [("altitude (m)", |p| p.1), ("speed (m/s)", |p| p.2)];
    for (panel, (label, of)) in panels.iter().zip(series) {
        let (low, high) = points
            .iter()
            .map(of)
            .fold((0.0f64, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("M1670 rocket with drag: {label}"),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..end, low..high * 1.05)?;
        chart
            .configure_mesh()
            .x_desc("t (s)")
            .y_desc(label)
            .draw()?;
        chart.draw_series(LineSeries::new(points.iter().map(|p| (p.0, of(p))), &BLUE))?;
    }
    root.present()?;
    Ok(())
}

fn main() -> ExitCode {
    let motor = match motor() {
        Ok(motor) => motor,
        Err(error) => {
            eprintln!("{error}");
            return ExitCode::FAILURE;
        }
    };
    let u_e = motor.exhaust_speed();
    let burn_time = motor.burn_time();
    // ½ ρ C_d A: sea-level air, C_d 0.5, a 98 mm airframe (benches/common/motor_rocket.rs).
    let k_d = 0.5 * 1.225 * 0.5 * std::f64::consts::PI * 0.049 * 0.049;
    println!(
        "Cesaroni M1670: total impulse {:.2} N·s, propellant {} kg, burn {burn_time} s, u_e = {u_e:.3} m/s",
        motor.total_impulse(),
        motor.propellant_kg
    );
    let flights = fly(&DragRocket { u_e, g: G, k_d }, burn_time).and_then(|drag| {
        fly(
            &DragRocket {
                u_e,
                g: G,
                k_d: 0.0,
            },
            burn_time,
        )
        .map(|vacuum| (drag, vacuum))
    });
    let (drag, vacuum) = match flights {
        Ok(flights) => flights,
        Err(error) => {
            eprintln!("the run failed: {error}");
            return ExitCode::FAILURE;
        }
    };
    let (t_b, v_b, y_b) = drag.burnout;
    println!("With drag (k_d = {k_d:.5} kg/m, lift-off {M0} kg), DOP853 at {TOLERANCE:e}:");
    println!(
        "  lift-off  t = {:.6} s (held on the pad until the thrust exceeds the weight)",
        drag.lift_off
    );
    println!("  burnout   t = {t_b:.4} s, v = {v_b:.3} m/s, y = {y_b:.2} m");
    println!(
        "  max speed v = {:.3} m/s at t = {:.4} s (over the steps)",
        drag.max_speed.1, drag.max_speed.0
    );
    println!(
        "  apex      t = {:.4} s, y = {:.2} m",
        drag.apex.0, drag.apex.1
    );
    let (t_v, v_v, _) = vacuum.burnout;
    let m_b = M0 - motor.propellant_kg;
    let impulse = Interpolation::Linear
        .interpolate(&motor.thrust)
        .antiderivative();
    let t_l = vacuum.lift_off;
    let m_l = M0 - impulse.value(t_l) / u_e;
    let exact = u_e * (m_l / m_b).ln() - G * (t_v - t_l);
    let error = (v_v - exact).abs() / exact;
    println!(
        "Without drag: apex t = {:.4} s, y = {:.2} m;",
        vacuum.apex.0, vacuum.apex.1
    );
    println!("  burnout speed {v_v:.9} m/s against u_e ln(m_L/m_b) - g (t_b - t_L) = {exact:.9} m/s: relative error {error:.1e}");
    if let Err(error) = plot(&drag.points) {
        eprintln!("the plot failed: {error}");
        return ExitCode::FAILURE;
    }
    println!("Plot: {PLOT}");
    if error > THRESHOLD {
        eprintln!("FAILED: the closed form is missed by more than {THRESHOLD:e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
