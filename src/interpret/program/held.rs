//! Sampled inputs in the interpreter (docs/inputs.md#sampled-inputs): the held values are
//! the state's last entries, after the state masses, read into their symbols' slots like
//! any state entry; [`Program::sample`] replaces them by each input's law (given with
//! `varmass run --input`) at the state reached, and the sample grid k·T joins the stop
//! times.

use varmass_core::input::{next_sample_time, Sampling};
use varmass_core::SystemError;

use super::{component, set, Program, Scratch};

impl Program {
    /// The number of held values of sampled inputs (the state's last entries).
    pub fn held_count(&self) -> usize {
        self.held_symbols.len()
    }

    /// The sampled inputs' names, in state order (their held values' entries).
    pub fn held_names(&self) -> impl Iterator<Item = &str> {
        let inputs = self.d.inputs.iter().filter(|i| i.held.is_some());
        inputs.map(|i| i.name.as_str())
    }

    /// Replaces the held values in `state` (a state `[q, p, m_s, u_held]`) of the sampled
    /// inputs `which` takes (each on its own grid, or all at a run's start) by each one's
    /// law at `(t, state)`: the zero-order hold's sample. The law reads t, the coordinates,
    /// the velocities recovered from the state and the parameters; an input not due is not
    /// evaluated.
    pub fn sample(&self, t: f64, state: &mut [f64], which: Sampling) -> Result<(), SystemError> {
        let due: Vec<usize> = (self.periods.iter().enumerate())
            .filter(|(_, period)| which.takes(**period, t))
            .map(|(j, _)| j)
            .collect();
        if due.is_empty() {
            return Ok(());
        }
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        let first = 2 * self.coordinate_count() + self.state_mass_count();
        for j in due {
            self.run(&self.held_laws[j], scratch);
            if let Some(error) = scratch.outside.take() {
                return Err(error);
            }
            let value = scratch.values.first().copied().unwrap_or(f64::NAN);
            let value = match value.is_finite() {
                true => value,
                false => {
                    let input = self.held_names().nth(j).unwrap_or("?");
                    let input = crate::interpret::names::intern(input);
                    return Err(SystemError::SampledInputNotFinite { input, value });
                }
            };
            if let Some(x) = state.get_mut(first + j) {
                *x = value;
            }
        }
        Ok(())
    }

    /// Sets the held values' slots from `state`.
    pub(super) fn load_held(&self, scratch: &mut Scratch, state: &[f64]) {
        let first = 2 * self.coordinate_count() + self.state_mass_count();
        for (j, symbol) in self.held_symbols.iter().enumerate() {
            set(
                &mut scratch.env,
                symbol.index(),
                component(state, first + j),
            );
        }
    }

    /// The next sample time of any sampled input after `after` (infinity without one).
    pub(super) fn next_sample_time(&self, after: f64) -> f64 {
        (self.periods.iter())
            .map(|period| next_sample_time(*period, after))
            .fold(f64::INFINITY, f64::min)
    }
}
