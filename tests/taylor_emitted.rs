//! The generated `taylor_coefficients` (`emit = [..., "taylor"]`) against the run-time
//! tapes' `Program::taylor` (itself held to an independent reference by
//! `tests/taylor_models.rs`): the same coefficients to order 20, on systems that exercise
//! every stage (a mass law, a state mass, the closed-form q̇, the numeric q̇ of three
//! coordinates, abs, sqrt and the trigonometric pairs), and order 1 equal to the generated
//! state rate.

use varmass::core::steppers::taylor::series::Scratch;
use varmass::interpret::Program;
use varmass::prelude::*;
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::{derive, mechanics::Parameters};

#[variable_mass_system(file = "models/sled.vms", with = ["impact"], emit = ["taylor"])]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

#[variable_mass_system(file = "models/rocket.vms", with = ["drag"], emit = ["taylor"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
    k_d: f64,
}

#[variable_mass_system(file = "models/leaking_spring_pendulum_cartesian.vms", emit = ["taylor"])]
struct Cartesian {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

#[variable_mass_system(file = "models/swinging_tank.vms", emit = ["taylor"])]
#[allow(non_snake_case)] // the model's parameter names
struct Tank {
    mu: f64,
    M0: f64,
    J0: f64,
    l: f64,
    g: f64,
    K: f64,
    u_e: f64,
}

const ORDER: usize = 20;

/// Compares the generated coefficients with the program's at `(t, state)`; returns the
/// largest difference relative to the largest coefficient of the same order.
fn compare<Sys, const N: usize, const S: usize>(
    system: &Sys,
    file: &str,
    with: &[&str],
    parameters: &[(&str, f64)],
    (t, state): (f64, [f64; S]),
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    let source =
        std::fs::read_to_string(format!("{}/models/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let ast = parse_system(&source).unwrap();
    let with: Vec<String> = with.iter().map(|s| s.to_string()).collect();
    let ast = select_tags(&ast, &with).unwrap();
    let program = Program::new(derive(&ast, Parameters::Inferred).unwrap(), parameters).unwrap();
    let mut expected = vec![f64::NAN; (ORDER + 1) * S];
    program.taylor(t, &state, ORDER, &mut expected).unwrap();
    let y0 = SVector::<f64, S>::from_column_slice(&state);
    let mut generated = [SVector::<f64, S>::zeros(); ORDER + 1];
    system
        .taylor_coefficients(t, &y0, &mut generated, &mut Scratch::new())
        .expect("emitted")
        .unwrap();
    // What a scratch held never reaches the result: filled with NaN (more rows than any of
    // these systems has), it gives the same bits, so every row read was written first or
    // zeroed.
    let mut poisoned = [SVector::<f64, S>::zeros(); ORDER + 1];
    system
        .taylor_coefficients(
            t,
            &y0,
            &mut poisoned,
            &mut Scratch::filled(4096, 64, f64::NAN),
        )
        .expect("emitted")
        .unwrap();
    for (k, (a, b)) in generated.iter().zip(&poisoned).enumerate() {
        let same = a
            .iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits());
        assert!(
            same,
            "{file}: order {k} read a row before writing it: {a} vs {b}"
        );
    }
    // Order 1 is the generated state rate (other generated code): equal to rounding.
    let rate = system.state_rate(t, &y0).unwrap();
    assert!(
        (generated[1] - rate).amax() <= 1e-14 * rate.amax().max(1.0),
        "{file}: {} vs {rate}",
        generated[1]
    );
    let mut worst: f64 = 0.0;
    for (k, c) in generated.iter().enumerate() {
        let size = (0..S).fold(0.0f64, |m, i| m.max(expected[k * S + i].abs()));
        for i in 0..S {
            let gap = (c[i] - expected[k * S + i]).abs() / size.max(1e-300);
            worst = worst.max(gap);
        }
    }
    worst
}

#[test]
fn generated_coefficients_equal_the_tapes_to_order_20() {
    let sled = Sled {
        m0: 2.0,
        c: 0.5,
        g: 9.81,
        theta: 0.5,
        f_d: 0.1,
    };
    let sled_parameters = [
        ("m0", 2.0),
        ("c", 0.5),
        ("g", 9.81),
        ("theta", 0.5),
        ("f_d", 0.1),
    ];
    let rocket = Rocket {
        mu: 0.05,
        u_e: 300.0,
        g: 9.81,
        k_d: 0.01,
    };
    let rocket_parameters = [("mu", 0.05), ("u_e", 300.0), ("g", 9.81), ("k_d", 0.01)];
    let cartesian = Cartesian {
        mu: 0.02,
        u_e: 3.0,
        k: 40.0,
        l0: 1.0,
        g: 9.81,
    };
    let pendulum_parameters = [
        ("mu", 0.02),
        ("u_e", 3.0),
        ("k", 40.0),
        ("l0", 1.0),
        ("g", 9.81),
    ];
    let tank = Tank {
        mu: 0.05,
        M0: 3.0,
        J0: 0.4,
        l: 0.5,
        g: 9.81,
        K: 50.0,
        u_e: 2.0,
    };
    let tank_parameters = [
        ("mu", 0.05),
        ("M0", 3.0),
        ("J0", 0.4),
        ("l", 0.5),
        ("g", 9.81),
        ("K", 50.0),
        ("u_e", 2.0),
    ];
    let gaps = [
        compare(
            &sled,
            "sled.vms",
            &["impact"],
            &sled_parameters,
            (0.3, [1.2, 5.2]),
        ),
        compare(
            &rocket,
            "rocket.vms",
            &["drag"],
            &rocket_parameters,
            (2.0, [100.0, 40.0, 0.8]),
        ),
        compare(
            &cartesian,
            "leaking_spring_pendulum_cartesian.vms",
            &[],
            &pendulum_parameters,
            (0.0, [0.4, -1.0, 0.2, -0.1, 0.9]),
        ),
        compare(
            &tank,
            "swinging_tank.vms",
            &[],
            &tank_parameters,
            (0.0, [0.1, -0.05, 0.3, 0.2, 0.1, -0.05, 1.0]),
        ),
    ];
    eprintln!("relative gaps: {gaps:?}");
    for gap in gaps {
        // The same recurrences in the same order: measured 0 (bit-identical) on all four;
        // a bound of 1e-15 still lets a platform's libm differ in the last bit at order 0.
        assert!(gap <= 1e-15, "{gaps:?}");
    }
}

#[test]
fn a_system_without_taylor_emitted_has_none() {
    #[variable_mass_system(file = "models/sled.vms", with = ["impact"], emit = [])]
    struct Plain {
        m0: f64,
        c: f64,
        g: f64,
        theta: f64,
        f_d: f64,
    }
    let plain = Plain {
        m0: 2.0,
        c: 0.5,
        g: 9.81,
        theta: 0.5,
        f_d: 0.1,
    };
    let y0 = SVector::<f64, 2>::new(1.2, 5.2);
    let mut c = [SVector::<f64, 2>::zeros(); 3];
    assert!(plain
        .taylor_coefficients(0.0, &y0, &mut c, &mut Scratch::new())
        .is_none());
    match Taylor::new(&plain, 0.0, y0, TaylorControl::default()) {
        Err(error) => assert!(matches!(
            error.kind,
            StepErrorKind::InvalidConfiguration { .. }
        )),
        Ok(_) => panic!("a system without Taylor coefficients was accepted"),
    }
}
