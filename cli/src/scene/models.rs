//! A scene's model, derived once for each set of tags its phases select and kept: a scene
//! run again (the Python package's `Scene.run`) derives nothing again while its model
//! file is unchanged. Deriving is most of the cost of a short scene (the 6-dof rocket:
//! about 11 ms of derivation against 1 ms for a `Model` run already derived).

use crate::args::ModelArgs;
use crate::error::CliError;
use crate::model::{load_source, LoadedModel};

/// The models derived so far, each with the file, tags and text it was derived from.
#[derive(Default)]
pub struct Models {
    derived: Vec<(ModelArgs, String, LoadedModel)>,
    derivations: usize,
    /// Whether the models are derived with their parameter Jacobians (`--sensitivity`).
    sensitivities: bool,
}

impl Models {
    /// The model file `args.file` with the tags `args.with`: the one derived before from
    /// the same text, else derived now (a file that cannot be read is the tool's error).
    pub fn load(&mut self, args: &ModelArgs) -> Result<LoadedModel, CliError> {
        let path = &args.file;
        let source = std::fs::read_to_string(path).map_err(|source| CliError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let known = self
            .derived
            .iter()
            .find(|(made_for, text, _)| made_for == args && *text == source);
        if let Some((_, _, model)) = known {
            if model.has_sensitivities() == self.sensitivities {
                return Ok(model.clone());
            }
        }
        let model =
            load_source(&source, path, &args.with)?.with_sensitivities(self.sensitivities)?;
        self.derivations += 1;
        // Only the latest text of a file is worth keeping.
        self.derived.retain(|(made_for, _, _)| made_for != args);
        self.derived.push((args.clone(), source, model.clone()));
        Ok(model)
    }

    /// Derive the models from now on with (`true`) or without their parameter Jacobians
    /// (a scene run with `--sensitivity`, docs/sensitivities.md#scenes).
    pub fn set_sensitivities(&mut self, sensitivities: bool) {
        self.sensitivities = sensitivities;
    }

    /// How many derivations these models cost so far.
    pub fn derivations(&self) -> usize {
        self.derivations
    }
}
