//! The names a run understands: `NAME=VALUE` pairs, numbers, and the model's quantities:
//! coordinates `x`, velocities `x'`, masses, and every named quantity of the registry
//! (`varmass_symbolic::quantity`: `H`, `L`, `T`, `V`, `power`, `p_x`, `Q_x`, `R1_x`,
//! `R2_x`, `dp_x`, `pdot_x`, `x''`, `mdot_m`).

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
    /// Mass `i` (state masses first, then laws).
    Mass(usize),
    /// Entry `index` (a coordinate, a mass, or 0 for a scalar) of a registry quantity.
    Quantity(Quantity, usize),
    /// The held value of sampled input `j` (recorded under the input's name).
    Held(usize),
}

/// Every quantity of `program` with its name, in a stable order: coordinates and their
/// velocities, masses, then the registry's names ([`Quantity::names`]).
pub fn observables(program: &Program) -> Vec<(String, Observable)> {
    let mut all = Vec::new();
    let coordinates: Vec<&str> = program.coordinate_names().collect();
    for (a, x) in coordinates.iter().enumerate() {
        all.push((x.to_string(), Observable::Coordinate(a)));
        all.push((format!("{x}'"), Observable::Velocity(a)));
    }
    let masses: Vec<&str> = program.mass_names().collect();
    for (i, m) in masses.iter().enumerate() {
        all.push((m.to_string(), Observable::Mass(i)));
    }
    for (j, u) in program.held_names().enumerate() {
        all.push((u.to_string(), Observable::Held(j)));
    }
    let named = Quantity::names(&coordinates, &masses).into_iter();
    all.extend(named.map(|(name, q, index)| (name, Observable::Quantity(q, index))));
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

/// A number as a user would write it, the inverse of [`number`]: `0.5`, `100`, `1e-30`,
/// `1e12`, every digit kept (Rust's `{}` spells 1e-310 with 310 digits).
pub fn shown(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
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
    match observable {
        Observable::Coordinate(a) => Ok(state[a]),
        Observable::Velocity(a) => scratch(n, |v| {
            program.velocities(t, state, v)?;
            Ok(pick(v, a))
        }),
        Observable::Mass(i) => scratch(program.derivation().masses.len(), |m| {
            program.masses(t, state, m);
            Ok(pick(m, i))
        }),
        Observable::Held(j) => {
            let first = 2 * n + program.state_mass_count();
            Ok(state.get(first + j).copied().unwrap_or(f64::NAN))
        }
        Observable::Quantity(quantity, index) => {
            let len = program.derivation().quantity(quantity).len().max(n);
            scratch(len, |out| {
                program.evaluate_at_state(quantity, t, state, out)?;
                Ok(pick(out, index))
            })
        }
    }
}

/// `f` given `len` NaNs to write into: on the stack up to a size beyond the tool's models
/// (a recorded column evaluates at every point: no allocation each time), on the heap
/// beyond.
fn scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    const STACK: usize = 32;
    if len <= STACK {
        let mut buffer = [f64::NAN; STACK];
        f(&mut buffer[..len])
    } else {
        f(&mut vec![f64::NAN; len])
    }
}

/// Entry `index` of `values`, NaN past its end (an index from [`observables`] is never).
fn pick(values: &[f64], index: usize) -> f64 {
    values.get(index).copied().unwrap_or(f64::NAN)
}

/// `[q, q̇, m_s]` of a state `[q, p, m_s]`.
pub fn velocity_state(program: &Program, t: f64, state: &[f64]) -> Result<Vec<f64>, SystemError> {
    let n = program.coordinate_count();
    let mut out = state.to_vec();
    program.velocities(t, state, &mut out[n..2 * n])?;
    Ok(out)
}
