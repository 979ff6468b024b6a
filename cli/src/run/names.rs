//! The names a run understands: `NAME=VALUE` pairs, numbers, and the model's quantities
//! (`x`, `x'`, `x''`, `p_x`, masses, `H`, `power`, `Q_x`, `R1_x`, `R2_x`, `pdot_x`).

use varmass::core::SystemError;
use varmass::interpret::{Program, Quantity};
use varmass::symbolic::parse::keywords::closest;

use crate::error::CliError;

/// A quantity of the model that can be recorded or watched by `--stop-when`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Observable {
    /// Coordinate `a`.
    Coordinate(usize),
    /// q̇ of coordinate `a`.
    Velocity(usize),
    /// q̈ of coordinate `a`.
    Acceleration(usize),
    /// p of coordinate `a`.
    Momentum(usize),
    /// Mass `i` (state masses first, then laws).
    Mass(usize),
    /// H.
    Hamiltonian,
    /// dH/dt.
    Power,
    /// A per-coordinate velocity-form quantity (Q*, R1, R2, ṗ) of coordinate `a`.
    Force(Quantity, usize),
}

/// Every quantity of `program` with its name, in a stable order.
pub fn observables(program: &Program) -> Vec<(String, Observable)> {
    let mut all = Vec::new();
    let coordinates: Vec<String> = program.coordinate_names().map(str::to_string).collect();
    for (a, x) in coordinates.iter().enumerate() {
        all.push((x.clone(), Observable::Coordinate(a)));
        all.push((format!("{x}'"), Observable::Velocity(a)));
        all.push((format!("{x}''"), Observable::Acceleration(a)));
        all.push((format!("p_{x}"), Observable::Momentum(a)));
    }
    for (i, m) in program.mass_names().enumerate() {
        all.push((m.to_string(), Observable::Mass(i)));
    }
    all.push(("H".to_string(), Observable::Hamiltonian));
    all.push(("power".to_string(), Observable::Power));
    let forces = [
        ("Q", Quantity::ActiveForce),
        ("R1", Quantity::ReactiveThrust),
        ("R2", Quantity::ImpactForce),
        ("pdot", Quantity::MomentumRate),
    ];
    for (prefix, quantity) in forces {
        for (a, x) in coordinates.iter().enumerate() {
            all.push((format!("{prefix}_{x}"), Observable::Force(quantity, a)));
        }
    }
    all
}

/// Looks `name` up among `known` (name, value) pairs; an unknown name is an error that
/// suggests the nearest and lists what `what` allows.
pub fn resolve<T: Copy>(name: &str, known: &[(String, T)], what: &str) -> Result<T, CliError> {
    if let Some((_, value)) = known.iter().find(|(n, _)| n == name) {
        return Ok(*value);
    }
    let names: Vec<&str> = known.iter().map(|(n, _)| n.as_str()).collect();
    let hint = closest(name, &names)
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default();
    Err(CliError::Input(format!(
        "`{name}` is not {what} of the model{hint}; it has: {}",
        names.join(", ")
    )))
}

/// Splits `NAME=VALUE` (spaces around `=` allowed) and parses the value.
pub fn assignment(text: &str, flag: &str) -> Result<(String, f64), CliError> {
    let Some((name, value)) = text.split_once('=') else {
        return Err(CliError::Input(format!(
            "{flag} `{text}`: expected NAME=VALUE"
        )));
    };
    named(text, flag, name, value)
}

/// The trimmed `name` (not empty) and the number `value` of `text`, given to `flag`.
pub fn named(text: &str, flag: &str, name: &str, value: &str) -> Result<(String, f64), CliError> {
    let name = name.trim();
    if name.is_empty() {
        return Err(CliError::Input(format!(
            "{flag} `{text}`: the name is empty"
        )));
    }
    Ok((name.to_string(), number(value.trim(), flag)?))
}

/// A finite number.
pub fn number(text: &str, what: &str) -> Result<f64, CliError> {
    match text.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        Ok(_) => Err(CliError::Input(format!("{what}: `{text}` is not finite"))),
        Err(_) => Err(CliError::Input(format!("{what}: `{text}` is not a number"))),
    }
}

/// The value of `observable` at `(t, state)`; `state` is `[q, p, m_s]`.
pub fn evaluate(
    program: &Program,
    observable: Observable,
    t: f64,
    state: &[f64],
) -> Result<f64, SystemError> {
    let n = program.coordinate_count();
    let pick = |values: Vec<f64>, index: usize| values.get(index).copied().unwrap_or(f64::NAN);
    Ok(match observable {
        Observable::Coordinate(a) => state[a],
        Observable::Momentum(a) => state[n + a],
        Observable::Velocity(a) => {
            let mut v = vec![f64::NAN; n];
            program.velocities(t, state, &mut v)?;
            pick(v, a)
        }
        Observable::Acceleration(a) => {
            let velocity_state = velocity_state(program, t, state)?;
            let mut q2 = vec![f64::NAN; n];
            program.accelerations(t, &velocity_state, &mut q2)?;
            pick(q2, a)
        }
        Observable::Mass(i) => {
            let mut m = vec![f64::NAN; program.derivation().masses.len()];
            program.masses(t, state, &mut m);
            pick(m, i)
        }
        Observable::Hamiltonian => at_state(program, Quantity::Energy, 1, t, state, 0)?,
        Observable::Power => at_state(program, Quantity::Power, 1, t, state, 0)?,
        Observable::Force(quantity, a) => at_state(program, quantity, n, t, state, a)?,
    })
}

fn at_state(
    program: &Program,
    quantity: Quantity,
    len: usize,
    t: f64,
    state: &[f64],
    index: usize,
) -> Result<f64, SystemError> {
    let mut out = vec![f64::NAN; len];
    program.evaluate_at_state(quantity, t, state, &mut out)?;
    Ok(out.get(index).copied().unwrap_or(f64::NAN))
}

/// `[q, q̇, m_s]` of a state `[q, p, m_s]`.
pub fn velocity_state(program: &Program, t: f64, state: &[f64]) -> Result<Vec<f64>, SystemError> {
    let n = program.coordinate_count();
    let mut out = state.to_vec();
    program.velocities(t, state, &mut out[n..2 * n])?;
    Ok(out)
}
