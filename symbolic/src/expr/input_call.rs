//! Inputs in the expression engine (docs/inputs.md#in-the-derivation): the pool keeps each
//! `input` of the model by name with its declared arguments, and a call is an opaque
//! [`Func::Input`] node. Differentiation is the chain rule over the arguments,
//! ∂/∂s u(a₁…a_k) = Σⱼ ∂ⱼu(a) · ∂aⱼ/∂s, with ∂ⱼu the node `Input { partial: j }` (computed
//! in generated code from the user's `u_partials`); a partial is not differentiated again
//! (`diff.rs` gives NaN, and the derivation refuses it with a diagnostic:
//! `mechanics/inputs.rs`).

use super::func::Func;
use super::node::Id;
use super::pool::ExprPool;

/// One input of the pool: its name in the model and its arguments as declared (`y'` for a
/// velocity).
#[derive(Clone, Debug)]
pub(crate) struct PoolInput {
    pub(crate) name: String,
    pub(crate) arguments: Vec<String>,
}

impl ExprPool {
    /// Registers the input `name` with its declared `arguments` and returns the index calls
    /// use; `None` past `u16::MAX` inputs.
    pub fn add_input(&mut self, name: &str, arguments: Vec<String>) -> Option<u16> {
        let index = u16::try_from(self.inputs.len()).ok()?;
        self.inputs.push(PoolInput {
            name: name.to_owned(),
            arguments,
        });
        Some(index)
    }

    /// The call `u(args)` of input `input` (`partial` 0), or its partial with respect to
    /// argument `partial` (1-based). Never folded, even at constant arguments.
    pub fn input_call(&mut self, input: u16, partial: u8, args: &[Id]) -> Id {
        self.call(Func::Input { input, partial }, args)
    }

    /// The model's name of input `input` (empty if unknown).
    pub fn input_name(&self, input: u16) -> &str {
        self.inputs
            .get(usize::from(input))
            .map_or("", |i| i.name.as_str())
    }

    /// The declared arguments of input `input` (`t`, `y`, `y'`).
    pub fn input_arguments(&self, input: u16) -> &[String] {
        self.inputs
            .get(usize::from(input))
            .map_or(&[], |i| i.arguments.as_slice())
    }

    /// Number of inputs registered.
    pub fn input_count(&self) -> usize {
        self.inputs.len()
    }

    /// How a call of `Input{input, partial}` is written: `u`, then `∂_y u` for a partial
    /// (`∂_y' u` with respect to a velocity).
    pub fn input_call_name(&self, input: u16, partial: u8) -> String {
        let name = self.input_name(input);
        match partial.checked_sub(1) {
            None => name.to_owned(),
            Some(j) => {
                let argument = self
                    .input_arguments(input)
                    .get(usize::from(j))
                    .map_or("?", String::as_str);
                format!("∂_{argument} {name}")
            }
        }
    }
}
